#include "planners/rover_route.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <functional>
#include <memory>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <unordered_set>
#include <vector>

#include "campo/json_reader.hpp"
#include "campo/random.hpp"
#include "grid/astar.hpp"
#include "planners/dubins.hpp"

namespace campo {

namespace {

using Clock = std::chrono::steady_clock;

// ---------------------------------------------------------------- parameters

// One list of fields per nested configuration serves reading and writing.
struct FieldReader {
  ObjectReader& r;
  void operator()(std::string_view key, double& v, const Range& range) { r.read(key, v, range); }
  void operator()(std::string_view key, int& v, std::int64_t lo, std::int64_t hi) { r.read(key, v, lo, hi); }
  void operator()(std::string_view key, std::uint64_t& v) { r.read_seed(key, v); }
  void operator()(std::string_view key, bool& v) { r.read(key, v); }
};

struct FieldWriter {
  nlohmann::json& j;
  void operator()(std::string_view key, double v, const Range&) { j[std::string(key)] = v; }
  void operator()(std::string_view key, int v, std::int64_t, std::int64_t) { j[std::string(key)] = v; }
  void operator()(std::string_view key, std::uint64_t v) { j[std::string(key)] = v; }
  void operator()(std::string_view key, bool v) { j[std::string(key)] = v; }
};

template <class Visit>
void fields(PurePursuitConfig& c, Visit&& f) {
  f("lookahead_m", c.lookahead_m, Range::positive());
  f("turn_gain_per_s", c.turn_gain_per_s, Range::positive());
  f("max_yaw_rate_rad_s", c.max_yaw_rate_rad_s, Range::positive());
  f("max_speed_m_s", c.max_speed_m_s, Range::closed(0.01, 10.0));
  f("min_speed_m_s", c.min_speed_m_s, Range::closed(0.0, 10.0));
  f("slowdown_turn_error_rad", c.slowdown_turn_error_rad, Range::positive());
  f("goal_tolerance_m", c.goal_tolerance_m, Range::positive());
}

template <class Visit>
void fields(FollowTheGapConfig& c, Visit&& f) {
  f("activation_range_m", c.activation_range_m, Range::positive());
  f("bubble_radius_m", c.bubble_radius_m, Range::positive());
  f("gap_jump_m", c.gap_jump_m, Range::positive());
  f("free_range_m", c.free_range_m, Range::non_negative());
  f("grow_gap_edges", c.grow_gap_edges);
  f("alpha_m", c.alpha_m, Range::non_negative());
  f("k_width", c.k_width, Range::non_negative());
  f("k_heading", c.k_heading, Range::non_negative());
  f("hysteresis_bonus", c.hysteresis_bonus, Range::non_negative());
}

template <class Visit>
void fields(VfhPlusConfig& c, Visit&& f) {
  f("sectors", c.sectors, 4, 3600);
  f("window_radius_m", c.window_radius_m, Range::positive());
  f("magnitude_a", c.magnitude_a, Range{1.0});
  f("robot_radius_m", c.robot_radius_m, Range::non_negative());
  f("safety_distance_m", c.safety_distance_m, Range::non_negative());
  f("threshold_low", c.threshold_low, Range::non_negative());
  f("threshold_high", c.threshold_high, Range::non_negative());
  f("min_turning_radius_m", c.min_turning_radius_m, Range::non_negative());
  f("wide_opening_sectors", c.wide_opening_sectors, 1, 3600);
  f("mu_target", c.mu_target, Range::non_negative());
  f("mu_heading", c.mu_heading, Range::non_negative());
  f("mu_previous", c.mu_previous, Range::non_negative());
}

template <class Visit>
void fields(RrtStarConfig& c, Visit&& f) {
  f("seed", c.seed);
  f("step_m", c.step_m, Range::positive());
  f("rewire_radius_m", c.rewire_radius_m, Range::non_negative());
  f("rewire_gamma_m", c.rewire_gamma_m, Range::non_negative());
  f("goal_radius_m", c.goal_radius_m, Range::positive());
  f("goal_bias", c.goal_bias, Range::closed(0.0, 1.0));
  f("max_iterations", c.max_iterations, 0, 10'000'000);
}

template <class Config>
void read_nested(ObjectReader& r, std::string_view key, Config& c) {
  if (const auto node = r.optional(key)) {
    ObjectReader nested(*node);
    fields(c, FieldReader{nested});
    nested.finish();
  }
}

template <class Config>
nlohmann::json write_nested(Config c) {
  nlohmann::json j = nlohmann::json::object();
  fields(c, FieldWriter{j});
  return j;
}

constexpr std::array<std::string_view, 3> kGlobalNames{"dubins", "astar", "rrt_star"};
constexpr std::array<std::string_view, 3> kLocalNames{"follow_the_gap", "vfh_plus", "none"};

// ---------------------------------------------------------------- routes

// Poses the route passes: the vehicle's start (unless the first waypoint is
// there) and the mission waypoints, headed as given or toward the next one.
std::vector<dubins::Pose2> route_poses(const Eigen::Vector2d& start, double start_yaw_rad,
                                       std::span<const Waypoint> mission, double tolerance_m) {
  std::vector<Eigen::Vector2d> points;
  std::vector<std::optional<double>> headings;
  if (mission.empty() || (mission.front().position_m.head<2>() - start).norm() > tolerance_m) {
    points.push_back(start);
    headings.push_back(start_yaw_rad);
  }
  for (const Waypoint& w : mission) {
    points.push_back(w.position_m.head<2>());
    headings.push_back(w.heading_deg ? std::optional(*w.heading_deg * M_PI / 180.0) : std::nullopt);
  }
  std::vector<dubins::Pose2> poses;
  for (std::size_t i = 0; i < points.size(); ++i) {
    double heading = 0.0;
    if (headings[i]) {
      heading = *headings[i];
    } else {
      const Eigen::Vector2d d = i + 1 < points.size() ? points[i + 1] - points[i] : points[i] - points[i - 1];
      heading = std::atan2(d.y(), d.x());
    }
    poses.push_back({points[i].x(), points[i].y(), heading});
  }
  return poses;
}

std::vector<dubins::Pose2> route_poses(const Observation& o, double tolerance_m) {
  return route_poses(o.state.position_m.head<2>(), o.state.yaw_rad(), o.mission, tolerance_m);
}

// A number for messages: 0.1 -> "0.1", 25200400 -> "25200400".
std::string format_number(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.10g", value);
  return buffer;
}

// Points dubins::sample_route makes of `path` at `step_m` (the junction with
// the previous path counted there), as a double so that no extent overflows.
double sampled_points(const dubins::Path& path, double step_m) { return std::ceil(path.length_m() / step_m); }

// The first pose whose Dubins path from the previous one takes the route past
// kMaxRoutePoints, or nullopt.
std::optional<std::size_t> dubins_route_overflow(const std::vector<dubins::Pose2>& poses, const RoverRouteConfig& c) {
  double points = 1.0;
  for (std::size_t i = 1; i < poses.size(); ++i) {
    points += sampled_points(dubins::shortest_path(poses[i - 1], poses[i], c.turning_radius_m), c.route_step_m);
    if (!(points <= static_cast<double>(kMaxRoutePoints))) return i;
  }
  return std::nullopt;
}

std::vector<Eigen::Vector2d> dubins_route(const std::vector<dubins::Pose2>& poses, const RoverRouteConfig& c) {
  std::vector<Eigen::Vector2d> out;
  const std::vector<dubins::Path> paths = dubins::route(poses, c.turning_radius_m);
  for (const dubins::Pose2& p : dubins::sample_route(paths, c.route_step_m)) out.emplace_back(p.x_m, p.y_m);
  return out;
}

// One leg of a grid route between two free points: a polyline from a to b, or nothing.
using LegPlanner = std::function<std::optional<std::vector<Eigen::Vector2d>>(
    std::size_t leg, const Eigen::Vector2d& a, const Eigen::Vector2d& b)>;

// Grid route through the poses, leg by leg, each leg leaving its waypoint and
// reaching the next one straight along their headings for `lead_m` (where that
// stretch is free): a search between the waypoints themselves would round the
// headland corner over the row end, too tight to drive. Each leg is shortcut
// on its own, so the leads stay; collinear points are dropped so the fillets
// get the whole straight runs.
std::optional<std::vector<Eigen::Vector2d>> grid_route(const OccupancyGrid& grid, const std::vector<dubins::Pose2>& poses,
                                                      double lead_m, const LegPlanner& plan_leg) {
  const auto at = [](const dubins::Pose2& p) { return Eigen::Vector2d(p.x_m, p.y_m); };
  const auto ahead = [](const dubins::Pose2& p) { return Eigen::Vector2d(std::cos(p.heading_rad), std::sin(p.heading_rad)); };
  std::vector<Eigen::Vector2d> path;
  for (std::size_t i = 0; i + 1 < poses.size(); ++i) {
    const Eigen::Vector2d a = at(poses[i]), b = at(poses[i + 1]);
    Eigen::Vector2d a_lead = a + lead_m * ahead(poses[i]), b_lead = b - lead_m * ahead(poses[i + 1]);
    if (!grid.segment_free(a, a_lead)) a_lead = a;
    if (!grid.segment_free(b_lead, b)) b_lead = b;
    const auto leg = plan_leg(i, a_lead, b_lead);
    if (!leg) return std::nullopt;
    std::vector<Eigen::Vector2d> piece{a};
    const std::vector<Eigen::Vector2d> middle = shortcut_path(grid, *leg);
    piece.insert(piece.end(), middle.begin(), middle.end());
    piece.push_back(b);
    for (const Eigen::Vector2d& q : piece) {
      if (!path.empty() && (q - path.back()).norm() <= 1e-9) continue;
      // Drop the last point when it lies on the straight line from its predecessor to q.
      if (path.size() >= 2) {
        const Eigen::Vector2d u = path.back() - path[path.size() - 2], v = q - path.back();
        if (std::abs(u.x() * v.y() - u.y() * v.x()) <= 1e-9 * u.norm() * v.norm() && u.dot(v) > 0.0) path.pop_back();
      }
      path.push_back(q);
    }
  }
  return path;
}

// A* (8-connected, no corner cutting) on the inflated occupancy grid.
LegPlanner astar_legs(const OccupancyGrid& grid) {
  auto graph = std::make_shared<grid::GridGraph>(grid::GridSize{grid.cols, grid.rows, 1}, grid::Connectivity::eight);
  for (int row = 0; row < grid.rows; ++row) {
    for (int col = 0; col < grid.cols; ++col) {
      if (grid.is_occupied(col, row)) graph->set_state({col, row, 0}, grid::CellState::blocked);
    }
  }
  return [&grid, graph](std::size_t, const Eigen::Vector2d& from, const Eigen::Vector2d& to)
             -> std::optional<std::vector<Eigen::Vector2d>> {
    const Eigen::Vector2i a = grid.cell_of(from), b = grid.cell_of(to);
    if (!grid.contains(a.x(), a.y()) || !grid.contains(b.x(), b.y())) return std::nullopt;
    grid::AStar astar(*graph);
    const grid::SearchResult leg = astar.plan({a.x(), a.y(), 0}, {b.x(), b.y(), 0});
    if (leg.status != grid::SearchStatus::found) return std::nullopt;
    // From and to themselves rather than their cells' centres.
    std::vector<Eigen::Vector2d> path{from};
    for (std::size_t k = 1; k + 1 < leg.path.size(); ++k) path.push_back(grid.centre_of(leg.path[k].x, leg.path[k].y));
    path.push_back(to);
    return path;
  };
}

LegPlanner rrt_star_legs(const OccupancyGrid& grid, const RrtStarConfig& config) {
  return [&grid, config](std::size_t i, const Eigen::Vector2d& from, const Eigen::Vector2d& to)
             -> std::optional<std::vector<Eigen::Vector2d>> {
    RrtStarConfig leg_config = config;
    leg_config.seed = Rng::derive_seed(config.seed, i);
    const RrtStarResult leg = rrt_star(grid, from, to, leg_config);
    if (leg.status != RrtStarStatus::solved) return std::nullopt;
    std::vector<Eigen::Vector2d> path = leg.path_m;
    // The tree stops inside the goal region: end on the goal itself.
    path.push_back(to);
    return path;
  };
}

// ---------------------------------------------------------------- the planner

class RoverRoutePlanner final : public Planner {
 public:
  RoverRoutePlanner(const RoverRouteConfig& config, const PlannerContext& context)
      : config_(config), scene_(context.scene) {}

