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

void leg_and_gate_metrics(const VehicleDef& def, const Eigen::Vector3d& start,
                          std::span<const TrajectorySample> trajectory,
                          std::span<const std::optional<std::size_t>> reached_sample, EpisodeMetrics& m) {
  std::vector<Eigen::Vector3d> points;
  std::vector<double> agl_m;
  for (const TrajectorySample& s : trajectory) {
    points.push_back(s.state.position_m);
    agl_m.push_back(s.height_above_ground_m);
  }
  const std::span<const Eigen::Vector3d> all(points);
  for (std::size_t k = 0; k < def.mission.size(); ++k) {
    LegMetrics& leg = m.legs.emplace_back();
    const std::optional<std::size_t> first = k == 0 ? std::optional<std::size_t>(0) : reached_sample[k - 1];
    const std::optional<std::size_t> last = reached_sample[k];
    if (!first || !last || *last < *first || *last >= points.size()) continue;
    const auto flown = all.subspan(*first, *last - *first + 1);
    leg.path_length_m = polyline_length_m(flown);
    const Eigen::Vector3d from = k == 0 ? start : def.mission[k - 1].position_m;
    leg.lateral_before_climb_m = lateral_before_climb_m(flown, from, def.mission[k].position_m);
  }
  for (const MissionGate& gate : def.gates) {
    GateMetrics& g = m.gates.emplace_back();
    g.name = gate.name;
    if (const auto i = first_inside(points, agl_m, gate.area_m, gate.max_agl_m)) g.time_s = trajectory[*i].time_s;
  }
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

double avoiding_time(std::span<const PlannerEvent> events, double end_time_s) {
  double total = 0.0;
  bool on = false;
  double since = 0.0;
  for (const PlannerEvent& e : events) {
    if (!e.decisions.avoiding) continue;
    const bool now = *e.decisions.avoiding;
    if (now && !on) since = e.time_s;
    if (!now && on) total += e.time_s - since;
    on = now;
  }
  if (on) total += std::max(0.0, end_time_s - since);
  return total;
}

namespace {

nlohmann::json collision_events_json(const std::vector<CollisionEvent>& events) {
  nlohmann::json list = nlohmann::json::array();
  for (const CollisionEvent& e : events) {
    list.push_back({{"time_s", e.time_s},
                    {"body", e.body},
                    {"ground", e.ground},
                    {"point_m", {e.point_m.x(), e.point_m.y(), e.point_m.z()}}});
  }
  return list;
}

}  // namespace

std::string_view to_string(Outcome outcome) {
  static constexpr std::string_view kNames[] = {"reached", "collision", "timeout", "aborted", "failed"};
  return kNames[static_cast<int>(outcome)];
}

nlohmann::json to_json(const EpisodeMetrics& m) {
  nlohmann::json j = {
      {"outcome", to_string(m.outcome)},
      {"reason", m.reason},
      {"sim_time_s", m.sim_time_s},
      {"wall_time_s", m.wall_time_s},
      {"path_length_m", m.path_length_m},  // the distance travelled
      {"path_ratio", m.path_ratio},
      // null when the scene has no obstacles at all
      {"min_clearance_m", std::isfinite(m.min_clearance_m) ? nlohmann::json(m.min_clearance_m) : nlohmann::json()},
      {"nearest_obstacle", m.nearest_obstacle.empty() ? nlohmann::json() : nlohmann::json(m.nearest_obstacle)},
      {"min_clearance_time_s", m.nearest_obstacle.empty() ? nlohmann::json() : nlohmann::json(m.min_clearance_time_s)},
      {"min_ground_clearance_m",
       std::isfinite(m.min_ground_clearance_m) ? nlohmann::json(m.min_ground_clearance_m) : nlohmann::json()},
      {"collisions", m.collisions},
      {"collision_events", collision_events_json(m.collision_events)},
      {"planner_calls", m.planner_calls},
      {"planner_time_ms_mean", m.planner_time_ms_mean},
      {"planner_time_ms_max", m.planner_time_ms_max},
      {"waypoints_planned", m.waypoints_planned},
      {"waypoints_reached", m.waypoints_reached},
      {"waypoints_discarded", m.waypoints_discarded},
      {"replans", m.replans},
      {"replan_time_ms_median", m.replan_time_ms_median},
      {"replan_time_ms_max", m.replan_time_ms_max},
      {"cross_track_rms_m", m.cross_track_rms_m},
      {"cross_track_mean_m", m.cross_track_mean_m},
      {"cross_track_max_m", m.cross_track_max_m},
      {"avoiding_time_s", m.avoiding_time_s},
  };
  const auto optional = [](const std::optional<double>& v) { return v ? nlohmann::json(*v) : nlohmann::json(); };
  for (std::size_t k = 0; k < m.legs.size(); ++k) {
    const std::string leg = "leg" + std::to_string(k);
    j[leg + "_path_length_m"] = optional(m.legs[k].path_length_m);
    j[leg + "_lateral_before_climb_m"] = optional(m.legs[k].lateral_before_climb_m);
  }
  for (const GateMetrics& gate : m.gates) {
    j["gate_" + gate.name + "_passed"] = gate.time_s.has_value();
    j["gate_" + gate.name + "_time_s"] = optional(gate.time_s);
  }
  return j;
}

}  // namespace campo
