#include "python/bindings/python_planner.hpp"

#include <array>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <iterator>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

#include <pybind11/stl.h>

#include "campo/json_reader.hpp"
#include "campo/planner_registry.hpp"
#include "campo/scene_loader.hpp"
#include "python/bindings/observation.hpp"
#include "python/bindings/planner_limits.hpp"
#include "run/event_log.hpp"

namespace campo::python {

namespace py = pybind11;

nlohmann::json to_json(const py::handle& value) {
  const std::string text = py::module_::import("json").attr("dumps")(value, py::arg("allow_nan") = false).cast<std::string>();
  return nlohmann::json::parse(text);
}

py::object from_json(const nlohmann::json& value) { return py::module_::import("json").attr("loads")(value.dump()); }

std::string traceback_text(py::error_already_set& error) {
  try {
    const py::object lines = py::module_::import("traceback")
                                 .attr("format_exception")(error.type(), error.value(), error.trace());
    return py::str("").attr("join")(lines).cast<std::string>();
  } catch (const std::exception&) {
    return error.what();
  }
}

namespace {

// Lower bounds of the JSON text of a decision, by which a Python planner's
// decisions are bounded before they are copied into C++ (docs/python.md, "Limits").
constexpr std::size_t kKeyMaxBytes = kEventLineMaxBytes;          // one decision: more is never kept
constexpr std::size_t kDecisionsMaxBytes = 16 * kEventLineMaxBytes;  // all of them, after dropping those
constexpr int kDecisionsMaxDepth = 100;                           // nesting of lists and dicts

// A decision larger than its budget (a lower bound of its JSON text's size).
struct OverBudget {
  std::size_t bytes;
};

// numpy's array and scalar types (campo imports numpy: observations are numpy arrays).
const py::object& numpy_type(const char* name) {
  static const py::object ndarray = py::module_::import("numpy").attr("ndarray");
  static const py::object generic = py::module_::import("numpy").attr("generic");
  return std::string_view(name) == "ndarray" ? ndarray : generic;
}

// A dict key as json.dumps writes it: a str as it is, other scalars as their JSON text.
py::object key_text(const py::handle& key) {
  if (py::isinstance<py::str>(key)) return py::reinterpret_borrow<py::object>(key);
  if (key.is_none()) return py::str("null");
  if (py::isinstance<py::bool_>(key)) return py::str(key.cast<bool>() ? "true" : "false");
  if (py::isinstance<py::int_>(key) || py::isinstance<py::float_>(key)) {
    return py::module_::import("json").attr("dumps")(key, py::arg("allow_nan") = false);  // ValueError for nan
  }
  return py::reinterpret_borrow<py::object>(key);  // json.dumps refuses it with its TypeError
}

std::string key_string(const py::handle& key) { return py::isinstance<py::str>(key) ? key.cast<std::string>() : ""; }

// A copy of one decision as the record keeps it, made without converting
// what the record would not keep: every list, tuple or numpy array over
// kEventArrayMaxEntries entries thinned exactly as bound_decisions thins
// the record (the same entries kept, the same `thinned` note), so a
// million-point path costs what 2048 points do. OverBudget as soon as its
// JSON text certainly exceeds `budget` bytes.
class BoundedCopy {
 public:
  explicit BoundedCopy(std::size_t budget) : budget_(budget) {}

  py::dict thinned;       // JSON pointer -> original length
  std::size_t bytes = 0;  // a lower bound of the JSON text so far

  py::object copy(const py::handle& value, const std::string& at, int depth = 0) {
    if (depth > kDecisionsMaxDepth) {
      throw std::runtime_error("the planner's decisions nest lists and dicts deeper than " +
                               std::to_string(kDecisionsMaxDepth) + " levels, at " + at);
    }
    if (PyDict_Check(value.ptr())) {
      py::dict out;
      add(2);
      for (const auto& [key, item] : py::reinterpret_borrow<py::dict>(value)) {
        const py::object name = key_text(key);
        const std::string text = key_string(name);
        add(text.size() + 4);  // "key": and a comma
        out[name] = copy(item, child_pointer(at, text), depth + 1);
      }
      return out;
    }
    if (PyList_Check(value.ptr()) || PyTuple_Check(value.ptr())) {
      const py::sequence items = py::reinterpret_borrow<py::sequence>(value);
      return sequence(items.size(), [&](std::size_t i) { return py::object(items[i]); }, at, depth);
    }
    if (py::isinstance(value, numpy_type("ndarray"))) {
      const py::object array = py::module_::import("numpy").attr("asarray")(value);  // a subclass as a plain array
      if (array.attr("ndim").cast<int>() == 0) return array.attr("item")();
      const std::size_t n = array.attr("shape").cast<py::tuple>()[0].cast<std::size_t>();
      return sequence(n, [&](std::size_t i) { return py::object(array[py::int_(i)]); }, at, depth);
    }
    if (py::isinstance<py::str>(value)) {
      add(py::len(value) + 2);
      return py::reinterpret_borrow<py::object>(value);
    }
    add(1);  // a number, true, false, null: at least a character
    if (py::isinstance(value, numpy_type("generic"))) return value.attr("item")();
    return py::reinterpret_borrow<py::object>(value);
  }

