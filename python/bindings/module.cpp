// campo._campo: the native part of the Python package `campo` (docs/python.md).
// Episodes stepped from Python, Python planners in the C++ closed loop, and
// runs written exactly as `campo run` writes them.
#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "campo/episode.hpp"
#include "campo/json_reader.hpp"
#include "campo/planner_registry.hpp"
#include "campo/run_record.hpp"
#include "campo/vehicle_factory.hpp"
#include "campo/version.hpp"
#include "core/output_dir.hpp"
#include "python/bindings/observation.hpp"
#include "python/bindings/planner_limits.hpp"
#include "python/bindings/python_planner.hpp"
#include "scene/scene_overrides.hpp"
#include "session/run_session.hpp"
#include "sweep/bundled.hpp"

namespace campo::python {

namespace py = pybind11;

namespace {

// What an episode driven from Python records as its planner.
constexpr std::string_view kExternalPlanner = "external";

// The run a Python call asks for: a scene file or a bundled scene's name,
// overrides as {JSON pointer: value}, and a seed.
RunRequest run_request(const std::string& scene, std::optional<std::uint64_t> seed, const py::object& overrides,
                       const std::string& vehicle, bool continue_after_collision) {
  RunRequest request;
  request.scene = file_or_bundled(scene, &bundled_scene);
  request.vehicle = vehicle;
  request.continue_after_collision = continue_after_collision;
  if (!overrides.is_none()) {
    if (!py::isinstance<py::dict>(overrides)) {
      throw InputError("overrides", "", "a dict {JSON pointer: value}, e.g. {\"/world/time_limit_s\": 60}");
    }
    for (const auto& [pointer, value] : overrides.cast<py::dict>()) {
      request.overrides.push_back(make_override(py::str(pointer).cast<std::string>(), to_json(value)));
    }
  }
  request.seed = seed;
  return request;
}

// One run of an Episode (a reset): its scene, the loop, and its result once it ended.
struct EpisodeRun {
  PreparedRun prepared;
  std::optional<Episode> episode;
  std::shared_ptr<const std::vector<Eigen::Vector3d>> mission_m;
  std::optional<EpisodeResult> result;
};

// campo.Episode.
class PythonEpisode {
 public:
  PythonEpisode(const std::string& scene, std::optional<std::uint64_t> seed, const py::object& overrides,
                const std::string& vehicle, bool continue_after_collision)
      : request_(run_request(scene, seed, overrides, vehicle, continue_after_collision)) {
    // Read and check everything now, so bad input fails at construction.
    refuse_planner_overrides();
    prepare_run(request_, false);
  }

  ObservationView reset() {
    run_ = std::make_shared<EpisodeRun>();
    run_->prepared = prepare_run(request_, false);
    VehicleDef& def = run_->prepared.scene.vehicles[run_->prepared.vehicle_index];
    def.planner.name = std::string(kExternalPlanner);
    def.planner.params.values = nlohmann::json::object();
    run_->episode.emplace(run_->prepared.scene, &make_vehicle, run_->prepared.options);
    run_->mission_m = mission_positions(def.mission);
    return observation();
  }

  py::tuple step(const CommandBox& command) {
    Episode& e = episode();
    if (e.done()) throw std::logic_error("the episode has ended: call reset() for a new one");
    PlanResult plan;
    plan.command = command.value;
    e.step(std::move(plan));  // std::invalid_argument (ValueError) for a command the vehicle cannot follow
    return py::make_tuple(observation(), e.done(), info());
  }

  ObservationView observation() const { return view_of(episode().observation(), run_->mission_m); }
  bool done() const { return run_ && run_->episode && run_->episode->done(); }

  py::dict info() const {
    const Episode& e = episode();
    // Once done, the finished metrics (the loop's counters move into them).
    const EpisodeMetrics& m = e.done() ? finished().only().metrics : e.metrics_so_far();
    py::dict info;
    info["time_s"] = e.done() ? m.sim_time_s : e.world().time_s();
    info["collisions"] = m.collisions;
    info["path_length_m"] = m.path_length_m;
    info["outcome"] = e.done() ? py::object(py::str(std::string(to_string(m.outcome)))) : py::none();
    info["reason"] = m.reason;
    return info;
  }

  py::object metrics() const { return from_json(campo::to_json(finished().only().metrics)); }

  py::object write(const std::filesystem::path& out, bool figures) const {
    check_output_directory(out, "out");
    const EpisodeResult& result = finished();
    RunRequest request = request_;
    request.out = out;
    request.figures = figures;
    SimulatedRun run;
    run.scene = run_->prepared.scene;
    run.document = run_->prepared.document;
    run.vehicle_index = run_->prepared.vehicle_index;
    run.result = result;
    run.record = run_json(run.scene, run.result, run_->prepared.options, override_texts(request.overrides));
    run.record["provenance"]["planner"] = {{"name", kExternalPlanner},
                                           {"source", "commands given to campo.Episode.step from Python"}};
    if (!run.document.contains("name")) run.document["name"] = run.scene.name;
    StagedOutput staged(out);
    const std::vector<FigureFailure> failures = write_run_files(run, request, staged);
    staged.commit();
    warn_figure_failures(failures);
    return from_json(run.record);
  }

