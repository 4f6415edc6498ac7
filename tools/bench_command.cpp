#include <chrono>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "campo/episode.hpp"
#include "campo/scene_loader.hpp"
#include "planners/registry.hpp"
#include "run/provenance.hpp"
#include "sensors/lidar.hpp"
#include "sensors/sensor_factory.hpp"
#include "tools/bundled.hpp"
#include "tools/commands.hpp"
#include "vehicles/factory.hpp"

namespace campo::cli {

namespace {

struct BenchOptions {
  std::string what = "all";
  double min_time_s = 2.0;
  int resolution = 256;
  double episode_time_s = 30.0;
  bool json = false;
};

void report(const BenchOptions& o, const nlohmann::json& record, const std::string& line) {
  if (o.json) {
    nlohmann::json r = record;
    r["campo_version"] = campo_version_string();
    std::cout << r.dump() << "\n";
  } else {
    std::cout << line << "\n";
  }
}

// Rays per second of one thread casting scanner3d scans from the scene's first
// vehicle, turned a little each scan, until min_time_s has passed.
double lidar_rays_per_second(const Scene& scene, int resolution, double min_time_s) {
  LidarConfig config = *lidar_preset("scanner3d");
  config.cols = config.rows = resolution;
  const Eigen::Isometry3d pose = scene.vehicles.front().pose * to_isometry(config.mount);
  RayCaster caster(scene);
  Lidar lidar(config, scene.world.seed);
  LidarScan scan;
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  long rays = 0;
  double elapsed = 0.0;
  for (int i = 0; elapsed < min_time_s; ++i) {
    Eigen::Isometry3d turned = pose;
    turned.linear() = Eigen::AngleAxisd(0.05 * i, Eigen::Vector3d::UnitZ()) * pose.linear();
    lidar.scan(caster, turned, 0.0, scan);
    rays += static_cast<long>(scan.ranges_m.size());
    elapsed = std::chrono::duration<double>(Clock::now() - start).count();
  }
  return static_cast<double>(rays) / elapsed;
}

void bench_lidar(const BenchOptions& o) {
  for (const char* name : {"trees_rolling_terrain", "vineyard"}) {
    const Scene scene = load_scene(bundled_scene(name));
    const double rate = lidar_rays_per_second(scene, o.resolution, o.min_time_s);
    std::ostringstream line;
    line << "lidar scanner3d " << o.resolution << "x" << o.resolution << " in " << std::left << std::setw(22)
         << name << std::right << std::fixed << std::setprecision(2) << rate / 1e6 << " M rays/s (1 thread)";
    report(o, {{"benchmark", "lidar_scanner3d"}, {"scene", name}, {"resolution", o.resolution},
               {"threads", 1}, {"rays_per_second", rate}},
           line.str());
  }
}

// Real-time factor of whole episodes with the straight planner (its default
// parameters): no sensor, then scanner3d at 64 x 64 and 256 x 256, 10 Hz.
void bench_episodes(const BenchOptions& o) {
  for (const auto& [name, vehicle] : {std::pair{"trees_rolling_terrain", "quadrotor"}, std::pair{"vineyard", "rover"}}) {
    for (int resolution : {0, 64, 256}) {
      Scene scene = load_scene(bundled_scene(name));
      scene.world.time_limit_s = o.episode_time_s;
      VehicleDef& def = scene.vehicles.front();
      def.sensors.clear();
      if (resolution > 0) {
        SensorDef sensor{"scanner", SensorType::lidar, *lidar_preset("scanner3d")};
        sensor.lidar.cols = sensor.lidar.rows = resolution;
        sensor.lidar.rate_hz = 10.0;
        def.sensors.push_back(sensor);
      }
      // The scene's planner parameters (the vineyard's rover_route) are not straight's.
      choose_planner(def.planner, "straight", "campo bench");
      EpisodeOptions options;
      options.stop_on_collision = false;
      options.make_sensor = range_sensor_factory();
      const EpisodeResult r = run_episode(scene, &make_vehicle, &create_planner, options);
      const double steps = r.metrics.sim_time_s / scene.world.physics_step_s;
      const double rtf = r.metrics.sim_time_s / r.metrics.wall_time_s;
      const std::string sensors = resolution > 0 ? "scanner3d " + std::to_string(resolution) + "x" +
                                                       std::to_string(resolution) + " @10Hz"
                                                 : "no sensor";
      std::ostringstream line;
      line << "episode " << std::left << std::setw(9) << vehicle << " " << std::setw(22) << name << std::setw(24)
           << sensors << std::right << std::fixed << std::setprecision(0) << std::setw(9) << steps / r.metrics.wall_time_s
           << " steps/s  " << std::setprecision(1) << std::setw(7) << rtf << "x real time";
      report(o, {{"benchmark", "episode"}, {"scene", name}, {"vehicle", vehicle}, {"sensor_resolution", resolution},
                 {"sim_time_s", r.metrics.sim_time_s}, {"wall_time_s", r.metrics.wall_time_s},
                 {"steps_per_second", steps / r.metrics.wall_time_s}, {"real_time_factor", rtf}},
             line.str());
    }
  }
}

}  // namespace

Command add_bench(CLI::App& app) {
  auto o = std::make_shared<BenchOptions>();
  app.add_option("what", o->what, "What to measure: lidar, episodes or all")
      ->check(CLI::IsMember({"lidar", "episodes", "all"}))
      ->capture_default_str();
  app.add_option("--min-time", o->min_time_s, "Seconds to measure each LIDAR case")
      ->check(CLI::Range(0.1, 600.0))
      ->capture_default_str();
  app.add_option("--res", o->resolution, "scanner3d resolution N (N x N beams) for the LIDAR cases")
      ->check(CLI::Range(1, 2048))
      ->capture_default_str();
  app.add_option("--episode-time", o->episode_time_s, "Simulated seconds of each episode case")
      ->check(CLI::Range(1.0, 3600.0))
      ->capture_default_str();
  app.add_flag("--json", o->json, "One JSON object per line instead of a table");
  app.footer(
      "lidar: rays per second on one core, scanner3d scans from the vehicle of\n"
      "trees_rolling_terrain and vineyard. episodes: physics steps per second and real-time\n"
      "factor of whole closed-loop episodes (straight planner with its default parameters;\n"
      "quadrotor in trees_rolling_terrain, rover in vineyard) without sensors and with scanner3d\n"
      "64x64 and 256x256 at 10 Hz. Single-threaded. Figures go in docs/PERFORMANCE.md.\n"
      "A quick check that every case runs: campo bench episodes --episode-time 1");
  return [o] {
    if (o->what != "episodes") bench_lidar(*o);
    if (o->what != "lidar") bench_episodes(*o);
    return kOk;
  };
}

}  // namespace campo::cli
