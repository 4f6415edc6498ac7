// campo._campo: the native part of the Python package `campo` (docs/python.md).
// Episodes stepped from Python, Python planners in the C++ closed loop, and
// runs written exactly as `campo run` writes them.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>
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
#include "python/bindings/gym_bindings.hpp"
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

// How a vehicle's mission ended while the others' went on (the end of the
// run gives every outcome, from its record).
struct Ending {
  Outcome outcome = Outcome::reached;
  double time_s = 0.0;
};

// One run of an Episode (a reset): its scene, the loop, and its result once it ended.
struct EpisodeRun {
  PreparedRun prepared;
  std::optional<Episode> episode;
  std::vector<std::shared_ptr<const std::vector<Eigen::Vector3d>>> missions_m;  // each vehicle's, scene order
  std::vector<std::optional<Ending>> endings;                                  // each vehicle's, scene order
  // The planners of the vehicles that are not agents (null for an agent), and what they decided at the
  // current tick once asked (kept when step() refuses the agents' commands, so none is asked twice).
  std::vector<std::unique_ptr<Planner>> planners;
  std::vector<nlohmann::json> planner_parameters;
  std::optional<std::vector<PlanResult>> planned;
  std::vector<double> planned_ms;
  std::optional<EpisodeResult> result;
};

// "a", "b", "c" for the messages that list the scene's vehicles.
std::string alias_list(const std::vector<std::string>& aliases) {
  std::string list;
  for (const std::string& a : aliases) list += (list.empty() ? "\"" : ", \"") + a + "\"";
  return list;
}

// A decision given to Episode.step: a campo.Command (the mission goes on) or
// a campo.PlanResult (its status may end the mission, its decisions are
// recorded). `who` prefixes the messages ("" or "vehicle \"a\": ").
PlanResult decision_of(const py::handle& value, const std::string& who) {
  if (py::isinstance<CommandBox>(value)) {
    PlanResult plan;
    plan.command = value.cast<const CommandBox&>().value;
    return plan;
  }
  if (py::isinstance<PlanResultBox>(value)) {
    try {
      return plan_result(value.cast<const PlanResultBox&>());
    } catch (const std::runtime_error& e) {
      throw std::invalid_argument(who + e.what());
    }
  }
  throw py::type_error(who + "expected a campo.Command or a campo.PlanResult, got " +
                       py::str(py::type::of(value).attr("__name__")).cast<std::string>());
}

// campo.Episode. A scene of one vehicle: reset() gives its observation,
// step(command) (observation, done, info). A scene of several, the shape of
// PettingZoo's parallel API keyed by alias: reset() gives {alias:
// observation}, step({alias: command}) ({alias: observation}, {alias: done,
// "__all__": done}, {alias: info}) for the vehicles that acted; `agents`
// shrinks as missions end (docs/python.md). agents= names the vehicles
// stepped from Python (keyed even when one); the others' planners run in the loop.
class PythonEpisode {
 public:
  PythonEpisode(const std::string& scene, std::optional<std::uint64_t> seed, const py::object& overrides,
                const std::string& vehicle, bool continue_after_collision, const py::object& agents)
      : request_(run_request(scene, seed, overrides, vehicle, continue_after_collision)) {
    // Read and check everything now, so bad input fails at construction.
    const std::optional<std::vector<std::string>> named = agent_names(agents);
    refuse_planner_overrides(named);
    const PreparedRun prepared = prepare_run(request_, false);
    for (const VehicleDef& v : prepared.scene.vehicles) aliases_.push_back(v.alias);
    if (several() && !request_.vehicle.empty()) {
      throw InputError("vehicle", "", "no vehicle to choose: campo.Episode steps every vehicle of a scene of several (" +
                                          alias_list(aliases_) + "), step() taking {alias: command}; agents= names "
                                          "those stepped from Python");
    }
    choose_agents(named);
    // prepare_run left the first vehicle's planner unchecked, as an episode's; one that runs is checked now.
    const VehicleDef& first = prepared.scene.vehicles.at(prepared.vehicle_index);
    if (!agent_[prepared.vehicle_index]) create_planner(first.planner, {first.type, &prepared.scene, &first});
  }

