#include "session/run_session.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <csignal>
#include <mutex>
#include <thread>
#include <functional>
#include <optional>
#include <cstdio>
#include <stdexcept>
#include <sstream>
#include <utility>

#include "campo/episode.hpp"
#include "campo/json_reader.hpp"
#include "campo/planner_registry.hpp"
#include "campo/pose.hpp"
#include "campo/run_record.hpp"
#include "campo/scene_loader.hpp"
#include "campo/sensor_factory.hpp"
#include "campo/vehicle_factory.hpp"
#include "core/output_dir.hpp"
#include "render/run_figures.hpp"
#include "render/run_files.hpp"
#include "run/event_log.hpp"
#include "scene/scene_overrides.hpp"
#include "sensors/depth_image.hpp"
#include "sensors/lidar.hpp"
#include "sensors/rgb_image_io.hpp"
#include "session/scene_checks.hpp"

#include <pthread.h>
#include <signal.h>
#include <sys/syscall.h>
#include <unistd.h>

namespace campo {

int planner_interrupt_signal() { return SIGRTMIN + 5; }

namespace {

constexpr double kMaxTimeLimitS = 1e9;  // about 32 years: longer is no limit, and would overflow the clock

// A run's wall-clock limit (RunRequest::time_limit_s): a planner wrapped by
// it refuses calls past the deadline, and a thread then sends the run's
// thread planner_interrupt_signal() while a planner call is in progress
// (every 0.1 s until the run ends), which interrupts a Python planner's call
// blocked or spinning there. Never between calls: a signal could interrupt
// a system call of campo's own.
class WallLimit {
 public:
  using Clock = std::chrono::steady_clock;

  WallLimit(double limit_s, const std::string& name)
      : deadline_(Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(limit_s))) {
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, "%g", limit_s);
    reason_ = std::string("exceeded the wall-clock limit of ") + seconds + " s for the whole run (" + name +
              ") and was stopped";
    // Only the main thread: there a signal reaches the Python planner's call (Python handles signals there only).
    if (::syscall(SYS_gettid) != ::getpid()) return;
    const int signal = planner_interrupt_signal();
    struct sigaction current {};
    if (::sigaction(signal, nullptr, &current) == 0 && current.sa_handler == SIG_DFL) {
      // Its default would end the process: ignored unless Python handles it.
      struct sigaction ignore {};
      ignore.sa_handler = [](int) {};
      ignore.sa_flags = SA_RESTART;
      ::sigemptyset(&ignore.sa_mask);
      ::sigaction(signal, &ignore, nullptr);
    }
    const pthread_t target = ::pthread_self();
    watcher_ = std::thread([this, target, signal] {
      std::unique_lock lock(mutex_);
      if (wake_.wait_until(lock, deadline_, [this] { return done_; })) return;
      while (!done_) {
        if (in_call) ::pthread_kill(target, signal);
        wake_.wait_for(lock, std::chrono::milliseconds(100), [this] { return done_; });
      }
    });
  }

  ~WallLimit() {
    {
      std::lock_guard lock(mutex_);
      done_ = true;
    }
    wake_.notify_all();
    if (watcher_.joinable()) watcher_.join();
  }

  bool passed() const { return Clock::now() >= deadline_; }
  const std::string& reason() const { return reason_; }
  bool tripped = false;  ///< the run ended because of it
  std::atomic<bool> in_call{false};  ///< a planner call is in progress

 private:
  Clock::time_point deadline_;
  std::string reason_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool done_ = false;
  std::thread watcher_;
};

// A planner held to the run's wall-clock limit.
class WallLimitedPlanner final : public Planner {
 public:
  WallLimitedPlanner(std::unique_ptr<Planner> planner, WallLimit& limit)
      : planner_(std::move(planner)), limit_(limit) {}

  PlanResult plan(const Observation& observation) override {
    if (!planner_ || limit_.passed()) stop();
    struct InCall {
      std::atomic<bool>& flag;
      explicit InCall(std::atomic<bool>& f) : flag(f) { flag = true; }
      ~InCall() { flag = false; }
    };
    try {
      const InCall in_call(limit_.in_call);
      return planner_->plan(observation);
    } catch (const InputError&) {
      throw;
    } catch (const std::exception&) {
      if (limit_.passed()) stop();  // interrupted by the limit's signal
      throw;
    }
  }

  nlohmann::json parameters() const override {
    return planner_ ? planner_->parameters() : nlohmann::json::object();
  }