  PlanResult plan(const Observation& o) override {
    PlanResult result;
    result.command = command::Hold{o.state.position_m, std::nullopt};
    const SensorReading* scanner = o.sensor(config_.sensor);
    if (config_.local != LocalAvoidance::none && !scanner) {
      result.status = PlanStatus::invalid_start;
      result.reason = config_.sensor.empty() ? "the vehicle has no sensor for obstacle avoidance"
                                             : "the vehicle has no sensor \"" + config_.sensor + "\"";
      return result;
    }
    if (route_.empty() && !build_route(o, result)) return result;

    const Eigen::Vector2d position = o.state.position_m.head<2>();
    const double heading = o.state.yaw_rad();
    // A waypoint is passed within tolerance, or once pursuit is past the
    // route point nearest it (a smoothed route may cut its corner).
    while (next_ < o.mission.size() &&
           ((o.mission[next_].position_m.head<2>() - position).norm() <= config_.waypoint_tolerance_m ||
            pursuit_.last_found_index >= waypoint_route_index_[next_])) {
      result.decisions.reached_waypoints.push_back(static_cast<int>(next_++));
    }

    if (scanner && scanner->fresh && scanner->scan) {
      remember(*scanner->scan, *scanner->config, position);
      assess_scan(*scanner, position, heading);
      if (!gap_record_.is_null()) result.decisions.extras["gap"] = std::move(gap_record_);
      gap_record_ = nullptr;
    }
    if (avoiding_ != last_avoiding_) {
      result.decisions.avoiding = avoiding_;
      last_avoiding_ = avoiding_;
      // Back on the route: pursue from the route point nearest the rover, ahead of where it left.
      if (!avoiding_) rejoin(position);
    }

    const PurePursuitStep step = pure_pursuit_step(config_.pure_pursuit, pursuit_, position, heading, route_);
    if (step.end_reached && next_ >= o.mission.size()) {
      result.status = PlanStatus::reached;
      result.reason = "route complete: all " + std::to_string(o.mission.size()) + " waypoints passed";
      return result;
    }
    double v = step.speed_m_s, w = step.yaw_rate_rad_s;
    if (avoiding_) {
      // Steer for the local planner's heading, slower, turning in place when blocked close ahead.
      const double error = wrap_to_pi(avoid_heading_rad_);
      w = std::clamp(config_.avoid_turn_gain * error, -config_.pure_pursuit.max_yaw_rate_rad_s,
                     config_.pure_pursuit.max_yaw_rate_rad_s);
      v = config_.avoid_speed_mps * std::max(0.0, std::cos(error));
      if (blocked_ahead_ || std::abs(error) > M_PI / 3.0) v = 0.0;
      if (blocked_ahead_ && std::abs(error) < kBlockedTurnRad) {
        // Stopped by an obstacle at one side of the way ahead while the heading is straight on:
        // turning in place toward that heading would never end. Turn away from the obstacle's side.
        w = (blocked_left_ ? -1.0 : 1.0) * config_.avoid_turn_gain * kBlockedTurnRad;
      }
    }
    result.command = guarded(v, w, position, heading);
    return result;
  }

