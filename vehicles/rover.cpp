#include "vehicles/rover.hpp"

#include "physics/bullet_convert.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <btBulletDynamicsCommon.h>

#include "campo/json_reader.hpp"

namespace campo {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDegToRad = kPi / 180.0;

double wrap_angle(double a) {
  a = std::remainder(a, 2.0 * kPi);
  return a <= -kPi ? a + 2.0 * kPi : a;
}

}  // namespace

const ConfigFields<RoverConfig>& rover_config_fields() {
  using C = RoverConfig;
  static const ConfigFields<C> fields =
      ConfigFields<C>()
          .vector("chassis_size_m", &C::chassis_size_m, Range::positive(), "m", "length x, width y, height z")
          .number("chassis_mass_kg", &C::chassis_mass_kg, Range::positive(), "kg",
                  "with four 2.5 kg wheels the rover weighs 50 kg")
          .number("chassis_friction", &C::chassis_friction, Range::closed(0.0, 10.0), "",
                  "Bullet multiplies it by the other body's friction")
          .number("wheel_radius_m", &C::wheel_radius_m, Range::positive(), "m", "r")
          .number("wheel_mass_kg", &C::wheel_mass_kg, Range::positive(), "kg", "each")
          .number("wheel_friction", &C::wheel_friction, Range::closed(0.0, 10.0), "",
                  "times the ground's friction (0.8 by default): the tyre-ground coefficient")
          .number("half_track_m", &C::half_track_m, Range::positive(), "m",
                  "l, lateral offset of the wheel centres from the centre line")
          .number("wheelbase_m", &C::wheelbase_m, Range::positive(), "m", "front to rear axle")
          .number("axle_drop_m", &C::axle_drop_m, Range{}, "m",
                  "axles below the chassis centre (the centre rests at r + this = 0.4 m); r + this must exceed half "
                  "the chassis height")
          .number("max_wheel_torque_nm", &C::max_wheel_torque_nm, Range::positive(), "N m", "per motor")
          .number("max_wheel_speed_radps", &C::max_wheel_speed_radps, Range::positive(), "rad/s",
                  "per motor (2 m/s at the rim)")
          .number("max_wheel_accel_radps2", &C::max_wheel_accel_radps2, Range::non_negative(), "rad/s²",
                  "second-order actuation limit (003 §3.5); 0 = off")
          .number("hold_gain", &C::hold_gain, Range::positive(), "1/s",
                  "wheel angle servo while holding: wheel speed target = -gain * wheel angle error")
          .integer("joint_solver_iterations", &C::joint_solver_iterations, {1, 1000}, "",
                   "Bullet solver iterations of the wheel hinges while driving")
          .integer("hold_solver_iterations", &C::hold_solver_iterations, {1, 1000}, "",
                   "and while holding (fewer make the locked wheels jitter)")
          .number("speed_kp", &C::speed_kp, Range::non_negative(), "(m/s)/(m/s)", "forward-speed correction: P gain")
          .number("speed_ki", &C::speed_ki, Range::non_negative(), "1/s", "forward-speed correction: I gain")
          .number("speed_integral_max_mps", &C::speed_integral_max_mps, Range::non_negative(), "m/s",
                  "forward-speed correction: integral bound")
          .number("yaw_rate_kp", &C::yaw_rate_kp, Range::non_negative(), "(rad/s)/(rad/s)", "yaw-rate correction: P gain")
          .number("yaw_rate_ki", &C::yaw_rate_ki, Range::non_negative(), "1/s", "yaw-rate correction: I gain")
          .number("yaw_rate_integral_max_radps", &C::yaw_rate_integral_max_radps, Range::non_negative(), "rad/s",
                  "yaw-rate correction: integral bound (turning in place takes wheel speeds ~4x the kinematic ones)")
          .number("heading_gain", &C::heading_gain, Range::positive(), "1/s",
                  "yaw rate per heading error (`go_to`, `face`)")
          .number("max_yaw_rate_radps", &C::max_yaw_rate_radps, Range::positive(), "rad/s", "for `go_to` and `face`")
          .number("approach_gain", &C::approach_gain, Range::positive(), "1/s",
                  "`go_to` speed per remaining distance")
          .number("turn_in_place_deg", &C::turn_in_place_deg, Range{0.0, 180.0, true, false}, "deg",
                  "`go_to` turns in place above this heading error")
          .number("arrival_radius_m", &C::arrival_radius_m, Range::positive(), "m", "`go_to` stops within this distance")
          .number("face_tolerance_deg", &C::face_tolerance_deg, Range::positive(), "deg",
                  "`face` stops within this heading error")
          .number("stable_speed_mps", &C::stable_speed_mps, Range::positive(), "m/s", "`stable` below this speed")
          .number("stable_rate_radps", &C::stable_rate_radps, Range::positive(), "rad/s",
                  "and below this angular speed");
  return fields;
}

