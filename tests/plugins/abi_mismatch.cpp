// Fixture plugin: built as if against a campo with another plugin ABI version.
#include "campo/version.hpp"
#undef CAMPO_PLUGIN_ABI_VERSION
#define CAMPO_PLUGIN_ABI_VERSION 999
#include "campo/plugin.hpp"

namespace {
std::unique_ptr<campo::Planner> make_nothing(const campo::ParamsBlock&, const campo::PlannerContext&) {
  return nullptr;
}
}  // namespace

CAMPO_REGISTER_PLANNERS(registrar) {
  registrar.add({"fixture_other_abi", "fixture: built for plugin ABI 999", &make_nothing, {campo::VehicleType::quadrotor}});
}
