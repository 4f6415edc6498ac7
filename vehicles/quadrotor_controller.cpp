#include "vehicles/quadrotor_controller.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace campo {

namespace {

constexpr double kEpsilon = 1e-9;
// Least vertical thrust commanded, as a fraction of the weight: keeps the
// thrust vector pointing up, so the attitude it asks for is defined.
constexpr double kMinThrustFraction = 0.1;

// Error at which a proportional loop reaches its output limit (no cap without gain).
double error_cap(const PidConfig& pid) {
  return pid.kp > 0.0 ? pid.output_limit / pid.kp : std::numeric_limits<double>::infinity();
}

// Horizontal heading from `from` to `to`, or `fallback` when `to` is (almost) straight above or below.
double heading_to(const Eigen::Vector3d& from, const Eigen::Vector3d& to, double fallback) {
  const Eigen::Vector2d d = (to - from).head<2>();
  return d.norm() > kEpsilon ? std::atan2(d.y(), d.x()) : fallback;
}

// Same kind and same target: a re-sent command rather than a new one.
bool same_target(const Command& a, const Command& b) {
  if (a.index() != b.index()) return false;
  if (const auto* h = std::get_if<command::Hold>(&a)) {
    return h->position_m == std::get<command::Hold>(b).position_m;
  }
  if (const auto* g = std::get_if<command::GoTo>(&a)) {
    return g->target_m == std::get<command::GoTo>(b).target_m;
  }
  if (const auto* f = std::get_if<command::Face>(&a)) {
    return f->point_m == std::get<command::Face>(b).point_m;
  }
  if (const auto* z = std::get_if<command::Altitude>(&a)) {
    return z->z_m == std::get<command::Altitude>(b).z_m;
  }
  return false;
}

// The values of a low-level command are finite (NaN would reach Bullet and ruin the whole world).
bool all_finite(const Command& c) {
  if (const auto* v = std::get_if<command::Velocity>(&c)) {
    return v->velocity_mps.allFinite() && std::isfinite(v->yaw_rate_radps);
  }
  if (const auto* a = std::get_if<command::AttitudeThrust>(&c)) {
    return std::isfinite(a->roll_rad) && std::isfinite(a->pitch_rad) && std::isfinite(a->yaw_rate_radps) &&
           std::isfinite(a->thrust_n);
  }
  if (const auto* r = std::get_if<command::Rotors>(&c)) {
    return std::all_of(r->speeds_radps.begin(), r->speeds_radps.end(), [](double w) { return std::isfinite(w); });
  }
  return true;
}

}  // namespace

Eigen::Vector3d rotor_position(int i, double arm_length_m) {
  assert(i >= 0 && i < 4);
  const double angle = std::numbers::pi / 4.0 + i * std::numbers::pi / 2.0;
  return {arm_length_m * std::cos(angle), arm_length_m * std::sin(angle), 0.0};
}

Eigen::Matrix4d allocation_matrix(double arm_length_m, double thrust_coefficient,
                                  double torque_coefficient) {
  Eigen::Matrix4d a;
  for (int i = 0; i < 4; ++i) {
    // Thrust k_f w^2 along body z at r gives torque r x (0, 0, T) = (y T, -x T, 0).
    const Eigen::Vector3d r = rotor_position(i, arm_length_m);
    a(0, i) = thrust_coefficient;
    a(1, i) = thrust_coefficient * r.y();
    a(2, i) = -thrust_coefficient * r.x();
    a(3, i) = torque_coefficient * kRotorTorqueSign[static_cast<std::size_t>(i)];
  }
  return a;
}

