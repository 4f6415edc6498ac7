// Fixture plugin: includes campo/plugin.hpp (so it carries the plugin marker)
// but registers no planner: CAMPO_REGISTER_PLANNER was forgotten.
#include "campo/plugin.hpp"

namespace {
std::unique_ptr<campo::Planner> make_nothing(const campo::ParamsBlock&, const campo::PlannerContext&) {
  return nullptr;
}
}  // namespace

// The factory exists, its registration does not.
extern "C" __attribute__((visibility("default"))) campo::PlannerFactory fixture_unregistered_factory() {
  return &make_nothing;
}