 private:
  void add(std::size_t more) {
    bytes += more;
    if (bytes > budget_) throw OverBudget{bytes};
  }

  template <typename Item>
  py::list sequence(std::size_t n, const Item& item, const std::string& at, int depth) {
    py::list out;
    add(n > 0 ? std::min(n, kEventArrayMaxEntries) + 1 : 2);  // brackets and commas of what is kept
    if (n > kEventArrayMaxEntries) {
      // As thin_arrays (run/event_log.cpp): entry i of the k kept is round(i (n - 1) / (k - 1)).
      const std::size_t k = kEventArrayMaxEntries;
      thinned[py::str(at)] = n;
      for (std::size_t i = 0; i < k; ++i) {
        out.append(copy(item((i * (n - 1) + (k - 1) / 2) / (k - 1)), child_pointer(at, i), depth + 1));
      }
    } else {
      for (std::size_t i = 0; i < n; ++i) out.append(copy(item(i), child_pointer(at, i), depth + 1));
    }
    return out;
  }

  std::size_t budget_;
};

// The decisions record of `decisions` (a dict), bounded before it is
// converted: arrays thinned as the record thins them; a decision whose text
// certainly exceeds an events.jsonl line dropped, as the record would drop
// it, and noted in `omitted` with that lower bound of its size; refused
// (std::runtime_error) past kDecisionsMaxBytes in all.
nlohmann::json bounded_decisions_json(const py::dict& decisions) {
  py::dict kept;
  py::dict thinned;
  nlohmann::json omitted = nlohmann::json::object();
  std::size_t total = 2;
  for (const auto& [key, value] : decisions) {
    const py::object name = key_text(key);
    const std::string text = key_string(name);
    BoundedCopy one(kKeyMaxBytes);
    try {
      py::object copied = one.copy(value, child_pointer("", text), 1);
      total += one.bytes + text.size() + 4;
      if (total > kDecisionsMaxBytes) {
        throw std::runtime_error("the planner's decisions hold more than " + std::to_string(kDecisionsMaxBytes >> 20) +
                                 " MiB of JSON even with every array thinned to " +
                                 std::to_string(kEventArrayMaxEntries) + " entries (an events.jsonl line holds " +
                                 std::to_string(kEventLineMaxBytes >> 10) + " KiB; docs/python.md, Limits)");
      }
      kept[name] = std::move(copied);
      for (const auto& [pointer, count] : one.thinned) thinned[pointer] = count;
    } catch (const OverBudget& over) {
      omitted[text] = over.bytes;
    }
  }
  if (py::len(thinned) > 0) kept["thinned"] = thinned;
  nlohmann::json record = to_json(kept);
  if (!omitted.empty()) {
    bound_decisions(record);  // what remains, bounded as the record is
    nlohmann::json& note = record["omitted"];
    if (!note.is_object()) note = nlohmann::json::object();
    for (const auto& [key, bytes] : omitted.items()) note[key] = bytes;
  }
  return record;
}

}  // namespace

namespace {

// A field's type by its name in a declaration ("integer"); nullopt when no type has it.
std::optional<RecordType> record_type(const std::string& name) {
  for (RecordType t : {RecordType::flag, RecordType::integer, RecordType::number, RecordType::text, RecordType::array,
                       RecordType::object}) {
    if (to_string(t) == name) return t;
  }
  return std::nullopt;
}

}  // namespace

std::shared_ptr<const RecordFields> declared_decision_fields(const py::handle& planner, const std::string& who) {
  if (!py::hasattr(planner, "decision_fields")) return nullptr;
  const py::object declared = planner.attr("decision_fields");
  if (declared.is_none()) return nullptr;
  const std::string at = who + ".decision_fields";
  constexpr const char* kEntry = "(name, type, unit, meaning), four strings";
  if (py::isinstance<py::str>(declared) || !py::isinstance<py::sequence>(declared)) {
    throw std::invalid_argument(at + ": expected a list of " + std::string(kEntry) + ", got " +
                                py::repr(declared).cast<std::string>());
  }
  auto fields = std::make_shared<RecordFields>();
  const py::sequence entries = py::reinterpret_borrow<py::sequence>(declared);
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const py::object entry = entries[i];
    const std::string where = at + "[" + std::to_string(i) + "]";
    const auto refuse = [&](const std::string& expected) {
      throw std::invalid_argument(where + ": expected " + expected + ", got " + py::repr(entry).cast<std::string>());
    };
    if (py::isinstance<py::str>(entry) || !py::isinstance<py::sequence>(entry) || py::len(entry) != 4) refuse(kEntry);
    std::vector<std::string> parts;
    for (const py::handle part : py::reinterpret_borrow<py::sequence>(entry)) {
      if (!py::isinstance<py::str>(part)) refuse(kEntry);
      parts.push_back(part.cast<std::string>());
    }
    if (parts[0].empty()) refuse("a field with a name");
    const std::optional<RecordType> type = record_type(parts[1]);
    if (!type) refuse("a type of flag, integer, number, text, array or object");
    if (fields->find(parts[0])) refuse("a field declared once (\"" + parts[0] + "\" is declared before)");
    fields->declare_json({parts[0], *type, parts[2], parts[3]});
  }
  return fields;
}

