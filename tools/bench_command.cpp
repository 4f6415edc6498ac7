#include <sched.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>
#include <valgrind/callgrind.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <numbers>
#include <sstream>
#include <thread>
#include <vector>

#include "campo/episode.hpp"
#include "campo/json_reader.hpp"
#include "campo/planner_registry.hpp"
#include "campo/scene_loader.hpp"
#include "campo/sensor_factory.hpp"
#include "campo/vehicle_factory.hpp"
#include "campo/version.hpp"
#include "core/output_dir.hpp"
#include "planners/depth_reactive.hpp"
#include "planners/octomap3d.hpp"
#include "run/provenance.hpp"
#include "sensors/lidar.hpp"
#include "sensors/raycaster.hpp"
#include "tools/bench_workloads.hpp"
#include "tools/bundled.hpp"
#include "tools/commands.hpp"
#include "tools/path_options.hpp"

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
  bool instructions = false;  ///< count instructions per ray and per physics step under callgrind instead of timing
  std::string work_file;      ///< (inside callgrind) where the counted cases' amounts of work go
  std::string table_file;     ///< print the peers table of this earlier --json record, measure nothing
  int pinned_core = -1;       ///< `peers`: the core the programs ran on
  std::vector<std::string> peers{"quadrotor", "lidar", "astar", "dubins", "rrt_star"};  ///< `peers`: which programs
};

// Under --instructions each case does a fixed amount of work, counted by callgrind between a
// reset and a dump of its counters named after the figure.
constexpr int kCountedScans = 2;
constexpr double kCountedEpisodeS = 2.0;
bool under_callgrind() { return RUNNING_ON_VALGRIND != 0; }

// Runs `work` counted by callgrind as the dump `id` when under it; otherwise just runs it.
template <class Work>
void counted(const std::string& id, Work work) {
  CALLGRIND_ZERO_STATS;
  work();
  CALLGRIND_DUMP_STATS_AT(id.c_str());
}

/// One measured figure; `id` names it across runs of campo bench (what --compare matches).
struct Figure {
  std::string id;
  double value = 0.0;
  std::string unit;  ///< higher is better, except for instruction counts ("instructions/...")
  nlohmann::json details;
};

bool lower_is_better(const std::string& unit) { return unit.rfind("instructions/", 0) == 0; }

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
  c << "campo bench " << o.what;
  if (o.what == "peers") {
    c << " --peers ";
    for (std::size_t i = 0; i < o.peers.size(); ++i) c << (i ? "," : "") << o.peers[i];
  } else if (o.instructions) {
    c << " --instructions --res " << o.resolution;
  } else {
    c << " --min-time " << o.min_time_s << " --res " << o.resolution << " --episode-time " << o.episode_time_s;
  }
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
  nlohmann::json provenance{{"campo_version", std::string(library_version())},
                             {"git_revision", std::string(library_git_revision())},
                             {"date", utc_now()},
                             {"command", command_line(o)},
                             {"machine", machine()}};
  if (o.pinned_core >= 0) provenance["pinning"] = "each program pinned to core " + std::to_string(o.pinned_core) + ".";
  return {{"campo_bench", 1}, {"provenance", provenance}, {"figures", list}};
}

// The baseline's figures by id; InputError naming the file and the pointer for anything else.
std::map<std::string, Figure> read_baseline(const std::string& file) {
  const nlohmann::json document = parse_json_text(read_text_file(file), file);
  ObjectReader r(JsonNode(document, file, ""));
  r.required("campo_bench").as_int(1, 1);
  r.required("provenance");
  std::map<std::string, Figure> figures;
  for (const JsonNode& figure : r.required("figures").as_array(0, 100000)) {
    ObjectReader f(figure);  // its other keys describe the figure
    Figure read;
    read.id = f.required("id").as_string();
    read.value = f.required("value").as_number(Range::positive());
    f.read("unit", read.unit);
    figures[read.id] = read;
  }
  return figures;
}

