// What campo/episode_record.hpp declares: the names of the outcomes, run.json's
// metrics, and the measures taken on the planner's decisions (cross_track_error:
// the distance of every trajectory sample to the route the planner had recorded
// by then; avoiding_time).
#include "campo/episode_record.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <span>
#include <vector>

#include <Eigen/Geometry>

namespace campo {

namespace {

// Exact horizontal distance to a polyline, in about log time per query: a
// binary tree of bounding boxes over halves of the segment index range (a
// route is spatially coherent, so consecutive segments make tight boxes),
// searched branch and bound starting from the previous query's nearest
// segment, which successive trajectory samples mostly share.
class RouteDistance {
 public:
  explicit RouteDistance(std::vector<Eigen::Vector2d> points) : points_(std::move(points)) {
    if (points_.size() == 1) points_.push_back(points_.front());  // one point: a zero-length segment
    nodes_.reserve(2 * (points_.size() - 1) / kLeafSegments + 2);
    build(0, points_.size() - 1);
  }

  double squared_distance(const Eigen::Vector2d& q) {
    double best = segment_squared_distance(q, hint_);
    std::vector<std::size_t>& stack = stack_;
    stack.assign(1, 0);
    while (!stack.empty()) {
      const Node& node = nodes_[stack.back()];
      stack.pop_back();
      if (box_squared_distance(q, node.box) >= best) continue;
      if (node.left == kNone) {
        for (std::size_t s = node.first; s < node.last; ++s) {
          const double d = segment_squared_distance(q, s);
          if (d < best) {
            best = d;
            hint_ = s;
          }
        }
        continue;
      }
      // The nearer child last, so that it is searched first.
      const double l = box_squared_distance(q, nodes_[node.left].box);
      const double r = box_squared_distance(q, nodes_[node.right].box);
      const std::size_t left = node.left, right = node.right;
      if (l < r) {
        stack.push_back(right);
        stack.push_back(left);
      } else {
        stack.push_back(left);
        stack.push_back(right);
      }
    }
    return best;
  }

 private:
  static constexpr std::size_t kLeafSegments = 8;
  static constexpr std::size_t kNone = static_cast<std::size_t>(-1);
  struct Node {
    Eigen::AlignedBox2d box;
    std::size_t first = 0, last = 0;  // segments [first, last)
    std::size_t left = kNone, right = kNone;
  };

  // Builds the node of segments [first, last) and returns its index.
  std::size_t build(std::size_t first, std::size_t last) {
    const std::size_t index = nodes_.size();
    nodes_.push_back({Eigen::AlignedBox2d(), first, last, kNone, kNone});
    if (last - first <= kLeafSegments) {
      Eigen::AlignedBox2d box;
      for (std::size_t i = first; i <= last; ++i) box.extend(points_[i]);
      nodes_[index].box = box;
      return index;
    }
    const std::size_t middle = first + (last - first) / 2;
    const std::size_t left = build(first, middle);
    const std::size_t right = build(middle, last);
    nodes_[index].left = left;
    nodes_[index].right = right;
    nodes_[index].box = nodes_[left].box.merged(nodes_[right].box);
    return index;
  }

  double segment_squared_distance(const Eigen::Vector2d& q, std::size_t s) const {
    const Eigen::Vector2d& a = points_[s];
    const Eigen::Vector2d d = points_[s + 1] - a;
    const double length2 = d.squaredNorm();
    const double t = length2 > 0.0 ? std::clamp((q - a).dot(d) / length2, 0.0, 1.0) : 0.0;
    return (a + t * d - q).squaredNorm();
  }

  static double box_squared_distance(const Eigen::Vector2d& q, const Eigen::AlignedBox2d& box) {
    const Eigen::Vector2d outside = (box.min() - q).cwiseMax(q - box.max()).cwiseMax(0.0);
    return outside.squaredNorm();
  }

  std::vector<Eigen::Vector2d> points_;
  std::vector<Node> nodes_;
  std::vector<std::size_t> stack_;
  std::size_t hint_ = 0;
};

// The (x, y) of a planned path's points.
std::vector<Eigen::Vector2d> route_points(const std::vector<Eigen::Vector3d>& path) {
  std::vector<Eigen::Vector2d> points;
  points.reserve(path.size());
  for (const Eigen::Vector3d& p : path) points.push_back(p.head<2>());
  return points;
}

}  // namespace

CrossTrack cross_track_error(std::span<const TrajectorySample> trajectory, std::span<const PlannerEvent> events) {
  CrossTrack result;
  std::optional<RouteDistance> route;
  const std::vector<Eigen::Vector3d>* pending = nullptr;  // the latest planned path, built when a sample needs it
  std::size_t e = 0;
  double sum = 0.0, sum_squares = 0.0, max_squared = 0.0;
  for (const TrajectorySample& s : trajectory) {
    for (; e < events.size() && events[e].time_s <= s.time_s; ++e) {
      if (const auto& path = events[e].decisions.planned_path) pending = &*path;
    }
    if (pending) {
      std::vector<Eigen::Vector2d> points = route_points(*pending);
      if (points.empty()) route.reset();
      else route.emplace(std::move(points));
      pending = nullptr;
    }
    if (!route) continue;
    const double d2 = route->squared_distance(s.state.position_m.head<2>());
    sum += std::sqrt(d2);
    sum_squares += d2;
    max_squared = std::max(max_squared, d2);
    ++result.samples;
  }
  if (result.samples > 0) {
    result.rms_m = std::sqrt(sum_squares / static_cast<double>(result.samples));
    result.mean_m = sum / static_cast<double>(result.samples);
    result.max_m = std::sqrt(max_squared);
  }
  return result;
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
  static constexpr std::string_view kNames[] = {"reached", "collision", "timeout", "aborted", "failed", "stopped"};
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
  // The fields other rooms declare (metrics/mission_metrics.hpp), beside these; json sorts the keys.
  if (m.declared.is_object()) j.update(m.declared);
  for (const VehicleSeparation& s : m.separations) {
    const bool measured = std::isfinite(s.min_distance_m);
    j["min_distance_to_" + s.other + "_m"] = measured ? nlohmann::json(s.min_distance_m) : nlohmann::json();
    j["min_distance_to_" + s.other + "_time_s"] = measured ? nlohmann::json(s.min_distance_time_s) : nlohmann::json();
  }
  return j;
}

nlohmann::json to_json(const FleetMetrics& m) {
  const bool measured = std::isfinite(m.min_vehicle_distance_m);
  return {
      {"outcome", to_string(m.outcome)},
      {"reason", m.reason},
      {"vehicles", m.vehicles},
      {"vehicles_reached", m.vehicles_reached},
      {"all_reached", m.all_reached},
      {"any_collision", m.any_collision},
      {"collisions", m.collisions},
      {"makespan_s", std::isnan(m.makespan_s) ? nlohmann::json() : nlohmann::json(m.makespan_s)},
      {"min_vehicle_distance_m", measured ? nlohmann::json(m.min_vehicle_distance_m) : nlohmann::json()},
      {"min_vehicle_distance_pair", measured ? nlohmann::json(m.min_vehicle_distance_pair) : nlohmann::json()},
      {"min_vehicle_distance_time_s", measured ? nlohmann::json(m.min_vehicle_distance_time_s) : nlohmann::json()},
      {"sim_time_s", m.sim_time_s},
      {"wall_time_s", m.wall_time_s},
  };
}

}  // namespace campo