  py::object reset(std::optional<std::uint64_t> seed) {
    if (seed) request_.seed = seed;  // this run's world seed and the next ones'
    run_ = std::make_shared<EpisodeRun>();
    run_->prepared = prepare_run(request_, false);
    const Scene& scene = run_->prepared.scene;
    for (std::size_t v = 0; v < aliases_.size(); ++v) {
      VehicleDef& def = run_->prepared.scene.vehicles[v];
      if (agent_[v]) {
        def.planner.name = std::string(kExternalPlanner);
        def.planner.params.values = nlohmann::json::object();
      }
      run_->missions_m.push_back(mission_positions(def.mission));
    }
    run_->endings.assign(aliases_.size(), std::nullopt);
    run_->episode.emplace(scene, &make_vehicle, run_->prepared.options);
    // The others' planners, made as run_episode makes them (after the world).
    for (std::size_t v = 0; v < aliases_.size(); ++v) {
      const VehicleDef& def = scene.vehicles[v];
      run_->planners.push_back(agent_[v] ? nullptr : create_planner(def.planner, {def.type, &scene, &def}));
      run_->planner_parameters.push_back(agent_[v] ? nlohmann::json::object() : run_->planners.back()->parameters());
    }
    return observation();
  }

  py::tuple step(const py::object& commands) {
    Episode& e = episode();
    if (e.done()) throw std::logic_error("the episode has ended: call reset() for a new one");
    if (!keyed()) {
      e.step(decision_of(commands, ""));  // std::invalid_argument (ValueError) for a command the vehicle cannot follow
      return py::make_tuple(observation(), e.done(), info());
    }
    const std::vector<std::size_t> acting = live();
    std::vector<PlanResult> plans = decisions(commands);
    step_with_planners(plans);
    // How a mission that ended now, while the run goes on, ended and when (the run's end gives every one).
    if (!e.done()) {
      for (const std::size_t v : acting) {
        if (e.done(v)) run_->endings[v] = Ending{*e.outcome(v), e.end_time_s(v)};
      }
    }
    py::dict observations;
    py::dict dones;
    py::dict infos;
    for (const std::size_t v : acting) {
      const py::str alias(aliases_[v]);
      observations[alias] = view(v);
      dones[alias] = e.done() || e.done(v);
      infos[alias] = agent_info(v);
    }
    dones["__all__"] = e.done();
    return py::make_tuple(observations, dones, infos);
  }

  py::object observation() const {
    if (!keyed()) return py::cast(view(0));
    py::dict observations;
    for (const std::size_t v : live()) observations[py::str(aliases_[v])] = view(v);
    return observations;
  }

  bool done() const { return run_ && run_->episode && run_->episode->done(); }

  // The vehicles still on their missions (none before reset() or once the run has ended).
  std::vector<std::string> agents() const {
    std::vector<std::string> names;
    if (!run_) return names;
    for (const std::size_t v : live()) names.push_back(aliases_[v]);
    return names;
  }
  const std::vector<std::string>& possible_agents() const { return keyed() ? agent_aliases_ : aliases_; }

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

  py::object metrics() const {
    const EpisodeResult& result = finished();
    if (!keyed()) return from_json(campo::to_json(result.only().metrics));
    nlohmann::json vehicles = nlohmann::json::object();
    for (const VehicleResult& v : result.vehicles) vehicles[v.alias] = campo::to_json(v.metrics);
    return from_json({{"fleet", campo::to_json(result.fleet)}, {"vehicles", vehicles}});
  }

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
    const nlohmann::json provenance = {{"name", kExternalPlanner},
                                       {"source", "commands given to campo.Episode.step from Python"}};
    if (several()) {
      for (std::size_t v = 0; v < aliases_.size(); ++v) {
        if (agent_[v]) run.record["vehicles"][v]["planner_provenance"] = provenance;
      }
    } else {
      run.record["provenance"]["planner"] = provenance;
    }
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
  bool several() const { return aliases_.size() > 1; }
  // Whether reset() and step() take and give dicts keyed by alias: with several vehicles, or agents named.
  bool keyed() const { return several() || named_agents_; }

  // agents=: the aliases of the vehicles stepped from Python; none: every one.
  static std::optional<std::vector<std::string>> agent_names(const py::object& agents) {
    if (agents.is_none()) return std::nullopt;
    if (py::isinstance<py::str>(agents) || !py::isinstance<py::iterable>(agents)) {
      throw InputError("agents", "", "a list of vehicle aliases, got " + py::repr(agents).cast<std::string>());
    }
    std::vector<std::string> names;
    for (const py::handle& item : agents) {
      if (!py::isinstance<py::str>(item)) {
        throw InputError("agents", "", "a list of vehicle aliases, got " + py::repr(item).cast<std::string>() +
                                           " in it");
      }
      names.push_back(item.cast<std::string>());
    }
    return names;
  }