// Prints each figure against its baseline; returns how many are more than the tolerance slower.
int compare(const BenchOptions& o, const std::vector<Figure>& figures) {
  const std::map<std::string, Figure> baseline = read_baseline(o.baseline_file);
  int regressed = 0;
  std::cout << "\ncompared with " << o.baseline_file << " (more than " << o.tolerance * 100
            << "% slower is a regression):\n";
  for (const Figure& f : figures) {
    const auto it = baseline.find(f.id);
    if (it == baseline.end()) {
      std::cout << "  " << std::left << std::setw(40) << f.id << " new: not in the baseline\n";
      continue;
    }
    if (it->second.unit != f.unit) {
      std::cout << "  " << std::left << std::setw(40) << f.id << " not comparable: " << f.unit << " against the baseline's "
                << it->second.unit << "\n";
      continue;
    }
    // Speed relative to the baseline: fewer instructions, or more of a rate, is faster.
    const double ratio = lower_is_better(f.unit) ? it->second.value / f.value : f.value / it->second.value;
    const bool slower = ratio < 1.0 - o.tolerance;
    regressed += slower;
    std::cout << "  " << std::left << std::setw(40) << f.id << std::right << std::fixed << std::setprecision(3)
              << std::setw(8) << ratio << "x the baseline's speed" << (slower ? "  SLOWER" : "") << "\n";
  }
  return regressed;
}

// scanner3d scans from the scene's first vehicle, turned 0.05 rad more each scan.
class LidarCase {
 public:
  LidarCase(const Scene& scene, int resolution) : config_(scanner3d(resolution)), caster_(scene), lidar_(config_, scene.world.seed) {
    pose_ = scene.vehicles.front().pose * to_isometry(config_.mount);
  }
  // Scan number i; the rays cast.
  long scan(int i) {
    Eigen::Isometry3d turned = pose_;
    turned.linear() = Eigen::AngleAxisd(0.05 * i, Eigen::Vector3d::UnitZ()) * pose_.linear();
    lidar_.scan(caster_, turned, 0.0, scan_);
    return static_cast<long>(scan_.ranges_m.size());
  }

 private:
  static RangeSensorConfig scanner3d(int resolution) {
    RangeSensorConfig config = *sensor_preset("scanner3d");
    config.cols = config.rows = resolution;
    return config;
  }
  RangeSensorConfig config_;
  RayCaster caster_;
  Lidar lidar_;
  Eigen::Isometry3d pose_;
  RangeScan scan_;
};

// Rays per second of one thread until min_time_s has passed.
double lidar_rays_per_second(const Scene& scene, int resolution, double min_time_s) {
  LidarCase lidar(scene, resolution);
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  long rays = 0;
  double elapsed = 0.0;
  for (int i = 0; elapsed < min_time_s; ++i) {
    rays += lidar.scan(i);
    elapsed = std::chrono::duration<double>(Clock::now() - start).count();
  }
  return static_cast<double>(rays) / elapsed;
}

// Rays of kCountedScans scans (after one uncounted), counted by callgrind as `id`.
double lidar_counted_rays(const Scene& scene, int resolution, const std::string& id) {
  LidarCase lidar(scene, resolution);
  lidar.scan(0);
  long rays = 0;
  counted(id, [&] {
    for (int i = 1; i <= kCountedScans; ++i) rays += lidar.scan(i);
  });
  return static_cast<double>(rays);
}

void bench_lidar(const BenchOptions& o, std::vector<Figure>& figures) {
  for (const char* name : {"trees_rolling_terrain", "vineyard"}) {
    const Scene scene = load_scene(bundled_scene(name));
    const std::string id = "lidar_scanner3d/" + std::string(name) + "/" + std::to_string(o.resolution);
    if (o.instructions) {
      // The amount of work now; the parent divides callgrind's count by it.
      figures.push_back({id, lidar_counted_rays(scene, o.resolution, id), "instructions/ray",
                         {{"scene", name}, {"resolution", o.resolution}, {"scans", kCountedScans}}});
      continue;
    }
    const double rate = lidar_rays_per_second(scene, o.resolution, o.min_time_s);
    std::ostringstream line;
    line << "lidar scanner3d " << o.resolution << "x" << o.resolution << " in " << std::left << std::setw(22)
         << name << std::right << std::fixed << std::setprecision(2) << rate / 1e6 << " M rays/s (1 thread)";
    std::cout << line.str() << "\n";
    figures.push_back({id, rate, "rays/s", {{"scene", name}, {"resolution", o.resolution}, {"threads", 1}}});
  }
}