RoverConfig parse_rover_config(const ParamsBlock& params) {
  const RoverConfig c = rover_config_fields().read(params);
  if (c.axle_drop_m + c.wheel_radius_m <= 0.5 * c.chassis_size_m.z()) {
    // The chassis would rest on its belly instead of on the wheels.
    const auto at = params.values.contains("axle_drop_m") ? "axle_drop_m" : "wheel_radius_m";
    throw InputError(params.file, child_pointer(params.pointer, at),
                     "expected axle_drop_m + wheel_radius_m > half the chassis height (" +
                         std::to_string(0.5 * c.chassis_size_m.z()) + " m)");
  }
  return c;
}

nlohmann::json to_json(const RoverConfig& c) { return rover_config_fields().write(c); }

// The Bullet objects of one rover; declaration order makes the destructor
// remove constraints before bodies and free bodies before their shapes.
struct Rover::Bodies {
  btDiscreteDynamicsWorld& world;
  std::unique_ptr<btBoxShape> chassis_shape;
  std::unique_ptr<btSphereShape> wheel_shape;
  std::unique_ptr<btRigidBody> chassis;
  std::array<std::unique_ptr<btRigidBody>, kWheels> wheels;
  std::array<std::unique_ptr<btHingeConstraint>, kWheels> hinges;

  explicit Bodies(btDiscreteDynamicsWorld& w) : world(w) {}
  ~Bodies() {
    for (auto& hinge : hinges) {
      if (hinge) world.removeConstraint(hinge.get());
    }
    for (auto& wheel : wheels) {
      if (wheel) world.removeRigidBody(wheel.get());
    }
    if (chassis) world.removeRigidBody(chassis.get());
  }
};

