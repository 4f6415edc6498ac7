#include "campo/planner.hpp"

namespace campo {

std::string_view to_string(PlanStatus status) {
  static constexpr std::string_view kNames[] = {"running", "reached", "no_path", "invalid_start", "aborted"};
  return kNames[static_cast<int>(status)];
}

const SensorReading* Observation::sensor(std::string_view alias) const {
  for (const SensorReading& r : sensors) {
    if (alias.empty() || r.alias == alias) return &r;
  }
  return nullptr;
}

}  // namespace campo