  nlohmann::json parameters() const override {
    const RoverRouteConfig& c = config_;
    nlohmann::json p = {{"global", kGlobalNames[static_cast<std::size_t>(c.global)]},
                        {"local", kLocalNames[static_cast<std::size_t>(c.local)]},
                        {"turning_radius_m", c.turning_radius_m},
                        {"route_step_m", c.route_step_m},
                        {"waypoint_tolerance_m", c.waypoint_tolerance_m},
                        {"clearance_m", c.clearance_m},
                        {"occupancy_resolution_m", c.occupancy_resolution_m},
                        {"corridor_half_width_m", c.corridor_half_width_m},
                        {"release_margin_m", c.release_margin_m},
                        {"avoid_speed_mps", c.avoid_speed_mps},
                        {"avoid_turn_gain", c.avoid_turn_gain},
                        {"stop_distance_m", c.stop_distance_m},
                        {"footprint_half_length_m", c.footprint_half_length_m},
                        {"footprint_half_width_m", c.footprint_half_width_m},
                        {"guard_horizon_s", c.guard_horizon_s},
                        {"pure_pursuit", write_nested(c.pure_pursuit)},
                        {"follow_the_gap", write_nested(c.follow_the_gap)},
                        {"vfh_plus", write_nested(c.vfh_plus)},
                        {"rrt_star", write_nested(c.rrt_star)}};
    if (!c.sensor.empty()) p["sensor"] = c.sensor;
    return p;
  }