namespace {

std::unique_ptr<btRigidBody> make_body(btCollisionShape& shape, double mass, double friction,
                                       const btTransform& pose, int tag) {
  btVector3 inertia(0, 0, 0);
  shape.calculateLocalInertia(mass, inertia);
  btRigidBody::btRigidBodyConstructionInfo info(mass, nullptr, &shape, inertia);
  info.m_startWorldTransform = pose;
  info.m_friction = friction;
  auto body = std::make_unique<btRigidBody>(info);
  body->setUserIndex(tag);
  body->setActivationState(DISABLE_DEACTIVATION);
  return body;
}

// Wheel mounting points in the chassis frame, in Rover::Wheel order.
std::array<Eigen::Vector3d, Rover::kWheels> wheel_mounts(const RoverConfig& c) {
  const double x = 0.5 * c.wheelbase_m;
  const double y = c.half_track_m;
  const double z = -c.axle_drop_m;
  return {{{x, y, z}, {x, -y, z}, {-x, y, z}, {-x, -y, z}}};
}

// The start pose, raised just enough that no wheel starts inside the ground
// (judged from the ground height under each wheel's footprint); never lowered.
Eigen::Isometry3d lifted_start(const World& world, const RoverConfig& c,
                               const std::array<Eigen::Vector3d, Rover::kWheels>& mounts,
                               const Eigen::Isometry3d& start) {
  const double r = c.wheel_radius_m;
  const Eigen::Vector2d footprint[] = {{0, 0}, {r, 0}, {-r, 0}, {0, r}, {0, -r}};
  double lift = 0.0;
  for (const Eigen::Vector3d& mount : mounts) {
    const Eigen::Vector3d centre = start * mount;
    for (const Eigen::Vector2d& d : footprint) {
      if (const auto ground = world.terrain_height(centre.x() + d.x(), centre.y() + d.y())) {
        lift = std::max(lift, *ground + r - centre.z());
      }
    }
  }
  Eigen::Isometry3d lifted = start;
  lifted.translation().z() += lift;
  return lifted;
}

// The values of each command that the rover uses are finite.
bool is_finite(const command::Twist& t) { return std::isfinite(t.v_mps) && std::isfinite(t.w_radps); }
bool is_finite(const command::GoTo& g) { return g.target_m.allFinite() && std::isfinite(g.speed_mps); }
bool is_finite(const command::Face& f) { return f.point_m.allFinite(); }
bool is_finite(const command::Hold&) { return true; }
bool is_finite(const command::Wheels& w) {
  return std::all_of(w.speeds_radps.begin(), w.speeds_radps.end(), [](double x) { return std::isfinite(x); });
}
// Refused before their values matter.
bool is_finite(const command::Altitude&) { return true; }
bool is_finite(const command::Velocity&) { return true; }
bool is_finite(const command::AttitudeThrust&) { return true; }
bool is_finite(const command::Rotors&) { return true; }

bool is_left(int wheel) { return wheel == Rover::front_left || wheel == Rover::rear_left; }

}  // namespace

Rover::Rover(World& world, const RoverConfig& config, const Eigen::Isometry3d& start_pose)
    : config_(config),
      geometry_{config.wheel_radius_m, config.half_track_m},
      bodies_(std::make_unique<Bodies>(world.bullet())),
      command_(command::Hold{start_pose.translation(), std::nullopt}) {
  Bodies& b = *bodies_;
  b.chassis_shape = std::make_unique<btBoxShape>(to_bt(0.5 * config.chassis_size_m));
  b.chassis_shape->setMargin(0.0);  // the exact box, without rounded edges (clearance)
  b.wheel_shape = std::make_unique<btSphereShape>(config.wheel_radius_m);
  const auto mounts = wheel_mounts(config);
  const btTransform chassis_pose = to_bt(lifted_start(world, config, mounts, start_pose));
  const std::size_t number = world.join_vehicle();
  b.chassis = make_body(*b.chassis_shape, config.chassis_mass_kg, config.chassis_friction, chassis_pose,
                        vehicle_tag(number, false));
  b.world.addRigidBody(b.chassis.get());

  const btVector3 axle(0, 1, 0);  // wheels spin about the chassis y axis
  for (int i = 0; i < kWheels; ++i) {
    btTransform wheel_pose = chassis_pose;
    wheel_pose.setOrigin(chassis_pose * to_bt(mounts[i]));
    // A wheel may roll on the ground.
    b.wheels[i] = make_body(*b.wheel_shape, config.wheel_mass_kg, config.wheel_friction, wheel_pose,
                            vehicle_tag(number, true));
    // A sphere's inertia is isotropic, so its gyroscopic torque is zero.
    b.wheels[i]->setFlags(b.wheels[i]->getFlags() & ~BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_BODY);
    b.world.addRigidBody(b.wheels[i].get());
    b.hinges[i] = std::make_unique<btHingeConstraint>(*b.chassis, *b.wheels[i], to_bt(mounts[i]),
                                                      btVector3(0, 0, 0), axle, axle);
    b.hinges[i]->enableAngularMotor(true, 0.0, 0.0);
    // Fewer iterations than the contacts: the joints are the bulk of the solver's work.
    b.hinges[i]->setOverrideNumSolverIterations(config.joint_solver_iterations);
    // True: no collisions between the chassis and its wheels.
    b.world.addConstraint(b.hinges[i].get(), true);
  }
  // Wheels of the same rover never collide with each other either.
  for (int i = 0; i < kWheels; ++i) {
    for (int j = i + 1; j < kWheels; ++j) {
      b.wheels[i]->setIgnoreCollisionCheck(b.wheels[j].get(), true);
      b.wheels[j]->setIgnoreCollisionCheck(b.wheels[i].get(), true);
    }
  }

  const double yaw = std::atan2(start_pose.linear()(1, 0), start_pose.linear()(0, 0));
  odometry_ = {start_pose.translation().x(), start_pose.translation().y(), yaw};
}

