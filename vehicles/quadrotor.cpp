#include "vehicles/quadrotor.hpp"

#include "physics/bullet_convert.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <string_view>

#include <btBulletDynamicsCommon.h>

#include "campo/json_reader.hpp"

namespace campo {

namespace {

// Standard gravity, for the parse-time check that the rotors can lift the vehicle.
constexpr double kStandardGravity = 9.80665;

std::string format(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

const ConfigFields<PidConfig>& pid_config_fields() {
  static const ConfigFields<PidConfig> fields =
      ConfigFields<PidConfig>()
          .number("kp", &PidConfig::kp, Range::non_negative(), "out/err", "proportional gain")
          .number("ki", &PidConfig::ki, Range::non_negative(), "out/(err s)", "integral gain")
          .number("kd", &PidConfig::kd, Range::non_negative(), "out/(err/s)", "derivative gain")
          .number("integral_limit", &PidConfig::integral_limit, Range::positive(), "out",
                  "bound on the magnitude of the integral term")
          .number("output_limit", &PidConfig::output_limit, Range::positive(), "out",
                  "bound on the magnitude of the output");
  return fields;
}

const ConfigFields<QuadrotorControllerConfig>& controller_config_fields() {
  using C = QuadrotorControllerConfig;
  static const ConfigFields<C> fields =
      ConfigFields<C>()
          .number("speed_limit_mps", &C::speed_limit_mps, Range::positive(), "m/s",
                  "speed of hold, face and altitude moves (000 flew at 0.6 m/s)")
          .number("max_tilt_deg", &C::max_tilt_deg, {0.0, 80.0, true, false}, "deg", "bound on the commanded tilt")
          .number("braking_decel_mps2", &C::braking_decel_mps2, Range::positive(), "m/s²",
                  "planned deceleration to stop at a target")
          .number("face_min_distance_m", &C::face_min_distance_m, Range::non_negative(), "m",
                  "`go_to` turns toward its target only when farther (horizontally)")
          .nested("position", &C::position, pid_config_fields(),
                  "position loop per world axis, m → m/s; the output limit is the highest speed commanded")
          .nested("velocity_xy", &C::velocity_xy, pid_config_fields(), "horizontal velocity loop, m/s → m/s²")
          .nested("velocity_z", &C::velocity_z, pid_config_fields(),
                  "vertical velocity loop, m/s → m/s² (added to the gravity feed-forward)")
          .nested("attitude_rp", &C::attitude_rp, pid_config_fields(), "roll and pitch attitude loop, rad → rad/s")
          .nested("attitude_yaw", &C::attitude_yaw, pid_config_fields(),
                  "yaw attitude loop, rad → rad/s; the output limit is the turn rate")
          .nested("rate_rp", &C::rate_rp, pid_config_fields(), "roll and pitch body rate loop, rad/s → rad/s²")
          .nested("rate_yaw", &C::rate_yaw, pid_config_fields(), "yaw body rate loop, rad/s → rad/s²");
  return fields;
}

}  // namespace

const ConfigFields<QuadrotorConfig>& quadrotor_config_fields() {
  using C = QuadrotorConfig;
  static const ConfigFields<C> fields =
      ConfigFields<C>()
          .number("mass_kg", &C::mass_kg, Range::positive(), "kg", "the whole vehicle")
          .vector("inertia_kgm2", &C::inertia_kgm2, Range::positive(), "kg m²", "principal moments about body x, y, z")
          .number("arm_length_m", &C::arm_length_m, Range::positive(), "m", "centre to rotor axis")
          .number("thrust_coefficient", &C::thrust_coefficient, Range::positive(), "N/(rad/s)²",
                  "k_f: hovers at 607 rad/s, 61 % of max")
          .number("torque_coefficient", &C::torque_coefficient, Range::positive(), "N m/(rad/s)²",
                  "k_m (k_m/k_f = 16 mm, a 10-inch propeller)")
          .number("motor_time_constant_s", &C::motor_time_constant_s, Range::positive(), "s",
                  "first-order lag of rotor speed")
          .number("min_rotor_speed_radps", &C::min_rotor_speed_radps, Range::non_negative(), "rad/s",
                  "idle speed in flight")
          .number("max_rotor_speed_radps", &C::max_rotor_speed_radps, Range::positive(), "rad/s",
                  "above `min_rotor_speed_radps`; thrust-to-weight 2.7")
          .number("linear_drag_n_per_mps", &C::linear_drag_n_per_mps, Range::non_negative(), "N/(m/s)",
                  "rotor drag -c v_air, v_air = velocity - wind (below)")
          .vector("drag_area_m2", &C::drag_area_m2, Range::closed(0.0, 10.0), "m²",
                  "quadratic body drag C_d A per body axis x, y, z: -½ ρ (C_d A)_i ‖v_air‖ v_air,i")
          .number("air_density_kgpm3", &C::air_density_kgpm3, Range::closed(0.01, 10.0), "kg/m³",
                  "ρ of the quadratic drag (1.225: ISA sea level)")
          .number("angular_drag_nm_per_radps", &C::angular_drag_nm_per_radps, Range::non_negative(), "N m/(rad/s)",
                  "drag torque -c ω")
          .vector("collision_half_extents_m", &C::collision_half_extents_m, Range::positive(), "m",
                  "collision box (frame and propellers)")
          .number("stable_linear_speed_mps", &C::stable_linear_speed_mps, Range::positive(), "m/s",
                  "`stable` below this speed (000 stabilize())")
          .number("stable_angular_speed_radps", &C::stable_angular_speed_radps, Range::positive(), "rad/s",
                  "and below this angular speed")
          .nested("controller", &C::controller, controller_config_fields(),
                  "gains and behaviour shaping; the loops outer to inner, each a PID with an integral clamp");
  return fields;
}

QuadrotorConfig parse_quadrotor_config(const ParamsBlock& params) {
  const QuadrotorConfig c = quadrotor_config_fields().read(params);

  // Checks across fields, reported at the field a user would change.
  const auto fail = [&](std::string_view key, const std::string& message) {
    throw InputError(params.file, child_pointer(params.pointer, key), message);
  };
  if (c.max_rotor_speed_radps <= c.min_rotor_speed_radps) {
    fail("max_rotor_speed_radps", "expected a speed above min_rotor_speed_radps (" +
                                      format(c.min_rotor_speed_radps) + " rad/s)");
  }
  const double max_thrust = 4.0 * c.thrust_coefficient * c.max_rotor_speed_radps * c.max_rotor_speed_radps;
  if (max_thrust <= c.mass_kg * kStandardGravity) {
    fail("thrust_coefficient", "the rotors cannot lift the vehicle: maximum thrust " +
                                   format(max_thrust) + " N, weight " +
                                   format(c.mass_kg * kStandardGravity) + " N");
  }
  return c;
}

nlohmann::json to_json(const QuadrotorConfig& config) { return quadrotor_config_fields().write(config); }

QuadrotorModel model_of(const QuadrotorConfig& config, const Eigen::Vector3d& gravity_mps2) {
  QuadrotorModel m;
  m.mass_kg = config.mass_kg;
  m.inertia_kgm2 = config.inertia_kgm2;
  m.arm_length_m = config.arm_length_m;
  m.thrust_coefficient = config.thrust_coefficient;
  m.torque_coefficient = config.torque_coefficient;
  m.min_rotor_speed_radps = config.min_rotor_speed_radps;
  m.max_rotor_speed_radps = config.max_rotor_speed_radps;
  m.gravity_mps2 = gravity_mps2;
  return m;
}

namespace {

VehicleState resting_at(const Eigen::Isometry3d& pose) {
  VehicleState s;
  s.position_m = pose.translation();
  s.orientation = Eigen::Quaterniond(pose.linear());
  return s;
}

}  // namespace

Quadrotor::Quadrotor(World& world, const QuadrotorConfig& config, const Eigen::Isometry3d& start_pose)
    : world_(world),
      bullet_(world.bullet()),
      config_(config),
      controller_(config.controller, model_of(config, world.scene().world.gravity_mps2),
                  resting_at(start_pose)) {
  shape_ = std::make_unique<btBoxShape>(to_bt(config.collision_half_extents_m));
  shape_->setMargin(0.0);  // the exact box, without rounded edges (clearance)
  // The construction info sets the configured inertia (setMassProps), not the box's. No
  // motion state: campo reads the body's own transform, and Bullet would interpolate one
  // for it every step.
  btRigidBody::btRigidBodyConstructionInfo info(config.mass_kg, nullptr, shape_.get(), to_bt(config.inertia_kgm2));
  info.m_startWorldTransform = to_bt(start_pose);
  body_ = std::make_unique<btRigidBody>(info);
  body_->setUserIndex(vehicle_tag(world.join_vehicle(), false));
  body_->setActivationState(DISABLE_DEACTIVATION);
  bullet_.addRigidBody(body_.get());

  for (int i = 0; i < 4; ++i) rotors_m_[static_cast<std::size_t>(i)] = rotor_position(i, config.arm_length_m);
  // Start with the rotors carrying the weight, so it does not drop at t = 0.
  const double hover = std::clamp(hover_rotor_speed(model_of(config, world.scene().world.gravity_mps2)),
                                  config.min_rotor_speed_radps, config.max_rotor_speed_radps);
  rotor_commands_.fill(hover);
  rotor_speeds_.fill(hover);
}

Quadrotor::~Quadrotor() { bullet_.removeRigidBody(body_.get()); }

void Quadrotor::command(const Command& c) { controller_.command(c, estimated_state()); }

void Quadrotor::pre_step(double dt_s) {
  rotor_commands_ = controller_.update(estimated_state(), dt_s);
  // Exact discretisation of the first-order motor lag over one step (the step is always
  // the world's, so the exponential is worked out once).
  if (dt_s != lag_step_s_) {
    lag_step_s_ = dt_s;
    motor_blend_ = 1.0 - std::exp(-dt_s / config_.motor_time_constant_s);
  }
  const double blend = motor_blend_;
  const btMatrix3x3& basis = body_->getWorldTransform().getBasis();
  const btVector3 up = basis.getColumn(2);
  double yaw_torque = 0.0;
  // Bullet clears applied forces after every stepSimulation, so these act for one step only.
  for (std::size_t i = 0; i < 4; ++i) {
    rotor_speeds_[i] += blend * (rotor_commands_[i] - rotor_speeds_[i]);
    const double w2 = rotor_speeds_[i] * rotor_speeds_[i];
    body_->applyForce(up * (config_.thrust_coefficient * w2), basis * to_bt(rotors_m_[i]));
    yaw_torque += kRotorTorqueSign[i] * config_.torque_coefficient * w2;
  }
  body_->applyTorque(up * yaw_torque - body_->getAngularVelocity() * config_.angular_drag_nm_per_radps);
  // Drag on the airspeed, at the centre of mass. In still air the wind is exactly zero and
  // v - 0 is v to the bit, so scenes without wind fly as before the wind existed.
  const btTransform& pose = body_->getWorldTransform();
  const btVector3 airspeed = body_->getLinearVelocity() - to_bt(world_.wind_mps(from_bt(pose.getOrigin())));
  body_->applyCentralForce(airspeed * -config_.linear_drag_n_per_mps);
  if (config_.drag_area_m2 != Eigen::Vector3d::Zero()) {
    const Eigen::Vector3d air_body = from_bt(airspeed * basis);  // basis^T airspeed
    const Eigen::Vector3d drag_body =
        -0.5 * config_.air_density_kgpm3 * air_body.norm() * config_.drag_area_m2.cwiseProduct(air_body);
    body_->applyCentralForce(basis * to_bt(drag_body));
  }
}

VehicleState Quadrotor::state() const {
  const btTransform& t = body_->getWorldTransform();
  const btQuaternion q = t.getRotation();
  VehicleState s;
  s.position_m = from_bt(t.getOrigin());
  s.orientation = Eigen::Quaterniond(q.w(), q.x(), q.y(), q.z());
  s.linear_velocity_mps = from_bt(body_->getLinearVelocity());
  s.angular_velocity_radps = from_bt(body_->getAngularVelocity());
  return s;
}

bool Quadrotor::stable() const {
  return body_->getLinearVelocity().length() < config_.stable_linear_speed_mps &&
         body_->getAngularVelocity().length() < config_.stable_angular_speed_radps;
}


double Quadrotor::thrust_n() const {
  double total = 0.0;
  for (const double w : rotor_speeds_) total += config_.thrust_coefficient * w * w;
  return total;
}

// Built in place, once per control tick: the same object an initializer list
// would give, without its intermediate copies of each key and array.
nlohmann::json Quadrotor::actuators() const {
  const auto array = [](const RotorSpeeds& speeds) {
    nlohmann::json::array_t a;
    a.reserve(speeds.size());
    for (const double w : speeds) a.emplace_back(w);
    return a;
  };
  nlohmann::json j(nlohmann::json::value_t::object);
  auto& fields = j.get_ref<nlohmann::json::object_t&>();
  fields.emplace("rotor_speed_command_radps", array(rotor_commands_));
  fields.emplace("rotor_speed_radps", array(rotor_speeds_));
  fields.emplace("thrust_n", thrust_n());
  return j;
}

}  // namespace campo
