#include <chrono>
#include <filesystem>
#include <iomanip>
#include <iostream>

#include "sim/lidar.hpp"
#include "sim/provenance.hpp"
#include "sim/scene_loader.hpp"
#include "tools/commands.hpp"

namespace campo::cli {

namespace {

struct BenchOptions {
  std::string scenes_dir = "scenes";
  double min_time_s = 2.0;
  int resolution = 256;
  bool json = false;
};

// Rays per second of one thread casting `preset` scans from the scene's first
// vehicle, repeated until min_time_s has passed.
double lidar_rays_per_second(const Scene& scene, int resolution, double min_time_s) {
  LidarConfig config = *lidar_preset("scanner3d");
  config.cols = config.rows = resolution;
  const Eigen::Isometry3d pose = scene.vehicles.empty()
                                     ? Eigen::Isometry3d::Identity()
                                     : scene.vehicles.front().pose * to_isometry(config.mount);
  RayCaster caster(scene);
  Lidar lidar(config, scene.world.seed);
  LidarScan scan;
  lidar.scan(caster, pose, 0.0, scan);  // warm-up
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  long rays = 0;
  double elapsed = 0.0;
  for (int i = 0; elapsed < min_time_s; ++i) {
    // Turn a little each scan so the rays see different geometry.
    Eigen::Isometry3d turned = pose;
    turned.linear() = Eigen::AngleAxisd(0.05 * i, Eigen::Vector3d::UnitZ()) * pose.linear();
    lidar.scan(caster, turned, 0.0, scan);
    rays += static_cast<long>(scan.ranges_m.size());
    elapsed = std::chrono::duration<double>(Clock::now() - start).count();
  }
  return static_cast<double>(rays) / elapsed;
}

int run_bench(const BenchOptions& o) {
  const char* scenes[] = {"trees_rolling_terrain", "vineyard"};
  for (const char* name : scenes) {
    const Scene scene = load_scene(std::filesystem::path(o.scenes_dir) / (std::string(name) + ".json"));
    const double rate = lidar_rays_per_second(scene, o.resolution, o.min_time_s);
    if (o.json) {
      std::cout << nlohmann::json{{"benchmark", "lidar_scanner3d"},
                                  {"scene", name},
                                  {"resolution", o.resolution},
                                  {"threads", 1},
                                  {"rays_per_second", rate},
                                  {"campo_version", campo_version_string()}}
                       .dump()
                << "\n";
    } else {
      std::cout << "lidar scanner3d " << o.resolution << "x" << o.resolution << " in " << std::setw(22)
                << std::left << name << std::right << std::fixed << std::setprecision(2)
                << rate / 1e6 << " M rays/s (1 thread)\n";
    }
  }
  return kOk;
}

}  // namespace

Command add_bench(CLI::App& app) {
  auto o = std::make_shared<BenchOptions>();
  app.add_option("--scenes-dir", o->scenes_dir, "Directory of the bundled scenes")->capture_default_str();
  app.add_option("--min-time", o->min_time_s, "Seconds to measure each case")
      ->check(CLI::Range(0.1, 600.0))
      ->capture_default_str();
  app.add_option("--res", o->resolution, "scanner3d resolution N (N x N beams)")
      ->check(CLI::Range(1, 2048))
      ->capture_default_str();
  app.add_flag("--json", o->json, "One JSON object per line instead of a table");
  app.footer(
      "Measures LIDAR rays per second on one core: scanner3d scans from the first vehicle of\n"
      "trees_rolling_terrain and vineyard. Figures go in docs/PERFORMANCE.md.");
  return [o] { return run_bench(*o); };
}

}  // namespace campo::cli
