#include "planners/registry.hpp"

#include <algorithm>
#include <array>
#include <fstream>
#include <iterator>
#include <sstream>

#include <dlfcn.h>
#include <link.h>

#include "campo/json_reader.hpp"
#include "campo/scene_loader.hpp"
#include "campo/version.hpp"
#include "planners/depth_reactive.hpp"
#include "planners/dstar_lite_3d.hpp"
#include "planners/rover_route.hpp"
#include "planners/straight.hpp"
// The registration entry point's declaration, without the marker that makes a library a plugin.
#define CAMPO_PLUGIN_NO_MARKER
#include "campo/plugin.hpp"

namespace campo {

namespace {

namespace fs = std::filesystem;

struct BuiltInPlanner {
  std::string_view name;
  std::string_view description;
  PlannerFactory create;
};

constexpr std::array kBuiltInPlanners{
    BuiltInPlanner{"straight", "head for each mission waypoint in turn in a straight line", &make_straight_planner},
    BuiltInPlanner{"depth_reactive",
                   "seed 000: reactive quadrotor navigation on dilated depth maps (TrovaWP, wall following)",
                   &make_depth_reactive_planner},
    BuiltInPlanner{"dstar_lite_3d", "seed 001: D* Lite on a LIDAR-mapped 3D grid, flying cell to cell",
                   &make_dstar_lite_3d_planner},
    BuiltInPlanner{"rover_route",
                   "seed 003: Dubins (or A*/RRT*) route, pure pursuit, follow-the-gap (or VFH+) avoidance",
                   &make_rover_route_planner},
};

/// One call of campo_plugin_register_planner, as the plugin made it.
struct Registration {
  int abi_version = 0;
  std::string name;
  std::string description;
  PlannerFactory create = nullptr;
};

struct LoadedHandle {
  LoadedPlugin plugin;
  void* handle = nullptr;
};

/// The registry's state. Plugins register while dlopen runs their static
/// initializers: `loading` tells their registrations apart from those of code
/// linked into the program (a registrar outside any plugin), which are
/// admitted on the next use of the registry.
struct Registry {
  std::vector<PlannerEntry> added;  ///< planners of plugins and linked registrars, in order
  std::vector<LoadedHandle> plugins;
  bool loading = false;
  std::vector<Registration> loading_registrations;
  std::vector<Registration> linked_registrations;
};

Registry& registry() {
  static Registry r;
  return r;
}

// Built-in planners, then those admitted so far.
std::vector<PlannerEntry> admitted_entries() {
  std::vector<PlannerEntry> entries;
  for (const BuiltInPlanner& p : kBuiltInPlanners) {
    PlannerEntry entry;
    entry.name = p.name;
    entry.description = p.description;
    entry.create = p.create;
    entries.push_back(std::move(entry));
  }
  entries.insert(entries.end(), registry().added.begin(), registry().added.end());
  return entries;
}

// Names as scenes, specs and command lines write them.
bool valid_planner_name(const std::string& name) {
  return !name.empty() && name.size() <= 64 && std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
  });
}

std::string abi_mismatch(int built_for) {
  return "built against campo plugin ABI version " + std::to_string(built_for) + ", but this campo (" +
         std::string(library_version()) + ") loads plugin ABI version " + std::to_string(library_plugin_abi_version()) +
         ": rebuild it against this campo";
}

// Checks the registrations of one source against each other and the planners
// registered so far; returns the problem ("" when none), to follow the source's
// name in a message.
std::string registration_problem(const std::vector<Registration>& registrations) {
  const std::vector<PlannerEntry> known = admitted_entries();
  for (std::size_t i = 0; i < registrations.size(); ++i) {
    const Registration& r = registrations[i];
    if (r.abi_version != library_plugin_abi_version()) {
      return "registers planner \"" + r.name + "\" " + abi_mismatch(r.abi_version);
    }
    if (!valid_planner_name(r.name)) {
      return "registers a planner named \"" + r.name +
             "\"; expected a name of 1 to 64 letters, digits, '_' and '-'";
    }
    if (r.create == nullptr) return "registers planner \"" + r.name + "\" without a factory; expected a PlannerFactory";
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

void admit(const std::vector<Registration>& registrations, const std::string& source, const std::string& sha256) {
  for (const Registration& r : registrations) {
    registry().added.push_back({r.name, r.description, r.create, source, sha256});
  }
}

// Registrars that ran outside a plugin load: code linked into the program.
void admit_linked_registrations() {
  Registry& reg = registry();
  while (!reg.linked_registrations.empty()) {
    const Registration r = reg.linked_registrations.front();
    reg.linked_registrations.erase(reg.linked_registrations.begin());
    Dl_info info{};
    const std::string source = dladdr(reinterpret_cast<void*>(r.create), &info) != 0 && info.dli_fname != nullptr
                                   ? std::string(info.dli_fname)
                                   : std::string("the program");
    const std::string problem = registration_problem({r});
    if (!problem.empty()) throw InputError(source, "", problem);
    admit({r}, source, "");
  }
}

std::string file_sha256(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return sha256_hex(bytes.str());
}

}  // namespace

}  // namespace campo