 private:
  bool build_route(const Observation& o, PlanResult& result) {
    const auto started = Clock::now();
    const std::vector<dubins::Pose2> poses = route_poses(o, config_.waypoint_tolerance_m);
    if (poses.size() < 2) {
      result.status = PlanStatus::reached;
      result.reason = "no mission waypoint to drive to";
      return false;
    }
    if (config_.global == GlobalRoute::dubins) {
      // Checked at creation from the scene's start; the start observed may differ.
      if (dubins_route_overflow(poses, config_)) {
        result.status = PlanStatus::aborted;
        result.reason = "the Dubins route through the mission waypoints would exceed " +
                        std::to_string(kMaxRoutePoints) + " points of route_step_m";
        return false;
      }
      route_ = dubins_route(poses, config_);
    } else {
      if (!scene_) {
        result.status = PlanStatus::invalid_start;
        result.reason = "global route " + std::string(kGlobalNames[static_cast<std::size_t>(config_.global)]) +
                        " needs the scene's map";
        return false;
      }
      OccupancyConfig occupancy;
      occupancy.resolution_m = config_.occupancy_resolution_m;
      occupancy.max_cells = kMaxRouteGridCells;  // checked at creation (check_rover_route_extent)
      const OccupancyGrid grid = inflate(build_occupancy_grid(*scene_, occupancy), config_.clearance_m);
      const LegPlanner legs = config_.global == GlobalRoute::astar ? astar_legs(grid) : rrt_star_legs(grid, config_.rrt_star);
      const auto raw = grid_route(grid, poses, config_.turning_radius_m, legs);
      if (!raw) {
        result.status = PlanStatus::no_path;
        result.reason = "no " + std::string(kGlobalNames[static_cast<std::size_t>(config_.global)]) +
                        " route through the mission waypoints on the occupancy grid inflated by " +
                        std::to_string(config_.clearance_m) + " m";
        return false;
      }
      PathSmoothingConfig smoothing;
      smoothing.min_turning_radius_m = config_.turning_radius_m;
      smoothing.max_turning_radius_m = std::max(smoothing.max_turning_radius_m, config_.turning_radius_m);
      smoothing.step_m = config_.route_step_m;
      route_ = fillet_corners(grid, *raw, smoothing).points_m;
    }
    if (route_.size() < 2) {
      result.status = PlanStatus::no_path;
      result.reason = "the route through the mission waypoints is empty";
      route_.clear();
      return false;
    }
    // Each mission waypoint's nearest route point, in order along the route.
    std::size_t from = 0;
    for (const Waypoint& w : o.mission) {
      std::size_t best = from;
      for (std::size_t i = from; i < route_.size(); ++i) {
        if ((route_[i] - w.position_m.head<2>()).squaredNorm() < (route_[best] - w.position_m.head<2>()).squaredNorm()) {
          best = i;
        }
      }
      waypoint_route_index_.push_back(static_cast<int>(best));
      from = best;
    }
    // The route as planned, every 0.25 m (a chord error under 4 mm on 2 m arcs), at the rover's height.
    std::vector<Eigen::Vector3d>& points = result.decisions.planned_path.emplace();
    const auto every = std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(0.25 / config_.route_step_m)));
    for (std::size_t i = 0; i < route_.size(); i += every) {
      points.emplace_back(route_[i].x(), route_[i].y(), o.state.position_m.z());
    }
    if ((route_.size() - 1) % every != 0) {
      points.emplace_back(route_.back().x(), route_.back().y(), o.state.position_m.z());
    }
    result.decisions.replan = ReplanDecision{
        .index = 0,
        .time_ms = std::chrono::duration<double, std::milli>(Clock::now() - started).count(),
        .details = {{"global", kGlobalNames[static_cast<std::size_t>(config_.global)]}, {"route_points", route_.size()}}};
    return true;
  }

