#pragma once
/// The vehicle concept as the closed loop sees it: commands in, state out.
/// Implementations live in vehicles/; a vehicle owns its Bullet bodies inside
/// a World (added on construction, removed on destruction, so it must be
/// destroyed before the World).
#include <array>
#include <optional>
#include <string_view>
#include <variant>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "campo/scene.hpp"
#include "campo/state_estimation.hpp"

namespace campo {

/// Ground-truth state of a vehicle body, world frame.
struct VehicleState {
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  ///< body to world
  Eigen::Vector3d linear_velocity_mps = Eigen::Vector3d::Zero();     ///< world frame
  Eigen::Vector3d angular_velocity_radps = Eigen::Vector3d::Zero();  ///< world frame
  /// Heading of the body x axis projected on the ground plane, radians from +x (east), CCW.
  double yaw_rad() const;
  Eigen::Isometry3d pose() const;
};

/// `truth` as an estimator with error `error` reports it: position and
/// velocity offset, heading turned about the world z axis.
VehicleState estimated(const VehicleState& truth, const StateError& error);

/// Commands a planner may give (SPEC §5 behaviours). Each vehicle accepts
/// those that make sense for it and rejects the others.
namespace command {
/// Stay at `position_m` (quadrotor: hover; rover: brake to a stop there).
struct Hold {
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();
  std::optional<double> yaw_rad;  ///< keep the current heading when unset
};
/// Go to `target_m` in a straight line at no more than `speed_mps`.
struct GoTo {
  Eigen::Vector3d target_m = Eigen::Vector3d::Zero();
  double speed_mps = 0.6;
  bool face_target = true;  ///< quadrotor: turn toward the target while flying
};
/// Turn in place to face `point_m` (000 ControllaRotazione).
struct Face {
  Eigen::Vector3d point_m = Eigen::Vector3d::Zero();
};
/// Hold the horizontal position and change altitude to `z_m` (000 ControllaAltitudine).
struct Altitude {
  double z_m = 0.0;
};
/// Rover body velocities: forward speed and yaw rate.
struct Twist {
  double v_mps = 0.0;
  double w_radps = 0.0;
};

// Low-level commands, for learning-based control (docs/extending.md, "Commands").
// The heading frame: x along the current heading projected on the ground, y to
// its left, z up (world z).

/// Quadrotor: fly at `velocity_mps` in the heading frame while turning at
/// `yaw_rate_radps` (CCW positive). The speed is capped at the position loop's
/// output limit, the turn rate at the yaw attitude loop's.
struct Velocity {
  Eigen::Vector3d velocity_mps = Eigen::Vector3d::Zero();
  double yaw_rate_radps = 0.0;
};
/// Quadrotor: hold roll and pitch (radians, of the body relative to the
/// heading frame: attitude = Rz(heading) Ry(pitch) Rx(roll)), turn at
/// `yaw_rate_radps`, collective thrust `thrust_n` (N) along body z. Positive
/// pitch tilts the nose down and accelerates forward (+x); positive roll tilts
/// the right side down and accelerates to the right (-y). Tilt capped at
/// max_tilt_deg, thrust at what the rotors give.
struct AttitudeThrust {
  double roll_rad = 0.0;
  double pitch_rad = 0.0;
  double yaw_rate_radps = 0.0;
  double thrust_n = 0.0;
};
/// Quadrotor: rotor speed commands, rad/s, in rotor order (rotor_position()),
/// clamped to [min_rotor_speed_radps, max_rotor_speed_radps]; they pass
/// through the motor lag like the controller's.
struct Rotors {
  std::array<double, 4> speeds_radps{};
};
/// Rover: motor target speeds, rad/s, per wheel in Rover::Wheel order
/// (front_left, front_right, rear_left, rear_right), positive rolling
/// forward, clamped to +-max_wheel_speed_radps (and to max_wheel_accel_radps2).
struct Wheels {
  std::array<double, 4> speeds_radps{};
};
}  // namespace command

/// New kinds go at the end, so that the index of every existing kind keeps its meaning.
using Command = std::variant<command::Hold, command::GoTo, command::Face, command::Altitude,
                             command::Twist, command::Velocity, command::AttitudeThrust, command::Rotors,
                             command::Wheels>;

/// Name of a command kind, for records and error messages.
std::string_view command_name(const Command& c);

class Vehicle {
 public:
  virtual ~Vehicle() = default;

  virtual VehicleType type() const = 0;
  /// Sets the behaviour until the next command. Throws std::invalid_argument
  /// for a command this vehicle cannot follow.
  virtual void command(const Command& c) = 0;
  /// Runs the low-level controllers and applies actuator forces; called
  /// before every physics step with the step length.
  virtual void pre_step(double dt_s) = 0;
  /// Ground-truth state after the last physics step.
  virtual VehicleState state() const = 0;
  /// The state the vehicle's own controllers act on: the true state with
  /// the estimation error set last (the truth when none is set).
  VehicleState estimated_state() const { return estimated(state(), estimation_error_); }
  /// Sets the estimation error the controllers see until the next call.
  void set_estimation_error(const StateError& error) { estimation_error_ = error; }
  /// Linear and angular speeds are below the "stabilized" thresholds (000 stabilize()).
  virtual bool stable() const = 0;
  /// Actuator values for the trajectory record (rotor speeds, wheel speeds ...).
  virtual nlohmann::json actuators() const = 0;
  /// The effective parameters, for provenance.
  virtual nlohmann::json parameters() const = 0;

 private:
  StateError estimation_error_;
};

}  // namespace campo