  // The agents among the scene's vehicles (`named`, else every one); the others' planners run in the loop.
  void choose_agents(const std::optional<std::vector<std::string>>& named) {
    agent_.assign(aliases_.size(), !named);
    named_agents_ = named.has_value();
    for (const std::string& alias : named.value_or(std::vector<std::string>{})) {
      const auto found = std::find(aliases_.begin(), aliases_.end(), alias);
      if (found == aliases_.end()) {
        throw InputError("agents", alias, "a vehicle of " + request_.scene.string() + " (" + alias_list(aliases_) + ")");
      }
      agent_[static_cast<std::size_t>(found - aliases_.begin())] = true;
    }
    if (std::find(agent_.begin(), agent_.end(), true) == agent_.end()) {
      throw InputError("agents", "", "at least one vehicle to step from Python (" + alias_list(aliases_) + ")");
    }
    if (!keyed()) return;
    for (std::size_t v = 0; v < aliases_.size(); ++v) {
      if (agent_[v]) agent_aliases_.push_back(aliases_[v]);
    }
  }

  // Steps the run with the agents' `plans` and the others' planners' decisions, as run_episode steps it: a
  // planner that raises, or gives a command its vehicle cannot follow, ends its vehicle's mission as failed.
  // A command an agent's vehicle cannot follow: VehicleCommandError (ValueError) naming it, nothing changed.
  void step_with_planners(std::vector<PlanResult>& plans) {
    using Clock = std::chrono::steady_clock;
    Episode& e = episode();
    const std::size_t n = aliases_.size();
    if (!run_->planned) {
      run_->planned.emplace(n);
      run_->planned_ms.assign(n, 0.0);
      for (std::size_t v = 0; v < n; ++v) {
        if (agent_[v] || e.done(v)) continue;
        const auto start = Clock::now();
        try {
          (*run_->planned)[v] = run_->planners[v]->plan(e.observation(v));
        } catch (const InputError&) {
          throw;  // bad input stays bad input
        } catch (const std::exception& error) {
          e.fail(v, std::string("the planner raised an error: ") + error.what());
          continue;
        }
        run_->planned_ms[v] = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
      }
    }
    for (std::size_t v = 0; v < n; ++v) {
      if (!agent_[v]) plans[v] = (*run_->planned)[v];
    }
    while (!e.done()) {
      std::vector<PlanResult> given = plans;
      try {
        e.step(std::move(given), run_->planned_ms);
        break;
      } catch (const VehicleCommandError& error) {
        if (agent_[error.vehicle()]) throw;
        e.fail(error.vehicle(), std::string("the planner gave a command the vehicle cannot follow: ") + error.what());
      }
    }
    run_->planned.reset();
  }

  Episode& episode() const {
    if (!run_) throw std::logic_error("call reset() first");
    return *run_->episode;
  }
  const EpisodeResult& finished() const {
    Episode& e = episode();
    if (!e.done()) throw std::logic_error("the episode is still running: its metrics are measured over a whole run");
    if (!run_->result) {
      run_->result = e.finish();
      // The agents' are the caller's commands, without a planner.
      for (std::size_t v = 0; v < aliases_.size(); ++v) {
        run_->result->vehicles[v].planner_parameters = run_->planner_parameters[v];
      }
    }
    return *run_->result;
  }

  ObservationView view(std::size_t v) const { return view_of(episode().observation(v), run_->missions_m.at(v)); }

  // The vehicles still on their missions, in scene order.
  std::vector<std::size_t> live() const {
    std::vector<std::size_t> indices;
    const Episode& e = episode();
    if (e.done()) return indices;
    for (std::size_t v = 0; v < aliases_.size(); ++v) {
      if (agent_[v] && !e.done(v)) indices.push_back(v);
    }
    return indices;
  }