Rover::~Rover() = default;

void Rover::command(const Command& c) {
  if (std::holds_alternative<command::Altitude>(c)) {
    throw std::invalid_argument("the rover cannot follow an altitude command");
  }
  if (std::holds_alternative<command::Velocity>(c) || std::holds_alternative<command::AttitudeThrust>(c) ||
      std::holds_alternative<command::Rotors>(c)) {
    throw std::invalid_argument("the rover cannot follow a quadrotor's " + std::string(command_name(c)) + " command");
  }
  // NaN or infinity would reach Bullet and ruin the whole world.
  if (!std::visit([](const auto& x) { return is_finite(x); }, c)) {
    throw std::invalid_argument("rover " + std::string(command_name(c)) + ": non-finite value");
  }
  if (const auto* go = std::get_if<command::GoTo>(&c); go && !(go->speed_mps > 0.0)) {
    throw std::invalid_argument("rover go_to: speed_mps must be > 0");
  }
  // A repeated GoTo or Face to the same point keeps its "arrived" latch, so
  // a planner may resend it every control tick.
  const auto target = [](const Command& x) -> std::optional<Eigen::Vector3d> {
    if (const auto* go = std::get_if<command::GoTo>(&x)) return go->target_m;
    if (const auto* face = std::get_if<command::Face>(&x)) return face->point_m;
    return std::nullopt;
  };
  const auto old_target = target(command_);
  const auto new_target = target(c);
  if (c.index() != command_.index() || !old_target || !new_target || *old_target != *new_target) {
    arrived_ = false;
  }
  command_ = c;
}

std::optional<BodyTwist> Rover::behaviour_twist(const VehicleState& s) {
  const auto heading_error = [&s](const Eigen::Vector3d& point) {
    const Eigen::Vector2d d = (point - s.position_m).head<2>();
    return wrap_angle(std::atan2(d.y(), d.x()) - s.yaw_rad());
  };
  const auto turn_rate = [this](double error) {
    return std::clamp(config_.heading_gain * error, -config_.max_yaw_rate_radps,
                      config_.max_yaw_rate_radps);
  };
  if (const auto* twist = std::get_if<command::Twist>(&command_)) {
    return BodyTwist{twist->v_mps, twist->w_radps};
  }
  if (const auto* go = std::get_if<command::GoTo>(&command_)) {
    const double distance = (go->target_m - s.position_m).head<2>().norm();
    arrived_ = arrived_ || distance < config_.arrival_radius_m;
    if (arrived_) return std::nullopt;
    const double error = heading_error(go->target_m);
    if (std::abs(error) > config_.turn_in_place_deg * kDegToRad) return BodyTwist{0.0, turn_rate(error)};
    const double v_max = config_.max_wheel_speed_radps * config_.wheel_radius_m;
    // Slow down near the target and while the heading is still off.
    const double v = std::min({go->speed_mps, v_max, config_.approach_gain * distance}) *
                     std::cos(error);
    return BodyTwist{v, turn_rate(error)};
  }
  if (const auto* face = std::get_if<command::Face>(&command_)) {
    const double error = heading_error(face->point_m);
    arrived_ = arrived_ || std::abs(error) < config_.face_tolerance_deg * kDegToRad;
    if (arrived_) return std::nullopt;
    return BodyTwist{0.0, turn_rate(error)};
  }
  return std::nullopt;  // command::Hold (Altitude is never accepted; Wheels does not get here)
}

