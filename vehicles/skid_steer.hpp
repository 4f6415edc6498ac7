#pragma once
/// Skid-steer (differential) kinematics of a four-wheel rover with fixed
/// wheels, 003 §3.5, as pure functions.
///
/// Sign convention: campo's frame is ENU with yaw counter-clockwise positive,
/// so with w the CCW yaw rate the right wheels turn faster in a left turn:
///   w_right = v/r + w*l/r,   w_left = v/r - w*l/r.
/// 003 writes w_r = v/r - w*l/r, w_l = v/r + w*l/r because its heading angle
/// is measured clockwise: the same model with the opposite sign of w.
/// The two wheels of a side turn at the same speed.

namespace campo {

/// Geometry the kinematic model needs.
struct SkidSteerGeometry {
  double wheel_radius_m = 0.2;  ///< r, > 0
  double half_track_m = 0.425;  ///< l: lateral offset of the wheel centres from the centre line, > 0
};

/// Angular speeds of the left and right wheels, rad/s, positive rolling forward.
struct WheelSpeeds {
  double left_radps = 0.0;
  double right_radps = 0.0;
};

/// Body velocities: forward speed and CCW yaw rate.
struct BodyTwist {
  double v_mps = 0.0;
  double w_radps = 0.0;
};

/// Planar pose estimate: position and CCW heading from +x.
struct PlanarPose {
  double x_m = 0.0;
  double y_m = 0.0;
  double yaw_rad = 0.0;
};

/// Inverse kinematics: wheel speeds that produce `twist` without slip.
WheelSpeeds wheel_speeds_from_twist(const BodyTwist& twist, const SkidSteerGeometry& g);

/// Forward kinematics: the body twist of wheel speeds without slip.
BodyTwist twist_from_wheel_speeds(const WheelSpeeds& wheels, const SkidSteerGeometry& g);

/// Scales both speeds by the same factor so neither exceeds `max_radps` in
/// magnitude; keeps their ratio, hence the path curvature.
WheelSpeeds saturate(const WheelSpeeds& wheels, double max_radps);

/// Second-order actuation (003 §3.5, dw/dt = u with |u| <= max_accel):
/// moves each of `current` toward `target` by at most max_accel*dt.
/// max_accel_radps2 <= 0 disables the limit (returns `target`).
WheelSpeeds rate_limit(const WheelSpeeds& current, const WheelSpeeds& target,
                       double max_accel_radps2, double dt_s);

/// Wheel odometry: advances `pose` by `dt_s` at constant wheel speeds,
/// integrating the arc exactly (a straight segment when the yaw rate is zero).
PlanarPose integrate_odometry(const PlanarPose& pose, const WheelSpeeds& wheels,
                              const SkidSteerGeometry& g, double dt_s);

}  // namespace campo