PlanResult plan_result(const PlanResultBox& box, const RecordFields* fields) {
  PlanResult result;
  result.command = box.command.value;
  result.status = box.status;
  result.reason = box.reason;
  if (!box.decisions.is_none()) {
    if (!py::isinstance<py::dict>(box.decisions)) throw std::runtime_error("PlanResult.decisions: expected a dict or None");
    try {
      result.decisions = decisions_from_json(bounded_decisions_json(box.decisions), "PlanResult", "/decisions");
      if (fields) {
        // Its own keys through its declarations; the record's notes of what was bounded stay as they are.
        nlohmann::json own = std::exchange(result.decisions.own, nlohmann::json::object());
        for (auto& [key, value] : own.items()) {
          if (key == "thinned" || key == "omitted") {
            result.decisions.own[key] = std::move(value);
          } else {
            fields->set(result.decisions.own, key, std::move(value), "PlanResult", "/decisions");
          }
        }
      }
    } catch (const InputError& e) {
      throw std::runtime_error(std::string("the planner's decisions: ") + e.what());
    }
  }
  return result;
}

namespace {

class PythonPlanner final : public Planner {
 public:
  PythonPlanner(py::object planner, nlohmann::json parameters, std::unique_ptr<PlannerGuard> guard,
                std::shared_ptr<const RecordFields> fields)
      : planner_(std::move(planner)),
        plan_(planner_.attr("plan")),
        parameters_(std::move(parameters)),
        guard_(std::move(guard)),
        fields_(std::move(fields)) {}

  ~PythonPlanner() override {
    // Python objects die with the interpreter's lock held.
    py::gil_scoped_acquire gil;
    plan_ = py::object();
    planner_ = py::object();
  }

  PlanResult plan(const Observation& observation) override {
    py::gil_scoped_acquire gil;
    if (parameters_error_) throw std::runtime_error(*parameters_error_);
    if (!mission_) mission_ = mission_positions(observation.mission);
    py::object returned;
    {
      // Held to the limits while in Python; what it returned is converted after.
      GuardedCall call(*guard_, "plan()");
      try {
        returned = plan_(view_of(observation, mission_));
      } catch (py::error_already_set& e) {
        call.check();
        throw std::runtime_error("Python exception in plan():\n" + traceback_text(e));
      }
      call.check();
    }
    try {
      if (!py::isinstance<PlanResultBox>(returned)) {
        throw std::runtime_error("plan() returned " + py::repr(returned).cast<std::string>() +
                                 "; expected a campo.PlanResult");
      }
      return plan_result(returned.cast<const PlanResultBox&>(), fields_.get());
    } catch (py::error_already_set& e) {
      throw std::runtime_error("Python exception converting what plan() returned:\n" + traceback_text(e));
    }
  }

  // Asked once, before the first plan(); a failure here (an exception, a
  // limit) is recorded and ends the run as failed at the first plan().
  nlohmann::json parameters() const override {
    py::gil_scoped_acquire gil;
    if (!py::hasattr(planner_, "parameters")) return parameters_;
    try {
      GuardedCall call(*guard_, "parameters()");
      py::object returned;
      try {
        returned = planner_.attr("parameters")();
      } catch (py::error_already_set& e) {
        call.check();
        throw std::runtime_error("Python exception in parameters():\n" + traceback_text(e));
      }
      call.check();
      return to_json(returned);
    } catch (py::error_already_set& e) {
      parameters_error_ = "Python exception converting what parameters() returned:\n" + traceback_text(e);
    } catch (const std::runtime_error& e) {
      parameters_error_ = e.what();
    }
    return nlohmann::json{{"error", *parameters_error_}};
  }

