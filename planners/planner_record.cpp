// planner_record (campo/planner_record.hpp): a planner's description of its
// record, found in the registry by the planner's name.
#include "campo/planner_record.hpp"

#include "campo/planner_registry.hpp"

namespace campo {

const PlannerRecord* planner_record(std::string_view name) {
  if (name.empty()) name = kDefaultPlanner;
  for (const PlannerEntry& entry : planner_registry()) {
    if (entry.name == name) return entry.record;
  }
  return nullptr;
}

}  // namespace campo
