#include "planners/pure_pursuit.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace campo {

double wrap_to_pi(double angle_rad) {
  double wrapped = std::remainder(angle_rad, 2.0 * M_PI);  // [-pi, pi]
  if (wrapped <= -M_PI) wrapped += 2.0 * M_PI;
  return wrapped;
}

std::optional<Eigen::Vector2d> circle_segment_goal(const Eigen::Vector2d& center, double radius_m,
                                                   const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  // |a - center + t (b - a)| = r, a quadratic in t (the circle moved to the origin, 003 Fig. 36).
  const Eigen::Vector2d p = a - center;
  const Eigen::Vector2d d = b - a;
  const double qa = d.squaredNorm();
  if (qa == 0.0) return std::nullopt;
  const double qb = 2.0 * p.dot(d);
  const double qc = p.squaredNorm() - radius_m * radius_m;
  const double discriminant = qb * qb - 4.0 * qa * qc;
  if (discriminant < 0.0) return std::nullopt;
  const double root = std::sqrt(discriminant);
  // The larger t is nearer b, so it is tried first.
  for (const double t : {(-qb + root) / (2.0 * qa), (-qb - root) / (2.0 * qa)}) {
    if (t >= 0.0 && t <= 1.0) return Eigen::Vector2d(a + t * d);
  }
  return std::nullopt;
}

PurePursuitStep pure_pursuit_step(const PurePursuitConfig& config, PurePursuitState& state,
                                  const Eigen::Vector2d& position, double heading_rad,
                                  std::span<const Eigen::Vector2d> path) {
  if (path.empty()) throw std::invalid_argument("pure_pursuit_step: empty path");
  const int last = static_cast<int>(path.size()) - 1;
  int& index = state.last_found_index;
  index = std::clamp(index, 0, last);

  PurePursuitStep step;  // source: waypoint until a crossing is accepted
  for (int i = index; i < last; ++i) {
    const auto crossing = circle_segment_goal(position, config.lookahead_m, path[i], path[i + 1]);
    if (!crossing) continue;
    // Not going back (003 Fig. 39): accept only a point that brings the robot nearer the next waypoint.
    if ((*crossing - path[i + 1]).norm() < (position - path[i + 1]).norm()) {
      index = i;
      step.goal = *crossing;
      step.source = GoalSource::intersection;
      break;
    }
    index = i + 1;
  }
  if (step.source == GoalSource::waypoint) {
    const auto inside = [&](const Eigen::Vector2d& p) { return (p - position).norm() <= config.lookahead_m; };
    if (std::all_of(path.begin() + index, path.end(), inside)) index = last;
    step.goal = path[index];
  }
  step.index = index;

  const Eigen::Vector2d to_goal = step.goal - position;
  const double bearing = to_goal.squaredNorm() > 0.0 ? std::atan2(to_goal.y(), to_goal.x()) : heading_rad;
  step.turn_error_rad = wrap_to_pi(bearing - heading_rad);
  step.end_reached = index >= last - 1 && (position - path[last]).norm() <= config.goal_tolerance_m;
  if (step.end_reached) return step;

  step.yaw_rate_rad_s =
      std::clamp(config.turn_gain_per_s * step.turn_error_rad, -config.max_yaw_rate_rad_s, config.max_yaw_rate_rad_s);
  const double slowdown = std::min(1.0, std::abs(step.turn_error_rad) / config.slowdown_turn_error_rad);
  step.speed_m_s = config.max_speed_m_s - (config.max_speed_m_s - config.min_speed_m_s) * slowdown;
  return step;
}

}  // namespace campo
