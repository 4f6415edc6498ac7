// What the program loads: OSMesa (and LLVM behind it) only when a run renders
// depth, cairo only when it draws a figure, OpenCV's image codecs (GDAL, ...)
// never; the dynamic loader's own report (LD_DEBUG=libs) says which libraries
// a process initialised.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include <unistd.h>

#include "tests/cli_support.hpp"

namespace campo {
namespace {

namespace fs = std::filesystem;

// The libraries the loader initialised while `arguments` ran.
std::string loaded_by(const std::string& arguments) {
  const fs::path log = fs::temp_directory_path() / ("campo_startup_" + std::to_string(::getpid()) + ".log");
  const std::string command = "cd " + std::string(CAMPO_SOURCE_DIR) + " && LD_DEBUG=libs LD_DEBUG_OUTPUT=" +
                              log.string() + " " + CAMPO_BINARY + " " + arguments + " >/dev/null 2>&1";
  EXPECT_EQ(std::system(command.c_str()), 0) << command;
  std::string text;
  for (const auto& entry : fs::directory_iterator(log.parent_path())) {
    if (entry.path().filename().string().rfind(log.filename().string(), 0) == 0) {
      text += testing::slurp(entry.path());
      fs::remove(entry.path());
    }
  }
  return text;
}

TEST(Startup, HelpLoadsNoOsmesaCairoOrImageCodecs) {
  const std::string loaded = loaded_by("--help");
  EXPECT_NE(loaded.find("calling init"), std::string::npos) << "no loader report";
  EXPECT_EQ(loaded.find("libOSMesa"), std::string::npos);
  EXPECT_EQ(loaded.find("libLLVM"), std::string::npos);
  EXPECT_EQ(loaded.find("libcairo"), std::string::npos);
  EXPECT_EQ(loaded.find("libfontconfig"), std::string::npos);
  EXPECT_EQ(loaded.find("libopencv_imgcodecs"), std::string::npos);
  EXPECT_EQ(loaded.find("libgdal"), std::string::npos);
}

TEST(Startup, OsmesaIsLoadedOnlyForADepthCamera) {
  const fs::path out = fs::temp_directory_path() / ("campo_startup_runs_" + std::to_string(::getpid()));
  // zigzag: LIDAR only; figures are drawn without OSMesa.
  const std::string lidar = loaded_by("run zigzag --set /world/time_limit_s=1 --out " + (out / "lidar").string());
  EXPECT_EQ(lidar.find("libOSMesa"), std::string::npos);
  // two_barriers with its scanner as a depth camera renders with OSMesa.
  const std::string depth = loaded_by("run two_barriers --set /world/time_limit_s=0.5 --set "
                                      "/objects/drone/sensors/scanner/type=\\\"depth_camera\\\" --out " +
                                      (out / "depth").string());
  EXPECT_NE(depth.find("libOSMesa"), std::string::npos);
  fs::remove_all(out);
}

TEST(Startup, CairoIsLoadedOnlyToDrawAFigure) {
  const fs::path out = fs::temp_directory_path() / ("campo_startup_figures_" + std::to_string(::getpid()));
  const std::string run = "run zigzag --set /world/time_limit_s=1 --out ";
  const std::string without = loaded_by(run + (out / "without").string() + " --no-figures");
  EXPECT_FALSE(fs::exists(out / "without" / "map.png"));
  EXPECT_EQ(without.find("libcairo"), std::string::npos);
  // A run draws map.png and side.png by default.
  const std::string with = loaded_by(run + (out / "with").string());
  EXPECT_TRUE(fs::exists(out / "with" / "map.png"));
  EXPECT_NE(with.find("libcairo.so.2"), std::string::npos);
  fs::remove_all(out);
}

}  // namespace
}  // namespace campo