 private:
  py::object planner_;
  py::object plan_;
  nlohmann::json parameters_;
  std::unique_ptr<PlannerGuard> guard_;
  std::shared_ptr<const RecordFields> fields_;  ///< its declared decision fields; null: its own keys are free
  mutable std::optional<std::string> parameters_error_;
  std::shared_ptr<const std::vector<Eigen::Vector3d>> mission_;
};

std::string file_sha256(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return sha256_hex(std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()));
}

// "python:package.module:ClassName" -> {"package.module", "ClassName"}; nullopt when malformed.
std::optional<std::pair<std::string, std::string>> split_python_name(std::string_view name) {
  constexpr std::string_view kPrefix = "python:";
  if (name.substr(0, kPrefix.size()) != kPrefix) return std::nullopt;
  const std::string_view rest = name.substr(kPrefix.size());
  const std::size_t colon = rest.rfind(':');
  if (colon == std::string_view::npos || colon == 0 || colon + 1 == rest.size()) return std::nullopt;
  return std::pair{std::string(rest.substr(0, colon)), std::string(rest.substr(colon + 1))};
}

// The class a "python:" name names.
py::object python_class(const std::string& module_name, const std::string& class_name) {
  py::object found = py::module_::import(module_name.c_str());
  // A qualified name ("Outer.Inner") walks attributes.
  std::size_t start = 0;
  while (start <= class_name.size()) {
    const std::size_t dot = class_name.find('.', start);
    found = found.attr(class_name.substr(start, dot - start).c_str());
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  return found;
}

// The objects the campo.run in progress gives its vehicles (GivenPlanners), or null.
const std::map<std::string, py::object>* given_planners = nullptr;

// The object given for the planner `spec` names in `context`, or null.
const py::object* given_planner(const PlannerSpec& spec, const PlannerContext& context) {
  if (!given_planners) return nullptr;
  for (const auto& entry : *given_planners) {
    if (context.vehicle_def && entry.first != context.vehicle_def->alias) continue;
    if (python_planner_name(entry.second) == spec.name) return &entry.second;
  }
  return nullptr;
}

std::unique_ptr<Planner> create_python_planner(const PlannerSpec& spec, const PlannerContext& context) {
  {
    py::gil_scoped_acquire gil;
    if (const py::object* given = given_planner(spec, context)) return given_python_planner(*given, spec);
  }
  const auto parts = split_python_name(spec.name);
  if (!parts) {
    throw InputError(spec.params.file, spec.name_pointer,
                     "a Python planner as \"python:package.module:ClassName\", not \"" + spec.name + "\"");
  }
  const auto& [module_name, class_name] = *parts;
  py::gil_scoped_acquire gil;
  py::object cls;
  try {
    cls = python_class(module_name, class_name);
  } catch (py::error_already_set& e) {
    throw InputError(spec.params.file, spec.name_pointer,
                     "an importable Python class " + module_name + ":" + class_name + " (on sys.path: the working "
                     "directory and PYTHONPATH); importing it failed:\n" + traceback_text(e));
  }
  if (!py::hasattr(cls, "plan")) {
    throw InputError(spec.params.file, spec.name_pointer,
                     "a Python planner class with a plan(self, obs) method; " + module_name + ":" + class_name +
                         " has none");
  }
  try {
    declared_decision_fields(cls, spec.name);
  } catch (const std::invalid_argument& e) {
    throw InputError(spec.params.file, spec.name_pointer, std::string("a Python planner's declaration: ") + e.what());
  }
  // The vehicle types it declares (class attribute `vehicles`), both by default.
  std::vector<std::string> vehicles{"quadrotor", "rover"};
  if (py::hasattr(cls, "vehicles")) vehicles = cls.attr("vehicles").cast<std::vector<std::string>>();
  const std::string vehicle(to_string(context.vehicle));
  if (std::find(vehicles.begin(), vehicles.end(), vehicle) == vehicles.end()) {
    std::string drives;
    for (const std::string& v : vehicles) drives += (drives.empty() ? "" : " or ") + v;
    throw InputError(spec.params.file, spec.params.pointer,
                     "planner " + spec.name + " drives a " + drives + " only, not a " + vehicle);
  }
  // The constructor is a call into the planner's code, held to the limits like plan().
  auto guard = std::make_unique<PlannerGuard>(spec.name, current_limits());
  try {
    const py::dict kwargs = from_json(spec.params.values);
    py::object planner;
    {
      GuardedCall call(*guard, "the constructor");
      try {
        planner = cls(**kwargs);
      } catch (py::error_already_set&) {
        call.check();
        throw;
      }
      call.check();
    }
    return wrap_python_planner(std::move(planner), spec.params.values, std::move(guard));
  } catch (const InputError&) {
    throw;
  } catch (const std::runtime_error& e) {
    // A constructor past a limit: the planner cannot be made with these params.
    throw InputError(spec.params.file, spec.params.pointer,
                     "parameters with which " + module_name + ":" + class_name + " can be made in time; " + e.what());
  } catch (py::error_already_set& e) {
    throw InputError(spec.params.file, spec.params.pointer,
                     "parameters " + module_name + ":" + class_name + " accepts (its constructor's keyword "
                     "arguments); constructing it failed:\n" + traceback_text(e));
  }
}

nlohmann::json python_planner_provenance(std::string_view name) {
  nlohmann::json provenance = {{"name", name}, {"source", nullptr}};
  const auto parts = split_python_name(name);
  if (!parts) return provenance;
  py::gil_scoped_acquire gil;
  try {
    const py::object module = py::module_::import(parts->first.c_str());
    if (py::hasattr(module, "__file__") && !module.attr("__file__").is_none()) {
      const std::string file = module.attr("__file__").cast<std::string>();
      provenance["source"] = file;
      provenance["sha256"] = file_sha256(file);
    }
  } catch (py::error_already_set&) {
    // An instance from a module that cannot be imported again (e.g. __main__ of a notebook): no source.
  }
  return provenance;
}

}  // namespace

