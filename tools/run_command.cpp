#include <filesystem>
#include <iostream>
#include <string>
#include <vector>


#include "planners/registry.hpp"
#include "render/sensors.hpp"
#include "render/depth_image.hpp"
#include "render/run_files.hpp"
#include "sim/episode.hpp"
#include "sim/output_dir.hpp"
#include "sim/run_record.hpp"
#include "sim/scene_loader.hpp"
#include "sim/scene_overrides.hpp"
#include "tools/bundled.hpp"
#include "tools/commands.hpp"
#include "tools/figures.hpp"
#include "vehicles/vehicle.hpp"

namespace campo::cli {

namespace {

struct RunOptions {
  std::string scene = bundled_scene("two_barriers").string();
  std::string planner;
  std::vector<std::string> sets;
  std::uint64_t seed = 0;
  bool seed_set = false;
  std::string vehicle;
  std::string out = "out/run";
  bool continue_after_collision = false;
  bool figures = true;
  int record_depth_every = 0;
};

int run_run(const RunOptions& o) {
  // Overrides are applied to the document, then validated like the file itself.
  const std::string bytes = read_text_file(o.scene);
  nlohmann::json document = parse_json_text(bytes, o.scene);
  std::vector<std::string> overrides = o.sets;
  if (o.seed_set) overrides.push_back("/world/seed=" + std::to_string(o.seed));
  for (const auto& assignment : overrides) apply_override(document, assignment);
  Scene scene = parse_scene(document, o.scene, std::filesystem::path(o.scene).parent_path(), sha256_hex(bytes));

  EpisodeOptions options;
  options.stop_on_collision = !o.continue_after_collision;
  options.make_sensor = range_sensor_factory();
  if (scene.vehicles.empty()) throw InputError(o.scene, "/objects", "expected a scene with a vehicle to run");
  if (!o.vehicle.empty()) {
    const VehicleDef* v = scene.find_vehicle(o.vehicle);
    if (!v) throw InputError("command line", "--vehicle", "no vehicle \"" + o.vehicle + "\" in " + o.scene);
    options.vehicle_index = static_cast<std::size_t>(v - scene.vehicles.data());
  }
  VehicleDef& def = scene.vehicles[options.vehicle_index];
  if (!o.planner.empty()) {
    def.planner.name = o.planner;
    def.planner.name_pointer = "";
    def.planner.params.file = "command line";
  }
  if (def.planner.name.empty()) def.planner.name = std::string(kDefaultPlanner);
  if (def.mission.empty()) {
    throw InputError(o.scene, "/objects", "expected vehicle \"" + def.alias + "\" to have a mission");
  }
  // Validate every parameter before anything runs.
  validate_vehicle_params(def);
  create_planner(def.planner, {def.type, &scene});

  StagedOutput out(o.out);
  // Depth maps of every n-th scan, for `campo render --kind depth`.
  std::vector<int> scans_seen(def.sensors.size(), 0);
  if (o.record_depth_every > 0) {
    std::filesystem::create_directories(out.path("depth"));
    options.on_scan = [&](std::size_t i, const LidarScan& scan) {
      if (scans_seen[i]++ % o.record_depth_every != 0) return;
      char name[96];
      std::snprintf(name, sizeof name, "%s_%08.3f.png", def.sensors[i].alias.c_str(), scan.time_s);
      write_depth_png(depth_map(scan, def.sensors[i].lidar), out.path("depth") / name);
    };
  }
  const EpisodeResult result = run_episode(scene, &make_vehicle, &create_planner, options);
  const nlohmann::json record = run_json(scene, result, options, overrides);

  write_file_atomically(out.path("trajectory.csv"), trajectory_csv(result));
  write_file_atomically(out.path("run.json"), record.dump(2) + "\n");
  if (!document.contains("name")) document["name"] = scene.name;
  write_file_atomically(out.path("scene.json"), document.dump(2) + "\n");
  std::string written = "run.json, trajectory.csv, scene.json";
  if (o.figures) {
    // Drawn from the files just written, exactly as `campo render` would.
    const std::filesystem::path staged = out.path("");
    RecordedRun recorded = load_run_dir(staged);
    recorded.view.label = std::filesystem::path(o.out).filename().string();
    for (const std::string kind : {"map", "side"}) write_figure(recorded, kind, staged);
    written += ", map.png, side.png";
  }
  out.commit();
  const EpisodeMetrics& m = result.metrics;
  std::cout << scene.name << ": " << to_string(m.outcome) << " (" << m.reason << ") after " << m.sim_time_s
            << " s simulated, path " << m.path_length_m << " m (ratio " << m.path_ratio << "), "
            << m.wall_time_s << " s wall; wrote " << written << " to " << o.out << "\n";
  return kOk;
}

}  // namespace

Command add_run(CLI::App& app) {
  auto o = std::make_shared<RunOptions>();
  app.add_option("scene", o->scene, "Scene file (JSON); default: the bundled two_barriers");
  std::string planners;
  for (const auto& entry : planner_registry()) planners += (planners.empty() ? "" : ", ") + std::string(entry.name);
  app.add_option("--planner", o->planner, "Planner (" + planners + "); default: the scene's, else straight");
  app.add_option("--set", o->sets,
                 "Override a scene field: PATH=VALUE with PATH a JSON pointer; inside arrays of objects an "
                 "alias may stand for the index (e.g. --set /objects/drone/planner/params/speed_mps=1.0). "
                 "Repeatable; validated like the file");
  app.add_option("--seed", o->seed, "World seed (same as --set /world/seed=N)")
      ->each([o](const std::string&) { o->seed_set = true; });
  app.add_option("--vehicle", o->vehicle, "Vehicle to run (default: the first)");
  app.add_flag("--continue-after-collision", o->continue_after_collision,
               "Count collisions but keep going until the mission ends or times out");
  app.add_flag("!--no-figures", o->figures, "Do not draw map.png and side.png (for sweeps)");
  app.add_option("--record-depth", o->record_depth_every,
                 "Save the depth map of every N-th scan of each sensor under DIR/depth/ (0 = none)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--out", o->out, "Output directory (created if missing)")->capture_default_str();
  app.footer(
      "Runs one closed-loop episode: sense -> plan -> control -> actuate -> step, until the mission\n"
      "is complete (reached), the vehicle collides (collision), the time limit passes (timeout) or the\n"
      "planner gives up (aborted). Writes DIR/run.json (metrics, outcome, provenance, every effective\n"
      "parameter), DIR/trajectory.csv (one row per planner call), DIR/scene.json (the effective\n"
      "scene) and the figures DIR/map.png and DIR/side.png (redraw with campo render).\n"
      "Exit 0 when the run completed, whatever its outcome; 2 on bad input; 1 on internal failure.");
  return [o] { return run_run(*o); };
}

}  // namespace campo::cli