// Real-time factor of whole episodes with the straight planner (its default
// parameters): no sensor, then scanner3d at 64 x 64 and 256 x 256, 10 Hz.
// `guards`: only the episodes without a sensor.
void bench_episodes(const BenchOptions& o, std::vector<Figure>& figures) {
  const std::vector<int> resolutions = o.what == "guards" ? std::vector<int>{0} : std::vector<int>{0, 64, 256};
  for (const auto& [name, vehicle] : {std::pair{"trees_rolling_terrain", "quadrotor"}, std::pair{"vineyard", "rover"}}) {
    for (const int resolution : resolutions) {
      Scene scene = load_scene(bundled_scene(name));
      scene.world.time_limit_s = o.episode_time_s;
      VehicleDef& def = scene.vehicles.front();
      def.sensors.clear();
      if (resolution > 0) {
        SensorDef sensor{"scanner", *sensor_preset("scanner3d")};
        sensor.range.cols = sensor.range.rows = resolution;
        sensor.range.rate_hz = 10.0;
        def.sensors.push_back(sensor);
      }
      // The scene's planner parameters (the vineyard's rover_route) are not straight's.
      choose_planner(def.planner, "straight", "campo bench");
      EpisodeOptions options;
      options.stop_on_collision = false;
      options.make_sensor = range_sensor_factory();
      const std::string id = "episode/" + std::string(name) + "/" + std::to_string(resolution);
      if (o.instructions) {
        // Built uncounted; then kCountedEpisodeS simulated seconds of the loop, planner included.
        Episode episode(scene, &make_vehicle, options);
        const std::unique_ptr<Planner> planner = create_planner(def.planner, {def.type, &scene, &def});
        counted(id, [&] {
          while (!episode.done() && episode.observation().time_s < kCountedEpisodeS) {
            episode.step(planner->plan(episode.observation()));
          }
        });
        const double steps = episode.observation().time_s / scene.world.physics_step_s;
        figures.push_back({id, steps, "instructions/physics step",
                           {{"scene", name}, {"vehicle", vehicle}, {"sensor_resolution", resolution},
                            {"sim_time_s", episode.observation().time_s}}});
        continue;
      }
      const EpisodeResult r = run_episode(scene, &make_vehicle, &create_planner, options);
      const double steps = r.only().metrics.sim_time_s / scene.world.physics_step_s;
      const double rtf = r.only().metrics.sim_time_s / r.only().metrics.wall_time_s;
      const std::string sensors = resolution > 0 ? "scanner3d " + std::to_string(resolution) + "x" +
                                                       std::to_string(resolution) + " @10Hz"
                                                 : "no sensor";
      std::ostringstream line;
      line << "episode " << std::left << std::setw(9) << vehicle << " " << std::setw(22) << name << std::setw(24)
           << sensors << std::right << std::fixed << std::setprecision(0) << std::setw(9) << steps / r.only().metrics.wall_time_s
           << " steps/s  " << std::setprecision(1) << std::setw(7) << rtf << "x real time";
      std::cout << line.str() << "\n";
      figures.push_back({id, steps / r.only().metrics.wall_time_s, "physics steps/s",
                         {{"scene", name}, {"vehicle", vehicle}, {"sensor_resolution", resolution},
                          {"sim_time_s", r.only().metrics.sim_time_s}, {"wall_time_s", r.only().metrics.wall_time_s},
                          {"real_time_factor", rtf}}});
    }
  }
}

// Where a fleet flies: an empty flat field, the drones 5 m apart at 2 m on
// lanes along x (a lone drone costs little there, so what several add shows
// undiluted); or seed 003's vineyard without its rover, the drones over its
// inter-rows (4 m apart) at 2.5 m, 0.7 m above the canopy, along the rows.
struct FleetField {
  const char* name;
  double spacing_m;                  ///< between lanes
  double height_m;
  Eigen::Vector2d start_m, along;    ///< the first lane's start; the lanes' direction
};
const std::array<FleetField, 2> kFleetFields{{{"field", 5.0, 2.0, {0.0, 0.0}, {1.0, 0.0}},
                                             {"vineyard", 4.0, 2.5, {0.0, -46.0}, {0.0, 1.0}}}};

