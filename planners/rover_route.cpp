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

const ConfigFields<PurePursuitConfig>& pure_pursuit_config_fields() {
  using P = PurePursuitConfig;
  static const ConfigFields<P> fields =
      ConfigFields<P>()
          .number("lookahead_m", &P::lookahead_m, Range::positive(), "m", "radius of the lookahead circle")
          .number("turn_gain_per_s", &P::turn_gain_per_s, Range::positive(), "1/s",
                  "k_turn: yaw rate per radian of turn error")
          .number("max_yaw_rate_rad_s", &P::max_yaw_rate_rad_s, Range::positive(), "rad/s", "yaw rate limit")
          .number("max_speed_m_s", &P::max_speed_m_s, Range::closed(0.01, 10.0), "m/s",
                  "speed when heading straight at the goal point")
          .number("min_speed_m_s", &P::min_speed_m_s, Range::closed(0.0, 10.0), "m/s",
                  "speed at a turn error of `slowdown_turn_error_rad` or more")
          .number("slowdown_turn_error_rad", &P::slowdown_turn_error_rad, Range::positive(), "rad",
                  "turn error at which the speed has fallen to the minimum")
          .number("goal_tolerance_m", &P::goal_tolerance_m, Range::positive(), "m",
                  "the end is reached within this distance of the last point");
  return fields;
}

const ConfigFields<FollowTheGapConfig>& follow_the_gap_config_fields() {
  using F = FollowTheGapConfig;
  static const ConfigFields<F> fields =
      ConfigFields<F>()
          .number("activation_range_m", &F::activation_range_m, Range::positive(), "m",
                  "length of the route ahead checked for obstacles in the way (003 §3.6)")
          .number("bubble_radius_m", &F::bubble_radius_m, Range::positive(), "m",
                  "R: the rover's half-diagonal plus a margin")
          .number("gap_jump_m", &F::gap_jump_m, Range::positive(), "m",
                  "003's gaps only: a range step between neighbouring beams above this splits a gap")
          .number("free_range_m", &F::free_range_m, Range::non_negative(), "m",
                  "> 0: free-space gaps, maximal runs of beams a disc of radius R drives farther than this along; "
                  "0: 003's gaps")
          .flag("grow_gap_edges", &F::grow_gap_edges,
                "003's gaps only: grow the near side of every range step bounding a gap by R (003 §2.4.2)")
          .number("alpha_m", &F::alpha_m, Range::non_negative(), "m",
                  "a in phi_gap: weight of the gap centre against the goal")
          .number("k_width", &F::k_width, Range::non_negative(), "1/m",
                  "k1: score per metre of width times normalised depth")
          .number("k_heading", &F::k_heading, Range::non_negative(), "1/rad",
                  "k2: score per radian of alignment with the goal")
          .number("hysteresis_bonus", &F::hysteresis_bonus, Range::non_negative(), "",
                  "added to the score of the gap overlapping the previous choice");
  return fields;
}

const ConfigFields<VfhPlusConfig>& vfh_plus_config_fields() {
  using V = VfhPlusConfig;
  static const ConfigFields<V> fields =
      ConfigFields<V>()
          .integer("sectors", &V::sectors, {4, 3600}, "", "n; sectors of 360 deg / n")
          .number("window_radius_m", &V::window_radius_m, Range::positive(), "m",
                  "cells within this distance form the active window; also the range checked for obstacles in the way")
          .number("magnitude_a", &V::magnitude_a, Range{1.0}, "",
                  "magnitude of an occupied cell at the robot's centre (a in m = a - b d^2)")
          .number("robot_radius_m", &V::robot_radius_m, Range::non_negative(), "m", "r_r")
          .number("safety_distance_m", &V::safety_distance_m, Range::non_negative(), "m",
                  "d_s; obstacle cells are enlarged by r_r + d_s")
          .number("threshold_low", &V::threshold_low, Range::non_negative(), "",
                  "below this a sector is free (in occupied-cell magnitudes)")
          .number("threshold_high", &V::threshold_high, Range::non_negative(), "",
                  "above this a sector is blocked; at least `threshold_low`")
          .number("min_turning_radius_m", &V::min_turning_radius_m, Range::non_negative(), "m",
                  "left and right; 0 masks only the robot's own disc")
          .integer("wide_opening_sectors", &V::wide_opening_sectors, {1, 3600}, "",
                   "s_max: openings with more free sectors are wide")
          .number("mu_target", &V::mu_target, Range::non_negative(), "",
                  "mu1, weight of the distance to the target direction")
          .number("mu_heading", &V::mu_heading, Range::non_negative(), "",
                  "mu2, of the distance to the current heading")
          .number("mu_previous", &V::mu_previous, Range::non_negative(), "",
                  "mu3, of the distance to the previous direction; mu1 > mu2 + mu3");
  return fields;
}

