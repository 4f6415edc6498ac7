#include "python/bindings/python_planner.hpp"

#include <fstream>
#include <iterator>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

#include <pybind11/stl.h>

#include "campo/json_reader.hpp"
#include "campo/scene_loader.hpp"
#include "planners/registry.hpp"
#include "python/bindings/observation.hpp"
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

PlanResult plan_result(const PlanResultBox& box) {
  PlanResult result;
  result.command = box.command.value;
  result.status = box.status;
  result.reason = box.reason;
  if (!box.decisions.is_none()) {
    if (!py::isinstance<py::dict>(box.decisions)) throw std::runtime_error("PlanResult.decisions: expected a dict or None");
    try {
      result.decisions = decisions_from_json(to_json(box.decisions), "PlanResult", "/decisions");
    } catch (const InputError& e) {
      throw std::runtime_error(std::string("the planner's decisions: ") + e.what());
    }
  }
  return result;
}

namespace {

class PythonPlanner final : public Planner {
 public:
  PythonPlanner(py::object planner, nlohmann::json parameters)
      : planner_(std::move(planner)), plan_(planner_.attr("plan")), parameters_(std::move(parameters)) {}

  ~PythonPlanner() override {
    // Python objects die with the interpreter's lock held.
    py::gil_scoped_acquire gil;
    plan_ = py::object();
    planner_ = py::object();
  }

  PlanResult plan(const Observation& observation) override {
    py::gil_scoped_acquire gil;
    if (!mission_) mission_ = mission_positions(observation.mission);
    try {
      const py::object returned = plan_(view_of(observation, mission_));
      if (!py::isinstance<PlanResultBox>(returned)) {
        throw std::runtime_error("plan() returned " + py::repr(returned).cast<std::string>() +
                                 "; expected a campo.PlanResult");
      }
      return plan_result(returned.cast<const PlanResultBox&>());
    } catch (py::error_already_set& e) {
      throw std::runtime_error("Python exception in plan():\n" + traceback_text(e));
    }
  }

  nlohmann::json parameters() const override {
    py::gil_scoped_acquire gil;
    if (!py::hasattr(planner_, "parameters")) return parameters_;
    try {
      return to_json(planner_.attr("parameters")());
    } catch (py::error_already_set& e) {
      throw std::runtime_error("Python exception in parameters():\n" + traceback_text(e));
    }
  }

 private:
  py::object planner_;
  py::object plan_;
  nlohmann::json parameters_;
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

std::unique_ptr<Planner> create_python_planner(const PlannerSpec& spec, const PlannerContext& context) {
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
  try {
    const py::dict kwargs = from_json(spec.params.values);
    return wrap_python_planner(cls(**kwargs), spec.params.values);
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

std::unique_ptr<Planner> wrap_python_planner(py::object planner, nlohmann::json parameters) {
  if (!py::hasattr(planner, "plan")) throw std::invalid_argument("a planner needs a plan(self, obs) method");
  return std::make_unique<PythonPlanner>(std::move(planner), std::move(parameters));
}

std::string python_planner_name(const py::handle& planner) {
  const py::object cls = py::type::of(planner);
  return "python:" + cls.attr("__module__").cast<std::string>() + ":" + cls.attr("__qualname__").cast<std::string>();
}

void register_python_scheme() {
  register_planner_scheme("python", {&create_python_planner, &python_planner_provenance});
}

namespace {

Eigen::Vector3d point(const py::handle& value, const char* name) {
  std::vector<double> v;
  try {
    v = py::cast<std::vector<double>>(py::module_::import("numpy").attr("asarray")(value, "float64").attr("ravel")());
  } catch (const std::exception&) {
    throw py::value_error(std::string(name) + ": expected 3 numbers (a list or a numpy array)");
  }
  if (v.size() != 3) throw py::value_error(std::string(name) + ": expected 3 numbers, got " + std::to_string(v.size()));
  return {v[0], v[1], v[2]};
}

std::string command_repr(const Command& c) {
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
                    return CommandBox{command::GoTo{point(target_m, "target_m"), speed_mps, face_target}};
                  },
                  py::arg("target_m"), py::arg("speed_mps") = 0.6, py::arg("face_target") = true,
                  "go to target_m in a straight line at no more than speed_mps (quadrotor: turning toward it)")
      .def_static("hold",
                  [](const py::handle& point_m, std::optional<double> yaw_rad) {
                    return CommandBox{command::Hold{point(point_m, "point_m"), yaw_rad}};
                  },
                  py::arg("point_m"), py::arg("yaw_rad") = py::none(),
                  "stay at point_m (quadrotor: hover; rover: brake to a stop there)")
      .def_static("face", [](const py::handle& point_m) { return CommandBox{command::Face{point(point_m, "point_m")}}; },
                  py::arg("point_m"), "turn in place to face point_m")
      .def_static("altitude", [](double z_m) { return CommandBox{command::Altitude{z_m}}; }, py::arg("z_m"),
                  "hold the horizontal position and climb or descend to z_m (quadrotor)")
      .def_static("twist", [](double v_mps, double w_radps) { return CommandBox{command::Twist{v_mps, w_radps}}; },
                  py::arg("v_mps"), py::arg("w_radps"), "forward speed and yaw rate (rover)")
      .def_property_readonly("kind", [](const CommandBox& c) { return std::string(command_name(c.value)); })
      .def("__repr__", [](const CommandBox& c) { return command_repr(c.value); });

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