  // Whether an obstacle is in the way, and the local planner's heading if so.
  void assess_scan(const SensorReading& reading, const Eigen::Vector2d& position, double heading) {
    const LidarScan& scan = *reading.scan;
    const LidarConfig& lidar = *reading.config;
    const double sensor_x = lidar.mount.position_m.x();
    // Nearest obstacle straight ahead of the sensor, close enough to stop for.
    double nearest_ahead = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) {
      if (!scan.hits[i]) continue;
      const double a = lidar.beams.empty() ? 0.0 : lidar.beams[i].azimuth_deg * M_PI / 180.0;
      const double r = scan.ranges_m[i];
      const double ahead = r * std::cos(a), lateral = r * std::sin(a) + lidar.mount.position_m.y();
      if (ahead >= 0.0 && std::abs(lateral) <= config_.corridor_half_width_m && ahead < nearest_ahead) {
        nearest_ahead = ahead;
        blocked_left_ = lateral > 0.0;
      }
    }
    // In the way: a hit near the route ahead, from the rover's route point on for the
    // activation range, not merely ahead of the rover — in a headland turn the row
    // ends lie ahead of the rover but beside the route.
    const double activation = config_.local == LocalAvoidance::vfh_plus ? config_.vfh_plus.window_radius_m
                                                                        : config_.follow_the_gap.activation_range_m;
    const std::size_t from = nearest_route_point(position);
    const std::size_t to = std::min(route_.size(), from + 1 + static_cast<std::size_t>(std::ceil(activation / config_.route_step_m)));
    bool in_way = false, in_wide = false;
    for (const Eigen::Vector3f& p : scan.points) {
      const Eigen::Vector2d q = p.head<2>().cast<double>();
      double d2 = std::numeric_limits<double>::infinity();
      for (std::size_t k = from; k < to; ++k) d2 = std::min(d2, (route_[k] - q).squaredNorm());
      const double d = std::sqrt(d2);
      in_way = in_way || d <= config_.corridor_half_width_m;
      in_wide = in_wide || d <= config_.corridor_half_width_m + config_.release_margin_m;
    }
    avoiding_ = config_.local != LocalAvoidance::none && (in_way || (avoiding_ && in_wide));
    blocked_ahead_ = nearest_ahead < config_.stop_distance_m;
    if (!avoiding_) return;

