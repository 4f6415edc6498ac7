#include "campo/planner_registry.hpp"

#include <algorithm>
#include <array>
#include <iterator>
#include <map>

#include <dlfcn.h>

#include "campo/json_reader.hpp"
#include "planners/depth_reactive.hpp"
#include "planners/dstar_lite_3d.hpp"
#include "planners/planner_admission.hpp"
#include "planners/rover_route.hpp"
#include "planners/straight.hpp"

namespace campo {

namespace {

namespace fs = std::filesystem;

constexpr VehicleType kQuadrotor = VehicleType::quadrotor;
constexpr VehicleType kRover = VehicleType::rover;

// The built-in planners, in --list-planners order.
std::vector<PlannerRegistration> built_in_planners() {
  return {
      {"straight", "head for each mission waypoint in turn in a straight line", &make_straight_planner,
       {kQuadrotor, kRover}},
      {"depth_reactive", "seed 000: reactive quadrotor navigation on dilated depth maps (TrovaWP, wall following)",
       &make_depth_reactive_planner, {kQuadrotor}, &depth_reactive_record().description},
      {"dstar_lite_3d", "seed 001: D* Lite on a LIDAR-mapped 3D grid, flying cell to cell", &make_dstar_lite_3d_planner,
       {kQuadrotor}, &dstar_lite_3d_record().description},
      {"rover_route", "seed 003: Dubins (or A*/RRT*) route, pure pursuit, follow-the-gap (or VFH+) avoidance",
       &make_rover_route_planner, {kRover}, &rover_route_record().description},
  };
}

/// The registry's state: the planners of plugins and of programs embedding campo, in order.
struct Registry {
  std::vector<PlannerEntry> added;
  std::map<std::string, PlannerScheme, std::less<>> schemes;
};

Registry& registry() {
  static Registry r;
  return r;
}

// Built-in planners, then those added so far.
std::vector<PlannerEntry> admitted_entries() {
  std::vector<PlannerEntry> entries;
  for (PlannerRegistration& p : built_in_planners()) entries.push_back({std::move(p), std::string(kBuiltInSource), ""});
  entries.insert(entries.end(), registry().added.begin(), registry().added.end());
  return entries;
}

// Names as scenes, specs and command lines write them.
bool valid_planner_name(const std::string& name) {
  return !name.empty() && name.size() <= 64 && std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
  });
}

// Checks the registrations of one source against each other and the planners
// registered so far; returns the problem ("" when none), to follow the source's
// name in a message.
std::string registration_problem(const std::vector<PlannerRegistration>& registrations) {
  const std::vector<PlannerEntry> known = admitted_entries();
  for (std::size_t i = 0; i < registrations.size(); ++i) {
    const PlannerRegistration& r = registrations[i];
    if (!valid_planner_name(r.name)) {
      return "registers a planner named \"" + r.name + "\"; expected a name of 1 to 64 letters, digits, '_' and '-'";
    }
    if (r.create == nullptr) return "registers planner \"" + r.name + "\" without a factory; expected a PlannerFactory";
    if (r.vehicles.empty()) {
      return "registers planner \"" + r.name + "\" for no vehicle type; expected at least one of quadrotor, rover";
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (registrations[j].name == r.name) return "registers planner \"" + r.name + "\" twice; expected each name once";
    }
    for (const PlannerEntry& e : known) {
      if (e.name != r.name) continue;
      const std::string other = e.source == kBuiltInSource ? std::string("the built-in planner of that name")
                                                           : "planner \"" + e.name + "\" of " + e.source;
      return "registers planner \"" + r.name + "\", a name already taken by " + other +
             "; expected a name no other planner has (rename one of them)";
    }
  }
  return "";
}

}  // namespace

std::vector<PlannerEntry> planner_registry() { return admitted_entries(); }

std::string admit_planners(const std::vector<PlannerRegistration>& planners, const std::string& source,
                           const std::string& sha256) {
  std::string problem = registration_problem(planners);
  if (!problem.empty()) return problem;
  for (const PlannerRegistration& r : planners) registry().added.push_back({r, source, sha256});
  return "";
}

void add_linked_planners(const std::vector<PlannerRegistration>& planners, const std::string& source) {
  const std::string problem = admit_planners(planners, source, "");
  if (!problem.empty()) throw InputError(source, "", problem);
}

void register_planner_scheme(const std::string& scheme, PlannerScheme handler) {
  registry().schemes[scheme] = std::move(handler);
}

