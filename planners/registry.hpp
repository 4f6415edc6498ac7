#pragma once
/// The one list of planners: name -> factory. Adding a planner is one file
/// plus one line in registry.cpp.
#include <memory>
#include <span>
#include <string>
#include <string_view>

#include "campo/planner.hpp"

namespace campo {

/// Builds a planner from its parameters; throws InputError (naming the
/// params block's file and pointer) for bad parameters.
using PlannerFactory = std::unique_ptr<Planner> (*)(const ParamsBlock& params, const PlannerContext& context);

struct PlannerEntry {
  std::string_view name;
  std::string_view description;
  PlannerFactory create;
  /// The vehicle types it drives; creating it for another is an InputError.
  std::span<const VehicleType> vehicles;
};

std::span<const PlannerEntry> planner_registry();

/// Name of the planner used when a vehicle names none.
inline constexpr std::string_view kDefaultPlanner = "straight";

/// Gives a vehicle the planner `name` chosen outside its scene (`origin`
/// names where, e.g. "command line"): the scene's parameters stay when it is
/// the scene's planner; another planner starts from its defaults (the scene's
/// parameters belong to the planner it names).
void choose_planner(PlannerSpec& spec, std::string_view name, const std::string& origin);

/// Creates the planner `spec` names (kDefaultPlanner when empty); an unknown
/// name is an InputError at the planner's params file/pointer.
std::unique_ptr<Planner> create_planner(const PlannerSpec& spec, const PlannerContext& context);

}  // namespace campo