    // The pure-pursuit goal point is where the local planner should head.
    PurePursuitState probe = pursuit_;
    const PurePursuitStep step = pure_pursuit_step(config_.pure_pursuit, probe, position, heading, route_);
    if (config_.local == LocalAvoidance::follow_the_gap) {
      // Bearings from the sensor, which sits on the centre line ahead of the body centre.
      const Eigen::Vector2d sensor_at = position + sensor_x * Eigen::Vector2d(std::cos(heading), std::sin(heading));
      const Eigen::Vector2d to_goal = step.goal - sensor_at;
      const double goal_bearing = wrap_to_pi(std::atan2(to_goal.y(), to_goal.x()) - heading);
      FollowTheGapConfig ftg = config_.follow_the_gap;
      ftg.max_range_m = lidar.max_range_m;
      ftg.activation_range_m = std::numeric_limits<double>::infinity();  // the corridor test decided
      PlanarScanView view{scan.ranges_m, M_PI / 2.0, -M_PI / 180.0};
      if (!lidar.beams.empty() && lidar.beams.size() > 1) {
        view.first_angle_rad = lidar.beams.front().azimuth_deg * M_PI / 180.0;
        view.increment_rad = (lidar.beams[1].azimuth_deg - lidar.beams[0].azimuth_deg) * M_PI / 180.0;
      }
      const FollowTheGapStep gap = follow_the_gap_step(ftg, gap_state_, view, goal_bearing, heading);
      avoid_heading_rad_ = gap.heading_rad;
      blocked_ahead_ = blocked_ahead_ || gap.chosen < 0;
      record_gap(gap, heading, goal_bearing, from);
    } else {
      // VFH+ on a local grid of this scan's hits around the rover.
      const OccupancyGrid local = scan_grid(scan, position, config_.vfh_plus.window_radius_m + 1.0);
      const VfhPlusResult vfh = vfh_plus_step(local, position, heading, step.goal, config_.vfh_plus, vfh_state_);
      if (vfh.direction_rad) {
        avoid_heading_rad_ = wrap_to_pi(*vfh.direction_rad - heading);
      } else {
        blocked_ahead_ = true;
      }
    }
  }

  // The chosen gap for the record, its angles relative to the route's
  // direction at the rover's nearest route point (positive: left of the route).
  void record_gap(const FollowTheGapStep& gap, double heading, double goal_bearing, std::size_t route_index) {
    const std::size_t a = std::min(route_index, route_.size() - 2);
    const Eigen::Vector2d along = route_[a + 1] - route_[a];
    const double route_heading = std::atan2(along.y(), along.x());
    const auto relative_deg = [&](double robot_frame_rad) {
      return wrap_to_pi(robot_frame_rad + heading - route_heading) * 180.0 / M_PI;
    };
    nlohmann::json g = {{"route_heading_deg", route_heading * 180.0 / M_PI},
                        {"goal_deg", relative_deg(goal_bearing)},
                        {"nearest_range_m", gap.nearest_range_m},
                        {"gaps", gap.gaps.size()}};
    if (gap.chosen >= 0) {
      const ScanGap& chosen = gap.gaps[static_cast<std::size_t>(gap.chosen)];
      g["gap_heading_deg"] = relative_deg(chosen.heading_rad);
      g["gap_center_deg"] = relative_deg(chosen.center_rad);
      g["gap_width_m"] = chosen.width_m;
    }
    gap_record_ = std::move(g);
  }

  // The first of (v, w), (v/2, w), (v, 0), (0, w), (-kReverseMps, 0), (0, 0) whose motion over
  // the horizon keeps the footprint off every point of the latest scan. Straight on comes before
  // turning in place: a turn refused while passing an obstacle is usually possible just past it.
  command::Twist guarded(double v, double w, const Eigen::Vector2d& position, double heading) const {
    if (recent_points_.empty()) return {v, w};
    const auto touches = [&](double cv, double cw) {
      constexpr double kDt = 0.1;
      Eigen::Vector2d p = position;
      double th = heading;
      for (double t = kDt; t <= config_.guard_horizon_s + 1e-9; t += kDt) {
        p += cv * kDt * Eigen::Vector2d(std::cos(th + 0.5 * cw * kDt), std::sin(th + 0.5 * cw * kDt));
        th += cw * kDt;
        const double c = std::cos(th), s = std::sin(th);
        for (const Eigen::Vector2d& q : recent_points_) {
          const double dx = q.x() - p.x(), dy = q.y() - p.y();
          if (std::abs(c * dx + s * dy) <= config_.footprint_half_length_m &&
              std::abs(-s * dx + c * dy) <= config_.footprint_half_width_m) {
            return true;
          }
        }
      }
      return false;
    };
    // Last, back off slowly (remembered hits cover what the sensor cannot see behind).
    for (const auto& [cv, cw] : {std::pair{v, w}, std::pair{0.5 * v, w}, std::pair{v, 0.0}, std::pair{0.0, w}, std::pair{-kReverseMps, 0.0}}) {
      if (!touches(cv, cw)) return {cv, cw};
    }
    return {0.0, 0.0};
  }

  // Hits near the rover from earlier scans: the sensor looks ahead, so an
  // obstacle being passed is only in earlier scans. A remembered hit the new
  // scan sees through (a longer range on its beam) is gone — the trail a
  // moving obstacle leaves; one out of the sensor's view stays.
  void remember(const LidarScan& scan, const LidarConfig& lidar, const Eigen::Vector2d& position) {
    const double reach = config_.footprint_half_length_m + config_.guard_horizon_s * config_.pure_pursuit.max_speed_m_s + 1.0;
    const Eigen::Vector2d sensor = scan.sensor_pose.translation().head<2>();
    const double sensor_yaw = std::atan2(scan.sensor_pose.linear()(1, 0), scan.sensor_pose.linear()(0, 0));
    const bool fan = lidar.beams.size() > 1 && scan.ranges_m.size() == lidar.beams.size();
    const double first = fan ? lidar.beams.front().azimuth_deg : 0.0;
    const double step = fan ? lidar.beams[1].azimuth_deg - first : 1.0;
    const auto seen_through = [&](const Eigen::Vector2d& q) {
      if (!fan) return true;  // no fan to test against: keep only this scan's hits
      const Eigen::Vector2d d = q - sensor;
      const double beam = std::round((wrap_to_pi(std::atan2(d.y(), d.x()) - sensor_yaw) * 180.0 / M_PI - first) / step);
      if (beam < 0.0 || beam >= static_cast<double>(scan.ranges_m.size())) return false;
      return scan.ranges_m[static_cast<std::size_t>(beam)] > d.norm() + 0.2;
    };
    // One point per 5 cm cell, so a rover standing still does not pile up copies.
    const auto key = [](const Eigen::Vector2d& q) {
      return (static_cast<std::int64_t>(std::floor(q.x() / 0.05)) << 32) ^
             static_cast<std::int64_t>(static_cast<std::uint32_t>(std::floor(q.y() / 0.05)));
    };
    cells_.clear();
    std::size_t kept = 0;
    for (const Eigen::Vector2d& q : recent_points_) {
      if ((q - position).norm() > reach || seen_through(q) || !cells_.insert(key(q)).second) continue;
      recent_points_[kept++] = q;
    }
    recent_points_.resize(kept);
    for (const Eigen::Vector3f& p : scan.points) {
      const Eigen::Vector2d q = p.head<2>().cast<double>();
      if ((q - position).norm() <= reach && cells_.insert(key(q)).second) recent_points_.push_back(q);
    }
  }

  static OccupancyGrid scan_grid(const LidarScan& scan, const Eigen::Vector2d& centre, double half_size_m) {
    OccupancyGrid g;
    g.resolution_m = 0.1;
    g.cols = g.rows = static_cast<int>(std::ceil(2.0 * half_size_m / g.resolution_m));
    g.origin_m = centre - Eigen::Vector2d::Constant(half_size_m);
    g.occupied.assign(static_cast<std::size_t>(g.cols) * g.rows, 0);
    for (const Eigen::Vector3f& p : scan.points) {
      const Eigen::Vector2i c = g.cell_of(p.head<2>().cast<double>());
      if (g.contains(c.x(), c.y())) g.occupied[static_cast<std::size_t>(c.y()) * g.cols + c.x()] = 1;
    }
    return g;
  }

  // The route point nearest the rover, within 5 m of route back and 30 m ahead of the last one pursued.
  std::size_t nearest_route_point(const Eigen::Vector2d& position) const {
    const auto pursued = static_cast<std::size_t>(pursuit_.last_found_index);
    const auto back = static_cast<std::size_t>(std::lround(5.0 / config_.route_step_m));
    const auto window = static_cast<std::size_t>(std::lround(30.0 / config_.route_step_m));
    std::size_t best = pursued;
    double best_d = std::numeric_limits<double>::infinity();
    for (std::size_t i = pursued > back ? pursued - back : 0; i < route_.size() && i <= pursued + window; ++i) {
      const double d = (route_[i] - position).squaredNorm();
      if (d < best_d) {
        best_d = d;
        best = i;
      }
    }
    return best;
  }

  // The nearest route point within 30 m ahead of the last one pursued.
  void rejoin(const Eigen::Vector2d& position) {
    const auto first = static_cast<std::size_t>(pursuit_.last_found_index);
    const std::size_t window = static_cast<std::size_t>(std::lround(30.0 / config_.route_step_m));
    std::size_t best = first;
    double best_d = std::numeric_limits<double>::infinity();
    for (std::size_t i = first; i < route_.size() && i <= first + window; ++i) {
      const double d = (route_[i] - position).squaredNorm();
      if (d < best_d) {
        best_d = d;
        best = i;
      }
    }
    pursuit_.last_found_index = static_cast<int>(best);
  }

  RoverRouteConfig config_;
  const Scene* scene_ = nullptr;
  std::vector<Eigen::Vector2d> route_;
  std::vector<int> waypoint_route_index_;  ///< per mission waypoint: its nearest route point
  PurePursuitState pursuit_;
  FollowTheGapState gap_state_;
  VfhPlusState vfh_state_;
  std::size_t next_ = 0;             ///< next mission waypoint to pass
  bool avoiding_ = false;            ///< the local planner steers (from the latest scan)
  bool last_avoiding_ = false;       ///< as last recorded
  bool blocked_ahead_ = false;       ///< stop and turn in place
  double avoid_heading_rad_ = 0.0;   ///< robot frame, from the latest scan
  nlohmann::json gap_record_;        ///< follow-the-gap's choice on the latest scan, for the record
  bool blocked_left_ = false;        ///< the obstacle that stops the rover lies left of its centre line
  static constexpr double kReverseMps = 0.2;
  static constexpr double kBlockedTurnRad = 0.35;  ///< least heading error turned for when stopped (20 deg)
  std::vector<Eigen::Vector2d> recent_points_;  ///< scan hits near the rover, world frame
  std::unordered_set<std::int64_t> cells_;      ///< scratch: 5 cm cells of recent_points_
};

}  // namespace

