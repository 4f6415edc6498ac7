#pragma once
/// The four-wheel skid-steer rover of 003 §3.1 and §3.5 in Bullet: a chassis
/// box and four wheel bodies on hinges, each wheel driven by its own motor
/// (torque vectoring), with real wheel-ground friction contacts.
#include <array>
#include <memory>
#include <optional>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "campo/config_fields.hpp"
#include "campo/scene.hpp"
#include "campo/vehicle.hpp"
#include "campo/world.hpp"
#include "vehicles/skid_steer.hpp"

namespace campo {

/// Rover parameters; the defaults are the preset. Body frame: x forward,
/// y left, z up, origin at the chassis centre. 003 gives the 1.0 m x 1.5 m
/// chassis and four fixed wheels with one motor each; the rest are values of
/// a small electric field platform (003 gives no mass, wheel size or motors).
struct RoverConfig {
  // Chassis.
  Eigen::Vector3d chassis_size_m{1.5, 1.0, 0.35};  ///< length x, width y, height z; each > 0
  double chassis_mass_kg = 40.0;  ///< > 0; with four 2.5 kg wheels the rover weighs 50 kg
  double chassis_friction = 0.5;  ///< [0, 10]; Bullet multiplies it by the other body's friction

  // Wheels: spheres, which roll smoothly over heightfield triangle edges and
  // collide cheaply (cylinders cost 3x on heightfields and make the yaw rate
  // jitter). Inside the 1.0 m x 1.5 m outline, as 003's footprint assumes.
  double wheel_radius_m = 0.2;  ///< r, > 0
  double wheel_mass_kg = 2.5;   ///< each, > 0
  double wheel_friction = 1.0;  ///< [0, 10]; times the ground's (0.8 by default): the tyre-ground coefficient
  double half_track_m = 0.3;    ///< l: lateral offset of the wheel centres from the centre line, > 0
  double wheelbase_m = 1.0;     ///< front to rear axle, > 0
  double axle_drop_m = 0.2;     ///< axles below the chassis centre; rest height of the centre = r + this

  // Motors.
  double max_wheel_torque_nm = 40.0;      ///< per motor, > 0
  double max_wheel_speed_radps = 10.0;    ///< per motor, > 0 (2 m/s at the rim with r = 0.2 m)
  double max_wheel_accel_radps2 = 0.0;    ///< >= 0; second-order actuation limit (003 §3.5), 0 = off

  // Holding still (Hold, or GoTo/Face done): once braked to zero, each wheel
  // servos to the angle it stopped at and its ground contact gets a Bullet
  // friction anchor; velocity motors and velocity-level friction alone let
  // a parked rover creep downhill.
  double hold_gain = 10.0;  ///< > 0, 1/s; wheel speed target = -gain * wheel angle error

  // Solver iterations of the four wheel hinges ([1, 1000]); the contacts use
  // the world's count. The hinges are most of the solver's work, so few while
  // driving; more while holding, where fewer make the locked wheels jitter
  // against their friction anchors.
  int joint_solver_iterations = 4;
  int hold_solver_iterations = 20;

  // Closed loop on measured body rates, on top of the kinematic feed-forward:
  // correction = kp*error + integral, integral += ki*error*dt, |integral| <= max.
  double speed_kp = 1.0;                   ///< >= 0, (m/s)/(m/s)
  double speed_ki = 2.0;                   ///< >= 0, 1/s
  double speed_integral_max_mps = 0.5;     ///< >= 0
  double yaw_rate_kp = 2.0;                ///< >= 0, (rad/s)/(rad/s)
  double yaw_rate_ki = 12.0;               ///< >= 0, 1/s
  /// >= 0; turning in place takes wheel speeds ~4x the kinematic ones
  double yaw_rate_integral_max_radps = 5.0;

  // Behaviours (GoTo, Face).
  double heading_gain = 1.5;            ///< > 0, yaw rate per heading error, 1/s
  double max_yaw_rate_radps = 1.0;      ///< > 0, for GoTo and Face
  double approach_gain = 0.8;           ///< > 0, GoTo speed per remaining distance, 1/s
  double turn_in_place_deg = 45.0;      ///< (0, 180]; GoTo turns in place above this heading error
  double arrival_radius_m = 0.15;       ///< > 0; GoTo brakes and holds within this distance
  double face_tolerance_deg = 2.0;      ///< > 0; Face brakes and holds within this heading error