Eigen::Vector4d mix(const Eigen::Matrix4d& inverse, double thrust_n, const Eigen::Vector3d& torque_nm,
                    double min_sq, double max_sq) {
  assert(min_sq < max_sq);
  const double range = max_sq - min_sq;
  // The allocation is linear, so the wrench splits into per-part contributions.
  const Eigen::Vector4d collective = inverse.col(0) * thrust_n;
  Eigen::Vector4d tilt = inverse.col(1) * torque_nm.x() + inverse.col(2) * torque_nm.y();
  const Eigen::Vector4d yaw = inverse.col(3) * torque_nm.z();

  // Roll/pitch: scale down only if its spread alone exceeds the motor range.
  const double spread = tilt.maxCoeff() - tilt.minCoeff();
  if (spread > range) tilt *= range / spread;

  // Collective thrust (equal on all rotors): shift it so that every rotor fits.
  const double c = std::clamp(collective(0), min_sq - tilt.minCoeff(), max_sq - tilt.maxCoeff());
  const Eigen::Vector4d base = tilt.array() + c;

  // Yaw: the largest fraction in [0, 1] that keeps every rotor within limits.
  double fraction = 1.0;
  for (int i = 0; i < 4; ++i) {
    if (yaw(i) > 0.0) fraction = std::min(fraction, (max_sq - base(i)) / yaw(i));
    else if (yaw(i) < 0.0) fraction = std::min(fraction, (min_sq - base(i)) / yaw(i));
  }
  fraction = std::max(fraction, 0.0);
  return (base + fraction * yaw).cwiseMax(min_sq).cwiseMin(max_sq);
}

double hover_rotor_speed(const QuadrotorModel& model) {
  return std::sqrt(model.mass_kg * model.gravity_mps2.norm() / (4.0 * model.thrust_coefficient));
}

Eigen::Quaterniond attitude_from_thrust(const Eigen::Vector3d& thrust_direction, double yaw_rad) {
  const Eigen::Vector3d z = thrust_direction.normalized();
  const Eigen::Vector3d heading(std::cos(yaw_rad), std::sin(yaw_rad), 0.0);
  // Body x in the vertical plane through the heading and normal to z, so that
  // its ground projection is the heading (the yaw VehicleState::yaw_rad reads).
  const Eigen::Vector3d x = (heading - (heading.dot(z) / z.z()) * Eigen::Vector3d::UnitZ()).normalized();
  Eigen::Matrix3d r;
  r.col(0) = x;
  r.col(1) = z.cross(x);
  r.col(2) = z;
  return Eigen::Quaterniond(r);
}

Eigen::Vector3d attitude_error(const Eigen::Quaterniond& current, const Eigen::Quaterniond& desired) {
  const Eigen::Quaterniond tilt = Eigen::Quaterniond::FromTwoVectors(current * Eigen::Vector3d::UnitZ(),
                                                                    desired * Eigen::Vector3d::UnitZ());
  // `aligned` is the current attitude tilted onto the desired body z axis.
  const Eigen::Quaterniond aligned = tilt * current;
  const Eigen::Quaterniond tilt_body = current.conjugate() * aligned;
  const Eigen::Quaterniond heading = aligned.conjugate() * desired;  // about body z only
  const double yaw = std::remainder(2.0 * std::atan2(heading.z(), heading.w()), 2.0 * std::numbers::pi);
  return {2.0 * tilt_body.x(), 2.0 * tilt_body.y(), yaw};
}

Eigen::Vector3d cap_cross_first(const Eigen::Vector3d& v, const Eigen::Vector3d& direction, double limit,
                                double along_limit) {
  const double along = v.dot(direction);
  Eigen::Vector3d across = v - along * direction;
  const double across_norm = across.norm();
  if (across_norm > limit) across *= limit / across_norm;
  const double left = std::sqrt(std::max(0.0, limit * limit - across.squaredNorm()));
  const double cap = std::min(left, along_limit);
  return across + std::clamp(along, -cap, cap) * direction;
}

QuadrotorController::QuadrotorController(const QuadrotorControllerConfig& config,
                                         const QuadrotorModel& model, const VehicleState& initial)
    : config_(config),
      model_(model),
      allocation_inverse_(
          allocation_matrix(model.arm_length_m, model.thrust_coefficient, model.torque_coefficient)
              .inverse()),
      min_sq_(model.min_rotor_speed_radps * model.min_rotor_speed_radps),
      max_sq_(model.max_rotor_speed_radps * model.max_rotor_speed_radps),
      tan_max_tilt_(std::tan(config.max_tilt_deg * std::numbers::pi / 180.0)),
      position_error_cap_(error_cap(config.position)),
      velocity_error_cap_(error_cap(config.velocity_xy)),
      yaw_error_cap_(error_cap(config.attitude_yaw)),
      max_thrust_n_(4.0 * model.thrust_coefficient * model.max_rotor_speed_radps * model.max_rotor_speed_radps),
      position_{Pid(config.position), Pid(config.position), Pid(config.position)},
      velocity_{Pid(config.velocity_xy), Pid(config.velocity_xy), Pid(config.velocity_z)},
      attitude_{Pid(config.attitude_rp), Pid(config.attitude_rp), Pid(config.attitude_yaw)},
      rate_{Pid(config.rate_rp), Pid(config.rate_rp), Pid(config.rate_yaw)} {
  assert(model.mass_kg > 0.0 && model.thrust_coefficient > 0.0);
  assert(model.min_rotor_speed_radps < model.max_rotor_speed_radps);
  reference_.command = command::Hold{initial.position_m, initial.yaw_rad()};
  reference_.position_m = initial.position_m;
  reference_.yaw_rad = initial.yaw_rad();
  reference_.speed_mps = config.speed_limit_mps;
}

