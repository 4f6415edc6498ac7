#include <chrono>
#include <ctime>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>
#include <thread>
#include <vector>

#include "campo/episode.hpp"
#include "campo/json_reader.hpp"
#include "campo/scene_loader.hpp"
#include "campo/version.hpp"
#include "core/output_dir.hpp"
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
  std::string json_file;      ///< write the figures with their provenance here
  std::string baseline_file;  ///< compare with the figures of this earlier --json file
  double tolerance = 0.10;    ///< a figure this much slower than its baseline is a regression
};

/// One measured figure; `id` names it across runs of campo bench (what --compare matches).
struct Figure {
  std::string id;
  double value = 0.0;
  std::string unit;  ///< higher is better for every figure
  nlohmann::json details;
};

// The machine as /proc describes it: figures compare only on the same one.
nlohmann::json machine() {
  std::string cpu = "unknown";
  std::ifstream cpuinfo("/proc/cpuinfo");
  for (std::string line; std::getline(cpuinfo, line);) {
    if (line.rfind("model name", 0) == 0) {
      cpu = line.substr(line.find(':') + 2);
      break;
    }
  }
  double memory_kib = 0.0;
  std::ifstream meminfo("/proc/meminfo");
  for (std::string line; std::getline(meminfo, line);) {
    if (line.rfind("MemTotal:", 0) == 0) memory_kib = std::stod(line.substr(9));
  }
  return {{"cpu", cpu}, {"cores", std::thread::hardware_concurrency()}, {"memory_gib", memory_kib / 1048576.0}};
}

// The date a figure was measured (wall-clock time is right here: it is the record's date, not the simulation's).
std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return text;
}

std::string command_line(const BenchOptions& o) {
  std::ostringstream c;
  c << "campo bench " << o.what << " --min-time " << o.min_time_s << " --res " << o.resolution << " --episode-time "
    << o.episode_time_s;
  return c.str();
}

nlohmann::json figures_json(const BenchOptions& o, const std::vector<Figure>& figures) {
  nlohmann::json list = nlohmann::json::array();
  for (const Figure& f : figures) {
    nlohmann::json j = f.details;
    j["id"] = f.id;
    j["value"] = f.value;
    j["unit"] = f.unit;
    list.push_back(j);
  }
  return {{"campo_bench", 1},
          {"provenance",
           {{"campo_version", std::string(library_version())},
            {"git_revision", std::string(library_git_revision())},
            {"date", utc_now()},
            {"command", command_line(o)},
            {"machine", machine()}}},
          {"figures", list}};
}

// The baseline's figures by id; InputError naming the file and the pointer for anything else.
std::map<std::string, double> read_baseline(const std::string& file) {
  const nlohmann::json document = parse_json_text(read_text_file(file), file);
  ObjectReader r(JsonNode(document, file, ""));
  r.required("campo_bench").as_int(1, 1);
  r.required("provenance");
  std::map<std::string, double> values;
  for (const JsonNode& figure : r.required("figures").as_array(0, 100000)) {
    ObjectReader f(figure);  // its other keys describe the figure
    values[f.required("id").as_string()] = f.required("value").as_number(Range::positive());
  }
  return values;
}

// Prints each figure against its baseline; returns how many are more than the tolerance slower.
int compare(const BenchOptions& o, const std::vector<Figure>& figures) {
  const std::map<std::string, double> baseline = read_baseline(o.baseline_file);
  int regressed = 0;
  std::cout << "\ncompared with " << o.baseline_file << " (more than " << o.tolerance * 100
            << "% slower is a regression):\n";
  for (const Figure& f : figures) {
    const auto it = baseline.find(f.id);
    if (it == baseline.end()) {
      std::cout << "  " << std::left << std::setw(40) << f.id << " new: not in the baseline\n";
      continue;
    }
    const double ratio = f.value / it->second;
    const bool slower = ratio < 1.0 - o.tolerance;
    regressed += slower;
    std::cout << "  " << std::left << std::setw(40) << f.id << std::right << std::fixed << std::setprecision(3)
              << std::setw(8) << ratio << "x the baseline" << (slower ? "  SLOWER" : "") << "\n";
  }
  return regressed;
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

void bench_lidar(const BenchOptions& o, std::vector<Figure>& figures) {
  for (const char* name : {"trees_rolling_terrain", "vineyard"}) {
    const Scene scene = load_scene(bundled_scene(name));
    const double rate = lidar_rays_per_second(scene, o.resolution, o.min_time_s);
    std::ostringstream line;
    line << "lidar scanner3d " << o.resolution << "x" << o.resolution << " in " << std::left << std::setw(22)
         << name << std::right << std::fixed << std::setprecision(2) << rate / 1e6 << " M rays/s (1 thread)";
    std::cout << line.str() << "\n";
    figures.push_back({"lidar_scanner3d/" + std::string(name) + "/" + std::to_string(o.resolution), rate, "rays/s",
                       {{"scene", name}, {"resolution", o.resolution}, {"threads", 1}}});
  }
}

// Real-time factor of whole episodes with the straight planner (its default
// parameters): no sensor, then scanner3d at 64 x 64 and 256 x 256, 10 Hz.
void bench_episodes(const BenchOptions& o, std::vector<Figure>& figures) {
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
      std::cout << line.str() << "\n";
      figures.push_back({"episode/" + std::string(name) + "/" + std::to_string(resolution),
                         steps / r.metrics.wall_time_s, "physics steps/s",
                         {{"scene", name}, {"vehicle", vehicle}, {"sensor_resolution", resolution},
                          {"sim_time_s", r.metrics.sim_time_s}, {"wall_time_s", r.metrics.wall_time_s},
                          {"real_time_factor", rtf}}});
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
  app.add_option("--json", o->json_file,
                 "Also write every figure to this file, with the machine, command, date and git revision "
                 "(the form --compare reads)");
  app.add_option("--compare", o->baseline_file,
                 "Compare every figure with the same figure of an earlier --json file; exit 3 when one is more "
                 "than --tolerance slower")
      ->check(CLI::ExistingFile);
  app.add_option("--tolerance", o->tolerance, "Fraction slower than the baseline that counts as a regression")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  app.footer(
      "lidar: rays per second on one core, scanner3d scans from the vehicle of\n"
      "trees_rolling_terrain and vineyard. episodes: physics steps per second and real-time\n"
      "factor of whole closed-loop episodes (straight planner with its default parameters;\n"
      "quadrotor in trees_rolling_terrain, rover in vineyard) without sensors and with scanner3d\n"
      "64x64 and 256x256 at 10 Hz. Single-threaded. Figures go in docs/PERFORMANCE.md.\n"
      "A quick check that every case runs: campo bench episodes --episode-time 1\n"
      "Regression check: campo bench --json base.json on one revision, then campo bench\n"
      "--compare base.json on another (same machine): exit 3 when a figure is slower.");
  return [o]() {
    // Read first: a bad baseline is bad input before minutes of measuring.
    if (!o->baseline_file.empty()) read_baseline(o->baseline_file);
    std::vector<Figure> figures;
    if (o->what != "episodes") bench_lidar(*o, figures);
    if (o->what != "lidar") bench_episodes(*o, figures);
    if (!o->json_file.empty()) write_file_atomically(o->json_file, figures_json(*o, figures).dump(2) + "\n");
    if (!o->baseline_file.empty() && compare(*o, figures) > 0) return kRegressed;
    return kOk;
  };
}

}  // namespace campo::cli
