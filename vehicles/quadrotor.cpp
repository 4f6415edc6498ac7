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

// One table per struct for both directions (reading and printing), so the
// JSON keys of parse_quadrotor_config() and to_json() cannot drift apart.
template <typename Struct>
struct NumberField {
  std::string_view key;
  double Struct::*member;
  Range range;
};

template <typename Struct>
struct VectorField {
  std::string_view key;
  Eigen::Vector3d Struct::*member;
  Range range;
};

struct PidField {
  std::string_view key;
  PidConfig QuadrotorControllerConfig::*member;
};

const NumberField<QuadrotorConfig> kNumbers[] = {
    {"mass_kg", &QuadrotorConfig::mass_kg, Range::positive()},
    {"arm_length_m", &QuadrotorConfig::arm_length_m, Range::positive()},
    {"thrust_coefficient", &QuadrotorConfig::thrust_coefficient, Range::positive()},
    {"torque_coefficient", &QuadrotorConfig::torque_coefficient, Range::positive()},
    {"motor_time_constant_s", &QuadrotorConfig::motor_time_constant_s, Range::positive()},
    {"min_rotor_speed_radps", &QuadrotorConfig::min_rotor_speed_radps, Range::non_negative()},
    {"max_rotor_speed_radps", &QuadrotorConfig::max_rotor_speed_radps, Range::positive()},
    {"linear_drag_n_per_mps", &QuadrotorConfig::linear_drag_n_per_mps, Range::non_negative()},
    {"angular_drag_nm_per_radps", &QuadrotorConfig::angular_drag_nm_per_radps, Range::non_negative()},
    {"stable_linear_speed_mps", &QuadrotorConfig::stable_linear_speed_mps, Range::positive()},
    {"stable_angular_speed_radps", &QuadrotorConfig::stable_angular_speed_radps, Range::positive()},
};

const VectorField<QuadrotorConfig> kVectors[] = {
    {"inertia_kgm2", &QuadrotorConfig::inertia_kgm2, Range::positive()},
    {"collision_half_extents_m", &QuadrotorConfig::collision_half_extents_m, Range::positive()},
};

const NumberField<QuadrotorControllerConfig> kControllerNumbers[] = {
    {"speed_limit_mps", &QuadrotorControllerConfig::speed_limit_mps, Range::positive()},
    {"max_tilt_deg", &QuadrotorControllerConfig::max_tilt_deg, {0.0, 80.0, true, false}},
    {"braking_decel_mps2", &QuadrotorControllerConfig::braking_decel_mps2, Range::positive()},
    {"face_min_distance_m", &QuadrotorControllerConfig::face_min_distance_m, Range::non_negative()},
};

const PidField kPids[] = {
    {"position", &QuadrotorControllerConfig::position},
    {"velocity_xy", &QuadrotorControllerConfig::velocity_xy},
    {"velocity_z", &QuadrotorControllerConfig::velocity_z},
    {"attitude_rp", &QuadrotorControllerConfig::attitude_rp},
    {"attitude_yaw", &QuadrotorControllerConfig::attitude_yaw},
    {"rate_rp", &QuadrotorControllerConfig::rate_rp},
    {"rate_yaw", &QuadrotorControllerConfig::rate_yaw},
};

const NumberField<PidConfig> kPidNumbers[] = {
    {"kp", &PidConfig::kp, Range::non_negative()},
    {"ki", &PidConfig::ki, Range::non_negative()},
    {"kd", &PidConfig::kd, Range::non_negative()},
    {"integral_limit", &PidConfig::integral_limit, Range::positive()},
    {"output_limit", &PidConfig::output_limit, Range::positive()},
};

template <typename Struct>
void read_numbers(ObjectReader& r, Struct& out, const auto& fields) {
  for (const auto& f : fields) r.read(f.key, out.*f.member, f.range);
}

template <typename Struct>
void write_numbers(nlohmann::json& j, const Struct& in, const auto& fields) {
  for (const auto& f : fields) j[std::string(f.key)] = in.*f.member;
}

QuadrotorControllerConfig read_controller(const JsonNode& node, QuadrotorControllerConfig c) {
  ObjectReader r(node);
  read_numbers(r, c, kControllerNumbers);
  for (const PidField& pid : kPids) {
    if (auto sub = r.optional(pid.key)) {
      ObjectReader pr(*sub);
      read_numbers(pr, c.*pid.member, kPidNumbers);
      pr.finish();
    }
  }
  r.finish();
  return c;
}

}  // namespace

QuadrotorConfig parse_quadrotor_config(const ParamsBlock& params) {
  QuadrotorConfig c;
  const JsonNode node(params.values, params.file, params.pointer);
  ObjectReader r(node);
  read_numbers(r, c, kNumbers);
  for (const auto& f : kVectors) r.read(f.key, c.*f.member, f.range);
  if (auto controller = r.optional("controller")) c.controller = read_controller(*controller, c.controller);
  r.finish();

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

nlohmann::json to_json(const QuadrotorConfig& config) {
  nlohmann::json j = nlohmann::json::object();
  write_numbers(j, config, kNumbers);
  for (const auto& f : kVectors) {
    const Eigen::Vector3d& v = config.*f.member;
    j[std::string(f.key)] = {v.x(), v.y(), v.z()};
  }
  nlohmann::json controller = nlohmann::json::object();
  write_numbers(controller, config.controller, kControllerNumbers);
  for (const PidField& pid : kPids) {
    nlohmann::json p = nlohmann::json::object();
    write_numbers(p, config.controller.*pid.member, kPidNumbers);
    controller[std::string(pid.key)] = p;
  }
  j["controller"] = controller;
  return j;
}

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
    : bullet_(world.bullet()),
      config_(config),
      controller_(config.controller, model_of(config, world.scene().world.gravity_mps2),
                  resting_at(start_pose)) {
  shape_ = std::make_unique<btBoxShape>(to_bt(config.collision_half_extents_m));
  shape_->setMargin(0.0);  // the exact box, without rounded edges (clearance)
  motion_state_ = std::make_unique<btDefaultMotionState>(to_bt(start_pose));
  // The construction info sets the configured inertia (setMassProps), not the box's.
  const btRigidBody::btRigidBodyConstructionInfo info(config.mass_kg, motion_state_.get(), shape_.get(),
                                                      to_bt(config.inertia_kgm2));
  body_ = std::make_unique<btRigidBody>(info);
  body_->setUserIndex(kVehicleBodyTag);
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
  // Exact discretisation of the first-order motor lag over one step.
  const double blend = 1.0 - std::exp(-dt_s / config_.motor_time_constant_s);
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
  body_->applyCentralForce(body_->getLinearVelocity() * -config_.linear_drag_n_per_mps);
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

nlohmann::json Quadrotor::actuators() const {
  return {{"rotor_speed_command_radps", rotor_commands_},
          {"rotor_speed_radps", rotor_speeds_},
          {"thrust_n", thrust_n()}};
}

}  // namespace campo
