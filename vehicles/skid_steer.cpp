#include "vehicles/skid_steer.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace campo {

namespace {

// sin(x)/x, with its series near 0 where the quotient loses precision.
double sinc(double x) {
  if (std::abs(x) < 1e-4) return 1.0 - x * x / 6.0;
  return std::sin(x) / x;
}

double wrap_yaw(double a) {
  a = std::remainder(a, 2.0 * std::numbers::pi);
  return a <= -std::numbers::pi ? a + 2.0 * std::numbers::pi : a;
}

double step_toward(double current, double target, double max_step) {
  return current + std::clamp(target - current, -max_step, max_step);
}

}  // namespace

WheelSpeeds wheel_speeds_from_twist(const BodyTwist& twist, const SkidSteerGeometry& g) {
  const double forward = twist.v_mps / g.wheel_radius_m;
  const double turn = twist.w_radps * g.half_track_m / g.wheel_radius_m;
  return {forward - turn, forward + turn};
}

BodyTwist twist_from_wheel_speeds(const WheelSpeeds& wheels, const SkidSteerGeometry& g) {
  return {0.5 * g.wheel_radius_m * (wheels.right_radps + wheels.left_radps),
          0.5 * g.wheel_radius_m * (wheels.right_radps - wheels.left_radps) / g.half_track_m};
}

WheelSpeeds saturate(const WheelSpeeds& wheels, double max_radps) {
  const double largest = std::max(std::abs(wheels.left_radps), std::abs(wheels.right_radps));
  if (largest <= max_radps) return wheels;
  const double scale = max_radps / largest;
  return {wheels.left_radps * scale, wheels.right_radps * scale};
}

WheelSpeeds rate_limit(const WheelSpeeds& current, const WheelSpeeds& target,
                       double max_accel_radps2, double dt_s) {
  if (max_accel_radps2 <= 0.0) return target;
  const double max_step = max_accel_radps2 * dt_s;
  return {step_toward(current.left_radps, target.left_radps, max_step),
          step_toward(current.right_radps, target.right_radps, max_step)};
}

PlanarPose integrate_odometry(const PlanarPose& pose, const WheelSpeeds& wheels,
                              const SkidSteerGeometry& g, double dt_s) {
  const BodyTwist twist = twist_from_wheel_speeds(wheels, g);
  const double turn = twist.w_radps * dt_s;
  // On a circular arc the chord has length v*dt*sinc(turn/2) and points
  // along the mean heading; this also covers the straight line (turn = 0).
  const double chord = twist.v_mps * dt_s * sinc(0.5 * turn);
  const double heading = pose.yaw_rad + 0.5 * turn;
  return {pose.x_m + chord * std::cos(heading), pose.y_m + chord * std::sin(heading),
          wrap_yaw(pose.yaw_rad + turn)};
}

}  // namespace campo