// `count` quadrotors in one world, each with a scanner3d of 64 x 64 at 10 Hz
// and the straight planner, flying parallel lanes 1 km long (they do not end
// within the episode): what several vehicles cost against one.
Scene fleet_scene(const FleetField& field, int count, double time_limit_s) {
  nlohmann::json document = {{"objects", {{{"alias", "ground"}, {"type", "plane"}}}}};
  if (std::string(field.name) == "vineyard") {
    document = nlohmann::json::parse(std::ifstream(bundled_scene("vineyard")));
    nlohmann::json kept = nlohmann::json::array();
    for (const auto& object : document.at("objects")) {
      if (object.value("type", "") != "rover") kept.push_back(object);
    }
    document["objects"] = kept;
  }
  const Eigen::Vector2d across(field.along.y(), -field.along.x());
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector2d start = field.start_m + field.spacing_m * i * (field.along.x() != 0.0 ? -across : across);
    const Eigen::Vector2d goal = start + 1000.0 * field.along;
    document["objects"].push_back(
        {{"alias", "drone" + std::to_string(i)},
         {"type", "quadrotor"},
         {"pose", {{"position_m", {start.x(), start.y(), field.height_m}}}},
         {"sensors", {{{"alias", "scanner"}, {"type", "lidar"}, {"preset", "scanner3d"}, {"resolution", {64, 64}},
                       {"rate_hz", 10}}}},
         {"planner", {{"name", "straight"}}},
         {"mission", {{"waypoints", {{{"position_m", {goal.x(), goal.y(), field.height_m}}}}}}}});
  }
  document["name"] = std::string(field.name) + "_fleet_" + std::to_string(count);
  document["world"]["time_limit_s"] = time_limit_s;
  return parse_scene(document, "campo bench", std::filesystem::current_path());
}

// Physics steps per second of a whole world of 1, 2, 4 and 8 vehicles, and
// what each vehicle costs against a world of one (per vehicle-step).
void bench_fleet(const BenchOptions& o, std::vector<Figure>& figures) {
  for (const FleetField& field : kFleetFields) {
    double one_vehicle_step_s = 0.0;
    for (const int count : {1, 2, 4, 8}) {
      const Scene scene = fleet_scene(field, count, o.instructions ? kCountedEpisodeS : o.episode_time_s);
      EpisodeOptions options;
      options.stop_on_collision = false;
      options.make_sensor = range_sensor_factory();
      const std::string id = "episode/fleet/" + std::string(field.name) + "/" + std::to_string(count);
      if (o.instructions) {
        // Built uncounted; then the loop to its time limit, planners included.
        Episode episode(scene, &make_vehicle, options);
        std::vector<std::unique_ptr<Planner>> planners;
        for (const VehicleDef& def : scene.vehicles) planners.push_back(create_planner(def.planner, {def.type, &scene, &def}));
        counted(id, [&] {
          while (!episode.done()) {
            std::vector<PlanResult> plans;
            for (std::size_t v = 0; v < planners.size(); ++v) plans.push_back(planners[v]->plan(episode.observation(v)));
            episode.step(std::move(plans));
          }
        });
        const double steps = kCountedEpisodeS / scene.world.physics_step_s;
        figures.push_back({id, steps * count, "instructions/vehicle-step",
                           {{"field", field.name}, {"vehicles", count}, {"sim_time_s", kCountedEpisodeS}}});
        continue;
      }
      const EpisodeResult r = run_episode(scene, &make_vehicle, &create_planner, options);
      const double steps = r.fleet.sim_time_s / scene.world.physics_step_s;
      const double vehicle_step_s = r.fleet.wall_time_s / (steps * count);
      if (count == 1) one_vehicle_step_s = vehicle_step_s;
      const double ratio = vehicle_step_s / one_vehicle_step_s;
      std::ostringstream line;
      line << "episode fleet of " << count << " quadrotors over the " << std::left << std::setw(9) << field.name
           << std::right << std::fixed << std::setprecision(0) << std::setw(9) << steps / r.fleet.wall_time_s
           << " steps/s  " << std::setprecision(2) << ratio << "x one vehicle's cost per vehicle";
      std::cout << line.str() << "\n";
      figures.push_back({id, steps / r.fleet.wall_time_s, "physics steps/s",
                         {{"field", field.name}, {"vehicles", count}, {"sim_time_s", r.fleet.sim_time_s},
                          {"wall_time_s", r.fleet.wall_time_s}, {"cost_per_vehicle_vs_one", ratio}}});
    }
  }
}

