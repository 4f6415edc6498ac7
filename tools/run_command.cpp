#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "campo/json_reader.hpp"
#include "campo/planner_registry.hpp"
#include "core/output_dir.hpp"
#include "render/run_figures.hpp"
#include "run/event_log.hpp"
#include "session/run_session.hpp"
#include "tools/bundled.hpp"
#include "tools/commands.hpp"
#include "tools/plugin_options.hpp"

namespace campo::cli {

namespace {

struct RunOptions {
  std::string scene = "two_barriers";  ///< a file, or a bundled scene's name (file_or_bundled)
  std::string planner;
  std::vector<std::string> sets;
  std::string seed;  ///< as given; checked by parse_seed
  bool seed_set = false;
  std::string vehicle;
  std::string out = "out/run";
  bool continue_after_collision = false;
  bool figures = true;
  FigureFormats figure_formats = kPngOnly;
  int record_depth_every = 0;
  int record_images_every = 0;
  bool record_replans = true;
  double time_limit_s = 0.0;  ///< 0: none
  std::vector<std::string> plugins;
  bool list_planners = false;
};

int run_run(const RunOptions& o) {
  load_plugins(o.plugins);
  if (o.list_planners) {
    print_planners(std::cout);
    return kOk;
  }
  check_output_directory(o.out, "--out");
  RunRequest request;
  request.scene = file_or_bundled(o.scene, &bundled_scene).string();
  for (const std::string& set : o.sets) request.overrides.push_back(parse_override(set));
  if (o.seed_set) request.seed = parse_seed(o.seed, "command line", "--seed");
  request.planner = o.planner;
  request.vehicle = o.vehicle;
  request.out = o.out;
  request.continue_after_collision = o.continue_after_collision;
  request.figures = o.figures;
  request.figure_formats = o.figure_formats;
  request.record_depth_every = o.record_depth_every;
  request.record_images_every = o.record_images_every;
  request.record_replans = o.record_replans;
  request.time_limit_s = o.time_limit_s;
  const ExecutedRun run = execute_run(request);
  const std::filesystem::path out = o.out;
  std::string figures;
  for (const FigureKind kind : {FigureKind::map, FigureKind::side, FigureKind::heightmap}) {
    for (const figure::FigureFormat format : o.figure_formats) {
      const std::string file = std::string(to_string(kind)) + "." + figure::extension(format);
      if (o.figures && std::filesystem::exists(out / file)) figures += ", " + file;
    }
  }
  // The run's files as run.json names them: one vehicle's events.jsonl and trajectory.csv, or each vehicle's.
  std::string files = std::string(kEventsFile) + ", trajectory.csv";
  if (std::filesystem::exists(out / "imu.csv")) files += ", imu.csv";  // a vehicle with IMUs
  if (const auto vehicles = run.record.find("vehicles"); vehicles != run.record.end()) {
    files.clear();
    for (const nlohmann::json& vehicle : *vehicles) {
      (files += files.empty() ? "" : ", ") += vehicle.at("event_log").at("file").get<std::string>();
      files += ", " + vehicle.at("trajectory_file").get<std::string>();
      const std::string imus = "imu_" + vehicle.at("alias").get<std::string>() + ".csv";
      if (std::filesystem::exists(out / imus)) files += ", " + imus;
    }
  }
  std::cout << run_summary_line(run.record) << "; wrote run.json, " << files << ", scene.json" << figures << " to "
            << o.out << "\n";
  if (!run.figure_failures.empty()) {
    // The run is kept: only the figures that failed are missing.
    const FigureFailureReport report = figure_failure_report(run.figure_failures, o.out);
    std::cerr << report.text;
    return report.bad_input ? kBadInput : kInternalError;
  }
  return kOk;
}

}  // namespace

Command add_run(CLI::App& app) {
  auto o = std::make_shared<RunOptions>();
  app.add_option("scene", o->scene,
                 "Scene file (JSON), or the name of a bundled scene (e.g. vineyard); default: the bundled "
                 "two_barriers")
      ->check(input_path());
  std::string planners;
  for (const auto& entry : planner_registry()) planners += (planners.empty() ? "" : ", ") + entry.name;
  app.add_option("--planner", o->planner,
                 "Planner (" + planners + ", a plugin's, or a Python class as python:package.module:ClassName, "
                 "found from the working directory and PYTHONPATH); default: the scene's, else straight. Another "
                 "planner than the scene's runs with its default parameters and the --set's of the vehicle's planner "
                 "parameters, checked by it");
  add_plugin_option(app, o->plugins);
  app.add_flag("--list-planners", o->list_planners,
               "Print every planner (with --plugin, the plugins' too): name, source (built-in or the plugin file) and "
               "description; run nothing");
  app.add_option("--set", o->sets,
                 "Override a scene field: PATH=VALUE with PATH a JSON pointer; inside arrays of objects an "
                 "alias may stand for the index (e.g. --set /objects/drone/planner/params/speed_mps=1.0). "
                 "Repeatable; validated like the file");
  app.add_option("--seed", o->seed, "World seed, an integer in [0, 2^64-1] (same as --set /world/seed=N)")
      ->each([o](const std::string&) { o->seed_set = true; });
  app.add_option("--vehicle", o->vehicle,
                 "In a scene of several vehicles, the one --planner applies to and whose sensors the figures' panel "
                 "shows, by alias (default: the first); every vehicle runs")
      ->type_name("ALIAS");
  app.add_flag("--continue-after-collision", o->continue_after_collision,
               "Count collisions but keep going until the mission ends or times out");
  app.add_flag("!--no-figures", o->figures, "Do not draw map.png and side.png (for sweeps)");
  add_figure_format_option(app, &o->figure_formats);
  app.add_option("--record-depth", o->record_depth_every,
                 "Save the depth map of every N-th scan of each sensor under DIR/depth/ (0 = none)")
      ->check(non_negative_number());
  app.add_option("--record-images", o->record_images_every,
                 "Save every N-th image of each colour camera (rgb_camera) as an RGB PNG under DIR/images/ "
                 "(0 = none)")
      ->check(non_negative_number());
  app.add_flag("!--no-replan-depth", o->record_replans,
               "Do not save the depth map of every replanning under DIR/replans/ (for sweeps)");
  app.add_option("--time-limit", o->time_limit_s,
                 "Wall-clock seconds the run may take (host time, not simulated): past them it ends as failed "
                 "with its files written, a Python planner's call in progress interrupted (default: no limit)")
      ->check(CLI::Validator(
          [](std::string& text) -> std::string {
            char* end = nullptr;
            const double s = std::strtod(text.c_str(), &end);
            if (end != text.c_str() && *end == '\0' && s > 0.0 && s <= 1e9) return "";
            return "expected a number of seconds in (0, 1e9], got \"" + text + "\"";
          },
          "SECONDS"));
  app.add_option("--out", o->out, "Output directory (created if missing)")->capture_default_str();
  app.footer(
      "Runs one closed-loop episode: sense -> plan -> control -> actuate -> step, until the mission\n"
      "is complete (reached), the vehicle collides (collision), the time limit passes (timeout) or the\n"
      "planner gives up (aborted). Writes DIR/run.json (metrics, outcome, provenance, every effective\n"
      "parameter), DIR/events.jsonl (the planner's decisions, one line each), DIR/trajectory.csv (one\n"
      "row per planner call), DIR/scene.json (the effective scene) and the figures DIR/map.png and\n"
      "DIR/side.png, plus DIR/heightmap.png for mapping planners (redraw with campo render).\n"
      "A scene of several vehicles runs them all in one world: run.json holds the run's metrics and\n"
      "each vehicle's, and each vehicle has its DIR/events_ALIAS.jsonl and DIR/trajectory_ALIAS.csv.\n"
      "Exit 0 when the run completed, whatever its outcome; 2 on bad input or an output that cannot be\n"
      "written (nothing is written); 1 on internal failure. A completed run whose figure fails keeps\n"
      "its files and exits 2 (or 1 for an internal failure) naming the figure.");
  return [o] { return run_run(*o); };
}

}  // namespace campo::cli