 private:
  [[noreturn]] void stop() {
    limit_.tripped = true;
    throw std::runtime_error(limit_.reason());
  }

  std::unique_ptr<Planner> planner_;
  WallLimit& limit_;
};

// `--planner` for vehicle `def`, whose planner the overrides (at
// `pointers`, as apply_override resolved them) have already set up as the scene's.
// The effective document (scene.json) then names the planner that runs, with its parameters.
void choose_planner_with_overrides(VehicleDef& def, const RunRequest& request,
                                   const std::vector<SceneOverride>& overrides,
                                   const std::vector<std::string>& pointers, nlohmann::json& document) {
  const std::string& params = def.planner.params.pointer;  // "/objects/<i>/planner/params"
  const std::string planner = params.substr(0, params.rfind('/'));
  const bool another = def.planner.name != request.planner;
  for (std::size_t i = 0; i < pointers.size(); ++i) {
    const std::string& p = pointers[i];
    if (another && (p == planner || p == planner + "/name")) {
      throw InputError("command line", "--set " + overrides[i].text,
                       "chooses the planner of vehicle " + def.alias + " (\"" + def.planner.name + "\") while --planner " +
                           request.planner + " chooses another: give the planner one way");
    }
  }
  choose_planner(def.planner, request.planner, "command line");
  if (!another) return;  // the scene's planner: its parameters, overrides included, stand
  for (std::size_t i = 0; i < pointers.size(); ++i) {
    const std::string& p = pointers[i];
    if (p != params && !p.starts_with(params + "/")) continue;
    const nlohmann::json& value = overrides[i].value;
    if (p == params) {
      def.planner.params.values = value;
    } else {
      def.planner.params.values[nlohmann::json::json_pointer(p.substr(params.size()))] = value;
    }
  }
  // Checked by the planner as the scene's own would be, at the block's place.
  def.planner.params.file = "command line (--planner " + request.planner + " with --set)";
  document[nlohmann::json::json_pointer(planner)] = {{"name", request.planner}, {"params", def.planner.params.values}};
}

// The request's overrides, then its seed's: what is applied, in order, and recorded.
std::vector<SceneOverride> applied_overrides(const RunRequest& request) {
  std::vector<SceneOverride> overrides = request.overrides;
  if (request.seed) overrides.push_back(make_override("/world/seed", *request.seed));
  return overrides;
}

}  // namespace

namespace {

PreparedRun prepare_checked_run(const RunRequest& request, bool validate_planner, const std::string& bytes,
                                PreparedRun& run);

}  // namespace

PreparedRun prepare_run(const RunRequest& request, bool validate_planner) {
  const std::string scene_file = request.scene.string();
  // Overrides are applied to the document, then validated like the file itself.
  const std::string bytes = read_text_file(scene_file);
  PreparedRun run;
  run.document = parse_json_text(bytes, scene_file);
  try {
    return prepare_checked_run(request, validate_planner, bytes, run);
  } catch (const InputError& e) {
    // Each error of the scene with the objects' aliases and its place in the file (an override's
    // new key has none).
    const InputError located = with_locations(with_aliases(e, scene_file, run.document), scene_file, bytes);
    // A value an override set is not the one in the file: no place in it.
    std::vector<InputIssue> issues = located.issues();
    for (InputIssue& issue : issues) {
      for (const std::string& p : run.override_pointers) {
        if (issue.pointer == p || issue.pointer.starts_with(p + "/")) issue.line = issue.column = 0;
      }
    }
    throw InputError(std::move(issues), located.count());
  }
}