  // step()'s {alias: command}: one for every vehicle still on its mission, none for another.
  std::vector<PlanResult> decisions(const py::object& commands) const {
    if (!py::isinstance<py::dict>(commands)) {
      throw py::type_error("a scene of several vehicles is stepped with a dict {alias: campo.Command or "
                           "campo.PlanResult}, one for each of episode.agents (" + alias_list(agents()) + ")");
    }
    const Episode& e = episode();
    std::vector<PlanResult> plans(aliases_.size());
    std::vector<bool> given(aliases_.size(), false);
    for (const auto& item : commands.cast<py::dict>()) {
      if (!py::isinstance<py::str>(item.first)) {
        throw std::invalid_argument("step()'s keys are vehicle aliases (" + alias_list(aliases_) + "), got " +
                                    py::repr(item.first).cast<std::string>());
      }
      const std::string alias = item.first.cast<std::string>();
      const auto found = std::find(aliases_.begin(), aliases_.end(), alias);
      if (found == aliases_.end()) {
        throw std::invalid_argument("no vehicle \"" + alias + "\" in the scene: its vehicles are " + alias_list(aliases_));
      }
      const auto v = static_cast<std::size_t>(found - aliases_.begin());
      if (!agent_[v]) {
        throw std::invalid_argument("vehicle \"" + alias + "\" is driven by its planner (" +
                                    run_->prepared.scene.vehicles[v].planner.name + "), not from Python: the agents "
                                    "are " + alias_list(agent_aliases_));
      }
      if (e.done(v)) {
        throw std::invalid_argument("vehicle \"" + alias + "\" has ended its mission: it is no longer among "
                                    "episode.agents (" + alias_list(agents()) + ")");
      }
      plans[v] = decision_of(item.second, "vehicle \"" + alias + "\": ");
      given[v] = true;
    }
    std::vector<std::string> missing;
    for (const std::size_t v : live()) {
      if (!given[v]) missing.push_back(aliases_[v]);
    }
    if (!missing.empty()) {
      throw std::invalid_argument("no command for " + std::string(missing.size() > 1 ? "vehicles " : "vehicle ") +
                                  alias_list(missing) + ": step() takes one for each of episode.agents (" +
                                  alias_list(agents()) + ")");
    }
    return plans;
  }

  // Vehicle v's info, as step()'s single-vehicle info: its outcome once its mission has ended.
  py::dict agent_info(std::size_t v) const {
    const Episode& e = episode();
    const EpisodeMetrics& m = e.done() ? finished().vehicles.at(v).metrics : e.metrics_so_far(v);
    const std::optional<Ending>& ending = run_->endings.at(v);
    py::dict info;
    py::object outcome = py::none();
    if (e.done()) {
      info["time_s"] = m.sim_time_s;
      outcome = py::str(std::string(to_string(m.outcome)));
    } else if (ending) {
      info["time_s"] = ending->time_s;
      outcome = py::str(std::string(to_string(ending->outcome)));
    } else {
      info["time_s"] = e.world().time_s();
    }
    info["collisions"] = m.collisions;
    info["path_length_m"] = m.path_length_m;
    info["outcome"] = outcome;
    info["reason"] = m.reason;
    return info;
  }

  // The caller's commands drive an agent (`named`, else every vehicle): an
  // override of its planner (/objects/<vehicle>/planner...) would be
  // recorded (run.json's overrides) and never applied; the other vehicles'
  // planners run, overrides and all. Checked on the document before the
  // scene is read, which would judge a planner block the override made first.
  void refuse_planner_overrides(const std::optional<std::vector<std::string>>& named) const {
    const std::string file = request_.scene.string();
    nlohmann::json document = parse_json_text(read_text_file(file), file);
    for (const SceneOverride& assignment : request_.overrides) {
      const std::string p = apply_override(document, assignment);
      const std::size_t index_end = p.find('/', std::string_view("/objects/").size());
      if (!p.starts_with("/objects/") || index_end == std::string::npos) continue;
      const std::string rest = p.substr(index_end);
      if (rest != "/planner" && !rest.starts_with("/planner/")) continue;
      const nlohmann::json::json_pointer object(p.substr(0, index_end));
      const nlohmann::json alias = document.contains(object) && document[object].is_object()
                                       ? document[object].value("alias", nlohmann::json())
                                       : nlohmann::json();
      if (named && !(alias.is_string() && std::find(named->begin(), named->end(), alias.get<std::string>()) != named->end())) {
        continue;  // a vehicle its planner drives
      }
      throw InputError("overrides", assignment.pointer,
                       "campo.Episode runs no planner for the vehicles it steps (step()'s commands drive them), so "
                       "an override of a planner would be ignored; pass planner parameters to campo.run");
    }
  }