void Rover::drive_wheels(const command::Wheels& wheels, double dt_s) {
  // No body-rate loop: its integrals start afresh when a behaviour takes over.
  speed_integral_mps_ = 0.0;
  yaw_integral_radps_ = 0.0;
  if (wheels_locked_) lock_wheels(false);
  const double max_speed = config_.max_wheel_speed_radps;
  const double max_impulse = config_.max_wheel_torque_nm * dt_s;
  // The motor targets each move toward their command as the side targets of
  // the behaviours do: at most max_wheel_accel_radps2 (when set) from the last ones.
  for (int i = 0; i < kWheels; i += 2) {
    const WheelSpeeds target{std::clamp(wheels.speeds_radps[i], -max_speed, max_speed),
                             std::clamp(wheels.speeds_radps[i + 1], -max_speed, max_speed)};
    const WheelSpeeds limited =
        rate_limit({wheel_targets_[i], wheel_targets_[i + 1]}, target, config_.max_wheel_accel_radps2, dt_s);
    wheel_targets_[i] = limited.left_radps;  // wheels i and i + 1: the left and right of an axle
    wheel_targets_[i + 1] = limited.right_radps;
  }
  for (int i = 0; i < kWheels; ++i) {
    // The hinge motor drives the chassis relative to the wheel: opposite sign.
    bodies_->hinges[i]->enableAngularMotor(true, -wheel_targets_[i], max_impulse);
  }
  // A behaviour after this starts (and rate-limits) from the sides' mean targets.
  side_targets_ = {0.5 * (wheel_targets_[front_left] + wheel_targets_[rear_left]),
                   0.5 * (wheel_targets_[front_right] + wheel_targets_[rear_right])};
}

void Rover::pre_step(double dt_s) {
  odometry_ = integrate_odometry(odometry_, measured_side_speeds(), geometry_, dt_s);

  if (const auto* wheels = std::get_if<command::Wheels>(&command_)) {
    drive_wheels(*wheels, dt_s);
    return;
  }
  const VehicleState s = estimated_state();
  const std::optional<BodyTwist> reference = behaviour_twist(s);
  const bool hold = !reference;
  WheelSpeeds desired;  // zero when holding
  double speed_error = 0.0;
  double yaw_error = 0.0;
  bool saturated = false;
  if (hold) {
    speed_integral_mps_ = 0.0;
    yaw_integral_radps_ = 0.0;
  } else {
    // Kinematic feed-forward plus a PI correction of the measured body
    // rates: skid steering slips, most of all when turning.
    const Eigen::Matrix3d r = s.orientation.toRotationMatrix();
    speed_error = reference->v_mps - s.linear_velocity_mps.dot(r.col(0));
    yaw_error = reference->w_radps - s.angular_velocity_radps.dot(r.col(2));
    const BodyTwist corrected{reference->v_mps + config_.speed_kp * speed_error + speed_integral_mps_,
                              reference->w_radps + config_.yaw_rate_kp * yaw_error + yaw_integral_radps_};
    const WheelSpeeds unlimited = wheel_speeds_from_twist(corrected, geometry_);
    desired = saturate(unlimited, config_.max_wheel_speed_radps);
    saturated = desired.left_radps != unlimited.left_radps || desired.right_radps != unlimited.right_radps;
  }
  const WheelSpeeds limited = rate_limit(side_targets_, desired, config_.max_wheel_accel_radps2, dt_s);
  const bool rate_limited =
      limited.left_radps != desired.left_radps || limited.right_radps != desired.right_radps;
  // Anti-windup: the integrals stand still while the motors cannot follow.
  if (!hold && !saturated && !rate_limited) {
    const double speed_max = config_.speed_integral_max_mps;
    const double yaw_max = config_.yaw_rate_integral_max_radps;
    speed_integral_mps_ =
        std::clamp(speed_integral_mps_ + config_.speed_ki * speed_error * dt_s, -speed_max, speed_max);
    yaw_integral_radps_ =
        std::clamp(yaw_integral_radps_ + config_.yaw_rate_ki * yaw_error * dt_s, -yaw_max, yaw_max);
  }
  side_targets_ = limited;

  const bool lock = hold && !rate_limited;  // braked to zero under Hold
  if (lock != wheels_locked_) lock_wheels(lock);
  const double max_impulse = config_.max_wheel_torque_nm * dt_s;
  for (int i = 0; i < kWheels; ++i) {
    if (wheels_locked_) {
      wheel_targets_[i] = -config_.hold_gain * wrap_angle(wheel_angle(i) - hold_angles_[i]);
    } else {
      wheel_targets_[i] = is_left(i) ? limited.left_radps : limited.right_radps;
    }
    // The hinge motor drives the chassis relative to the wheel: opposite sign.
    bodies_->hinges[i]->enableAngularMotor(true, -wheel_targets_[i], max_impulse);
  }
}