void QuadrotorController::command(const Command& c, const VehicleState& state) {
  if (std::holds_alternative<command::Twist>(c) || std::holds_alternative<command::Wheels>(c)) {
    throw std::invalid_argument("the quadrotor cannot follow a " + std::string(command_name(c)) +
                                " command (a rover's)");
  }
  if (const auto* go = std::get_if<command::GoTo>(&c); go && !(go->speed_mps > 0.0 && std::isfinite(go->speed_mps))) {
    throw std::invalid_argument("go_to needs a finite speed > 0, got " + std::to_string(go->speed_mps));
  }
  if (!all_finite(c)) {
    throw std::invalid_argument("quadrotor " + std::string(command_name(c)) + ": non-finite value");
  }
  const Mode mode = std::holds_alternative<command::Velocity>(c)         ? Mode::velocity
                    : std::holds_alternative<command::AttitudeThrust>(c) ? Mode::attitude
                    : std::holds_alternative<command::Rotors>(c)         ? Mode::rotors
                                                                         : Mode::position;
  if (mode != Mode::position) {
    // A low-level command is re-sent with new values every control tick: the
    // same kind keeps its heading reference (and every integrator).
    const bool same_kind = c.index() == reference_.command.index();
    if (!same_kind) {
      Reference r;
      r.mode = mode;
      r.position_m = state.position_m;
      // Between Velocity and AttitudeThrust the turn goes on from the heading
      // reference; after any other command it starts from the current heading.
      const bool turning = reference_.mode == Mode::velocity || reference_.mode == Mode::attitude;
      r.yaw_rad = turning && mode != Mode::rotors ? reference_.yaw_rad : state.yaw_rad();
      r.speed_mps = config_.speed_limit_mps;
      restart_idle_loops(reference_.mode, mode);
      reset_position_loop();
      reference_ = r;
    }
    reference_.command = c;
    return;
  }
  restart_idle_loops(reference_.mode, mode);
  const bool same = same_target(c, reference_.command);
  Reference r = same ? reference_ : Reference{};
  r.command = c;
  if (const auto* hold = std::get_if<command::Hold>(&c)) {
    if (!same) {
      r.position_m = hold->position_m;
      r.yaw_rad = state.yaw_rad();
      r.speed_mps = config_.speed_limit_mps;
    }
    if (hold->yaw_rad) r.yaw_rad = *hold->yaw_rad;
  } else if (const auto* go = std::get_if<command::GoTo>(&c)) {
    if (!same) {
      r.position_m = go->target_m;
      const Eigen::Vector3d line = go->target_m - state.position_m;
      r.direction = line.norm() > kEpsilon ? Eigen::Vector3d(line.normalized()) : Eigen::Vector3d::Zero();
      r.yaw_rad = state.yaw_rad();
    }
    r.speed_mps = go->speed_mps;
    r.face_target = go->face_target;
  } else if (const auto* face = std::get_if<command::Face>(&c)) {
    if (!same) {
      r.position_m = state.position_m;
      r.yaw_rad = heading_to(state.position_m, face->point_m, state.yaw_rad());
      r.speed_mps = config_.speed_limit_mps;
    }
  } else if (const auto* altitude = std::get_if<command::Altitude>(&c)) {
    if (!same) {
      r.position_m = {state.position_m.x(), state.position_m.y(), altitude->z_m};
      r.yaw_rad = state.yaw_rad();
      r.speed_mps = config_.speed_limit_mps;
    }
  }
  reference_ = r;
  if (!same) reset_position_loop();
}