// The median of `samples` (seconds), copied.
double median_s(std::vector<double> samples) {
  std::nth_element(samples.begin(), samples.begin() + static_cast<long>(samples.size() / 2), samples.end());
  return samples[samples.size() / 2];
}

// Times `work` (one unit each call) until min_time_s has passed, at least 5 times; the median, in seconds.
template <class Work>
double median_time_s(double min_time_s, Work work) {
  using Clock = std::chrono::steady_clock;
  std::vector<double> samples;
  const auto start = Clock::now();
  while (samples.size() < 5 || std::chrono::duration<double>(Clock::now() - start).count() < min_time_s) {
    const auto t0 = Clock::now();
    work();
    samples.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
  }
  return median_s(std::move(samples));
}

// depth_reactive's first replanning of a seed 000 scene, as the planner replans: the depth map
// of the scene's scanner at 256 x 256 from the drone's start, DilataMappa, ControllaVisibilita
// and TrovaWP with the planner's default parameters (BM_Replan's workload).
class ReplanCase {
 public:
  explicit ReplanCase(const std::string& name)
      : view_(start_view(load_scene(bundled_scene(name)), kResolution)),
        params_(dilation_params(config_, view_.grid)),
        target_sensor_(view_.scan.sensor_pose.inverse() * view_.target_m) {}
  void replan() const { candidates_seen_ += replan_step(view_, params_, target_sensor_, config_).candidates; }
  static constexpr int kResolution = 256;

 private:
  DepthReactiveConfig config_;
  StartView view_;
  DilationParams params_;
  Eigen::Vector3d target_sensor_;
  mutable long candidates_seen_ = 0;  // used, so the search is not optimised away
};

// OctoMap mapping as dstar_lite_3d maps with "mapping": "octomap": a 64 x 8 scanner (90 x 30 deg,
// 20 m) flown up and then north under the bridge of scenes/bridge.json (0.1 m per scan), its
// scans cast beforehand, inserted into a fresh map one after the other (the first scans of
// BM_OctoMapInsertScan's flight).
class OctoMapCase {
 public:
  OctoMapCase() : flight_(bridge_flight(load_scene(bundled_scene("bridge")), mapping_scanner_64x8(), kNorthScans)) {}
  // Maps the whole flight into a fresh map; the scans inserted.
  int map_flight() const {
    GridMap3dConfig grid;
    grid.ground_z_m = 0.3;
    OctoMap3d map(grid, OctoMap3dConfig{});
    for (const MappedScan& s : flight_) map.insert_scan(s.origin_m, s.ends_m, s.returns);
    return scans();
  }
  int scans() const { return static_cast<int>(flight_.size()); }

 private:
  static constexpr int kNorthScans = 99;  // and 41 up: 140 scans
  std::vector<MappedScan> flight_;
};

// depth_reactive's replanning at 256 x 256 on both seed 000 scenes, and OctoMap's mapping of a
// 64 x 8 scan: per replan and per scan, timed (median) or counted.
void bench_planners(const BenchOptions& o, std::vector<Figure>& figures) {
  for (const char* name : {"two_barriers", "trees_rolling_terrain"}) {
    const ReplanCase replan(name);
    const std::string id = "replan/depth_reactive/" + std::string(name) + "/" + std::to_string(ReplanCase::kResolution);
    const nlohmann::json details{{"scene", name}, {"resolution", ReplanCase::kResolution}};
    if (o.instructions) {
      replan.replan();  // uncounted: first-touch allocations
      constexpr int kReplans = 3;
      counted(id, [&] {
        for (int i = 0; i < kReplans; ++i) replan.replan();
      });
      figures.push_back({id, kReplans, "instructions/replan", details});
      continue;
    }
    const double median = median_time_s(o.min_time_s, [&] { replan.replan(); });
    std::cout << "replan depth_reactive 256x256 in " << std::left << std::setw(22) << name << std::right << std::fixed
              << std::setprecision(3) << median * 1e3 << " ms (median, 1 thread)\n";
    figures.push_back({id, 1.0 / median, "replans/s", details});
  }
  const OctoMapCase octomap;
  const std::string id = "mapping/octomap/bridge/64x8";
  const nlohmann::json details{{"scene", "bridge"}, {"scanner", "64 x 8, 90 x 30 deg, 20 m"}, {"scans", octomap.scans()}};
  if (o.instructions) {
    int scans = 0;
    counted(id, [&] { scans = octomap.map_flight(); });
    figures.push_back({id, static_cast<double>(scans), "instructions/scan", details});
    return;
  }
  const double median = median_time_s(o.min_time_s, [&] { octomap.map_flight(); }) / octomap.scans();
  std::cout << "mapping octomap 64x8 scans under the bridge " << std::fixed << std::setprecision(3) << median * 1e3
            << " ms per scan (median flight, 1 thread)\n";
  figures.push_back({id, 1.0 / median, "scans/s", details});
}

