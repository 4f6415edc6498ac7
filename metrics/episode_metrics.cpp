#include "metrics/episode_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <nlohmann/json.hpp>

#include "metrics/route_metrics.hpp"

namespace campo {

void count_decisions(std::span<const PlannerEvent> events, EpisodeMetrics& m) {
  int planned = 0, reached = 0, discarded = 0;
  std::vector<double> replan_ms;
  for (const PlannerEvent& e : events) {
    planned += e.decisions.planned_waypoint.has_value();
    reached += e.decisions.reached_intermediate.has_value();
    discarded += e.decisions.discarded_waypoint.has_value();
    if (e.decisions.replan) replan_ms.push_back(e.decisions.replan->time_ms);
  }
  m.waypoints_planned = planned;
  m.waypoints_reached = reached;
  m.waypoints_discarded = discarded;
  m.replans = static_cast<int>(replan_ms.size());
  m.replan_time_ms_median = 0.0;
  m.replan_time_ms_max = 0.0;
  if (replan_ms.empty()) return;
  std::sort(replan_ms.begin(), replan_ms.end());
  const std::size_t n = replan_ms.size();
  m.replan_time_ms_median = n % 2 ? replan_ms[n / 2] : 0.5 * (replan_ms[n / 2 - 1] + replan_ms[n / 2]);
  m.replan_time_ms_max = replan_ms.back();
}

double nominal_route_m(VehicleType type, const Eigen::Vector3d& start, std::span<const Waypoint> mission,
                       std::span<const std::optional<Eigen::Vector3d>> reached_at) {
  double nominal = 0.0;
  Eigen::Vector3d from = start;
  for (std::size_t i = 0; i < mission.size(); ++i) {
    const Eigen::Vector3d to = reached_at[i].value_or(mission[i].position_m);
    const Eigen::Vector3d leg = to - from;
    nominal += type == VehicleType::rover ? leg.head<2>().norm() : leg.norm();
    from = to;
  }
  return nominal;
}

double path_ratio(double path_length_m, double nominal_route_m) {
  return nominal_route_m > 1e-9 ? path_length_m / nominal_route_m : 0.0;
}

std::string body_name(const Scene& scene, int id) {
  if (is_vehicle_tag(id)) return scene.vehicles.at(vehicle_of_tag(id)).alias;
  if (id >= 0) return scene.shapes.at(static_cast<std::size_t>(id)).alias;
  return scene.movers.at(static_cast<std::size_t>(-1 - id)).shape.alias;
}

void ClearanceMinima::update(const Clearance& c, double t_s) {
  if (c.obstacle_m < obstacle_m) {
    obstacle_m = c.obstacle_m;
    obstacle = c.obstacle;
    obstacle_time_s = t_s;
  }
  ground_m = std::min(ground_m, c.ground_m);
}

void ClearanceMinima::write(const Scene& scene, EpisodeMetrics& m) const {
  m.min_clearance_m = obstacle_m;
  m.min_ground_clearance_m = ground_m;
  if (std::isfinite(obstacle_m)) {
    m.nearest_obstacle = body_name(scene, obstacle);
    m.min_clearance_time_s = obstacle_time_s;
  }
}

}  // namespace campo