void QuadrotorController::reset_position_loop() {
  for (Pid& pid : position_) pid.reset();
}

void QuadrotorController::restart_idle_loops(Mode from, Mode to) {
  // A mode runs the loops from where it enters the cascade down (the enum's
  // order); the position loop restarts with every new target anyway.
  const auto runs = [](Mode mode, Mode entry) { return mode <= entry; };
  if (runs(to, Mode::velocity) && !runs(from, Mode::velocity)) {
    for (Pid& pid : velocity_) pid.reset();
  }
  if (runs(to, Mode::attitude) && !runs(from, Mode::attitude)) {
    for (Pid& pid : attitude_) pid.reset();
    for (Pid& pid : rate_) pid.reset();
  }
}

void QuadrotorController::advance_yaw(double yaw_rad, double yaw_rate_radps, double dt_s) {
  // The heading reference integrates the commanded rate and the yaw attitude
  // loop tracks it as under the other commands (rather than the rate going
  // straight to the yaw-rate loop): a zero rate holds the heading without
  // drift, a disturbance turned away is turned back, and a constant rate is
  // followed at that rate with the reference a constant rate/kp ahead. The
  // rate is capped at the loop's output limit (the turn rate), and the
  // reference never leads the heading by more than the error at which the
  // loop saturates, so a vehicle that cannot turn as fast does not wind it up.
  const double turn = config_.attitude_yaw.output_limit;
  const double rate = std::clamp(yaw_rate_radps, -turn, turn);
  const double lead = std::remainder(reference_.yaw_rad + rate * dt_s - yaw_rad, 2.0 * std::numbers::pi);
  reference_.yaw_rad = std::remainder(yaw_rad + std::clamp(lead, -yaw_error_cap_, yaw_error_cap_), 2.0 * std::numbers::pi);
}

