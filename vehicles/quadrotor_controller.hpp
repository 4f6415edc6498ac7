#pragma once
/// Flight controller of the quadrotor (SPEC §5): the behaviours planners ask
/// for (hover, go to a point in a straight line, face a point, change
/// altitude) on top of a cascade position -> velocity -> attitude -> body
/// rates -> mixer, and the low-level commands that enter it lower down
/// (velocity, attitude and thrust, rotor speeds). Pure: no Bullet; it sees
/// only VehicleState.
#include <array>
#include <limits>

#include <Eigen/Geometry>

#include "campo/vehicle.hpp"
#include "vehicles/pid.hpp"

namespace campo {

/// Gains of the cascade and the shaping of the behaviours. The defaults suit
/// the 1.5 kg preset of QuadrotorConfig; loops are listed outer to inner.
struct QuadrotorControllerConfig {
  /// Position, per world axis: m -> m/s. Derivative on the measured velocity.
  /// The output limit is the highest speed any behaviour commands.
  PidConfig position{1.0, 0.0, 0.0, 0.5, 10.0};
  /// Horizontal velocity, per world axis: m/s -> m/s^2.
  PidConfig velocity_xy{2.5, 0.4, 0.0, 1.0, 4.0};
  /// Vertical velocity: m/s -> m/s^2 (added to the gravity feed-forward).
  PidConfig velocity_z{4.0, 1.0, 0.0, 2.0, 4.0};
  /// Roll and pitch attitude: rad -> rad/s. Derivative on the measured body rate.
  PidConfig attitude_rp{6.0, 0.0, 0.0, 0.5, 3.0};
  /// Yaw attitude: rad -> rad/s; the output limit is the turn rate.
  PidConfig attitude_yaw{2.5, 0.0, 0.0, 0.5, 1.0};
  /// Roll and pitch body rates: rad/s -> rad/s^2.
  PidConfig rate_rp{18.0, 2.0, 0.0, 5.0, 60.0};
  /// Yaw body rate: rad/s -> rad/s^2.
  PidConfig rate_yaw{6.0, 1.0, 0.0, 2.0, 3.0};
  double speed_limit_mps = 0.6;      ///< speed of Hold, Face and Altitude moves (000 flew at 0.6 m/s), > 0
  double max_tilt_deg = 30.0;        ///< bound on the commanded tilt, degrees in (0, 80]
  double braking_decel_mps2 = 1.0;   ///< deceleration planned to stop at a target, > 0
  double face_min_distance_m = 0.5;  ///< GoTo turns toward its target only when farther than this (horizontally), >= 0
};

/// What the controller knows of the airframe; built from QuadrotorConfig and
/// the world's gravity by the Quadrotor (see model_of() in quadrotor.hpp).
struct QuadrotorModel {
  double mass_kg = 0.0;                                   ///< > 0
  Eigen::Vector3d inertia_kgm2 = Eigen::Vector3d::Zero(); ///< principal moments about body x, y, z
  double arm_length_m = 0.0;                              ///< centre to rotor axis
  double thrust_coefficient = 0.0;                        ///< k_f, N/(rad/s)^2
  double torque_coefficient = 0.0;                        ///< k_m, N m/(rad/s)^2
  double min_rotor_speed_radps = 0.0;                     ///< rad/s
  double max_rotor_speed_radps = 0.0;                     ///< rad/s
  Eigen::Vector3d gravity_mps2 = Eigen::Vector3d::Zero(); ///< world frame, m/s^2
};

/// Rotor speeds, rad/s, in rotor order (see rotor_position()).
using RotorSpeeds = std::array<double, 4>;

/// Body-frame position of rotor i in the X configuration: arm_length_m at
/// 45, 135, 225 and 315 degrees from body +x (front-left, rear-left,
/// rear-right, front-right), in the plane z = 0 of the centre of mass.
Eigen::Vector3d rotor_position(int i, double arm_length_m);

/// Sign of the drag torque rotor i exerts on the body about body +z: rotors 0
/// and 2 spin clockwise seen from above (reaction +z), 1 and 3 anticlockwise.
inline constexpr std::array<double, 4> kRotorTorqueSign{1.0, -1.0, 1.0, -1.0};

/// Allocation matrix A: [thrust N, roll, pitch, yaw torque N m] (body frame)
/// = A * (w_0^2 ... w_3^2), with the layout of rotor_position() and kRotorTorqueSign.
Eigen::Matrix4d allocation_matrix(double arm_length_m, double thrust_coefficient,
                                  double torque_coefficient);

/// Squared rotor speeds, each in [min_sq, max_sq], that realise a wrench as
/// closely as the limits allow, given inverse = allocation_matrix()^-1.
/// Priorities when a limit is hit: roll/pitch torque first (scaled down only
/// if it alone exceeds the motor range), since losing the attitude loses the
/// vehicle; then collective thrust (shifted to fit); yaw torque last (scaled).
Eigen::Vector4d mix(const Eigen::Matrix4d& inverse, double thrust_n, const Eigen::Vector3d& torque_nm,
                    double min_sq, double max_sq);

/// Rotor speed at which the rotors carry the weight, rad/s.
double hover_rotor_speed(const QuadrotorModel& model);

/// Attitude whose body z is along `thrust_direction` (world frame, need not be
/// unit, must point upward) and whose body x points at heading `yaw_rad` as
/// seen from above.
Eigen::Quaterniond attitude_from_thrust(const Eigen::Vector3d& thrust_direction, double yaw_rad);

/// Rotation from `current` to `desired` in the body frame, tilt first (so
/// that a large heading change does not disturb the tilt): x and y are the
/// shortest rotation that aligns the body z axes (axis times 2 sin(angle/2));
/// z is the heading change that remains, radians in [-pi, pi].
Eigen::Vector3d attitude_error(const Eigen::Quaterniond& current, const Eigen::Quaterniond& desired);

/// Caps `v` at `limit` in norm, its part across the unit `direction` first
/// (that part alone is capped at `limit`; the part along gets what is left),
/// and caps its part along `direction` at `along_limit` as well. A zero
/// direction caps the norm only. Used to keep a move on its line: the
/// cross-track correction is never sacrificed to speed along the line.
Eigen::Vector3d cap_cross_first(const Eigen::Vector3d& v, const Eigen::Vector3d& direction, double limit,
                                double along_limit = std::numeric_limits<double>::infinity());

class QuadrotorController {
 public:
  /// Starts holding `initial`'s position and heading.
  QuadrotorController(const QuadrotorControllerConfig& config, const QuadrotorModel& model,
                      const VehicleState& initial);