namespace {

PreparedRun prepare_checked_run(const RunRequest& request, bool validate_planner, const std::string& bytes,
                                PreparedRun& run) {
  const std::string scene_file = request.scene.string();
  const std::vector<SceneOverride> overrides = applied_overrides(request);
  for (const SceneOverride& assignment : overrides) {
    run.override_pointers.push_back(apply_override(run.document, assignment));
  }
  // A scene without a planner block gets one from overrides of its
  // parameters; with --planner, it is that planner's.
  if (!request.planner.empty()) {
    for (const std::string& p : run.override_pointers) {
      const std::size_t at = p.find("/planner/params");
      const std::size_t end = at + std::string_view("/planner").size();
      if (at == std::string::npos || (p.size() > end + 7 && p[end + 7] != '/')) continue;
      const nlohmann::json::json_pointer planner(p.substr(0, end));
      if (!run.document.contains(planner)) continue;
      nlohmann::json& block = run.document[planner];
      if (block.is_object() && !block.contains("name")) block["name"] = request.planner;
    }
  }
  // The parameter blocks are checked with the scene's other keys (one list of errors), but for the
  // planner of the vehicle that runs when another planner replaces it (--planner, a caller's own):
  // it is checked once chosen.
  SceneChecks checks = parameter_checks();
  if (!request.planner.empty() || !validate_planner) {
    checks.planner = [check = checks.planner, vehicle = request.vehicle, first = true](const VehicleDef& v) mutable {
      const bool is_first = std::exchange(first, false);
      if (vehicle.empty() ? is_first : v.alias == vehicle) return;
      check(v);
    };
  }
  run.scene = parse_scene(run.document, scene_file, request.scene.parent_path(), sha256_hex(bytes), {}, checks);
  Scene& scene = run.scene;

  EpisodeOptions& options = run.options;
  options.stop_on_collision = !request.continue_after_collision;
  options.make_sensor = range_sensor_factory();
  options.make_camera = rgb_camera_factory();
  check_runnable(scene);  // a vehicle at all, each with a mission
  if (!request.vehicle.empty()) {
    const VehicleDef* v = scene.find_vehicle(request.vehicle);
    if (!v) throw InputError("command line", "--vehicle", "no vehicle \"" + request.vehicle + "\" in " + scene_file);
    run.vehicle_index = static_cast<std::size_t>(v - scene.vehicles.data());
  }
  VehicleDef& def = scene.vehicles[run.vehicle_index];
  // Another planner than the scene's starts from its defaults, and takes the
  // overrides of the vehicle's planner parameters: they were given for the
  // planner that runs, and a --set recorded must be a --set applied.
  if (!request.planner.empty()) choose_planner_with_overrides(def, request, overrides, run.override_pointers, run.document);
  for (VehicleDef& vehicle : scene.vehicles) {
    if (vehicle.planner.name.empty()) vehicle.planner.name = std::string(kDefaultPlanner);
  }
  // Validate every parameter before anything runs.
  validate_vehicle_params(def);
  if (validate_planner) {
    const PlannerMaker make_planner = request.make_planner ? request.make_planner : PlannerMaker(&create_planner);
    make_planner(def.planner, {def.type, &scene, &def});
  }
  // The other vehicles' too, as `campo validate` checks them: a file is valid or not whichever vehicle runs.
  check_vehicles_and_planners(scene, run.vehicle_index);
  return std::move(run);
}

}  // namespace