void Rover::lock_wheels(bool on) {
  wheels_locked_ = on;
  for (int i = 0; i < kWheels; ++i) {
    if (on) hold_angles_[i] = wheel_angle(i);
    btRigidBody& wheel = *bodies_->wheels[i];
    const int flags = wheel.getCollisionFlags();
    wheel.setCollisionFlags(on ? flags | btCollisionObject::CF_HAS_FRICTION_ANCHOR
                               : flags & ~btCollisionObject::CF_HAS_FRICTION_ANCHOR);
    bodies_->hinges[i]->setOverrideNumSolverIterations(on ? config_.hold_solver_iterations
                                                          : config_.joint_solver_iterations);
  }
}

double Rover::wheel_angle(int wheel) const {
  // The hinge measures the chassis relative to the wheel (see the motor sign).
  return -bodies_->hinges[wheel]->getHingeAngle();
}

VehicleState Rover::state() const {
  const btRigidBody& body = *bodies_->chassis;
  const btTransform& t = body.getWorldTransform();
  const btQuaternion q = t.getRotation();
  VehicleState s;
  s.position_m = from_bt(t.getOrigin());
  s.orientation = Eigen::Quaterniond(q.w(), q.x(), q.y(), q.z());
  s.linear_velocity_mps = from_bt(body.getLinearVelocity());
  s.angular_velocity_radps = from_bt(body.getAngularVelocity());
  return s;
}

bool Rover::stable() const {
  const btRigidBody& body = *bodies_->chassis;
  return body.getLinearVelocity().length() < config_.stable_speed_mps &&
         body.getAngularVelocity().length() < config_.stable_rate_radps;
}

std::array<double, Rover::kWheels> Rover::wheel_speeds_radps() const {
  const btRigidBody& chassis = *bodies_->chassis;
  const btVector3 axle = chassis.getWorldTransform().getBasis().getColumn(1);
  std::array<double, kWheels> speeds{};
  for (int i = 0; i < kWheels; ++i) {
    speeds[i] = (bodies_->wheels[i]->getAngularVelocity() - chassis.getAngularVelocity()).dot(axle);
  }
  return speeds;
}

WheelSpeeds Rover::measured_side_speeds() const {
  const auto w = wheel_speeds_radps();
  return {0.5 * (w[front_left] + w[rear_left]), 0.5 * (w[front_right] + w[rear_right])};
}

nlohmann::json Rover::actuators() const {
  static constexpr std::string_view kNames[kWheels] = {"front_left", "front_right", "rear_left",
                                                       "rear_right"};
  // Built in place, once per control tick: the same object an initializer
  // list would give, without its intermediate copies.
  const auto measured = wheel_speeds_radps();
  nlohmann::json j(nlohmann::json::value_t::object);
  auto& wheels = j.get_ref<nlohmann::json::object_t&>();
  for (int i = 0; i < kWheels; ++i) {
    nlohmann::json::object_t wheel;
    wheel.emplace("command_radps", wheel_targets_[i]);
    wheel.emplace("speed_radps", measured[i]);
    wheels.emplace(std::string(kNames[i]), std::move(wheel));
  }
  return j;
}

}  // namespace campo