// A rate for the peers table: "20.64 M rays/s", "1076976 steps/s", "92.7 problems/s".
std::string rate_text(double value, const std::string& unit) {
  char text[64];
  if (value >= 1e7) {
    std::snprintf(text, sizeof text, "%.2f M %s", value / 1e6, unit.c_str());
  } else if (value >= 1000.0) {
    std::snprintf(text, sizeof text, "%.0f %s", value, unit.c_str());
  } else {
    std::snprintf(text, sizeof text, "%.1f %s", value, unit.c_str());
  }
  return text;
}

// docs/PERFORMANCE.md's peers table from a record's peer figures (those with a "peer" rate).
std::string peers_table(const nlohmann::json& record) {
  const nlohmann::json& p = record.at("provenance");
  const nlohmann::json& m = p.at("machine");
  std::ostringstream out;
  out << "Machine: " << m.value("cpu", "unknown") << ", " << m.value("cores", 0) << " cores, " << std::fixed
      << std::setprecision(0) << m.value("memory_gib", 0.0) << " GiB; " << p.value("date", "").substr(0, 10) << "; git "
      << p.value("git_revision", "unknown").substr(0, 12) << "; " << p.value("pinning", "") << "\n\n"
      << "| comparison | campo | peer | campo / peer | checked |\n| --- | ---: | ---: | ---: | --- |\n";
  for (const auto& f : record.at("figures")) {
    if (!f.contains("peer")) continue;
    const std::string unit = f.at("unit");
    char ratio[32];
    std::snprintf(ratio, sizeof ratio, "%.2fx", f.at("value").get<double>() / f.at("peer").get<double>());
    out << "| " << f.value("comparison", f.at("id").get<std::string>()) << " | "
        << rate_text(f.at("value").get<double>(), unit) << " | " << f.value("peer_name", "") << ": "
        << rate_text(f.at("peer").get<double>(), unit) << " | " << ratio << " | " << f.value("note", "") << " |\n";
  }
  return out.str();
}

// `campo bench peers`: every peer program built beside this campo (bench/peers), pinned to the
// last core, its comparisons (JSON lines) as figures: campo's rate, with the peer's beside it.
std::vector<Figure> run_peers(const std::vector<std::string>& which, int& pinned_core) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::read_symlink("/proc/self/exe").parent_path();
  cpu_set_t previous;
  CPU_ZERO(&previous);
  sched_getaffinity(0, sizeof previous, &previous);
  pinned_core = static_cast<int>(std::thread::hardware_concurrency()) - 1;
  cpu_set_t one;
  CPU_ZERO(&one);
  CPU_SET(pinned_core, &one);
  sched_setaffinity(0, sizeof one, &one);  // the programs inherit it
  std::vector<Figure> figures;
  for (const std::string& name : which) {
    const std::string program = "campo_peer_" + name;
    const fs::path path = dir / program;
    if (!fs::exists(path)) {
      std::cout << program << ": not built (its peer is not installed: CAMPO_PEERS=1 tools/setup.sh)\n";
      continue;
    }
    std::cout << program << "...\n" << std::flush;
    FILE* pipe = ::popen(("'" + path.string() + "' --json").c_str(), "r");
    if (!pipe) throw std::runtime_error("cannot run " + path.string());
    std::string output;
    char buffer[4096];
    for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) output.append(buffer, n);
    if (::pclose(pipe) != 0) {
      sched_setaffinity(0, sizeof previous, &previous);
      throw std::runtime_error(path.string() + " failed");
    }
    std::istringstream lines(output);
    for (std::string line; std::getline(lines, line);) {
      if (line.empty()) continue;
      const nlohmann::json c = nlohmann::json::parse(line);
      Figure f{"peers/" + c.at("id").get<std::string>(), c.at("campo"), c.at("unit"), nlohmann::json::object()};
      for (const char* key : {"comparison", "peer", "peer_name", "note"}) f.details[key] = c.at(key);
      f.details["program"] = program;
      figures.push_back(std::move(f));
    }
  }
  sched_setaffinity(0, sizeof previous, &previous);
  return figures;
}