SimulatedRun simulate_run(const RunRequest& request, const OutputProvider& output) {
  if (request.time_limit_s != 0.0 && !(request.time_limit_s > 0.0 && request.time_limit_s <= kMaxTimeLimitS)) {
    throw InputError("command line", request.time_limit_name,
                     "expected a wall-clock limit in seconds in (0, 1e9], got " + nlohmann::json(request.time_limit_s).dump());
  }
  PreparedRun prepared = prepare_run(request);
  SimulatedRun run;
  run.scene = std::move(prepared.scene);
  run.document = std::move(prepared.document);
  run.vehicle_index = prepared.vehicle_index;
  const Scene& scene = run.scene;
  EpisodeOptions& options = prepared.options;
  const VehicleDef& def = scene.vehicles[run.vehicle_index];

  if ((request.record_depth_every > 0 || request.record_images_every > 0 || request.record_replans) && !output) {
    throw std::logic_error("simulate_run: depth maps asked for without an output directory");
  }
  // Depth maps of every n-th scan of the chosen vehicle (--vehicle), for `campo render --kind depth`.
  std::vector<int> scans_seen(def.sensors.size(), 0);
  if (request.record_depth_every > 0) {
    create_output_directories(output().path("depth"));
    options.on_scan = [&](std::size_t vehicle, std::size_t i, const RangeScan& scan) {
      if (vehicle != run.vehicle_index || scans_seen[i]++ % request.record_depth_every != 0) return;
      write_depth_png(depth_map(scan, def.sensors[i].range),
                      output().path("depth") / recorded_file_name(def.sensors[i].alias, scan.time_s));
    };
  }
  // Every n-th image of each colour camera of the chosen vehicle, for videos' sensor panels.
  std::vector<int> images_seen(def.rgb_cameras.size(), 0);
  if (request.record_images_every > 0) {
    create_output_directories(output().path("images"));
    options.on_image = [&](std::size_t vehicle, std::size_t i, const RgbImage& image) {
      if (vehicle != run.vehicle_index || images_seen[i]++ % request.record_images_every != 0) return;
      write_rgb_png(image, output().path("images") / recorded_file_name(def.rgb_cameras[i].alias, image.time_s));
    };
  }
  // The depth map each replanning used, for `campo render --kind depth --step K`.
  if (request.record_replans) {
    options.on_plan = [&](std::size_t vehicle, const Observation& observation, const PlanResult& plan) {
      const std::optional<ReplanDecision>& replan = plan.decisions.replan;
      if (vehicle != run.vehicle_index || !replan || !replan->sensor) return;
      for (const SensorReading& reading : observation.sensors) {
        // Only image sensors give a depth map worth drawing (not a leddar's single row).
        if (reading.alias != *replan->sensor || !reading.scan || !is_image(*reading.config)) continue;
        create_output_directories(output().path("replans"));
        write_depth_png(depth_map(*reading.scan, *reading.config),
                        output().path("replans") / replan_depth_file(replan->index));
      }
    };
  }
  // Every IMU sample at its own rate (imu.csv).
  ImuRecorder imus(scene.vehicles.size());
  options.on_imu = [&imus](std::size_t vehicle, std::size_t imu, const ImuReading& reading) {
    imus.record(vehicle, imu, reading);
  };
  PlannerMaker make_planner = request.make_planner ? request.make_planner : PlannerMaker(&create_planner);
  std::optional<WallLimit> limit;
  if (request.time_limit_s > 0) {
    limit.emplace(request.time_limit_s, request.time_limit_name);
    make_planner = [inner = std::move(make_planner), &limit](const PlannerSpec& spec, const PlannerContext& context) {
      std::unique_ptr<Planner> planner;
      try {
        planner = inner(spec, context);
      } catch (const std::exception&) {
        if (!limit->passed()) throw;  // a constructor interrupted by the limit: the run fails at its first call
      }
      return std::unique_ptr<Planner>(std::make_unique<WallLimitedPlanner>(std::move(planner), *limit));
    };
  }
  run.result = run_episode(scene, &make_vehicle, make_planner, options);
  run.imu_samples = std::move(imus.samples());
  // Ended by the limit, not by the planner: the reason says so.
  if (limit && limit->tripped) {
    for (VehicleResult& vehicle : run.result.vehicles) {
      if (vehicle.metrics.outcome == Outcome::failed) vehicle.metrics.reason = limit->reason();
    }
    if (run.result.fleet.outcome == Outcome::failed) run.result.fleet.reason = limit->reason();
  }
  limit.reset();
  run.record = run_json(scene, run.result, options, override_texts(applied_overrides(request)));
  // Whose sensors the depth maps under depth/ and replans/ are, when there are several to choose from.
  if (scene.vehicles.size() > 1) run.record["recorded_vehicle"] = def.alias;
  if (!run.document.contains("name")) run.document["name"] = scene.name;
  return run;
}

std::vector<FigureFailure> write_run_files(const SimulatedRun& run, const RunRequest& request,
                                           const StagedOutput& out) {
  for (std::size_t v = 0; v < run.result.vehicles.size(); ++v) {
    write_file_atomically(out.path(trajectory_file(run.result, v)), trajectory_csv(run.result.vehicles[v]));
    write_file_atomically(out.path(events_file(run.result, v)), events_jsonl(run.result.vehicles[v].events));
    if (!run.scene.vehicles[v].imus.empty() && v < run.imu_samples.size()) {
      write_file_atomically(out.path(imu_file(run.result, v)), imu_csv(run.scene.vehicles[v], run.imu_samples[v]));
    }
  }
  write_file_atomically(out.path("run.json"), run.record.dump(2) + "\n");
  write_file_atomically(out.path("scene.json"), run.document.dump(2) + "\n");
  std::vector<FigureFailure> failures;
  if (!request.figures) return failures;
  // Drawn from the files just written, exactly as `campo render` would; each on its own, so one that
  // fails costs neither the others nor the run.
  const auto attempt = [&](const std::string& figure, const std::function<void()>& draw) {
    try {
      draw();
    } catch (const InputError& e) {
      failures.push_back({figure, e.what(), true});
    } catch (const std::exception& e) {
      failures.push_back({figure, e.what(), false});
    }
  };
  const std::filesystem::path staged = out.path("");
  std::optional<RecordedRun> recorded;
  attempt("run directory", [&] {
    recorded = load_run_dir(staged, request.vehicle);
    recorded->view.label = request.label.empty() ? request.out.filename().string() : request.label;
  });
  if (!recorded) return failures;  // no figure could be drawn from it
  const FigureWriter draw = request.write_figure ? request.write_figure
                                                 : FigureWriter([](const RecordedRun& run, FigureKind kind,
                                                                   const std::filesystem::path& dir,
                                                                   const FigureFormats& formats) {
                                                     write_figure(run, kind, dir, formats);
                                                   });
  for (const FigureKind kind : run_directory_figures(*recorded)) {
    attempt(std::string(to_string(kind)), [&] { draw(*recorded, kind, staged, request.figure_formats); });
  }
  return failures;
}