namespace {

// The scheme of a name "scheme:rest", or empty.
std::string_view scheme_of(std::string_view name) {
  const std::size_t colon = name.find(':');
  return colon == std::string_view::npos ? std::string_view() : name.substr(0, colon);
}

// Python planners need an interpreter: a program that is not Python itself
// (campo run, a sweep's runs) loads libcampo_python, installed beside
// libcampo, which starts one and imports the campo module; the module
// registers the "python" scheme.
void load_python_support(const std::string& file, const std::string& pointer) {
  Dl_info info{};
  if (dladdr(reinterpret_cast<const void*>(&load_python_support), &info) == 0 || !info.dli_fname) {
    throw InputError(file, pointer, "a Python planner, but campo cannot find its own library to look for libcampo_python beside it");
  }
  const fs::path support = fs::path(info.dli_fname).parent_path() / "libcampo_python.so";
  std::error_code ec;
  if (!fs::exists(support, ec)) {
    throw InputError(file, pointer,
                     "a Python planner, but this campo was built without Python support (" + support.string() +
                         " is missing; build with pybind11-dev, python3-dev and python3-numpy installed)");
  }
  void* handle = dlopen(support.c_str(), RTLD_NOW | RTLD_GLOBAL);
  if (!handle) throw InputError(file, pointer, std::string("cannot load campo's Python support: ") + dlerror());
  using Start = int (*)(char* error, std::size_t size);
  const auto start = reinterpret_cast<Start>(dlsym(handle, "campo_python_start"));
  char error[4096] = "";
  if (!start) throw InputError(file, pointer, support.string() + " has no campo_python_start");
  if (start(error, sizeof error) != 0) throw InputError(file, pointer, std::string("cannot start Python: ") + error);
}

const PlannerScheme& scheme_handler(std::string_view scheme, const std::string& file, const std::string& pointer) {
  Registry& reg = registry();
  auto it = reg.schemes.find(scheme);
  if (it == reg.schemes.end() && scheme == "python") {
    load_python_support(file, pointer);
    it = reg.schemes.find(scheme);
  }
  if (it == reg.schemes.end()) {
    throw InputError(file, pointer,
                     "a planner name, or \"python:package.module:ClassName\"; no planners come from \"" +
                         std::string(scheme) + ":\"");
  }
  return it->second;
}

}  // namespace

nlohmann::json planner_provenance(std::string_view name) {
  if (name.empty()) name = kDefaultPlanner;
  if (const std::string_view scheme = scheme_of(name); !scheme.empty()) {
    const auto it = registry().schemes.find(scheme);
    if (it != registry().schemes.end() && it->second.provenance) return it->second.provenance(name);
    return {{"name", name}, {"source", nullptr}};
  }
  for (const PlannerEntry& entry : planner_registry()) {
    if (entry.name != name) continue;
    nlohmann::json provenance = {{"name", entry.name}, {"source", entry.source}};
    if (!entry.source_sha256.empty()) provenance["sha256"] = entry.source_sha256;
    return provenance;
  }
  return {{"name", name}, {"source", nullptr}};
}

void choose_planner(PlannerSpec& spec, std::string_view name, const std::string& origin) {
  if (name != spec.name) spec.params.values = nlohmann::json::object();
  spec.name = std::string(name);
  spec.name_pointer = "";
  spec.params.file = origin;
}

std::unique_ptr<Planner> create_planner(const PlannerSpec& spec, const PlannerContext& context) {
  const std::string_view name = spec.name.empty() ? kDefaultPlanner : std::string_view(spec.name);
  if (const std::string_view scheme = scheme_of(name); !scheme.empty()) {
    return scheme_handler(scheme, spec.params.file, spec.name_pointer).create(spec, context);
  }
  const std::vector<PlannerEntry> entries = planner_registry();
  for (const PlannerEntry& entry : entries) {
    if (entry.name != name) continue;
    if (std::find(entry.vehicles.begin(), entry.vehicles.end(), context.vehicle) == entry.vehicles.end()) {
      std::string drives;
      for (VehicleType v : entry.vehicles) drives += (drives.empty() ? "" : " or ") + std::string(to_string(v));
      throw InputError(spec.params.file, spec.params.pointer,
                       "planner " + entry.name + " drives a " + drives + " only, not a " +
                           std::string(to_string(context.vehicle)));
    }
    return entry.create(spec.params, context);
  }
  std::string known;
  for (const PlannerEntry& entry : entries) known += (known.empty() ? "" : ", ") + entry.name;
  throw InputError(spec.params.file, spec.name_pointer,
                   "unknown planner \"" + std::string(name) + "\"; expected one of: " + known +
                       " (a plugin's planner needs its plugin: --plugin PATH, or the sweep spec's \"plugins\")");
}

}  // namespace campo