std::unique_ptr<Planner> wrap_python_planner(py::object planner, nlohmann::json parameters,
                                             std::unique_ptr<PlannerGuard> guard) {
  if (!py::hasattr(planner, "plan")) throw std::invalid_argument("a planner needs a plan(self, obs) method");
  const std::string name = python_planner_name(planner);
  if (!guard) guard = std::make_unique<PlannerGuard>(name, current_limits());
  std::shared_ptr<const RecordFields> fields = declared_decision_fields(planner, name);
  return std::make_unique<PythonPlanner>(std::move(planner), std::move(parameters), std::move(guard),
                                         std::move(fields));
}

std::shared_ptr<const PlannerRecord> planner_record_of(std::string_view name) {
  if (const auto parts = split_python_name(name)) {
    const auto& [module_name, class_name] = *parts;
    py::object cls;
    try {
      cls = python_class(module_name, class_name);
    } catch (py::error_already_set& e) {
      throw InputError("planner", "", "an importable Python class " + module_name + ":" + class_name +
                                          "; importing it failed:\n" + traceback_text(e));
    }
    std::shared_ptr<const RecordFields> fields;
    try {
      fields = declared_decision_fields(cls, std::string(name));
    } catch (const std::invalid_argument& e) {
      throw InputError("planner", "", std::string("a Python planner's declaration: ") + e.what());
    }
    if (!fields) return nullptr;
    auto record = std::make_shared<PlannerRecord>();
    record->decisions = *fields;
    return record;
  }
  const std::string_view wanted = name.empty() ? kDefaultPlanner : name;
  std::string known;
  for (const PlannerEntry& entry : planner_registry()) {
    if (entry.name == wanted) {
      if (!entry.record) return nullptr;
      return std::shared_ptr<const PlannerRecord>(entry.record, [](const PlannerRecord*) {});  // the registry's own
    }
    known += (known.empty() ? "" : ", ") + entry.name;
  }
  throw InputError("planner", "", "a registered planner (" + known + ") or \"python:module:Class\", got \"" +
                                      std::string(name) + "\"");
}

GivenPlanners::GivenPlanners(const std::map<std::string, py::object>& by_alias) : previous_(given_planners) {
  given_planners = &by_alias;
}

GivenPlanners::~GivenPlanners() { given_planners = previous_; }

std::unique_ptr<Planner> given_python_planner(const py::object& planner, const PlannerSpec& spec) {
  // The object was built by the caller: overrides of the vehicle's planner parameters would be dropped.
  if (!spec.params.values.empty()) {
    throw InputError(spec.params.file, spec.params.pointer,
                     "a planner given as a Python object takes its parameters from its own constructor, not "
                     "from overrides (they would be ignored): got " + spec.params.values.dump());
  }
  return wrap_python_planner(planner, nlohmann::json::object());
}