  /// Sets the behaviour from the vehicle's current `state`. Throws
  /// std::invalid_argument for Twist and Wheels (rover commands) and for
  /// non-finite values of the low-level commands. Re-sending the active
  /// command (same kind and target) keeps the behaviour and every integrator,
  /// updating only its secondary fields (GoTo speed and face_target, Hold
  /// yaw); a new target restarts the behaviour and resets the position loop,
  /// while the inner loops keep their trims, which do not depend on the target.
  ///
  /// The low-level commands enter the cascade lower down: Velocity at the
  /// velocity loop, AttitudeThrust at the attitude loop (its thrust straight
  /// to the mixer), Rotors after the mixer (the controller returns the rotor
  /// speeds given, clamped). Re-sending one of them with new values keeps
  /// its heading reference and every integrator. Loops that did not run under
  /// the previous command are reset when a command needs them again (Hold
  /// after Rotors starts every loop afresh), so no stale integral kicks.
  void command(const Command& c, const VehicleState& state);

  /// One control step of `dt_s` seconds: rotor speed commands, rad/s.
  RotorSpeeds update(const VehicleState& state, double dt_s);

  const QuadrotorControllerConfig& config() const { return config_; }

 private:
  /// Where the active command enters the cascade.
  enum class Mode {
    position,  ///< Hold, GoTo, Face, Altitude: the whole cascade
    velocity,  ///< Velocity: from the velocity loop down
    attitude,  ///< AttitudeThrust: from the attitude loop down
    rotors,    ///< Rotors: no loop
  };

  /// The active behaviour reduced to references for the cascade.
  struct Reference {
    Command command;                                            ///< as given (for the same-target test)
    Mode mode = Mode::position;
    Eigen::Vector3d position_m = Eigen::Vector3d::Zero();       ///< where to go or stay
    Eigen::Vector3d direction = Eigen::Vector3d::Zero();        ///< GoTo: unit line direction, else zero
    double yaw_rad = 0.0;
    double speed_mps = 0.0;
    bool face_target = false;  ///< GoTo: turn toward position_m on the way
  };

  void reset_position_loop();
  /// Hold, GoTo, Face, Altitude: the position loop's velocity command, m/s, world frame.
  Eigen::Vector3d position_to_velocity(const VehicleState& state, double dt_s);
  /// Resets the loops that mode `to` runs and mode `from` left idle.
  void restart_idle_loops(Mode from, Mode to);
  /// Velocity and AttitudeThrust: advances the heading reference by the yaw rate over `dt_s`.
  void advance_yaw(double yaw_rad, double yaw_rate_radps, double dt_s);

  QuadrotorControllerConfig config_;
  QuadrotorModel model_;
  Eigen::Matrix4d allocation_inverse_;
  double min_sq_ = 0.0;
  double max_sq_ = 0.0;
  double tan_max_tilt_ = 0.0;
  double position_error_cap_ = 0.0;  ///< m, see update()
  double velocity_error_cap_ = 0.0;  ///< m/s, horizontal
  double yaw_error_cap_ = 0.0;       ///< rad, where the yaw attitude loop saturates
  double max_thrust_n_ = 0.0;        ///< all rotors at max_rotor_speed_radps
  Reference reference_;
  std::array<Pid, 3> position_;  ///< world x, y, z
  std::array<Pid, 3> velocity_;  ///< world x, y, z
  std::array<Pid, 3> attitude_;  ///< body roll, pitch, yaw
  std::array<Pid, 3> rate_;      ///< body roll, pitch, yaw
};

}  // namespace campo