extern "C" void campo_plugin_register_planner(int abi_version, const char* name, const char* description,
                                              campo::PlannerFactory factory) noexcept {
  campo::Registry& reg = campo::registry();
  try {
    (reg.loading ? reg.loading_registrations : reg.linked_registrations)
        .push_back({abi_version, name ? name : "", description ? description : "", factory});
  } catch (...) {
    // Out of memory during static initialization: the plugin then registers fewer planners, which the loader reports.
  }
}

namespace campo {

std::vector<PlannerEntry> planner_registry() {
  admit_linked_registrations();
  return admitted_entries();
}

LoadedPlugin load_planner_plugin(const fs::path& path, const std::string& origin, const std::string& pointer) {
  admit_linked_registrations();
  Registry& reg = registry();
  const fs::path file = fs::absolute(path).lexically_normal();
  const auto fail = [&](const std::string& problem) {
    throw InputError(origin, pointer, "plugin " + file.string() + ": " + problem);
  };
  for (const LoadedHandle& loaded : reg.plugins) {
    if (loaded.plugin.path == file.string()) return loaded.plugin;
  }

  reg.loading = true;
  reg.loading_registrations.clear();
  dlerror();
  void* handle = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
  reg.loading = false;
  const std::vector<Registration> registrations = std::move(reg.loading_registrations);
  reg.loading_registrations.clear();
  if (handle == nullptr) {
    const char* error = dlerror();
    fail("cannot load it (" + std::string(error ? error : "dlopen failed") +
         "); expected a planner plugin: a shared library built against campo (docs/extending.md)");
  }
  // The same file under another path: dlopen returns the handle it loaded before and runs nothing again.
  for (const LoadedHandle& loaded : reg.plugins) {
    if (loaded.handle == handle) {
      dlclose(handle);
      return loaded.plugin;
    }
  }
  const auto refuse = [&](const std::string& problem) {
    dlclose(handle);
    fail(problem);
  };

  // The marker must be the plugin's own: dlsym also searches the libraries it depends on.
  dlerror();
  const void* marker = dlsym(handle, "campo_plugin_abi_version");
  link_map* map = nullptr;
  Dl_info where{};
  const bool own_marker = marker != nullptr && dlinfo(handle, RTLD_DI_LINKMAP, &map) == 0 && map != nullptr &&
                          dladdr(marker, &where) != 0 && where.dli_fname != nullptr &&
                          std::string(where.dli_fname) == map->l_name;
  if (!own_marker) {
    refuse("not a campo planner plugin: it does not define the symbol campo_plugin_abi_version; expected a shared "
           "library whose sources include campo/plugin.hpp and register planners with CAMPO_REGISTER_PLANNER");
  }
  const int abi_version = *static_cast<const int*>(marker);
  if (abi_version != library_plugin_abi_version()) refuse(abi_mismatch(abi_version));
  if (registrations.empty()) {
    refuse("registers no planner; expected at least one CAMPO_REGISTER_PLANNER(name, description, factory) in its "
           "sources");
  }
  const std::string problem = registration_problem(registrations);
  if (!problem.empty()) refuse(problem);

  LoadedHandle loaded;
  loaded.plugin.path = file.string();
  loaded.plugin.sha256 = file_sha256(file);
  for (const Registration& r : registrations) loaded.plugin.planners.push_back(r.name);
  loaded.handle = handle;
  admit(registrations, loaded.plugin.path, loaded.plugin.sha256);
  reg.plugins.push_back(loaded);
  return loaded.plugin;
}

std::vector<LoadedPlugin> loaded_plugins() {
  std::vector<LoadedPlugin> plugins;
  for (const LoadedHandle& loaded : registry().plugins) plugins.push_back(loaded.plugin);
  return plugins;
}

nlohmann::json planner_provenance(std::string_view name) {
  if (name.empty()) name = kDefaultPlanner;
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
  const std::vector<PlannerEntry> entries = planner_registry();
  for (const PlannerEntry& entry : entries) {
    if (entry.name == name) return entry.create(spec.params, context);
  }
  std::string known;
  for (const PlannerEntry& entry : entries) known += (known.empty() ? "" : ", ") + entry.name;
  throw InputError(spec.params.file, spec.name_pointer,
                   "unknown planner \"" + std::string(name) + "\"; expected one of: " + known +
                       " (a plugin's planner needs its plugin: --plugin PATH, or the sweep spec's \"plugins\")");
}

}  // namespace campo
