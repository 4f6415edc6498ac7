#pragma once
/// Pure pursuit path following (003 §3.4, SPEC §7.3) as a pure function: the
/// goal point is where a circle of the lookahead radius around the robot
/// crosses the path, and the yaw rate turns the robot toward it.
#include <optional>
#include <span>

#include <Eigen/Core>

namespace campo {

struct PurePursuitConfig {
  double lookahead_m = 1.5;              ///< radius of the lookahead circle, > 0
  double turn_gain_per_s = 2.0;          ///< k_turn: yaw rate per radian of turnError, 1/s, > 0
  double max_yaw_rate_rad_s = 1.0;       ///< |yaw rate| limit, rad/s, > 0
  double max_speed_m_s = 1.0;            ///< speed when heading straight at the goal point, m/s
  double min_speed_m_s = 0.2;            ///< speed at turnError >= slowdown_turn_error_rad, m/s, <= max
  double slowdown_turn_error_rad = 1.0;  ///< |turnError| at which the speed has fallen to the minimum, rad, > 0
  double goal_tolerance_m = 0.3;         ///< the end is reached within this distance of the last point, m
};

/// What pure pursuit carries from one step to the next.
struct PurePursuitState {
  /// lastFoundIndex: the search for the goal point starts at segment
  /// [i, i+1]; it only grows, so passed segments are never searched again.
  int last_found_index = 0;
};

enum class GoalSource {
  intersection,  ///< the lookahead circle crosses segment `index`
  waypoint,      ///< fallback: no acceptable crossing, aim at waypoint `index`
};

struct PurePursuitStep {
  Eigen::Vector2d goal = Eigen::Vector2d::Zero();  ///< goal point, path frame
  GoalSource source = GoalSource::waypoint;
  int index = 0;                ///< segment [index, index+1] or waypoint holding the goal; = state.last_found_index
  double turn_error_rad = 0.0;  ///< bearing of the goal minus heading, wrapped to (-pi, pi]
  double yaw_rate_rad_s = 0.0;  ///< counter-clockwise positive; 0 once the end is reached
  double speed_m_s = 0.0;       ///< forward; 0 once the end is reached
  bool end_reached = false;     ///< on the last segment and within goal_tolerance_m of the last point
};

/// `angle_rad` wrapped to (-pi, pi].
double wrap_to_pi(double angle_rad);

/// The crossing of the circle of radius `radius_m` around `center` with the
/// segment a-b that lies on the segment (parameter in [0, 1]); of two such,
/// the one nearer b (003 Fig. 37); nullopt when there is none.
std::optional<Eigen::Vector2d> circle_segment_goal(const Eigen::Vector2d& center, double radius_m,
                                                   const Eigen::Vector2d& a, const Eigen::Vector2d& b);

/// One pure pursuit step for a robot at `position` (path frame) with heading
/// `heading_rad` (counter-clockwise from the x axis) following the polyline
/// `path` (at least one point; throws std::invalid_argument when empty).
/// Segments are searched from state.last_found_index on; the first crossing
/// (circle_segment_goal) that is nearer the segment's end waypoint than the
/// robot is becomes the goal and its segment the new lastFoundIndex (003 Fig.
/// 38: the first valid point, so tight bends are not cut). A crossing that is
/// not (the robot would go back, 003 Fig. 39) moves lastFoundIndex on to the
/// segment's end and the search goes on. Without an accepted crossing the
/// goal is waypoint[lastFoundIndex], or the last point when the rest of the
/// path lies inside the circle (else a robot that has passed
/// waypoint[lastFoundIndex] near the end would turn back to it). Yaw rate = k_turn turnError, clamped;
/// speed falls linearly from max to min as |turnError| grows to
/// slowdown_turn_error_rad (slower in curves, 003 §3.7).
PurePursuitStep pure_pursuit_step(const PurePursuitConfig& config, PurePursuitState& state,
                                  const Eigen::Vector2d& position, double heading_rad,
                                  std::span<const Eigen::Vector2d> path);

}  // namespace campo