RoverRouteConfig parse_rover_route_config(const ParamsBlock& params) {
  RoverRouteConfig c;
  ObjectReader r(JsonNode(params.values, params.file, params.pointer));
  r.read("sensor", c.sensor);
  if (const auto global = r.optional("global")) {
    c.global = static_cast<GlobalRoute>(global->as_choice(std::vector<std::string_view>(kGlobalNames.begin(), kGlobalNames.end())));
  }
  if (const auto local = r.optional("local")) {
    c.local = static_cast<LocalAvoidance>(local->as_choice(std::vector<std::string_view>(kLocalNames.begin(), kLocalNames.end())));
  }
  r.read("turning_radius_m", c.turning_radius_m, Range::closed(0.05, 100.0));
  r.read("route_step_m", c.route_step_m, Range::closed(0.01, 5.0));
  r.read("waypoint_tolerance_m", c.waypoint_tolerance_m, Range::positive());
  r.read("clearance_m", c.clearance_m, Range::non_negative());
  r.read("occupancy_resolution_m", c.occupancy_resolution_m, Range::closed(0.01, 10.0));
  r.read("corridor_half_width_m", c.corridor_half_width_m, Range::positive());
  r.read("release_margin_m", c.release_margin_m, Range::non_negative());
  r.read("avoid_speed_mps", c.avoid_speed_mps, Range::closed(0.0, 10.0));
  r.read("avoid_turn_gain", c.avoid_turn_gain, Range::positive());
  r.read("stop_distance_m", c.stop_distance_m, Range::non_negative());
  r.read("footprint_half_length_m", c.footprint_half_length_m, Range::positive());
  r.read("footprint_half_width_m", c.footprint_half_width_m, Range::positive());
  r.read("guard_horizon_s", c.guard_horizon_s, Range::closed(0.0, 10.0));
  read_nested(r, "pure_pursuit", c.pure_pursuit);
  read_nested(r, "follow_the_gap", c.follow_the_gap);
  read_nested(r, "vfh_plus", c.vfh_plus);
  read_nested(r, "rrt_star", c.rrt_star);
  r.finish();
  try {
    validate(c.vfh_plus);
    validate(c.rrt_star);
  } catch (const std::invalid_argument& e) {
    throw InputError(params.file, params.pointer, e.what());
  }
  return c;
}

