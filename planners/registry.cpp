#include "planners/registry.hpp"

#include <array>

#include "campo/json_reader.hpp"
#include "planners/depth_reactive.hpp"
#include "planners/dstar_lite_3d.hpp"
#include "planners/rover_route.hpp"
#include "planners/straight.hpp"

namespace campo {

namespace {

constexpr VehicleType kBoth[] = {VehicleType::quadrotor, VehicleType::rover};
constexpr VehicleType kQuadrotor[] = {VehicleType::quadrotor};
constexpr VehicleType kRover[] = {VehicleType::rover};

constexpr std::array kPlanners{
    PlannerEntry{"straight", "head for each mission waypoint in turn in a straight line", &make_straight_planner, kBoth},
    PlannerEntry{"depth_reactive", "seed 000: reactive quadrotor navigation on dilated depth maps (TrovaWP, wall following)",
                 &make_depth_reactive_planner, kQuadrotor},
    PlannerEntry{"dstar_lite_3d", "seed 001: D* Lite on a LIDAR-mapped 3D grid, flying cell to cell", &make_dstar_lite_3d_planner, kQuadrotor},
    PlannerEntry{"rover_route", "seed 003: Dubins (or A*/RRT*) route, pure pursuit, follow-the-gap (or VFH+) avoidance",
                 &make_rover_route_planner, kRover},
};

}  // namespace

std::span<const PlannerEntry> planner_registry() { return kPlanners; }

void choose_planner(PlannerSpec& spec, std::string_view name, const std::string& origin) {
  if (name != spec.name) spec.params.values = nlohmann::json::object();
  spec.name = std::string(name);
  spec.name_pointer = "";
  spec.params.file = origin;
}

std::unique_ptr<Planner> create_planner(const PlannerSpec& spec, const PlannerContext& context) {
  const std::string_view name = spec.name.empty() ? kDefaultPlanner : std::string_view(spec.name);
  for (const PlannerEntry& entry : kPlanners) {
    if (entry.name == name) return entry.create(spec.params, context);
  }
  std::string known;
  for (const PlannerEntry& entry : kPlanners) known += (known.empty() ? "" : ", ") + std::string(entry.name);
  throw InputError(spec.params.file, spec.name_pointer,
                   "unknown planner \"" + std::string(name) + "\"; expected one of: " + known);
}

}  // namespace campo
