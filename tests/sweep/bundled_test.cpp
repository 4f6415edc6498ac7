// The bundled scenes and sweep specs: found from libcampo's folder as well as the working
// folder, and an unknown name's error lists where it was looked for (sweep/bundled.cpp).
#include "sweep/bundled.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "campo/json_reader.hpp"
#include "sweep/sweep_spec.hpp"

namespace campo {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

bool same_file(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  return fs::equivalent(a, b, ec);
}

std::string error_of(void (*call)()) {
  try {
    call();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(Bundled, FoldersAreTheWorkingFoldersThenTheSourceTreesBesideTheBuildDirectory) {
  // This test links build/libcampo.so, build/ inside the source tree: the source tree's scenes/.
  const std::vector<fs::path> folders = bundled_folders();
  ASSERT_GE(folders.size(), 2u);
  EXPECT_EQ(folders.front(), fs::path("scenes"));
  for (std::size_t i = 1; i < folders.size(); ++i) EXPECT_TRUE(folders[i].is_absolute()) << folders[i];
  EXPECT_TRUE(std::any_of(folders.begin() + 1, folders.end(), [](const fs::path& folder) {
    return same_file(folder, fs::path(CAMPO_SOURCE_DIR) / "scenes");
  }));
}

TEST(Bundled, FoundFromAnyWorkingFolderTheWorkingFoldersFirst) {
  const fs::path dir = fs::temp_directory_path() / "campo_bundled_test";
  fs::remove_all(dir);
  fs::create_directories(dir / "scenes");
  fs::create_directories(dir / "elsewhere");
  fs::copy_file(fs::path(CAMPO_SOURCE_DIR) / "scenes" / "two_barriers.json", dir / "scenes" / "two_barriers.json");
  const fs::path here = fs::current_path();
  fs::current_path(dir);  // a scenes/ of its own: that one
  const fs::path own = bundled_scene("two_barriers");
  fs::current_path(dir / "elsewhere");  // none: the source tree's, from libcampo's folder
  const fs::path scene = bundled_scene("two_barriers");
  const fs::path spec = bundled_sweep_spec("resolution_000");
  fs::current_path(here);
  fs::remove_all(dir);
  EXPECT_EQ(own, fs::path("scenes") / "two_barriers.json");
  EXPECT_TRUE(scene.is_absolute()) << scene;
  EXPECT_TRUE(same_file(scene, fs::path(CAMPO_SOURCE_DIR) / "scenes" / "two_barriers.json")) << scene;
  EXPECT_TRUE(same_file(spec, fs::path(CAMPO_SOURCE_DIR) / "scenes" / "sweeps" / "resolution_000.json")) << spec;
}

TEST(Bundled, AnUnknownNameListsTheFoldersSearched) {
  std::string folders;
  for (const fs::path& folder : bundled_folders()) folders += (folders.empty() ? "" : ", ") + folder.string();
  const std::string listed = "scenes (from the working directory)" + folders.substr(std::string("scenes").size());
  EXPECT_EQ(error_of([] { bundled_scene("no_such_scene"); }),
            "no_such_scene: no bundled scene of that name: looked for no_such_scene.json in " + listed);
  EXPECT_EQ(error_of([] { bundled_sweep_spec("no_such_spec"); }),
            "no_such_spec: no bundled sweep spec of that name: looked for sweeps/no_such_spec.json in " + listed);
  // A file that exists is taken as it is; a bare name is looked up.
  EXPECT_EQ(file_or_bundled("scenes/two_barriers.json", &bundled_scene), fs::path("scenes/two_barriers.json"));
  EXPECT_THAT(error_of([] { file_or_bundled("no_such_scene", &bundled_scene); }),
              HasSubstr("no_such_scene: no bundled scene of that name: looked for no_such_scene.json in scenes"));
}

TEST(Bundled, ASweepSpecsUnknownSceneIsReportedWhereTheSpecNamesIt) {
  const fs::path dir = fs::temp_directory_path() / "campo_bundled_spec_test";
  fs::create_directories(dir);
  const fs::path spec = dir / "spec.json";
  std::ofstream(spec) << R"({"campo_sweep": 1, "scenes": ["two_barriers", "no_such_scene"]})";
  std::string error;
  try {
    read_sweep_spec(spec);
  } catch (const InputError& e) {
    error = e.what();
  }
  fs::remove_all(dir);
  EXPECT_THAT(error, HasSubstr(spec.string()));  // then maybe the line and column of the value
  EXPECT_THAT(error, HasSubstr(": /scenes/1: no bundled scene of that name: looked for no_such_scene.json in scenes "
                               "(from the working directory), "));
}

}  // namespace
}  // namespace campo
