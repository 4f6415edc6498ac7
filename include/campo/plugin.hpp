#pragma once
/// Planner plugins (docs/extending.md): a shared library, built against an
/// installed campo (a CMake MODULE library linked to campo::campo), whose
/// planners campo loads at run time (`campo run --plugin PATH`, a sweep spec's
/// "plugins"). A plugin has one entry point, defined once in one of its
/// sources with CAMPO_REGISTER_PLANNERS, that adds its planners:
///
///     CAMPO_REGISTER_PLANNERS(registrar) {
///       registrar.add({"bug2", "go to goal, follow obstacles' edges", &make_bug2_planner,
///                      {campo::VehicleType::quadrotor}});
///     }
///
/// The loader first asks the plugin which CAMPO_PLUGIN_ABI_VERSION it was
/// compiled against and refuses it unless that is this campo's, then calls
/// the entry point once; nothing runs at load time (no static registrars).
#include <string>
#include <vector>

#include "campo/planner.hpp"
#include "campo/planner_record.hpp"
#include "campo/version.hpp"

namespace campo {

/// A planner as a plugin (or the built-in list) declares it.
struct PlannerRegistration {
  std::string name;         ///< what scenes and --planner use: 1 to 64 letters, digits, '_' and '-'
  std::string description;  ///< one line, for campo run --list-planners
  PlannerFactory create = nullptr;
  /// The vehicle types it drives; creating it for another is an InputError
  /// naming the planner's params block (the factory need not check).
  std::vector<VehicleType> vehicles;
  /// What it records beyond the generic decisions, and the overlays its
  /// figures draw (campo/planner_record.hpp); null for none. Must outlive the
  /// registration (a function-local static).
  const PlannerRecord* record = nullptr;
};

/// What a plugin's entry point receives. The loader checks every planner
/// added (name, factory, vehicle types, no clash with another planner) after
/// the entry point returns, and refuses the whole plugin on any problem.
class PlannerRegistrar {
 public:
  virtual void add(PlannerRegistration planner) = 0;

 protected:
  ~PlannerRegistrar() = default;
};

}  // namespace campo

/// Defines the plugin's exported entry point `campo_plugin_register_planners`
/// and its ABI marker `campo_plugin_abi_version`; follow it with the body
/// that adds the planners to `registrar` (a campo::PlannerRegistrar&). Use it
/// once per plugin, at namespace scope.
#define CAMPO_REGISTER_PLANNERS(registrar)                                                             \
  extern "C" __attribute__((visibility("default"))) int campo_plugin_abi_version() noexcept {          \
    return CAMPO_PLUGIN_ABI_VERSION;                                                                   \
  }                                                                                                    \
  extern "C" __attribute__((visibility("default"))) void campo_plugin_register_planners(               \
      ::campo::PlannerRegistrar& registrar)