// The totals of the counter dumps callgrind wrote in `dir`, by the name campo gave each dump.
std::map<std::string, double> callgrind_totals(const std::filesystem::path& dir) {
  std::map<std::string, double> totals;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    std::ifstream in(entry.path());
    std::string id;
    for (std::string line; std::getline(in, line);) {
      const std::string trigger = "desc: Trigger: Client Request: ";
      if (line.rfind(trigger, 0) == 0) id = line.substr(trigger.size());
      if (line.rfind("totals: ", 0) == 0 && !id.empty()) totals[id] = std::stod(line.substr(8));
    }
  }
  return totals;
}

// --instructions: campo bench runs itself under callgrind, each case a fixed amount of work
// counted on its own; a figure is the instructions it took per ray or per physics step. The
// same binary and input give the same count to within 0.1% (Embree's and the allocator's
// bookkeeping vary a little), so a change is the code's, not the machine's load.
std::vector<Figure> count_instructions(const BenchOptions& o) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("campo_bench_callgrind_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string work = (dir / "work.json").string();
  std::vector<std::string> args{"valgrind", "--tool=callgrind", "--quiet",
                                "--callgrind-out-file=" + (dir / "callgrind.%p").string(),
                                fs::read_symlink("/proc/self/exe").string(), "bench", o.what, "--instructions",
                                "--res", std::to_string(o.resolution), "--work-file", work};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = -1;
  std::cout << "counting instructions under callgrind (about a minute)...\n" << std::flush;
  if (::posix_spawnp(&pid, "valgrind", nullptr, nullptr, argv.data(), environ) != 0) {
    fs::remove_all(dir);
    throw std::runtime_error("campo bench --instructions runs campo under valgrind: install the Debian package valgrind");
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || !fs::exists(work)) {
    fs::remove_all(dir);
    throw std::runtime_error("campo bench under callgrind failed");
  }
  const nlohmann::json counted_work = nlohmann::json::parse(read_text_file(work));
  const std::map<std::string, double> totals = callgrind_totals(dir);
  fs::remove_all(dir);
  std::vector<Figure> figures;
  for (const auto& f : counted_work) {
    const std::string id = f.at("id");
    const auto total = totals.find(id);
    if (total == totals.end()) throw std::runtime_error("callgrind wrote no count for " + id);
    Figure figure{id, total->second / f.at("value").get<double>(), f.at("unit"), f.at("details")};
    figure.details["instructions"] = total->second;
    figure.details["work"] = f.at("value");
    std::cout << std::left << std::setw(40) << id << std::right << std::fixed << std::setprecision(1) << std::setw(12)
              << figure.value << " " << figure.unit << "\n";
    figures.push_back(std::move(figure));
  }
  return figures;
}

}  // namespace