std::string python_planner_name(const py::handle& planner) {
  const py::object cls = py::type::of(planner);
  return "python:" + cls.attr("__module__").cast<std::string>() + ":" + cls.attr("__qualname__").cast<std::string>();
}

void register_python_scheme() {
  register_planner_scheme("python", {&create_python_planner, &python_planner_provenance});
}

namespace {

// As Python prints them: nan, inf, -inf.
std::string number_text(double x) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  return py::repr(py::float_(x)).cast<std::string>();
}

std::string number_list(const std::vector<double>& v) {
  std::string text = "[";
  for (std::size_t i = 0; i < v.size(); ++i) text += (i ? ", " : "") + number_text(v[i]);
  return text + "]";
}

Eigen::Vector3d point(const py::handle& value, const char* name) {
  std::vector<double> v;
  try {
    v = py::cast<std::vector<double>>(py::module_::import("numpy").attr("asarray")(value, "float64").attr("ravel")());
  } catch (const std::exception&) {
    throw py::value_error(std::string(name) + ": expected 3 numbers (a list or a numpy array)");
  }
  if (v.size() != 3) throw py::value_error(std::string(name) + ": expected 3 numbers, got " + std::to_string(v.size()));
  for (const double x : v) {
    if (!std::isfinite(x)) throw py::value_error(std::string(name) + ": expected 3 finite numbers, got " + number_list(v));
  }
  return {v[0], v[1], v[2]};
}

// A number a command takes: finite (NaN or an infinity would turn the vehicle's state into NaN).
double finite(double value, const char* name) {
  if (!std::isfinite(value)) throw py::value_error(std::string(name) + ": expected a finite number, got " + number_text(value));
  return value;
}

// Four finite numbers (rotor or wheel speeds), from a list or a numpy array.
std::array<double, 4> four(const py::handle& value, const char* name) {
  std::vector<double> v;
  try {
    v = py::cast<std::vector<double>>(py::module_::import("numpy").attr("asarray")(value, "float64").attr("ravel")());
  } catch (const std::exception&) {
    throw py::value_error(std::string(name) + ": expected 4 numbers (a list or a numpy array)");
  }
  if (v.size() != 4) throw py::value_error(std::string(name) + ": expected 4 numbers, got " + std::to_string(v.size()));
  for (const double x : v) {
    if (!std::isfinite(x)) throw py::value_error(std::string(name) + ": expected 4 finite numbers, got " + number_list(v));
  }
  return {v[0], v[1], v[2], v[3]};
}

// The low-level commands, built from Python's arguments.
command::Velocity velocity_command(const py::handle& velocity_mps, double yaw_rate_radps) {
  return {point(velocity_mps, "velocity_mps"), finite(yaw_rate_radps, "yaw_rate_radps")};
}
command::AttitudeThrust attitude_thrust_command(double roll_rad, double pitch_rad, double yaw_rate_radps,
                                                double thrust_n) {
  return {finite(roll_rad, "roll_rad"), finite(pitch_rad, "pitch_rad"), finite(yaw_rate_radps, "yaw_rate_radps"),
          finite(thrust_n, "thrust_n")};
}
CommandBox attitude_thrust_command_box(double roll_rad, double pitch_rad, double yaw_rate_radps, double thrust_n) {
  return CommandBox{attitude_thrust_command(roll_rad, pitch_rad, yaw_rate_radps, thrust_n)};
}

// campo.Velocity, campo.AttitudeThrust, campo.Rotors, campo.Wheels: campo.Command subclasses built
// from their fields (so accepted wherever a Command is) whose fields read back.
struct VelocityBox : CommandBox {};
struct AttitudeThrustBox : CommandBox {};
struct RotorsBox : CommandBox {};
struct WheelsBox : CommandBox {};

py::tuple tuple_of(const double* values, std::size_t n) {
  py::tuple t(n);
  for (std::size_t i = 0; i < n; ++i) t[i] = py::float_(values[i]);
  return t;
}

std::string number_tuple(const double* values, std::size_t n) {
  std::string text = "(";
  for (std::size_t i = 0; i < n; ++i) text += (i ? ", " : "") + number_text(values[i]);
  return text + ")";
}