RotorSpeeds QuadrotorController::update(const VehicleState& state, double dt_s) {
  if (reference_.mode == Mode::rotors) {
    RotorSpeeds speeds = std::get<command::Rotors>(reference_.command).speeds_radps;
    for (double& w : speeds) w = std::clamp(w, model_.min_rotor_speed_radps, model_.max_rotor_speed_radps);
    return speeds;
  }
  const Eigen::Vector3d& v = state.linear_velocity_mps;
  const Eigen::Quaterniond& q = state.orientation;
  const Eigen::Vector3d body_rate = q.conjugate() * state.angular_velocity_radps;

  double thrust = 0.0;
  Eigen::Quaterniond q_des;
  if (reference_.mode == Mode::attitude) {
    // Desired attitude Rz(heading reference) Ry(pitch) Rx(roll): its body z
    // in the heading frame, tilt-capped keeping its direction; the thrust as given.
    const auto& cmd = std::get<command::AttitudeThrust>(reference_.command);
    advance_yaw(state.yaw_rad(), cmd.yaw_rate_radps, dt_s);
    const double max_tilt = config_.max_tilt_deg * std::numbers::pi / 180.0;
    const double roll = std::clamp(cmd.roll_rad, -max_tilt, max_tilt);
    const double pitch = std::clamp(cmd.pitch_rad, -max_tilt, max_tilt);
    Eigen::Vector3d z_axis(std::cos(roll) * std::sin(pitch), -std::sin(roll), std::cos(roll) * std::cos(pitch));
    const double horizontal = z_axis.head<2>().norm();
    const double max_horizontal = z_axis.z() * tan_max_tilt_;
    if (horizontal > max_horizontal) z_axis.head<2>() *= max_horizontal / horizontal;
    const Eigen::Vector3d z_world = Eigen::AngleAxisd(reference_.yaw_rad, Eigen::Vector3d::UnitZ()) * z_axis;
    q_des = attitude_from_thrust(z_world, reference_.yaw_rad);
    thrust = std::clamp(cmd.thrust_n, 0.0, max_thrust_n_);
  } else {
    Eigen::Vector3d v_cmd;
    if (reference_.mode == Mode::velocity) {
      // The heading-frame velocity turned to world by the current heading, capped at the highest speed commanded.
      const auto& cmd = std::get<command::Velocity>(reference_.command);
      advance_yaw(state.yaw_rad(), cmd.yaw_rate_radps, dt_s);
      v_cmd = Eigen::AngleAxisd(state.yaw_rad(), Eigen::Vector3d::UnitZ()) * cmd.velocity_mps;
      const double speed = v_cmd.norm();
      if (speed > config_.position.output_limit) v_cmd *= config_.position.output_limit / speed;
    } else {
      v_cmd = position_to_velocity(state, dt_s);
    }

    // Velocity -> acceleration (the horizontal error capped likewise) -> thrust
    // vector with the gravity feed-forward, tilt-limited.
    Eigen::Vector3d velocity_error = v_cmd - v;
    const double horizontal_error = velocity_error.head<2>().norm();
    if (horizontal_error > velocity_error_cap_) velocity_error.head<2>() *= velocity_error_cap_ / horizontal_error;
    Eigen::Vector3d accel;
    for (int i = 0; i < 3; ++i) accel(i) = velocity_[i].update(velocity_error(i), dt_s);
    Eigen::Vector3d force = model_.mass_kg * (accel - model_.gravity_mps2);
    force.z() = std::max(force.z(), kMinThrustFraction * model_.mass_kg * model_.gravity_mps2.norm() + kEpsilon);
    const double horizontal = force.head<2>().norm();
    const double max_horizontal = force.z() * tan_max_tilt_;
    if (horizontal > max_horizontal) force.head<2>() *= max_horizontal / horizontal;
    // Collective thrust: the part of the wanted force the current body z can give.
    thrust = std::max(0.0, force.dot(q * Eigen::Vector3d::UnitZ()));
    q_des = attitude_from_thrust(force, reference_.yaw_rad);
  }

  // Attitude -> body rate command.
  const Eigen::Vector3d att_error = attitude_error(q, q_des);
  Eigen::Vector3d rate_cmd;
  for (int i = 0; i < 3; ++i) rate_cmd(i) = attitude_[i].update(att_error(i), dt_s, body_rate(i));

  // Body rate -> angular acceleration -> torque (with the gyroscopic term).
  const Eigen::Vector3d rate_error = rate_cmd - body_rate;
  Eigen::Vector3d angular_accel;
  for (int i = 0; i < 3; ++i) angular_accel(i) = rate_[i].update(rate_error(i), dt_s);
  const Eigen::Vector3d j = model_.inertia_kgm2;
  const Eigen::Vector3d torque =
      j.cwiseProduct(angular_accel) + body_rate.cross(j.cwiseProduct(body_rate));

  const Eigen::Vector4d squared = mix(allocation_inverse_, thrust, torque, min_sq_, max_sq_);
  return {std::sqrt(squared(0)), std::sqrt(squared(1)), std::sqrt(squared(2)), std::sqrt(squared(3))};
}

Eigen::Vector3d QuadrotorController::position_to_velocity(const VehicleState& state, double dt_s) {
  const Eigen::Vector3d& p = state.position_m;
  const Eigen::Vector3d& v = state.linear_velocity_mps;

  // GoTo turns toward its target until close, then keeps that heading.
  if (reference_.face_target &&
      (reference_.position_m - p).head<2>().norm() > config_.face_min_distance_m) {
    reference_.yaw_rad = heading_to(p, reference_.position_m, reference_.yaw_rad);
  }

  // Position -> velocity command. The error is first capped (cross-track
  // first) where the loop reaches its output limit, so that per-axis limits
  // never bend the direction of a long move; then the command is capped at
  // the behaviour's speed and at the speed that still stops at the target.
  const Eigen::Vector3d position_error = reference_.position_m - p;
  const double distance = position_error.norm();
  const Eigen::Vector3d direction =
      reference_.direction.squaredNorm() > 0.0 ? reference_.direction
      : distance > kEpsilon                     ? Eigen::Vector3d(position_error / distance)
                                                : Eigen::Vector3d(Eigen::Vector3d::Zero());
  const Eigen::Vector3d capped_error = cap_cross_first(position_error, direction, position_error_cap_);
  Eigen::Vector3d v_cmd;
  for (int i = 0; i < 3; ++i) v_cmd(i) = position_[i].update(capped_error(i), dt_s, v(i));
  const double stopping_speed = std::sqrt(2.0 * config_.braking_decel_mps2 * std::abs(direction.dot(position_error)));
  return cap_cross_first(v_cmd, direction, reference_.speed_mps, stopping_speed);
}

}  // namespace campo