  // Status.
  double stable_speed_mps = 0.05;       ///< > 0, stable() below this linear speed
  double stable_rate_radps = 0.05;      ///< > 0, and below this angular speed
};

/// The fields of a "params" block.
const ConfigFields<RoverConfig>& rover_config_fields();

/// The preset overridden by the keys of `params` (the names of the
/// RoverConfig fields); unknown keys and bad values throw InputError naming
/// params.file and the JSON pointer.
RoverConfig parse_rover_config(const ParamsBlock& params);

/// Every effective parameter.
nlohmann::json to_json(const RoverConfig& config);

class Rover final : public Vehicle {
 public:
  /// Wheels in the order used by actuators() and the wheel arrays.
  enum Wheel { front_left, front_right, rear_left, rear_right };
  static constexpr int kWheels = 4;

  /// Adds the rover's bodies to `world` with the chassis centre at
  /// `start_pose` (rest height above the ground: wheel_radius_m + axle_drop_m).
  Rover(World& world, const RoverConfig& config, const Eigen::Isometry3d& start_pose);
  ~Rover() override;
  Rover(const Rover&) = delete;
  Rover& operator=(const Rover&) = delete;

  VehicleType type() const override { return VehicleType::rover; }
  /// Accepts Twist, Hold (brake and hold the wheels still; Hold's position
  /// and yaw are not used), GoTo (in the ground plane; target z and
  /// face_target are not used), Face and Wheels (the four motor targets as
  /// given, clamped to +-max_wheel_speed_radps and rate-limited by
  /// max_wheel_accel_radps2, no body-rate loop); throws std::invalid_argument
  /// for Altitude and the quadrotor's Velocity, AttitudeThrust and Rotors,
  /// non-finite values and a GoTo speed that is not > 0.
  void command(const Command& c) override;
  /// Integrates the odometry over the last step, runs the behaviour and
  /// the body-rate loop (or takes the Wheels command's speeds) and sets the
  /// four wheel motors. No heap allocation.
  void pre_step(double dt_s) override;
  /// Chassis state.
  VehicleState state() const override;
  bool stable() const override;
  /// The chassis touches anything, or a wheel touches anything but a plane
  /// or heightfield scene shape (obstacles, movers, other vehicles).
  /// Per wheel (front_left, front_right, rear_left, rear_right): the motor's
  /// target speed and the measured speed relative to the chassis, rad/s.
  nlohmann::json actuators() const override;
  nlohmann::json parameters() const override { return to_json(config_); }
  const RoverConfig& config() const { return config_; }

  /// Wheel-odometry pose estimate integrated from the measured wheel speeds
  /// since the start (starts at the start pose's x, y and heading).
  const PlanarPose& odometry() const { return odometry_; }
  /// Measured wheel speeds relative to the chassis, rad/s, positive forward.
  std::array<double, kWheels> wheel_speeds_radps() const;
  /// Motor target speeds set by the last pre_step, rad/s.
  const std::array<double, kWheels>& wheel_commands_radps() const { return wheel_targets_; }

 private:
  struct Bodies;
  /// The body twist the current command asks for; nullopt: brake and hold.
  std::optional<BodyTwist> behaviour_twist(const VehicleState& s);
  WheelSpeeds measured_side_speeds() const;
  /// Sets the four motors to a Wheels command's speeds.
  void drive_wheels(const command::Wheels& wheels, double dt_s);
  /// Locks the wheels at their current angles (servo, friction anchors, hold
  /// solver iterations) or releases them for driving (anchors would resist rolling).
  void lock_wheels(bool on);
  /// Rotation of a wheel relative to the chassis, (-pi, pi], positive rolling forward.
  double wheel_angle(int wheel) const;

  RoverConfig config_;
  SkidSteerGeometry geometry_;
  std::unique_ptr<Bodies> bodies_;
  Command command_;
  bool arrived_ = false;           ///< GoTo/Face target reached: holding until the next command
  double speed_integral_mps_ = 0.0;   ///< integral term of the forward-speed loop
  double yaw_integral_radps_ = 0.0;   ///< integral term of the yaw-rate loop
  WheelSpeeds side_targets_;       ///< feed-forward plus correction after the limits, per side
  std::array<double, kWheels> wheel_targets_{};
  bool wheels_locked_ = false;     ///< stopped under Hold: the wheels servo to hold_angles_
  std::array<double, kWheels> hold_angles_{};  ///< wheel angles when the wheels stopped, rad
  PlanarPose odometry_;
};

}  // namespace campo