std::string command_repr(const Command& c) {
  if (const auto* v = std::get_if<command::Velocity>(&c)) {
    return "Velocity(velocity_mps=" + number_tuple(v->velocity_mps.data(), 3) +
           ", yaw_rate_radps=" + number_text(v->yaw_rate_radps) + ")";
  }
  if (const auto* a = std::get_if<command::AttitudeThrust>(&c)) {
    return "AttitudeThrust(roll_rad=" + number_text(a->roll_rad) + ", pitch_rad=" + number_text(a->pitch_rad) +
           ", yaw_rate_radps=" + number_text(a->yaw_rate_radps) + ", thrust_n=" + number_text(a->thrust_n) + ")";
  }
  if (const auto* r = std::get_if<command::Rotors>(&c)) {
    return "Rotors(speeds_radps=" + number_tuple(r->speeds_radps.data(), 4) + ")";
  }
  if (const auto* w = std::get_if<command::Wheels>(&c)) {
    return "Wheels(speeds_radps=" + number_tuple(w->speeds_radps.data(), 4) + ")";
  }
  return "Command." + std::string(command_name(c)) + "(...)";
}

PlanStatus status_of(const std::string& status) {
  for (PlanStatus s : {PlanStatus::running, PlanStatus::reached, PlanStatus::no_path, PlanStatus::invalid_start,
                       PlanStatus::aborted}) {
    if (to_string(s) == status) return s;
  }
  throw py::value_error("status: expected one of running, reached, no_path, invalid_start, aborted; got \"" +
                        status + "\"");
}

}  // namespace