void check_rover_route_extent(const RoverRouteConfig& c, const VehicleDef& vehicle, const Scene& scene) {
  // The loader puts a vehicle's "params" block (present or not) at <vehicle>/params.
  const auto waypoint_at = [](const VehicleDef& v, std::size_t i) {
    const std::string& params = v.params.pointer;
    const std::size_t slash = params.rfind('/');
    return std::pair<std::string, std::string>{
        v.params.file,
        (slash == std::string::npos ? std::string() : params.substr(0, slash)) + "/mission/waypoints/" + std::to_string(i)};
  };
  if (c.global == GlobalRoute::dubins) {
    const Eigen::Vector3d x_axis = vehicle.pose.linear() * Eigen::Vector3d::UnitX();
    const std::vector<dubins::Pose2> poses = route_poses(vehicle.pose.translation().head<2>(),
                                                         std::atan2(x_axis.y(), x_axis.x()), vehicle.mission,
                                                         c.waypoint_tolerance_m);
    if (const auto i = dubins_route_overflow(poses, c)) {
      // poses: the start (when it is not at the first waypoint), then the waypoints.
      const std::size_t waypoint = *i - (poses.size() - vehicle.mission.size());
      const auto at = waypoint_at(vehicle, waypoint);
      throw InputError(at.first, at.second,
                       "expected a waypoint nearer the previous one: the rover's Dubins route to it would exceed " +
                           std::to_string(kMaxRoutePoints) + " points of route_step_m " + format_number(c.route_step_m) +
                           " m (" + format_number(static_cast<double>(kMaxRoutePoints) * c.route_step_m / 1000.0) +
                           " km in all)");
    }
    return;
  }
  // A* and RRT* plan on an occupancy grid over the obstacles and every
  // vehicle's start and waypoints: the first waypoint that takes it past the
  // limit is named.
  OccupancyConfig occupancy;
  occupancy.resolution_m = c.occupancy_resolution_m;
  const auto cells = [&](const Eigen::AlignedBox2d& box) {
    const Eigen::Vector2d size = occupancy_grid_cells(box, occupancy);
    return size.x() * size.y();
  };
  const auto limit = static_cast<double>(kMaxRouteGridCells);
  const std::string expected = "an occupancy grid of at most " + std::to_string(kMaxRouteGridCells) +
                               " cells of occupancy_resolution_m " + format_number(c.occupancy_resolution_m) +
                               " m over the obstacles, starts and waypoints";
  Eigen::AlignedBox2d bounds = occupancy_bounds(scene, false);
  if (!(cells(bounds) <= limit)) {
    throw InputError(vehicle.planner.params.file, vehicle.planner.params.pointer,
                     "expected " + expected + ", got " + format_number(cells(bounds)) +
                         " cells for the obstacles and starts alone (a coarser occupancy_resolution_m?)");
  }
  for (const VehicleDef& v : scene.vehicles) {
    for (std::size_t i = 0; i < v.mission.size(); ++i) {
      bounds.extend(Eigen::Vector2d(v.mission[i].position_m.head<2>()));
      if (!(cells(bounds) <= limit)) {
        const auto at = waypoint_at(v, i);
        throw InputError(at.first, at.second,
                         "expected a waypoint nearer the obstacles and starts: rover_route's " +
                             std::string(kGlobalNames[static_cast<std::size_t>(c.global)]) + " route needs " +
                             expected + ", and with this waypoint it would have " + format_number(cells(bounds)));
      }
    }
  }
}

std::unique_ptr<Planner> make_rover_route_planner(const ParamsBlock& params, const PlannerContext& context) {
  if (context.vehicle != VehicleType::rover) {
    throw InputError(params.file, params.pointer, "planner rover_route drives a rover only");
  }
  RoverRouteConfig config = parse_rover_route_config(params);
  if (context.scene && context.vehicle_def) check_rover_route_extent(config, *context.vehicle_def, *context.scene);
  if (context.scene && !params.values.contains("rrt_star")) {
    config.rrt_star.seed = context.scene->world.seed;  // seeded from the world unless given
  }
  return std::make_unique<RoverRoutePlanner>(config, context);
}

}  // namespace campo