const ConfigFields<RrtStarConfig>& rrt_star_config_fields() {
  using R = RrtStarConfig;
  static const ConfigFields<R> fields =
      ConfigFields<R>()
          .seed("seed", &R::seed, "of the sampler; without an `rrt_star` object, the world's seed")
          .number("step_m", &R::step_m, Range::positive(), "m",
                  "lambda: the farthest a new node lies from its nearest node; at least 0.001 and at most 10^6 "
                  "(see [grid.md](grid.md#rrt_star))")
          .number("rewire_radius_m", &R::rewire_radius_m, Range::non_negative(), "m",
                  "> 0: fixed rewiring radius; 0: shrinking, min(gamma (log n / n)^(1/2), lambda); at most 10^6")
          .number("rewire_gamma_m", &R::rewire_gamma_m, Range::non_negative(), "m",
                  "gamma of the shrinking radius; 0: from the free area; at most 10^6")
          .number("goal_radius_m", &R::goal_radius_m, Range::positive(), "m", "a node this near the goal solves it")
          .number("goal_bias", &R::goal_bias, Range::closed(0.0, 1.0), "", "probability of sampling the goal itself")
          .integer("max_iterations", &R::max_iterations, {0, 10'000'000}, "",
                   "the budget; a new node considers at most ⌈3e ln n⌉ neighbours");
  return fields;
}

constexpr std::array<std::string_view, 3> kGlobalNames{"dubins", "astar", "rrt_star"};
constexpr std::array<std::string_view, 3> kLocalNames{"follow_the_gap", "vfh_plus", "none"};

