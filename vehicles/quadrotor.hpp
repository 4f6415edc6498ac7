#pragma once
/// The quadrotor (SPEC §5; 000, 001): one Bullet rigid body driven by four
/// rotors in X configuration, each giving thrust k_f w^2 along body z at its
/// position and drag torque k_m w^2 about body z, behind a first-order motor
/// lag; drag on the airspeed (the body's velocity relative to World::wind_mps:
/// linear rotor drag, optional quadratic body drag) and angular drag. Flown by
/// QuadrotorController at the physics rate, which is not told the wind.
#include <array>
#include <memory>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "campo/config_fields.hpp"
#include "campo/scene.hpp"
#include "campo/vehicle.hpp"
#include "campo/world.hpp"
#include "vehicles/quadrotor_controller.hpp"

class btCollisionShape;

namespace campo {

/// A ~1.5 kg research quadrotor (the preset); scene files override any field
/// through the vehicle's "params" block (parse_quadrotor_config).
struct QuadrotorConfig {
  double mass_kg = 1.5;                                       ///< > 0
  Eigen::Vector3d inertia_kgm2{0.029, 0.029, 0.055};          ///< principal moments about body x, y, z, kg m^2, > 0
  double arm_length_m = 0.225;                                ///< centre to rotor axis, > 0
  double thrust_coefficient = 1.0e-5;                         ///< k_f, N/(rad/s)^2: hovers at 607 rad/s, 61 % of max
  double torque_coefficient = 1.6e-7;                         ///< k_m, N m/(rad/s)^2 (k_m/k_f = 16 mm, a 10-inch propeller)
  double motor_time_constant_s = 0.02;                        ///< first-order lag of rotor speed, > 0
  double min_rotor_speed_radps = 150.0;                       ///< idle speed in flight, rad/s, >= 0
  double max_rotor_speed_radps = 1000.0;                      ///< rad/s, > min_rotor_speed_radps
  double linear_drag_n_per_mps = 0.3;                         ///< rotor drag -c v_air (v_air = v - wind), N per m/s, >= 0
  /// Quadratic body drag: C_d A per body axis, m^2, >= 0; force per body axis
  /// -0.5 rho (C_d A)_i |v_air| v_air_i. Zero in the preset (docs/vehicles.md).
  Eigen::Vector3d drag_area_m2{0.0, 0.0, 0.0};
  double air_density_kgpm3 = 1.225;                           ///< rho of the quadratic drag, kg/m^3, > 0 (ISA sea level)
  double angular_drag_nm_per_radps = 0.005;                   ///< drag torque -c w, N m per rad/s, >= 0
  Eigen::Vector3d collision_half_extents_m{0.3, 0.3, 0.06};   ///< collision box (frame and propellers), > 0
  double stable_linear_speed_mps = 0.05;                      ///< stable() below this speed (000 stabilize()), > 0
  double stable_angular_speed_radps = 0.05;                   ///< and below this angular speed, > 0
  QuadrotorControllerConfig controller;                       ///< gains and behaviour shaping
};

/// The fields of a "params" block (the controller's loops as nested objects).
const ConfigFields<QuadrotorConfig>& quadrotor_config_fields();

/// The preset with the overrides of `params` (keys as in to_json(); the
/// controller's loops as nested objects). Unknown keys, wrong types,
/// out-of-range or inconsistent values (rotor speed range empty, rotors
/// unable to lift the vehicle at standard gravity, bounding sphere smaller
/// than the collision box) throw InputError naming params.file and the JSON
/// pointer under params.pointer.
QuadrotorConfig parse_quadrotor_config(const ParamsBlock& params);

/// Every effective parameter, in the form parse_quadrotor_config() reads.
nlohmann::json to_json(const QuadrotorConfig& config);

/// The airframe as the controller sees it, under `gravity_mps2`.
QuadrotorModel model_of(const QuadrotorConfig& config, const Eigen::Vector3d& gravity_mps2);

class Quadrotor final : public Vehicle {
 public:
  /// Adds the body to `world` at `start_pose`, rotors at hover speed, holding
  /// that position and heading. `world` must outlive the Quadrotor.
  Quadrotor(World& world, const QuadrotorConfig& config, const Eigen::Isometry3d& start_pose);
  ~Quadrotor() override;
  Quadrotor(const Quadrotor&) = delete;
  Quadrotor& operator=(const Quadrotor&) = delete;

  VehicleType type() const override { return VehicleType::quadrotor; }
  void command(const Command& c) override;
  void pre_step(double dt_s) override;
  VehicleState state() const override;
  bool stable() const override;
  nlohmann::json actuators() const override;
  nlohmann::json parameters() const override { return to_json(config_); }

  const QuadrotorConfig& config() const { return config_; }
  /// Rotor speeds after the motor lag, rad/s.
  const RotorSpeeds& rotor_speeds() const { return rotor_speeds_; }
  /// Total rotor thrust, N.
  double thrust_n() const;

 private:
  const World& world_;  ///< the wind
  btDiscreteDynamicsWorld& bullet_;
  QuadrotorConfig config_;
  std::unique_ptr<btCollisionShape> shape_;
  std::unique_ptr<btRigidBody> body_;
  std::array<Eigen::Vector3d, 4> rotors_m_;  ///< body-frame rotor positions
  QuadrotorController controller_;
  RotorSpeeds rotor_commands_{};
  RotorSpeeds rotor_speeds_{};
  double lag_step_s_ = 0.0;  ///< the step motor_blend_ was computed for
  double motor_blend_ = 0.0;
};

}  // namespace campo
