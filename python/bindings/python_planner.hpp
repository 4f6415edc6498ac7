#pragma once
/// Planners written in Python, in campo's C++ closed loop: the adapter that
/// makes a Python object with plan(obs) a campo::Planner, the conversions of
/// commands and plan results, and the "python:package.module:ClassName"
/// planner scheme (campo/planner_registry.hpp).
#include <map>
#include <memory>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>
#include <pybind11/pybind11.h>

#include "campo/planner.hpp"
#include "campo/planner_record.hpp"
#include "python/bindings/planner_limits.hpp"

namespace campo::python {

/// campo.Command: one command a planner may give (campo/vehicle.hpp).
struct CommandBox {
  Command value;
};

/// campo.PlanResult, as Python builds it.
struct PlanResultBox {
  CommandBox command;
  PlanStatus status = PlanStatus::running;
  std::string reason;
  pybind11::object decisions = pybind11::none();
};

/// A Python object as JSON (through Python's json module), and back.
nlohmann::json to_json(const pybind11::handle& value);
pybind11::object from_json(const nlohmann::json& value);

/// The decision fields a Python planner declares: its `decision_fields`
/// attribute (of the object, or of the class), a list of (name, type, unit,
/// meaning), type one of "flag", "integer", "number", "text", "array",
/// "object" (campo/record_fields.hpp). Null when it has none (or None): its
/// own keys are then free, as before declarations existed.
/// std::invalid_argument naming `who`, the entry and what was expected when
/// the declaration is malformed.
std::shared_ptr<const RecordFields> declared_decision_fields(const pybind11::handle& planner, const std::string& who);

/// The PlanResult of a PlanResultBox; its decisions dict read as events.jsonl's
/// (run/event_log.hpp), and, when the planner declares its decision fields,
/// each of its own keys written through `fields` (RecordFields::set: an
/// undeclared key or a value not of its type refused). Throws
/// std::runtime_error naming what is wrong.
PlanResult plan_result(const PlanResultBox& box, const RecordFields* fields = nullptr);

/// The description of the planner `name` as Python sees it (campo.planner_record):
/// a built-in's or a loaded plugin's PlannerRecord, or for "python:module:Class"
/// the class's declared decision fields (imported); null when it has none.
/// InputError (file "planner") when `name` names no planner.
std::shared_ptr<const PlannerRecord> planner_record_of(std::string_view name);

/// The planner the Python object `planner` is: plan() called with a
/// campo.Observation at every control tick. A Python exception ends the run
/// as failed with its traceback (std::runtime_error to the closed loop).
/// `parameters` is what it was made with, recorded unless the object has a
/// parameters() method of its own. Its calls are held to the limits of
/// `guard` (planner_limits.hpp); without one, to current_limits().
std::unique_ptr<Planner> wrap_python_planner(pybind11::object planner, nlohmann::json parameters,
                                             std::unique_ptr<PlannerGuard> guard = nullptr);

/// "python:" + the module and qualified name of `planner`'s class, the name a run records.
std::string python_planner_name(const pybind11::handle& planner);

/// The Python traceback of the exception being handled, as Python prints it.
std::string traceback_text(pybind11::error_already_set& error);

/// Python planner objects a campo.run call gives its vehicles, by alias
/// (python:module:Class names the class of each in the scene the run reads).
/// While one lives, the "python" scheme makes the planner of a vehicle named
/// here from its object, when the spec names the object's class, instead of
/// importing the class and constructing it: a check of a planner block with
/// no vehicle in its context takes any object of that class. Its parameters
/// come from the object's constructor: a spec with parameters is refused.
class GivenPlanners {
 public:
  explicit GivenPlanners(const std::map<std::string, pybind11::object>& by_alias);
  ~GivenPlanners();
  GivenPlanners(const GivenPlanners&) = delete;
  GivenPlanners& operator=(const GivenPlanners&) = delete;

 private:
  const std::map<std::string, pybind11::object>* previous_;
};

/// The planner `planner` (a Python object) for `spec`, as campo.run gives it:
/// InputError when `spec` carries parameters (an override would be ignored).
std::unique_ptr<Planner> given_python_planner(const pybind11::object& planner, const PlannerSpec& spec);

/// Registers the "python" planner scheme: "python:package.module:ClassName"
/// imports the module, checks the class, and constructs it with the
/// planner's params as keyword arguments.
void register_python_scheme();

/// Binds campo.Command and campo.PlanResult.
void bind_plan_types(pybind11::module_& m);

}  // namespace campo::python