Command add_bench(CLI::App& app) {
  auto o = std::make_shared<BenchOptions>();
  app.add_option("what", o->what,
                 "What to measure: lidar, episodes, planners, all (the three), guards (the figures the test "
                 "suite guards), or peers (the bench/peers programs side by side)")
      ->check(CLI::IsMember({"lidar", "episodes", "planners", "all", "guards", "peers"}))
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
                 "(the form --compare reads)")
      ->check(input_path());  // an empty path is refused, not taken for "no record"
  app.add_option("--compare", o->baseline_file,
                 "Compare every figure with the same figure of an earlier --json file; exit 3 when one is more "
                 "than --tolerance slower")
      ->check(existing_file());
  app.add_option("--tolerance", o->tolerance, "Fraction slower than the baseline that counts as a regression")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  app.add_flag("--instructions", o->instructions,
               "Count instructions (per ray, per physics step) under callgrind instead of timing: "
               "exact and independent of the machine's load, for regression checks on a noisy machine");
  app.add_option("--peers", o->peers, "With peers: the programs to run (default: all)")
      ->delimiter(',')
      ->check(CLI::IsMember({"quadrotor", "lidar", "astar", "dubins", "rrt_star"}));
  app.add_option("--table", o->table_file,
                 "Print docs/PERFORMANCE.md's peers table from an earlier `campo bench peers --json` record "
                 "(measures nothing)")
      ->check(existing_file());
  app.add_option("--work-file", o->work_file, "(internal: campo bench --instructions under callgrind)")
      ->group("");
  app.footer(
      "lidar: rays per second on one core, scanner3d scans from the vehicle of\n"
      "trees_rolling_terrain and vineyard. episodes: physics steps per second and real-time\n"
      "factor of whole closed-loop episodes (straight planner with its default parameters;\n"
      "quadrotor in trees_rolling_terrain, rover in vineyard) without sensors and with scanner3d\n"
      "64x64 and 256x256 at 10 Hz. planners: depth_reactive's replanning at 256x256 on the views\n"
      "at the start of two_barriers and trees_rolling_terrain (median time per replan), and OctoMap's\n"
      "mapping of 64x8 scans flown under the bridge (median time per scan). guards: the figures the\n"
      "test suite holds against bench/instruction_guards.json (run with --instructions): LIDAR at\n"
      "256x256, the episodes without a sensor, and planners. Single-threaded. Figures go in\n"
      "docs/PERFORMANCE.md.\n"
      "A quick check that every case runs: campo bench episodes --episode-time 1\n"
      "Regression check: campo bench --json base.json on one revision, then campo bench\n"
      "--compare base.json on another (same machine): exit 3 when a figure is slower. With\n"
      "--instructions both count instructions under callgrind (valgrind): 2 scans per LIDAR case and\n"
      "2 simulated seconds per episode case; counts of the same build agree to 0.1%.\n"
      "peers: runs every campo_peer_* program built beside campo (bench/peers; their peers with\n"
      "CAMPO_PEERS=1 tools/setup.sh) pinned to the last core, records campo's rate of each comparison\n"
      "with the peer's beside it, and prints docs/PERFORMANCE.md's peers table (--table FILE prints\n"
      "it again from the --json record).");
  return [o]() {
    // Read first: a bad baseline or an unwritable record is bad input before minutes of measuring.
    if (!o->baseline_file.empty()) read_baseline(o->baseline_file);
    if (!o->json_file.empty()) check_output_file(o->json_file, "--json");
    if (!o->table_file.empty()) {
      try {
        std::cout << peers_table(parse_json_text(read_text_file(o->table_file), o->table_file));
      } catch (const nlohmann::json::exception& e) {
        throw InputError(o->table_file, "", std::string("expected a campo bench peers record: ") + e.what());
      }
      return kOk;
    }
    std::vector<Figure> figures;
    if (o->what == "peers") {
      if (o->instructions) throw InputError("command line", "--instructions", "counts campo's own cases, not peers");
      figures = run_peers(o->peers, o->pinned_core);
      const nlohmann::json record = figures_json(*o, figures);
      std::cout << "\n" << peers_table(record);
    } else if (o->instructions && !under_callgrind()) {
      figures = count_instructions(*o);
    } else {
      if (o->instructions && o->work_file.empty()) {
        throw InputError("command line", "--instructions", "under valgrind, campo bench runs itself: drop valgrind");
      }
      const auto measures = [&](std::initializer_list<const char*> whats) {
        return std::any_of(whats.begin(), whats.end(), [&](const char* w) { return o->what == w; });
      };
      if (measures({"lidar", "all", "guards"})) bench_lidar(*o, figures);
      if (measures({"episodes", "all", "guards"})) bench_episodes(*o, figures);
      if (measures({"episodes", "all"})) bench_fleet(*o, figures);
      if (measures({"planners", "all", "guards"})) bench_planners(*o, figures);
      if (o->instructions) {  // inside callgrind: the amounts of work, for the parent
        nlohmann::json work = nlohmann::json::array();
        for (const Figure& f : figures) work.push_back({{"id", f.id}, {"value", f.value}, {"unit", f.unit}, {"details", f.details}});
        write_file_atomically(o->work_file, work.dump());
        return kOk;
      }
    }
    if (!o->json_file.empty()) write_file_atomically(o->json_file, figures_json(*o, figures).dump(2) + "\n");
    if (!o->baseline_file.empty() && compare(*o, figures) > 0) return kRegressed;
    return kOk;
  };
}

}  // namespace campo::cli
