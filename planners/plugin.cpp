// Planner plugins (campo/plugin.hpp): loading a plugin's shared library,
// checking its ABI version and asking its one entry point for its planners,
// which the registry (campo/planner_registry.hpp) then admits.
#include "campo/plugin.hpp"

#include <exception>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <dlfcn.h>
#include <link.h>

#include "campo/json_reader.hpp"
#include "campo/planner_registry.hpp"
#include "campo/scene_loader.hpp"
#include "campo/version.hpp"
#include "planners/planner_admission.hpp"

namespace campo {

namespace {

namespace fs = std::filesystem;

// Collects what a plugin's entry point adds.
class CollectingRegistrar final : public PlannerRegistrar {
 public:
  void add(PlannerRegistration planner) override { added.push_back(std::move(planner)); }
  std::vector<PlannerRegistration> added;
};

struct LoadedHandle {
  LoadedPlugin plugin;
  void* handle = nullptr;
};

// The plugins loaded so far, in load order.
std::vector<LoadedHandle>& plugins() {
  static std::vector<LoadedHandle> loaded;
  return loaded;
}

std::string abi_mismatch(int built_for) {
  return "built against campo plugin ABI version " + std::to_string(built_for) + ", but this campo (" +
         std::string(library_version()) + ") loads plugin ABI version " + std::to_string(library_plugin_abi_version()) +
         ": rebuild it against this campo";
}

// The address of `symbol` in the plugin `handle` itself, or null: dlsym also searches the
// libraries a plugin depends on, whose symbols are not the plugin's.
void* own_symbol(void* handle, const char* symbol) {
  dlerror();
  void* address = dlsym(handle, symbol);
  link_map* map = nullptr;
  Dl_info where{};
  const bool own = address != nullptr && dlinfo(handle, RTLD_DI_LINKMAP, &map) == 0 && map != nullptr &&
                   dladdr(address, &where) != 0 && where.dli_fname != nullptr &&
                   std::string(where.dli_fname) == map->l_name;
  return own ? address : nullptr;
}

std::string file_sha256(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return sha256_hex(bytes.str());
}

}  // namespace

LoadedPlugin load_planner_plugin(const fs::path& path, const std::string& origin, const std::string& pointer) {
  std::vector<LoadedHandle>& loaded_handles = plugins();
  if (path.empty()) throw InputError(origin, pointer, "expected the path of a plugin (a shared library), got an empty string");
  const fs::path file = fs::absolute(path).lexically_normal();
  const auto fail = [&](const std::string& problem) {
    throw InputError(origin, pointer, "plugin " + file.string() + ": " + problem);
  };
  for (const LoadedHandle& loaded : loaded_handles) {
    if (loaded.plugin.path == file.string()) return loaded.plugin;
  }

  dlerror();
  void* handle = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (handle == nullptr) {
    const char* error = dlerror();
    fail("cannot load it (" + std::string(error ? error : "dlopen failed") +
         "); expected a planner plugin: a shared library built against campo (docs/extending.md)");
  }
  // The same file under another path: dlopen returns the handle it loaded before and runs nothing again.
  for (const LoadedHandle& loaded : loaded_handles) {
    if (loaded.handle == handle) {
      dlclose(handle);
      return loaded.plugin;
    }
  }
  const auto refuse = [&](const std::string& problem) {
    dlclose(handle);
    fail(problem);
  };

  using AbiVersion = int (*)() noexcept;
  using Register = void (*)(PlannerRegistrar&);
  const auto abi = reinterpret_cast<AbiVersion>(own_symbol(handle, "campo_plugin_abi_version"));
  if (abi == nullptr) {
    refuse("not a campo planner plugin: it does not define the symbol campo_plugin_abi_version; expected a shared "
           "library with one CAMPO_REGISTER_PLANNERS(registrar) { ... } (campo/plugin.hpp) in its sources");
  }
  const int abi_version = abi();
  if (abi_version != library_plugin_abi_version()) refuse(abi_mismatch(abi_version));
  const auto register_planners = reinterpret_cast<Register>(own_symbol(handle, "campo_plugin_register_planners"));
  if (register_planners == nullptr) {
    refuse("defines campo_plugin_abi_version but not the symbol campo_plugin_register_planners; expected both from "
           "CAMPO_REGISTER_PLANNERS(registrar) { ... } (campo/plugin.hpp)");
  }
  CollectingRegistrar registrar;
  try {
    register_planners(registrar);
  } catch (const std::exception& e) {
    refuse(std::string("threw while registering its planners: ") + e.what());
  }
  const std::vector<PlannerRegistration>& registrations = registrar.added;
  if (registrations.empty()) {
    refuse("registers no planner; expected at least one registrar.add({name, description, factory, vehicles}) in "
           "its CAMPO_REGISTER_PLANNERS body");
  }
  LoadedHandle loaded;
  loaded.plugin.path = file.string();
  loaded.plugin.sha256 = file_sha256(file);
  for (const PlannerRegistration& r : registrations) loaded.plugin.planners.push_back(r.name);
  loaded.handle = handle;
  const std::string problem = admit_planners(registrations, loaded.plugin.path, loaded.plugin.sha256);
  if (!problem.empty()) refuse(problem);
  loaded_handles.push_back(loaded);
  return loaded.plugin;
}

std::vector<LoadedPlugin> loaded_plugins() {
  std::vector<LoadedPlugin> out;
  for (const LoadedHandle& loaded : plugins()) out.push_back(loaded.plugin);
  return out;
}

}  // namespace campo