// The choices of a field from a name table indexed by the enum's values.
template <class Enum, std::size_t N>
std::vector<std::pair<std::string, Enum>> enum_choices(const std::array<std::string_view, N>& names) {
  std::vector<std::pair<std::string, Enum>> choices;
  for (std::size_t i = 0; i < N; ++i) choices.emplace_back(std::string(names[i]), static_cast<Enum>(i));
  return choices;
}

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
      if (gap_record_) rover_route_record().gap.set(result.decisions.own, *std::exchange(gap_record_, std::nullopt));
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
      if (blocked_ahead_ || std::abs(error) > config_.avoid_stop_heading_deg * M_PI / 180.0) v = 0.0;
      if (blocked_ahead_ && std::abs(error) < config_.blocked_turn_rad) {
        // Stopped by an obstacle at one side of the way ahead while the heading is straight on:
        // turning in place toward that heading would never end. Turn away from the obstacle's side.
        w = (blocked_left_ ? -1.0 : 1.0) * config_.avoid_turn_gain * config_.blocked_turn_rad;
      }
    }
    result.command = guarded(v, w, position, heading);
    return result;
  }

  nlohmann::json parameters() const override { return rover_route_config_fields().write(config_); }

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
    // The route as planned, every record_path_step_m, at the rover's height.
    std::vector<Eigen::Vector3d>& points = result.decisions.planned_path.emplace();
    const auto every = std::max<std::size_t>(
        1, static_cast<std::size_t>(std::lround(config_.record_path_step_m / config_.route_step_m)));
    for (std::size_t i = 0; i < route_.size(); i += every) {
      points.emplace_back(route_[i].x(), route_[i].y(), o.state.position_m.z());
    }
    if ((route_.size() - 1) % every != 0) {
      points.emplace_back(route_.back().x(), route_.back().y(), o.state.position_m.z());
    }
    ReplanDecision& step = result.decisions.replan.emplace(ReplanDecision{
        .index = 0, .time_ms = std::chrono::duration<double, std::milli>(Clock::now() - started).count()});
    rover_route_record().global.set(step.details, std::string(kGlobalNames[static_cast<std::size_t>(config_.global)]));
    rover_route_record().route_points.set(step.details, static_cast<std::int64_t>(route_.size()));
    return true;
  }

  // Whether an obstacle is in the way, and the local planner's heading if so.
  void assess_scan(const SensorReading& reading, const Eigen::Vector2d& position, double heading) {
    const RangeScan& scan = *reading.scan;
    const RangeSensorConfig& lidar = *reading.config;
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
      const OccupancyGrid local = scan_grid(scan, position, config_.vfh_plus.window_radius_m + config_.vfh_grid_margin_m,
                                                config_.vfh_grid_resolution_m);
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
    GapDecision& g = gap_record_.emplace(GapDecision{.gaps = static_cast<int>(gap.gaps.size()),
                                                     .nearest_range_m = gap.nearest_range_m,
                                                     .route_heading_deg = route_heading * 180.0 / M_PI,
                                                     .goal_deg = relative_deg(goal_bearing)});
    if (gap.chosen >= 0) {
      const ScanGap& chosen = gap.gaps[static_cast<std::size_t>(gap.chosen)];
      g.chosen = ChosenGap{.center_deg = relative_deg(chosen.center_rad),
                           .heading_deg = relative_deg(chosen.heading_rad),
                           .width_m = chosen.width_m};
    }
  }

  // The first of (v, w), (v/2, w), (v, 0), (0, w), (-guard_reverse_speed_mps, 0), (0, 0) whose motion over
  // the horizon keeps the footprint off every point of the latest scan. Straight on comes before
  // turning in place: a turn refused while passing an obstacle is usually possible just past it.
  command::Twist guarded(double v, double w, const Eigen::Vector2d& position, double heading) const {
    if (recent_points_.empty()) return {v, w};
    const auto touches = [&](double cv, double cw) {
      const double dt = config_.guard_step_s;
      Eigen::Vector2d p = position;
      double th = heading;
      for (double t = dt; t <= config_.guard_horizon_s + 1e-9; t += dt) {
        p += cv * dt * Eigen::Vector2d(std::cos(th + 0.5 * cw * dt), std::sin(th + 0.5 * cw * dt));
        th += cw * dt;
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
    for (const auto& [cv, cw] : {std::pair{v, w}, std::pair{0.5 * v, w}, std::pair{v, 0.0}, std::pair{0.0, w}, std::pair{-config_.guard_reverse_speed_mps, 0.0}}) {
      if (!touches(cv, cw)) return {cv, cw};
    }
    return {0.0, 0.0};
  }

  // Hits near the rover from earlier scans: the sensor looks ahead, so an
  // obstacle being passed is only in earlier scans. A remembered hit the new
  // scan sees through (a longer range on its beam) is gone — the trail a
  // moving obstacle leaves; one out of the sensor's view stays.
  void remember(const RangeScan& scan, const RangeSensorConfig& lidar, const Eigen::Vector2d& position) {
    const double reach = config_.footprint_half_length_m + config_.guard_horizon_s * config_.pure_pursuit.max_speed_m_s +
                          config_.memory_margin_m;
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
      return scan.ranges_m[static_cast<std::size_t>(beam)] > d.norm() + config_.see_through_margin_m;
    };
    // One point per memory cell, so a rover standing still does not pile up copies. The row
    // index's low 32 bits through a signed integer: a negative double converted straight to an
    // unsigned one is undefined behaviour.
    const auto key = [cell = config_.memory_cell_m](const Eigen::Vector2d& q) {
      return (static_cast<std::int64_t>(std::floor(q.x() / cell)) << 32) ^
             static_cast<std::int64_t>(static_cast<std::uint32_t>(static_cast<std::int64_t>(std::floor(q.y() / cell))));
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

  static OccupancyGrid scan_grid(const RangeScan& scan, const Eigen::Vector2d& centre, double half_size_m,
                                 double resolution_m) {
    OccupancyGrid g;
    g.resolution_m = resolution_m;
    g.cols = g.rows = static_cast<int>(std::ceil(2.0 * half_size_m / g.resolution_m));
    g.origin_m = centre - Eigen::Vector2d::Constant(half_size_m);
    g.occupied.assign(static_cast<std::size_t>(g.cols) * g.rows, 0);
    for (const Eigen::Vector3f& p : scan.points) {
      const Eigen::Vector2i c = g.cell_of(p.head<2>().cast<double>());
      if (g.contains(c.x(), c.y())) g.occupied[static_cast<std::size_t>(c.y()) * g.cols + c.x()] = 1;
    }
    return g;
  }

  // The route point nearest the rover, within rejoin_behind_m of route back and rejoin_ahead_m ahead of the last one pursued.
  std::size_t nearest_route_point(const Eigen::Vector2d& position) const {
    const auto pursued = static_cast<std::size_t>(pursuit_.last_found_index);
    const auto back = static_cast<std::size_t>(std::lround(config_.rejoin_behind_m / config_.route_step_m));
    const auto window = static_cast<std::size_t>(std::lround(config_.rejoin_ahead_m / config_.route_step_m));
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

  // The nearest route point within rejoin_ahead_m ahead of the last one pursued.
  void rejoin(const Eigen::Vector2d& position) {
    const auto first = static_cast<std::size_t>(pursuit_.last_found_index);
    const std::size_t window = static_cast<std::size_t>(std::lround(config_.rejoin_ahead_m / config_.route_step_m));
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
  std::optional<GapDecision> gap_record_;  ///< follow-the-gap's choice on the latest scan, for the record
  bool blocked_left_ = false;        ///< the obstacle that stops the rover lies left of its centre line
  std::vector<Eigen::Vector2d> recent_points_;  ///< scan hits near the rover, world frame
  std::unordered_set<std::int64_t> cells_;      ///< scratch: 5 cm cells of recent_points_
};

}  // namespace

const ConfigFields<RoverRouteConfig>& rover_route_config_fields() {
  using C = RoverRouteConfig;
  static const ConfigFields<C> fields =
      ConfigFields<C>()
          .text("sensor", &C::sensor, "alias of the planar LIDAR (`planar180`); none: the vehicle's first sensor")
          .omitted_when_default()
          .choice("global", &C::global, enum_choices<GlobalRoute>(kGlobalNames),
                  "the global route: Dubins paths through the waypoints, or A* / RRT* on the occupancy grid, smoothed")
          .choice("local", &C::local, enum_choices<LocalAvoidance>(kLocalNames),
                  "the local planner that steers while an obstacle is in the way")
          .number("turning_radius_m", &C::turning_radius_m, Range::closed(0.05, 100.0), "m",
                  "Dubins radius; smallest fillet of grid routes and their straight lead at each waypoint")
          .number("route_step_m", &C::route_step_m, Range::closed(0.01, 5.0), "m", "spacing of the route polyline")
          .number("waypoint_tolerance_m", &C::waypoint_tolerance_m, Range::positive(), "m",
                  "a mission waypoint is passed within this distance")
          .number("clearance_m", &C::clearance_m, Range::non_negative(), "m",
                  "inflation of the occupancy grid for `astar` and `rrt_star`")
          .number("occupancy_resolution_m", &C::occupancy_resolution_m, Range::closed(0.01, 10.0), "m",
                  "cell of that grid")
          .number("corridor_half_width_m", &C::corridor_half_width_m, Range::positive(), "m",
                  "distance from the route ahead within which a hit is \"in the way\"; also the width of the stop "
                  "check ahead")
          .number("release_margin_m", &C::release_margin_m, Range::non_negative(), "m",
                  "avoidance ends once this much wider a corridor is clear")
          .number("avoid_speed_mps", &C::avoid_speed_mps, Range::closed(0.0, 10.0), "m/s",
                  "forward speed while avoiding (times cos of the heading error)")
          .number("avoid_turn_gain", &C::avoid_turn_gain, Range::positive(), "1/s",
                  "yaw rate per radian of heading error while avoiding")
          .number("stop_distance_m", &C::stop_distance_m, Range::non_negative(), "m",
                  "an obstacle nearer ahead of the sensor stops the rover (it still turns)")
          .number("footprint_half_length_m", &C::footprint_half_length_m, Range::positive(), "m",
                  "guard footprint: 003's chassis is 1.5 m long, plus a margin")
          .number("footprint_half_width_m", &C::footprint_half_width_m, Range::positive(), "m",
                  "guard footprint: and 1.0 m wide, plus a margin")
          .number("guard_horizon_s", &C::guard_horizon_s, Range::closed(0.0, 10.0), "s",
                  "how far ahead the guard drives each command")
          .number("guard_step_s", &C::guard_step_s, Range::closed(0.01, 1.0), "s",
                  "time step of the guard's drive (written only when changed)")
          .omitted_when_default()
          .number("guard_reverse_speed_mps", &C::guard_reverse_speed_mps, Range::closed(0.0, 10.0), "m/s",
                  "the guard's last resort before stopping: back off at this speed (written only when changed)")
          .omitted_when_default()
          .number("avoid_stop_heading_deg", &C::avoid_stop_heading_deg, Range::closed(0.0, 180.0), "deg",
                  "while avoiding, the rover stops (and only turns) above this heading error (written only when "
                  "changed)")
          .omitted_when_default()
          .number("blocked_turn_rad", &C::blocked_turn_rad, Range::closed(0.0, 3.15), "rad",
                  "stopped by an obstacle at one side with the heading straight on, turn away from it as for this "
                  "heading error (written only when changed)")
          .omitted_when_default()
          .number("memory_margin_m", &C::memory_margin_m, Range::closed(0.0, 10.0), "m",
                  "scan hits are remembered within the guard's reach plus this (written only when changed)")
          .omitted_when_default()
          .number("memory_cell_m", &C::memory_cell_m, Range::closed(0.01, 1.0), "m",
                  "one remembered hit per square cell of this side (written only when changed)")
          .omitted_when_default()
          .number("see_through_margin_m", &C::see_through_margin_m, Range::closed(0.0, 10.0), "m",
                  "a remembered hit is forgotten once its beam reads this much farther (written only when changed)")
          .omitted_when_default()
          .number("vfh_grid_resolution_m", &C::vfh_grid_resolution_m, Range::closed(0.05, 1.0), "m",
                  "VFH+: cell of the grid of one scan's hits (written only when changed)")
          .omitted_when_default()
          .number("vfh_grid_margin_m", &C::vfh_grid_margin_m, Range::closed(0.0, 10.0), "m",
                  "VFH+: that grid reaches this far beyond the active window (written only when changed)")
          .omitted_when_default()
          .number("rejoin_behind_m", &C::rejoin_behind_m, Range::closed(0.0, 100.0), "m",
                  "the route point nearest the rover is looked for this far behind the one pursued (written only "
                  "when changed)")
          .omitted_when_default()
          .number("rejoin_ahead_m", &C::rejoin_ahead_m, Range::closed(0.0, 100.0), "m",
                  "and this far ahead of it, also when rejoining the route after avoidance (written only when "
                  "changed)")
          .omitted_when_default()
          .number("record_path_step_m", &C::record_path_step_m, Range::closed(0.01, 100.0), "m",
                  "spacing of the planned path in the record (written only when changed)")
          .omitted_when_default()
          .nested("pure_pursuit", &C::pure_pursuit, pure_pursuit_config_fields(), "pure pursuit of the route")
          .nested("follow_the_gap", &C::follow_the_gap, follow_the_gap_config_fields(),
                  "follow-the-gap (`local` `follow_the_gap`)")
          .nested("vfh_plus", &C::vfh_plus, vfh_plus_config_fields(), "VFH+ (`local` `vfh_plus`)")
          .nested("rrt_star", &C::rrt_star, rrt_star_config_fields(), "RRT* (`global` `rrt_star`)");
  return fields;
}

RoverRouteConfig parse_rover_route_config(const ParamsBlock& params) {
  RoverRouteConfig c = rover_route_config_fields().read(params);
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

namespace {

nlohmann::json gap_json(const GapDecision& gap) {
  nlohmann::json j = {{"gaps", gap.gaps},
                      {"nearest_range_m", gap.nearest_range_m},
                      {"route_heading_deg", gap.route_heading_deg},
                      {"goal_deg", gap.goal_deg}};
  if (gap.chosen) {
    j["gap_center_deg"] = gap.chosen->center_deg;
    j["gap_heading_deg"] = gap.chosen->heading_deg;
    j["gap_width_m"] = gap.chosen->width_m;
  }
  return j;
}

GapDecision read_gap(const JsonNode& node) {
  ObjectReader r(node);
  GapDecision gap;
  gap.gaps = static_cast<int>(r.required("gaps").as_int(0, std::numeric_limits<int>::max()));
  gap.nearest_range_m = r.required("nearest_range_m").as_number(Range::non_negative());
  gap.route_heading_deg = r.required("route_heading_deg").as_number();
  gap.goal_deg = r.required("goal_deg").as_number();
  // A chosen gap has all three or none.
  if (r.has("gap_center_deg") || r.has("gap_heading_deg") || r.has("gap_width_m")) {
    gap.chosen = ChosenGap{.center_deg = r.required("gap_center_deg").as_number(),
                           .heading_deg = r.required("gap_heading_deg").as_number(),
                           .width_m = r.required("gap_width_m").as_number(Range::non_negative())};
  }
  r.finish();
  return gap;
}

// The sequence figure's and the video's mark of a gap decision: the route's direction, the chosen gap's heading.
std::optional<HeadingMark> gap_mark(const Decisions& decisions) {
  const std::optional<GapDecision> gap = rover_route_record().gap.get(decisions.own, "", "/decisions");
  if (!gap) return std::nullopt;
  HeadingMark mark{.reference_deg = gap->route_heading_deg, .nearest_m = gap->nearest_range_m};
  if (gap->chosen) {
    mark.heading_deg = gap->chosen->heading_deg;
    // Sides by the gap's centre: the heading is blended toward the goal and may cross the route.
    mark.side = gap->chosen->center_deg > 0.0 ? "left" : "right";
    mark.status = "gap on the " + mark.side;
    char heading[32];
    std::snprintf(heading, sizeof heading, "%+.0f", gap->chosen->heading_deg);
    mark.caption = mark.status + ", heading " + heading + " deg (arrow)";
  }
  return mark;
}

}  // namespace

RoverRouteRecord::RoverRouteRecord()
    : gap(description.decisions.declare<GapDecision>(
          {"gap", RecordType::object, "",
           "follow-the-gap's view of the scan read this call: gaps (count), nearest_range_m (d_min, m), "
           "route_heading_deg (the route's direction at the nearest route point, deg counter-clockwise from east), "
           "goal_deg (the pure-pursuit goal) and, when a gap was chosen, gap_center_deg (phi_center), "
           "gap_heading_deg (phi_gap) and gap_width_m (L_gap, m); angles in deg relative to the route, positive left"},
          gap_json, read_gap)),
      global(description.replan.declare<std::string>("global", "", "the global planner that made the route")),
      route_points(description.replan.declare<std::int64_t>("route_points", "", "points of the route")) {
  description.heading = gap_mark;
}

const RoverRouteRecord& rover_route_record() {
  static const RoverRouteRecord record;
  return record;
}

std::unique_ptr<Planner> make_rover_route_planner(const ParamsBlock& params, const PlannerContext& context) {
  RoverRouteConfig config = parse_rover_route_config(params);
  if (context.scene && context.vehicle_def) check_rover_route_extent(config, *context.vehicle_def, *context.scene);
  if (context.scene && !params.values.contains("rrt_star")) {
    config.rrt_star.seed = context.scene->world.seed;  // seeded from the world unless given
  }
  return std::make_unique<RoverRoutePlanner>(config, context);
}

}  // namespace campo