FigureFailureReport figure_failure_report(const std::vector<FigureFailure>& failures, const std::string& out) {
  FigureFailureReport report;
  for (const FigureFailure& f : failures) {
    report.text += (f.bad_input ? "error: " : "internal error: ") + f.figure + " figure: " + f.message + "\n";
    report.bad_input = report.bad_input && f.bad_input;
  }
  report.text += "the run completed and its files are kept in " + out +
                 "; only the figures above are missing (campo render " + out + " redraws them)\n";
  return report;
}

RunNotKeptError::RunNotKeptError(const OutputError& cause, nlohmann::json record)
    : OutputError(cause.file(), cause.message() + "; the run completed (" + run_summary_line(record) +
                                    ") but none of its files were kept"),
      record_(std::move(record)) {}

ExecutedRun execute_run(const RunRequest& request) {
  std::optional<StagedOutput> out;
  const auto output = [&]() -> const StagedOutput& {
    if (!out) out.emplace(request.out);
    return *out;
  };
  const SimulatedRun run = simulate_run(request, output);
  ExecutedRun executed{run.record, {}};
  try {
    executed.figure_failures = write_run_files(run, request, output());
    out->commit();
  } catch (const OutputError& e) {
    throw RunNotKeptError(e, run.record);
  }
  return executed;
}

void write_final_depth(const SimulatedRun& run, const std::filesystem::path& png) {
  const VehicleDef& vehicle = run.scene.vehicles[run.vehicle_index];
  const std::vector<TrajectorySample>& trajectory = run.result.vehicles.at(run.vehicle_index).trajectory;
  if (trajectory.empty()) throw std::runtime_error("no recorded pose to draw a depth map from");
  const auto image = std::find_if(vehicle.sensors.begin(), vehicle.sensors.end(), [](const SensorDef& s) {
    return is_image(s.range);
  });
  SensorDef sensor;
  if (image != vehicle.sensors.end()) {
    sensor = *image;
  } else {
    sensor = parse_sensor(JsonNode(nlohmann::json{{"type", "depth_camera"}, {"preset", "scanner3d"}}, "triage", ""));
    if (!vehicle.sensors.empty()) sensor.range.mount = vehicle.sensors.front().range.mount;
  }
  const TrajectorySample& last = trajectory.back();
  const std::unique_ptr<RangeSensor> ranger = make_range_sensor(run.scene, sensor, run.scene.world.seed);
  RangeScan scan;
  // The bodies where the run left them.
  ranger->scan(last.state.pose() * to_isometry(sensor.range.mount), last.time_s, run.result.final_body_poses, scan);
  write_depth_png(depth_map(scan, sensor.range), png);
}

std::string run_summary_line(const nlohmann::json& record) {
  const nlohmann::json& m = record.at("metrics");
  std::ostringstream line;
  line << record.at("provenance").at("scene").value("name", "scene") << ": " << m.at("outcome").get<std::string>()
       << " (" << m.at("reason").get<std::string>() << ") after " << m.at("sim_time_s").get<double>()
       << " s simulated, ";
  if (record.contains("vehicles")) {  // several vehicles: the run as a whole
    line << m.at("vehicles_reached").get<int>() << " of " << m.at("vehicles").get<int>() << " vehicles reached, "
         << m.at("collisions").get<int>() << " collisions, ";
  } else {
    line << "path " << m.at("path_length_m").get<double>() << " m (ratio " << m.at("path_ratio").get<double>()
         << "), ";
  }
  line << m.at("wall_time_s").get<double>() << " s wall";
  return line.str();
}

}  // namespace campo
