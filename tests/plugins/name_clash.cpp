// Fixture plugin: registers a planner under the name of a built-in one.
#include "campo/plugin.hpp"

namespace {
std::unique_ptr<campo::Planner> make_nothing(const campo::ParamsBlock&, const campo::PlannerContext&) {
  return nullptr;
}
}  // namespace

CAMPO_REGISTER_PLANNERS(registrar) {
  registrar.add({"straight", "fixture: a second \"straight\"", &make_nothing, {campo::VehicleType::quadrotor}});
}
