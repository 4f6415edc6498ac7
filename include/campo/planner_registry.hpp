#pragma once
/// The one list of planners: name -> factory. The built-in planners are one
/// file each plus one line in planners/planner_registry.cpp; planner plugins
/// add theirs through their one entry point when loaded (load_planner_plugin,
/// planners/plugin.cpp), and a program embedding campo its own
/// (add_linked_planners). Public, so an embedding program creates planners by
/// name exactly as `campo run` does (create_planner).
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "campo/planner.hpp"
#include "campo/plugin.hpp"

namespace campo {

/// The source of the planners compiled into libcampo.
inline constexpr std::string_view kBuiltInSource = "built-in";

struct PlannerEntry : PlannerRegistration {
  /// kBuiltInSource, or the absolute path of the plugin that registered it.
  std::string source = std::string(kBuiltInSource);
  std::string source_sha256;  ///< SHA-256 of the plugin file; empty for a built-in planner
};

/// Every planner: the built-in ones, then those of the plugins in the order
/// they were loaded.
std::vector<PlannerEntry> planner_registry();

/// A loaded planner plugin.
struct LoadedPlugin {
  std::string path;                   ///< absolute
  std::string sha256;                 ///< of the file as loaded
  std::vector<std::string> planners;  ///< the names it registered
};

/// Loads the planner plugin `path` (dlopen) and registers its planners. A
/// plugin already loaded (by this or another path to the same file) is not
/// loaded again. `origin` and `pointer` name where the plugin was asked for
/// (e.g. "command line" and "--plugin", or a sweep spec and "/plugins/0").
/// Throws InputError, naming the plugin file and what was expected, when it
/// cannot be loaded, is no campo plugin, was built against another plugin ABI
/// version, registers no planner or a name another planner has; nothing is
/// registered then. Not thread-safe: load plugins before starting threads.
LoadedPlugin load_planner_plugin(const std::filesystem::path& path, const std::string& origin,
                                 const std::string& pointer);

/// The plugins loaded so far, in load order.
std::vector<LoadedPlugin> loaded_plugins();

/// Adds planners compiled into a program that embeds campo (its own list, as
/// planners/planner_registry.cpp's), checked as a plugin's are; `source` names them in
/// --list-planners and provenance. Throws InputError at `source` on a problem.
void add_linked_planners(const std::vector<PlannerRegistration>& planners, const std::string& source);

/// Planners named "<scheme>:<rest>" are made by the scheme's handler rather
/// than looked up: "python:package.module:ClassName" is a Python class,
/// whose handler the Python module registers when imported (python/).
struct PlannerScheme {
  /// Makes the planner `spec.name` names; InputError at spec's pointers on a problem.
  PlannerMaker create;
  /// {"name", "source", "sha256"} of the planner `name` (planner_provenance).
  std::function<nlohmann::json(std::string_view name)> provenance;
};

/// Registers (or replaces) the handler of `scheme` ("python").
void register_planner_scheme(const std::string& scheme, PlannerScheme handler);

/// Name of the planner used when a vehicle names none.
inline constexpr std::string_view kDefaultPlanner = "straight";

/// Provenance of the planner `name` (kDefaultPlanner when empty): {"name",
/// "source"} and, for a plugin's planner, the plugin's "sha256", so that a
/// record names the code that produced it.
nlohmann::json planner_provenance(std::string_view name);

/// Gives a vehicle the planner `name` chosen outside its scene (`origin`
/// names where, e.g. "command line"): the scene's parameters stay when it is
/// the scene's planner; another planner starts from its defaults (the scene's
/// parameters belong to the planner it names).
void choose_planner(PlannerSpec& spec, std::string_view name, const std::string& origin);

/// Creates the planner `spec` names (kDefaultPlanner when empty); an unknown
/// name, or a vehicle type the planner does not declare, is an InputError at
/// the planner's params file/pointer.
std::unique_ptr<Planner> create_planner(const PlannerSpec& spec, const PlannerContext& context);

}  // namespace campo