  static void warn_figure_failures(const std::vector<FigureFailure>& failures) {
    for (const FigureFailure& f : failures) {
      PyErr_WarnEx(PyExc_RuntimeWarning, ("figure " + f.figure + " not drawn: " + f.message).c_str(), 1);
    }
  }

 private:
  Episode& episode() const {
    if (!run_) throw std::logic_error("call reset() first");
    return *run_->episode;
  }
  const EpisodeResult& finished() const {
    Episode& e = episode();
    if (!e.done()) throw std::logic_error("the episode is still running: its metrics are measured over a whole run");
    if (!run_->result) {
      run_->result = e.finish();
      run_->result->only().planner_parameters = nlohmann::json::object();  // no planner: the caller's commands
    }
    return *run_->result;
  }

  // The caller's commands drive the vehicle: an override of a vehicle's
  // planner (/objects/<vehicle>/planner...) would be recorded (run.json's
  // overrides) and never applied. Checked on the document before the scene
  // is read, which would judge a planner block the override made first.
  void refuse_planner_overrides() const {
    const std::string file = request_.scene.string();
    nlohmann::json document = parse_json_text(read_text_file(file), file);
    for (const SceneOverride& assignment : request_.overrides) {
      const std::string p = apply_override(document, assignment);
      const std::size_t index_end = p.find('/', std::string_view("/objects/").size());
      if (!p.starts_with("/objects/") || index_end == std::string::npos) continue;
      const std::string rest = p.substr(index_end);
      if (rest != "/planner" && !rest.starts_with("/planner/")) continue;
      throw InputError("overrides", assignment.pointer,
                       "campo.Episode runs no planner (step()'s commands drive the vehicle), so an override of a "
                       "planner would be ignored; pass planner parameters to campo.run");
    }
  }