  RunRequest request_;
  std::vector<std::string> aliases_;        // the scene's vehicles, in scene order
  std::vector<bool> agent_;                 // each one stepped from Python, else by its planner
  std::vector<std::string> agent_aliases_;  // when keyed(), the agents' aliases in scene order
  bool named_agents_ = false;               // agents= given
  std::shared_ptr<EpisodeRun> run_;
};

// A planner object campo.run is given: one with plan(obs) whose declaration
// (decision_fields) is well formed; InputError at `where` else.
void check_planner_object(const py::handle& planner, const std::string& where) {
  if (!py::hasattr(planner, "plan")) {
    throw InputError("planner", where == "planner" ? "" : where,
                     "a planner name or an object with a plan(self, obs) method");
  }
  try {
    declared_decision_fields(planner, python_planner_name(planner));  // a malformed declaration is bad input
  } catch (const std::invalid_argument& e) {
    throw InputError("planner", where == "planner" ? "" : where,
                     std::string("a Python planner's declaration: ") + e.what());
  }
}

// campo.run's planner={alias: object}: each object drives its vehicle, the
// others keep the scene's planners. The chosen vehicle's (request.vehicle,
// else the first) is given as `--planner` gives one; each other's planner
// block is replaced by one naming the object's class (an override,
// recorded), which the "python" scheme makes from the object. An override
// of such a vehicle's planner is refused: it would be ignored.
std::map<std::string, py::object> planners_by_alias(const py::dict& planners, RunRequest& request) {
  const PreparedRun prepared = prepare_run(request, false);
  const Scene& scene = prepared.scene;
  std::vector<std::string> aliases;
  for (const VehicleDef& v : scene.vehicles) aliases.push_back(v.alias);
  std::map<std::string, py::object> given;
  for (const auto& item : planners) {
    const std::string alias = py::str(item.first).cast<std::string>();
    if (!py::isinstance<py::str>(item.first) || !scene.find_vehicle(alias)) {
      throw InputError("planner", alias, "a vehicle of " + request.scene.string() + " (" + alias_list(aliases) +
                                             ") as the key of a planner object");
    }
    const py::object object = py::reinterpret_borrow<py::object>(item.second);
    check_planner_object(object, alias);
    given.emplace(alias, object);
  }
  const std::string& chosen = scene.vehicles.at(prepared.vehicle_index).alias;
  std::vector<SceneOverride> replaced;
  for (const auto& [alias, object] : given) {
    const std::string name = python_planner_name(object);
    if (alias == chosen) {
      request.planner = name;
      continue;
    }
    const VehicleDef& def = *scene.find_vehicle(alias);
    const std::string& params = def.params.pointer;  // "<object>/params"
    const std::string block = params.substr(0, params.rfind('/')) + "/planner";
    for (std::size_t i = 0; i < request.overrides.size() && i < prepared.override_pointers.size(); ++i) {
      const std::string& p = prepared.override_pointers[i];
      if (p != block && !p.starts_with(block + "/")) continue;
      throw InputError("overrides", request.overrides[i].pointer,
                       "vehicle " + alias + "'s planner is the object given for it (" + name +
                           "), which takes its parameters from its own constructor: an override of its planner "
                           "would be ignored");
    }
    replaced.push_back(make_override("/objects/" + alias + "/planner", nlohmann::json{{"name", name}}));
  }
  request.overrides.insert(request.overrides.end(), replaced.begin(), replaced.end());
  return given;
}

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
  // Objects given for vehicles by alias, made by the "python" scheme while the run lasts (GivenPlanners).
  std::map<std::string, py::object> given;
  if (py::isinstance<py::str>(planner)) {
    request.planner = planner.cast<std::string>();
  } else if (py::isinstance<py::dict>(planner)) {
    given = planners_by_alias(planner.cast<py::dict>(), request);
  } else if (!planner.is_none()) {
    check_planner_object(planner, "planner");
    request.planner = python_planner_name(planner);
    // The chosen vehicle's (--vehicle, else the first): the others keep the scene's.
    request.make_planner = [planner, chosen = request.vehicle](const PlannerSpec& spec, const PlannerContext& context) {
      const bool is_chosen =
          !context.vehicle_def || !context.scene ||
          context.vehicle_def->alias == (chosen.empty() ? context.scene->vehicles.front().alias : chosen);
      return is_chosen ? given_python_planner(planner, spec) : create_planner(spec, context);
    };
  }
  const GivenPlanners scope(given);
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
  bind_gym(m);
  register_python_scheme();

  py::class_<PythonEpisode>(m, "Episode",
                            "One run of the closed loop stepped from Python, Gymnasium-style: reset(), then "
                            "step(command) at every control tick until done. A scene of several vehicles takes "
                            "the shape of PettingZoo's parallel API: reset() -> {alias: observation}, "
                            "step({alias: command}) -> (observations, dones, infos), keyed by alias, dones with "
                            "\"__all__\"; agents lists the vehicles still on their missions.")
      .def(py::init<const std::string&, std::optional<std::uint64_t>, const py::object&, const std::string&, bool,
                    const py::object&>(),
           py::arg("scene"), py::arg("seed") = py::none(), py::arg("overrides") = py::none(), py::arg("vehicle") = "",
           py::arg("continue_after_collision") = false, py::arg("agents") = py::none())
      .def("reset", &PythonEpisode::reset, py::arg("seed") = py::none(),
           "start (again) from the scene's start, with world.seed set to seed when given (for this run and the "
           "next); returns the first Observation ({alias: Observation} with several vehicles)")
      .def("step", &PythonEpisode::step, py::arg("command"),
           "apply command (a Command, or a PlanResult whose status may end the mission) until the next control "
           "tick; returns (observation, done, info). With several vehicles: {alias: command} for each of agents; "
           "returns ({alias: observation}, {alias: done, \"__all__\": run done}, {alias: info}) for the vehicles "
           "that acted")
      .def_property_readonly("observation", &PythonEpisode::observation,
                             "the current Observation ({alias: Observation} of agents with several vehicles)")
      .def_property_readonly("done", &PythonEpisode::done, "whether the run has ended")
      .def_property_readonly("agents", &PythonEpisode::agents,
                             "aliases of the vehicles still on their missions, in scene order (empty once done)")
      .def_property_readonly("possible_agents", &PythonEpisode::possible_agents,
                             "aliases of every vehicle of the scene, in scene order")
      .def("metrics", &PythonEpisode::metrics,
           "the run's metrics, as run.json's (once done); with several vehicles {\"fleet\": run.json's metrics, "
           "\"vehicles\": {alias: that vehicle's}}")
      .def("write", &PythonEpisode::write, py::arg("out"), py::arg("figures") = true,
           "write the run directory as campo run does (once done); returns run.json's content");

  m.def("run", &run, py::arg("scene"), py::arg("planner") = py::none(), py::arg("out") = py::none(),
        py::arg("seed") = py::none(), py::arg("overrides") = py::none(), py::arg("vehicle") = "",
        py::arg("figures") = true, py::arg("continue_after_collision") = false, py::arg("time_limit_s") = py::none(),
        py::arg("call_limit_s") = py::none(),
        "run scene to its end with planner (a name, \"python:module:Class\", or an object with plan(obs), for "
        "the vehicle chosen by vehicle, else the first; or {alias: object}, the scene's planners for the rest); "
        "writes the run directory to out when given; returns run.json's content. time_limit_s: wall clock the "
        "whole run may take; call_limit_s: wall clock of one call into a Python planner (default "
        "$CAMPO_PYTHON_CALL_LIMIT_S, else 60); past either the run ends as failed");
  m.def("_guard_process_exit", &guard_process_exit,
        "in an interpreter campo embeds: os._exit from a planner ends its run as failed, not the process");
  m.def("bundled_scene", &bundled_scene, py::arg("name"),
        "the file of the bundled scene name, found as campo run finds it (scenes/ of the working directory, "
        "else the installed prefix's share/campo/scenes, else the source tree's scenes/ beside the build "
        "directory, or a pip-installed package's data/scenes); InputError listing the folders searched when none "
        "holds it");
  m.def("_set_package_bundled_folder", [](const std::string& scenes) { set_package_bundled_folder(scenes); },
        py::arg("scenes"), "pip-installed, campo/__init__.py names its data/scenes: searched after the working "
        "directory's scenes/, instead of the prefix's and the source tree's (sweep/bundled.hpp)");
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
