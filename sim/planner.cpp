#include "sim/planner.hpp"

namespace campo {

std::string_view to_string(PlanStatus status) {
  static constexpr std::string_view kNames[] = {"running", "reached", "no_path", "invalid_start", "aborted"};
  return kNames[static_cast<int>(status)];
}

}  // namespace campo