void bind_plan_types(py::module_& m) {
  py::class_<CommandBox>(m, "Command", "A command for the vehicle (docs/extending.md, campo/vehicle.hpp).")
      .def_static("go_to",
                  [](const py::handle& target_m, double speed_mps, bool face_target) {
                    return CommandBox{command::GoTo{point(target_m, "target_m"), finite(speed_mps, "speed_mps"), face_target}};
                  },
                  py::arg("target_m"), py::arg("speed_mps") = 0.6, py::arg("face_target") = true,
                  "go to target_m in a straight line at no more than speed_mps (quadrotor: turning toward it)")
      .def_static("hold",
                  [](const py::handle& point_m, std::optional<double> yaw_rad) {
                    if (yaw_rad) finite(*yaw_rad, "yaw_rad");
                    return CommandBox{command::Hold{point(point_m, "point_m"), yaw_rad}};
                  },
                  py::arg("point_m"), py::arg("yaw_rad") = py::none(),
                  "stay at point_m (quadrotor: hover; rover: brake to a stop there)")
      .def_static("face", [](const py::handle& point_m) { return CommandBox{command::Face{point(point_m, "point_m")}}; },
                  py::arg("point_m"), "turn in place to face point_m")
      .def_static("altitude", [](double z_m) { return CommandBox{command::Altitude{finite(z_m, "z_m")}}; }, py::arg("z_m"),
                  "hold the horizontal position and climb or descend to z_m (quadrotor)")
      .def_static("twist", [](double v_mps, double w_radps) {
                    return CommandBox{command::Twist{finite(v_mps, "v_mps"), finite(w_radps, "w_radps")}};
                  },
                  py::arg("v_mps"), py::arg("w_radps"), "forward speed and yaw rate (rover)")
      .def_static("velocity",
                  [](const py::handle& velocity_mps, double yaw_rate_radps) {
                    return CommandBox{velocity_command(velocity_mps, yaw_rate_radps)};
                  },
                  py::arg("velocity_mps"), py::arg("yaw_rate_radps") = 0.0,
                  "fly at velocity_mps in the heading frame (x forward, y left, z up) turning at yaw_rate_radps "
                  "(quadrotor); as campo.Velocity")
      .def_static("attitude_thrust", &attitude_thrust_command_box, py::arg("roll_rad") = 0.0,
                  py::arg("pitch_rad") = 0.0, py::arg("yaw_rate_radps") = 0.0, py::arg("thrust_n") = 0.0,
                  "hold roll and pitch, turn at yaw_rate_radps, collective thrust thrust_n (quadrotor); as "
                  "campo.AttitudeThrust")
      .def_static("rotors", [](const py::handle& speeds_radps) { return CommandBox{command::Rotors{four(speeds_radps, "speeds_radps")}}; },
                  py::arg("speeds_radps"), "the four rotor speeds, rad/s (quadrotor); as campo.Rotors")
      .def_static("wheels", [](const py::handle& speeds_radps) { return CommandBox{command::Wheels{four(speeds_radps, "speeds_radps")}}; },
                  py::arg("speeds_radps"), "the four wheel motor speeds, rad/s (rover); as campo.Wheels")
      .def_property_readonly("kind", [](const CommandBox& c) { return std::string(command_name(c.value)); })
      .def("__repr__", [](const CommandBox& c) { return command_repr(c.value); });

  py::class_<VelocityBox, CommandBox>(
      m, "Velocity",
      "Quadrotor: fly at velocity_mps (m/s) in the heading frame (x along the heading projected on the ground, y to "
      "its left, z up) while turning at yaw_rate_radps (rad/s, counter-clockwise positive); capped at the "
      "controller's limits (docs/python.md, Commands).")
      .def(py::init([](const py::handle& velocity_mps, double yaw_rate_radps) {
             return VelocityBox{{velocity_command(velocity_mps, yaw_rate_radps)}};
           }),
           py::arg("velocity_mps") = py::make_tuple(0.0, 0.0, 0.0), py::arg("yaw_rate_radps") = 0.0)
      .def_property_readonly("velocity_mps", [](const VelocityBox& c) {
        return tuple_of(std::get<command::Velocity>(c.value).velocity_mps.data(), 3);
      })
      .def_property_readonly("yaw_rate_radps",
                             [](const VelocityBox& c) { return std::get<command::Velocity>(c.value).yaw_rate_radps; });

  py::class_<AttitudeThrustBox, CommandBox>(
      m, "AttitudeThrust",
      "Quadrotor: hold roll_rad and pitch_rad (of the body relative to the heading frame, R = Rz(heading) Ry(pitch) "
      "Rx(roll): positive pitch tilts the nose down and accelerates forward, positive roll the right side down and "
      "accelerates to the right), turn at yaw_rate_radps, collective thrust thrust_n (N). Tilt capped at the "
      "controller's max_tilt_deg, thrust at what the rotors give.")
      .def(py::init([](double roll_rad, double pitch_rad, double yaw_rate_radps, double thrust_n) {
             return AttitudeThrustBox{{attitude_thrust_command(roll_rad, pitch_rad, yaw_rate_radps, thrust_n)}};
           }),
           py::arg("roll_rad") = 0.0, py::arg("pitch_rad") = 0.0, py::arg("yaw_rate_radps") = 0.0,
           py::arg("thrust_n") = 0.0)
      .def_property_readonly("roll_rad", [](const AttitudeThrustBox& c) { return std::get<command::AttitudeThrust>(c.value).roll_rad; })
      .def_property_readonly("pitch_rad", [](const AttitudeThrustBox& c) { return std::get<command::AttitudeThrust>(c.value).pitch_rad; })
      .def_property_readonly("yaw_rate_radps",
                             [](const AttitudeThrustBox& c) { return std::get<command::AttitudeThrust>(c.value).yaw_rate_radps; })
      .def_property_readonly("thrust_n", [](const AttitudeThrustBox& c) { return std::get<command::AttitudeThrust>(c.value).thrust_n; });

  py::class_<RotorsBox, CommandBox>(
      m, "Rotors",
      "Quadrotor: the four rotor speed commands, rad/s, in rotor order (front-left, rear-left, rear-right, "
      "front-right), clamped to the motor range; they pass through the motor lag.")
      .def(py::init([](const py::handle& speeds_radps) {
             return RotorsBox{{command::Rotors{four(speeds_radps, "speeds_radps")}}};
           }),
           py::arg("speeds_radps"))
      .def_property_readonly("speeds_radps", [](const RotorsBox& c) {
        return tuple_of(std::get<command::Rotors>(c.value).speeds_radps.data(), 4);
      });

  py::class_<WheelsBox, CommandBox>(
      m, "Wheels",
      "Rover: the four wheel motor target speeds, rad/s, positive rolling forward, in the order front_left, "
      "front_right, rear_left, rear_right; clamped to the rover's max_wheel_speed_radps.")
      .def(py::init([](const py::handle& speeds_radps) {
             return WheelsBox{{command::Wheels{four(speeds_radps, "speeds_radps")}}};
           }),
           py::arg("speeds_radps"))
      .def_property_readonly("speeds_radps", [](const WheelsBox& c) {
        return tuple_of(std::get<command::Wheels>(c.value).speeds_radps.data(), 4);
      });

  py::class_<PlanResultBox>(m, "PlanResult", "What plan() returns: a command and a status, and optional decisions.")
      .def(py::init([](const CommandBox& command, const std::string& status, std::string reason, py::object decisions) {
             return PlanResultBox{command, status_of(status), std::move(reason), std::move(decisions)};
           }),
           py::arg("command"), py::arg("status") = "running", py::arg("reason") = "",
           py::arg("decisions") = py::none())
      .def_property_readonly("command", [](const PlanResultBox& r) { return r.command; })
      .def_property_readonly("status", [](const PlanResultBox& r) { return std::string(to_string(r.status)); })
      .def_readonly("reason", &PlanResultBox::reason)
      .def_readonly("decisions", &PlanResultBox::decisions);
}

}  // namespace campo::python