  RunRequest request_;
  std::shared_ptr<EpisodeRun> run_;
};

// campo.run: one run in the closed loop, with a planner named (built in, a
// plugin's, "python:...") or given as a Python object.
py::object run(const std::string& scene, const py::object& planner, const std::optional<std::filesystem::path>& out,
               std::optional<std::uint64_t> seed, const py::object& overrides, const std::string& vehicle,
               bool figures, bool continue_after_collision, std::optional<double> time_limit_s,
               std::optional<double> call_limit_s) {
  RunRequest request = run_request(scene, seed, overrides, vehicle, continue_after_collision);
  request.figures = figures;
  // The limits its Python planners are held to (planner_limits.hpp), the run's own limit among them.
  PlannerLimits limits = limits_from_environment();
  if (call_limit_s) {
    if (!std::isfinite(*call_limit_s) || *call_limit_s < 0) {
      throw InputError("call_limit_s", "", "expected a number of seconds >= 0 (0: no limit)");
    }
    limits.call_limit_s = *call_limit_s;
  }
  if (time_limit_s) {
    if (!std::isfinite(*time_limit_s) || *time_limit_s <= 0) {
      throw InputError("time_limit_s", "", "expected a number of seconds > 0");
    }
    request.time_limit_s = *time_limit_s;
    request.time_limit_name = "time_limit_s";
  }
  const ScopedLimits scoped(limits);
  if (py::isinstance<py::str>(planner)) {
    request.planner = planner.cast<std::string>();
  } else if (!planner.is_none()) {
    if (!py::hasattr(planner, "plan")) {
      throw InputError("planner", "", "a planner name or an object with a plan(self, obs) method");
    }
    request.planner = python_planner_name(planner);
    try {
      declared_decision_fields(planner, request.planner);  // a malformed declaration is bad input, before the run
    } catch (const std::invalid_argument& e) {
      throw InputError("planner", "", std::string("a Python planner's declaration: ") + e.what());
    }
    request.make_planner = [planner](const PlannerSpec& spec, const PlannerContext&) {
      // The object was built by the caller: overrides of the vehicle's planner parameters would be dropped.
      if (!spec.params.values.empty()) {
        throw InputError(spec.params.file, spec.params.pointer,
                         "a planner given as a Python object takes its parameters from its own constructor, not "
                         "from overrides (they would be ignored): got " + spec.params.values.dump());
      }
      return wrap_python_planner(planner, nlohmann::json::object());
    };
  }
  nlohmann::json record;
  if (out) {
    check_output_directory(*out, "out");  // before the episode is simulated
    request.out = *out;
    const ExecutedRun executed = execute_run(request);
    PythonEpisode::warn_figure_failures(executed.figure_failures);
    record = executed.record;
  } else {
    request.record_replans = false;  // nowhere to write them
    record = simulate_run(request, {}).record;
  }
  return from_json(record);
}

// The description of the planner `name` as campo.planner_record reads it
// (planner_record_of); "external" (campo.Episode's runs) has none.
std::shared_ptr<const PlannerRecord> record_of(const std::string& name) {
  return name == kExternalPlanner ? nullptr : planner_record_of(name);
}

// The fields of one part ("decisions", "replan", "metrics") of a planner's record.
const RecordFields& record_part(const PlannerRecord& record, const std::string& part) {
  if (part == "decisions") return record.decisions;
  if (part == "replan") return record.replan;
  if (part == "metrics") return record.metrics;
  throw std::invalid_argument("a part of a planner's record: decisions, replan or metrics; got \"" + part + "\"");
}

// campo.planner_record's native half: None, or each part's fields as (name, type, unit, meaning).
py::object planner_fields(const std::string& name) {
  const std::shared_ptr<const PlannerRecord> record = record_of(name);
  if (!record) return py::none();
  py::dict parts;
  for (const char* part : {"decisions", "replan", "metrics"}) {
    py::list fields;
    for (const RecordFieldInfo& f : record_part(*record, part).fields()) {
      fields.append(py::make_tuple(f.name, std::string(to_string(f.type)), f.unit, f.meaning));
    }
    parts[part] = fields;
  }
  return parts;
}

// A recorded part of the planner's record checked against its declarations
// (RecordFields::check): InputError at `file` and `pointer` for an undeclared
// key or a value not what its field holds.
void check_record(const std::string& name, const std::string& part, const py::handle& record, const std::string& file,
                  const std::string& pointer) {
  const std::shared_ptr<const PlannerRecord> description = record_of(name);
  static const PlannerRecord kNone;  // a planner without a description declares no field
  record_part(description ? *description : kNone, part).check(to_json(record), file, pointer);
}

}  // namespace

PYBIND11_MODULE(_campo, m) {
  m.doc() = "campo's native module: episodes, planners, runs (see the package campo)";
  m.attr("__version__") = library_version();

  py::register_exception<InputError>(m, "InputError", PyExc_ValueError);
  py::register_exception<OutputError>(m, "OutputError", m.attr("InputError"));

  bind_observation(m);
  bind_plan_types(m);
  bind_limits(m);
  register_python_scheme();

  py::class_<PythonEpisode>(m, "Episode",
                            "One run of the closed loop stepped from Python, Gymnasium-style: reset(), then "
                            "step(command) at every control tick until done.")
      .def(py::init<const std::string&, std::optional<std::uint64_t>, const py::object&, const std::string&, bool>(),
           py::arg("scene"), py::arg("seed") = py::none(), py::arg("overrides") = py::none(), py::arg("vehicle") = "",
           py::arg("continue_after_collision") = false)
      .def("reset", &PythonEpisode::reset, "start (again) from the scene's start; returns the first Observation")
      .def("step", &PythonEpisode::step, py::arg("command"),
           "apply command until the next control tick; returns (observation, done, info)")
      .def_property_readonly("observation", &PythonEpisode::observation)
      .def_property_readonly("done", &PythonEpisode::done)
      .def("metrics", &PythonEpisode::metrics, "the run's metrics, as run.json's (once done)")
      .def("write", &PythonEpisode::write, py::arg("out"), py::arg("figures") = true,
           "write the run directory as campo run does (once done); returns run.json's content");

  m.def("run", &run, py::arg("scene"), py::arg("planner") = py::none(), py::arg("out") = py::none(),
        py::arg("seed") = py::none(), py::arg("overrides") = py::none(), py::arg("vehicle") = "",
        py::arg("figures") = true, py::arg("continue_after_collision") = false, py::arg("time_limit_s") = py::none(),
        py::arg("call_limit_s") = py::none(),
        "run scene to its end with planner (a name, \"python:module:Class\", or an object with plan(obs)); "
        "writes the run directory to out when given; returns run.json's content. time_limit_s: wall clock the "
        "whole run may take; call_limit_s: wall clock of one call into a Python planner (default "
        "$CAMPO_PYTHON_CALL_LIMIT_S, else 60); past either the run ends as failed");
  m.def("_guard_process_exit", &guard_process_exit,
        "in an interpreter campo embeds: os._exit from a planner ends its run as failed, not the process");
  m.def("bundled_scene", &bundled_scene, py::arg("name"),
        "the file of the bundled scene name, found as campo run finds it (scenes/ of the working directory, "
        "else the installed prefix's share/campo/scenes, else the source tree's scenes/ beside the build "
        "directory); InputError listing the folders searched when none holds it");
  m.def("planners", [] {
    std::vector<std::string> names;
    for (const PlannerEntry& entry : planner_registry()) names.push_back(entry.name);
    return names;
  }, "the registered planners' names");
  m.def("_planner_fields", &planner_fields, py::arg("name"),
        "the declared fields of planner name's record, {part: [(name, type, unit, meaning)]}, or None "
        "(campo.planner_record)");
  m.def("_check_record", &check_record, py::arg("planner"), py::arg("part"), py::arg("record"), py::arg("file"),
        py::arg("pointer"), "checks a recorded part of planner's record against its declarations (InputError)");
}

}  // namespace campo::python
