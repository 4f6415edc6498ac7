// The low-level commands (campo/vehicle.hpp): the quadrotor's Velocity,
// AttitudeThrust and Rotors and the rover's Wheels, checked against the
// physics they stand for (a thrust balance, g tan(tilt), rolling without
// slip, an independent integration of the vertical dynamics).
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "campo/pose.hpp"
#include "campo/scene_loader.hpp"
#include "vehicles/quadrotor.hpp"
#include "vehicles/rover.hpp"
#include "tests/vehicles/vehicle_test_support.hpp"
#include "tests/test_units.hpp"

namespace campo {
namespace {

using test::parse;
using test::at;
using test::wrap;
using test::kGround;

using ::testing::HasSubstr;

using namespace campo::test_units;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();


// A quadrotor flown as the episode loop flies it: the command re-sent at the
// control rate, pre_step and a world step every physics step.
struct CommandFlight {
  explicit CommandFlight(const Eigen::Isometry3d& start = at({0.0, 0.0, 5.0}), const QuadrotorConfig& config = {})
      : scene(parse(kGround)), world(scene), quad(world, config, start) {}

  /// Flies `c` for `seconds`, calling `each` after every physics step.
  void fly(const Command& c, double seconds, const std::function<void()>& each = [] {}) {
    const int control_period = static_cast<int>(std::lround(1.0 / (scene.world.control_rate_hz * dt())));
    const auto steps = static_cast<long>(std::lround(seconds / dt()));
    for (long k = 0; k < steps; ++k) {
      if (k % control_period == 0) quad.command(c);
      quad.pre_step(dt());
      world.step();
      each();
    }
  }
  double dt() const { return scene.world.physics_step_s; }
  double g() const { return -scene.world.gravity_mps2.z(); }
  QuadrotorModel model() const { return model_of(quad.config(), scene.world.gravity_mps2); }
  double hover() const { return hover_rotor_speed(model()); }
  VehicleState s() const { return quad.state(); }
  // Roll, pitch and yaw of the body, radians (R = Rz(yaw) Ry(pitch) Rx(roll), as trajectory.csv's).
  Eigen::Vector3d rpy() const { return rpy_deg_from_rotation(s().orientation.toRotationMatrix()) * kPi / 180.0; }

  Scene scene;
  World world;
  Quadrotor quad;
};

// The vertical motion of a level quadrotor whose four rotors are commanded
// `w_cmd` from `w0`, integrated independently of Bullet (RK4, fine step):
// m z'' = 4 k_f w^2 - m g - c z', w' = (w_cmd - w) / tau. Returns z(t) - z(0).
double vertical_rise(const QuadrotorConfig& c, double g, double w0, double w_cmd, double t_s) {
  struct X {
    double z, vz, w;
  };
  const auto f = [&](const X& x) {
    return X{x.vz, (4.0 * c.thrust_coefficient * x.w * x.w - c.mass_kg * g - c.linear_drag_n_per_mps * x.vz) / c.mass_kg,
             (w_cmd - x.w) / c.motor_time_constant_s};
  };
  const auto add = [](const X& a, const X& b, double h) { return X{a.z + h * b.z, a.vz + h * b.vz, a.w + h * b.w}; };
  X x{0.0, 0.0, w0};
  const int n = 20000;
  const double h = t_s / n;
  for (int i = 0; i < n; ++i) {
    const X k1 = f(x), k2 = f(add(x, k1, h / 2)), k3 = f(add(x, k2, h / 2)), k4 = f(add(x, k3, h));
    x = {x.z + h / 6 * (k1.z + 2 * k2.z + 2 * k3.z + k4.z), x.vz + h / 6 * (k1.vz + 2 * k2.vz + 2 * k3.vz + k4.vz),
         x.w + h / 6 * (k1.w + 2 * k2.w + 2 * k3.w + k4.w)};
  }
  return x.z;
}

TEST(LowLevelCommands, NamesOfTheNewKinds) {
  EXPECT_EQ(command_name(command::Velocity{}), "velocity");
  EXPECT_EQ(command_name(command::AttitudeThrust{}), "attitude_thrust");
  EXPECT_EQ(command_name(command::Rotors{}), "rotors");
  EXPECT_EQ(command_name(command::Wheels{}), "wheels");
  // The existing kinds keep their indices.
  EXPECT_EQ(Command(command::Twist{}).index(), 4u);
  EXPECT_EQ(command_name(command::Twist{}), "twist");
}

// ---- Rotors --------------------------------------------------------------

TEST(QuadrotorRotors, HoverSpeedOnAllFourHoldsAltitude) {
  CommandFlight f;
  const double w = f.hover();
  const Eigen::Vector3d start = f.s().position_m;
  f.fly(command::Rotors{{w, w, w, w}}, 5.0);
  // The rotors start at hover speed (no lag transient), so the thrust is the
  // weight, the body at rest has no drag, and four equal rotors give no
  // torque: the net force is zero but for rounding (relative 1e-16 of the
  // weight, whose effect over 5 s, g t^2 1e-16, is some 1e-14 m). A micrometre
  // leaves room for Bullet's own rounding.
  EXPECT_LT((f.s().position_m - start).norm(), 1e-6);
  EXPECT_LT(f.s().linear_velocity_mps.norm(), 1e-6);
  for (const double speed : f.quad.rotor_speeds()) EXPECT_NEAR(speed, w, 1e-6);
}

TEST(QuadrotorRotors, AboveHoverClimbsAndBelowSinksAsTheVerticalDynamicsSay) {
  for (const double factor : {1.05, 0.95}) {
    SCOPED_TRACE("rotor speed " + std::to_string(factor) + " x hover");
    CommandFlight f;
    const double w0 = f.hover();
    const double w = factor * w0;
    const double z0 = f.s().position_m.z();
    const double t = 2.0;
    f.fly(command::Rotors{{w, w, w, w}}, t);
    const double expected = vertical_rise(f.quad.config(), f.g(), w0, w, t);
    EXPECT_EQ(expected > 0.0, factor > 1.0);
    // The discrete loop leads the continuous model by about half a step
    // twice: the lagged rotor speed applied over a step is the one at its end
    // (the thrust leads by dt/2, the position by a t dt/2, a the net
    // acceleration) and Bullet's semi-implicit Euler moves with the velocity
    // at the end of the step (by v dt/2). Bounded here by a whole step each.
    const double a = std::abs(factor * factor - 1.0) * f.g();
    const double v = std::abs(f.s().linear_velocity_mps.z());
    EXPECT_NEAR(f.s().position_m.z() - z0, expected, (a * t + v) * f.dt());
    // Equal rotors: no torque, it stays level and over its start.
    EXPECT_LT(f.s().position_m.head<2>().norm(), 1e-3);
    EXPECT_LT(f.rpy().head<2>().norm(), 1e-3);
  }
}

TEST(QuadrotorRotors, SpeedsPassThroughTheMotorLag) {
  CommandFlight f;
  const double w0 = f.hover();
  const double w = 800.0;
  const int steps = 5;
  f.fly(command::Rotors{{w, w, w, w}}, steps * f.dt());
  // First-order lag, exact over each step: w0 + (w - w0)(1 - exp(-n dt / tau)).
  const double expected = w + (w0 - w) * std::exp(-steps * f.dt() / f.quad.config().motor_time_constant_s);
  for (const double speed : f.quad.rotor_speeds()) EXPECT_NEAR(speed, expected, 1e-9);
}

TEST(QuadrotorRotors, SpeedsAreClampedToTheMotorRange) {
  CommandFlight f;
  const QuadrotorConfig& c = f.quad.config();
  f.fly(command::Rotors{{-50.0, 0.5 * c.min_rotor_speed_radps, 2.0 * c.max_rotor_speed_radps, 700.0}}, f.dt());
  const auto commanded = f.quad.actuators()["rotor_speed_command_radps"].get<std::array<double, 4>>();
  EXPECT_EQ(commanded[0], c.min_rotor_speed_radps);
  EXPECT_EQ(commanded[1], c.min_rotor_speed_radps);
  EXPECT_EQ(commanded[2], c.max_rotor_speed_radps);
  EXPECT_EQ(commanded[3], 700.0);
}

TEST(QuadrotorRotors, HoldAfterUnevenRotorsRecoversAndHolds) {
  CommandFlight f;
  const double w = f.hover();
  // Front rotors (0 and 3) faster: it pitches up and drifts.
  f.fly(command::Rotors{{1.02 * w, w, w, 1.02 * w}}, 0.3);
  EXPECT_GT(f.rpy().head<2>().norm(), 0.02);
  const Eigen::Vector3d target(0.0, 0.0, 5.0);
  f.fly(command::Hold{target, 0.0}, 8.0);
  EXPECT_LT((f.s().position_m - target).norm(), 0.05);
  EXPECT_TRUE(f.quad.stable());
}

// ---- Velocity --------------------------------------------------------------

TEST(QuadrotorVelocity, ReachesTheHeadingFrameVelocity) {
  const double yaw = 0.5;
  CommandFlight f(at({0.0, 0.0, 5.0}, yaw));
  const QuadrotorControllerConfig& k = f.quad.config().controller;
  const double c_over_m = f.quad.config().linear_drag_n_per_mps / f.quad.config().mass_kg;
  struct Case {
    Eigen::Vector3d heading_frame;
    Eigen::Vector3d world;
  };
  const Case cases[] = {
      {{1.0, 0.0, 0.0}, {std::cos(yaw), std::sin(yaw), 0.0}},                 // forward: along the heading
      {{0.0, 0.5, 0.3}, {-0.5 * std::sin(yaw), 0.5 * std::cos(yaw), 0.3}},  // left and up
  };
  for (const Case& c : cases) {
    SCOPED_TRACE("heading-frame velocity " + std::to_string(c.heading_frame.x()) + ", " +
                 std::to_string(c.heading_frame.y()) + ", " + std::to_string(c.heading_frame.z()));
    f.fly(command::Velocity{c.heading_frame, 0.0}, 8.0);
    const Eigen::Vector3d v = f.s().linear_velocity_mps;
    // The velocity loops are PI over the drag c v: their proportional part
    // alone would settle c|v| / (m kp) short, the integral only shortens that.
    EXPECT_NEAR(v.head<2>().dot(c.world.head<2>().normalized()), c.world.head<2>().norm(),
                c_over_m * c.world.head<2>().norm() / k.velocity_xy.kp);
    EXPECT_NEAR((v - c.world).head<2>().norm(), 0.0, c_over_m * c.world.head<2>().norm() / k.velocity_xy.kp);
    EXPECT_NEAR(v.z(), c.world.z(), c_over_m * std::abs(c.world.z()) / k.velocity_z.kp + 1e-3);
    // No yaw rate: the heading stays.
    EXPECT_NEAR(wrap(f.s().yaw_rad() - yaw), 0.0, 0.01);
  }
}

TEST(QuadrotorVelocity, TurnsAtTheYawRateUpToTheTurnRateLimit) {
  const double limit = QuadrotorControllerConfig{}.attitude_yaw.output_limit;
  for (const double rate : {0.5, -0.3, 5.0}) {
    SCOPED_TRACE("yaw rate " + std::to_string(rate));
    CommandFlight f;
    // Unwrapped heading, sampled every step.
    double heading = f.s().yaw_rad();
    double last = heading;
    const auto track = [&] {
      const double now = f.s().yaw_rad();
      heading += wrap(now - last);
      last = now;
    };
    f.fly(command::Velocity{Eigen::Vector3d::Zero(), rate}, 2.0, track);
    const double from = heading;
    const double span = 3.0;
    f.fly(command::Velocity{Eigen::Vector3d::Zero(), rate}, span, track);
    const double expected = std::clamp(rate, -limit, limit);
    EXPECT_NEAR((heading - from) / span, expected, 0.02 * std::abs(expected));
    // Turning in place.
    EXPECT_LT(f.s().linear_velocity_mps.norm(), 0.02);
  }
}

TEST(QuadrotorVelocity, HoldAfterwardsStopsAtTheHoldPoint) {
  CommandFlight f;
  f.fly(command::Velocity{{1.0, 0.0, 0.0}, 0.2}, 4.0);
  EXPECT_GT(f.s().linear_velocity_mps.norm(), 0.8);
  const VehicleState s = f.s();
  f.fly(command::Hold{s.position_m, {}}, 8.0);
  EXPECT_LT((f.s().position_m - s.position_m).norm(), 0.05);
  EXPECT_TRUE(f.quad.stable());
  // Hold keeps the heading it was given (the current one at the switch).
  EXPECT_NEAR(wrap(f.s().yaw_rad() - s.yaw_rad()), 0.0, 0.05);
}

TEST(QuadrotorVelocity, SpeedIsCappedAtTheHighestSpeedCommanded) {
  CommandFlight f;
  const double cap = f.quad.config().controller.position.output_limit;
  double fastest = 0.0;
  f.fly(command::Velocity{{0.0, 0.0, 100.0}, 0.0}, 6.0,
        [&] { fastest = std::max(fastest, f.s().linear_velocity_mps.norm()); });
  EXPECT_LE(fastest, cap * 1.02);
  EXPECT_GT(fastest, 0.9 * cap);
}

// ---- AttitudeThrust --------------------------------------------------------

TEST(QuadrotorAttitudeThrust, WeightAtLevelAttitudeHoldsAltitude) {
  CommandFlight f(at({0.0, 0.0, 5.0}, 1.0));
  const double weight = f.quad.config().mass_kg * f.g();
  const Eigen::Vector3d start = f.s().position_m;
  f.fly(command::AttitudeThrust{0.0, 0.0, 0.0, weight}, 3.0);
  // Level, rotors at hover from the start: thrust balances the weight exactly.
  EXPECT_LT((f.s().position_m - start).norm(), 1e-3);
  EXPECT_LT(f.rpy().head<2>().norm(), 1e-3);
  EXPECT_NEAR(wrap(f.s().yaw_rad() - 1.0), 0.0, 1e-3);
}

TEST(QuadrotorAttitudeThrust, TiltAcceleratesAtGTanTiltInTheRightDirection) {
  const double yaw = 0.7;
  const double tilt = 0.2;
  const Eigen::Vector2d forward(std::cos(yaw), std::sin(yaw));
  const Eigen::Vector2d right(std::sin(yaw), -std::cos(yaw));
  struct Case {
    double roll, pitch;
    Eigen::Vector2d direction;
  };
  // Positive pitch: nose down, forward; positive roll: right side down, to the right.
  const Case cases[] = {{0.0, tilt, forward}, {0.0, -tilt, -forward}, {tilt, 0.0, right}, {-tilt, 0.0, -right}};
  for (const Case& c : cases) {
    SCOPED_TRACE("roll " + std::to_string(c.roll) + ", pitch " + std::to_string(c.pitch));
    CommandFlight f(at({0.0, 0.0, 5.0}, yaw));
    const QuadrotorConfig& config = f.quad.config();
    // Thrust whose vertical part is the weight.
    const double thrust = config.mass_kg * f.g() / std::cos(tilt);
    const command::AttitudeThrust cmd{c.roll, c.pitch, 0.0, thrust};
    f.fly(cmd, 0.5);  // the attitude settles
    EXPECT_NEAR(f.rpy().x(), c.roll, 0.01);
    EXPECT_NEAR(f.rpy().y(), c.pitch, 0.01);
    EXPECT_NEAR(wrap(f.rpy().z() - yaw), 0.0, 0.01);
    const Eigen::Vector2d v0 = f.s().linear_velocity_mps.head<2>();
    const double span = 0.5;
    f.fly(cmd, span);
    const Eigen::Vector2d v1 = f.s().linear_velocity_mps.head<2>();
    // m a = T sin(tilt) - c v horizontally: g tan(tilt) less the drag at the mean velocity.
    const Eigen::Vector2d expected =
        f.g() * std::tan(tilt) * c.direction - config.linear_drag_n_per_mps / config.mass_kg * 0.5 * (v0 + v1);
    const Eigen::Vector2d measured = (v1 - v0) / span;
    EXPECT_NEAR((measured - expected).norm(), 0.0, 0.03 * f.g() * std::tan(tilt));
    EXPECT_NEAR(f.s().linear_velocity_mps.z(), 0.0, 0.05);
  }
}

TEST(QuadrotorAttitudeThrust, TiltIsCappedAtMaxTilt) {
  CommandFlight f;
  const double max_tilt = f.quad.config().controller.max_tilt_deg * kPi / 180.0;
  const double thrust = f.quad.config().mass_kg * f.g() / std::cos(max_tilt);
  f.fly(command::AttitudeThrust{0.0, 1.2, 0.0, thrust}, 0.6);
  EXPECT_NEAR(f.rpy().y(), max_tilt, 0.01);
  // Combined roll and pitch: the body z tilts by max_tilt at most.
  CommandFlight g;
  g.fly(command::AttitudeThrust{0.6, 0.6, 0.0, thrust}, 0.6);
  const double tilt = std::acos((g.s().orientation * Eigen::Vector3d::UnitZ()).z());
  EXPECT_NEAR(tilt, max_tilt, 0.01);
}

TEST(QuadrotorAttitudeThrust, TurnsAtTheYawRate) {
  CommandFlight f;
  const double weight = f.quad.config().mass_kg * f.g();
  f.fly(command::AttitudeThrust{0.0, 0.0, 0.4, weight}, 2.0);
  const double from = f.s().yaw_rad();
  f.fly(command::AttitudeThrust{0.0, 0.0, 0.4, weight}, 2.0);
  EXPECT_NEAR(wrap(f.s().yaw_rad() - from) / 2.0, 0.4, 0.01);
}

TEST(LowLevelCommands, SwitchingBetweenAllTheQuadrotorsCommandsStaysInControl) {
  CommandFlight f;
  const double w = f.hover();
  const double weight = f.quad.config().mass_kg * f.g();
  f.fly(command::Velocity{{1.0, 0.0, 0.2}, 0.3}, 2.0);
  f.fly(command::AttitudeThrust{0.05, -0.1, 0.3, weight}, 0.5);
  f.fly(command::Rotors{{w, w, w, w}}, 0.3);
  f.fly(command::GoTo{{2.0, 2.0, 5.0}, 1.0, true}, 1.0);
  f.fly(command::Velocity{{0.0, 0.0, 0.0}, 0.0}, 3.0);
  // Velocity zero: it has stopped and holds its heading.
  EXPECT_LT(f.s().linear_velocity_mps.norm(), 0.05);
  const Eigen::Vector3d here = f.s().position_m;
  f.fly(command::Hold{here, {}}, 5.0);
  EXPECT_LT((f.s().position_m - here).norm(), 0.05);
  EXPECT_TRUE(f.quad.stable());
  EXPECT_FALSE(f.world.vehicle_clearance().touching());
}

// ---- Rejections ------------------------------------------------------------

TEST(LowLevelCommands, QuadrotorRefusesTheRoversCommandsAndNonFiniteValues) {
  CommandFlight f;
  const auto refuses = [&](const Command& c, const std::string& message) {
    SCOPED_TRACE(std::string(command_name(c)));
    try {
      f.quad.command(c);
      ADD_FAILURE() << "accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_THAT(e.what(), HasSubstr(message));
    }
  };
  refuses(command::Twist{1.0, 0.0}, "cannot follow a twist command");
  refuses(command::Wheels{{1.0, 1.0, 1.0, 1.0}}, "cannot follow a wheels command");
  refuses(command::Velocity{{kNaN, 0.0, 0.0}, 0.0}, "velocity: non-finite");
  refuses(command::Velocity{{0.0, 0.0, 0.0}, kInf}, "velocity: non-finite");
  refuses(command::AttitudeThrust{0.0, kNaN, 0.0, 10.0}, "attitude_thrust: non-finite");
  refuses(command::AttitudeThrust{0.0, 0.0, 0.0, -kInf}, "attitude_thrust: non-finite");
  refuses(command::Rotors{{600.0, 600.0, kNaN, 600.0}}, "rotors: non-finite");
  // A refused command leaves the last one in force: still hovering in place.
  const Eigen::Vector3d start = f.s().position_m;
  f.fly(command::Hold{start, {}}, 1.0);
  EXPECT_LT((f.s().position_m - start).norm(), 0.01);
}

// ---- Rover Wheels ----------------------------------------------------------

Eigen::Isometry3d rover_start(double yaw = 0.0) { return at({0.0, 0.0, 0.4}, yaw); }

// A rover in a flat world, stepped as the episode loop does.
struct Drive {
  explicit Drive(const RoverConfig& config = {}) : scene(parse(kGround)), world(scene), rover(world, config, rover_start()) {}
  void run(const Command& c, double seconds) {
    rover.command(c);
    const long steps = std::lround(seconds / scene.world.physics_step_s);
    for (long i = 0; i < steps; ++i) {
      rover.pre_step(scene.world.physics_step_s);
      world.step();
    }
  }
  // Forward speed and yaw rate in the body frame.
  BodyTwist body_rates() const {
    const VehicleState s = rover.state();
    const Eigen::Matrix3d r = s.orientation.toRotationMatrix();
    return {s.linear_velocity_mps.dot(r.col(0)), s.angular_velocity_radps.dot(r.col(2))};
  }
  Scene scene;
  World world;
  Rover rover;
};

TEST(RoverWheels, EqualSpeedsDriveStraightAtWheelSpeedTimesRadius) {
  for (const double w : {5.0, -3.0}) {
    SCOPED_TRACE("wheel speed " + std::to_string(w));
    Drive d;
    d.run(command::Wheels{{w, w, w, w}}, 3.0);
    const double r = d.rover.config().wheel_radius_m;
    // Rolling without slip on flat ground: v = w r, no turn.
    EXPECT_NEAR(d.body_rates().v_mps, w * r, 0.03 * std::abs(w * r));
    EXPECT_NEAR(d.body_rates().w_radps, 0.0, 0.01);
    EXPECT_NEAR(d.rover.state().position_m.y(), 0.0, 0.02);
    for (const double measured : d.rover.wheel_speeds_radps()) EXPECT_NEAR(measured, w, 0.03 * std::abs(w));
  }
}

TEST(RoverWheels, LeftSlowerThanRightTurnsLeft) {
  Drive d;
  const double left = 3.0, right = 6.0;
  d.run(command::Wheels{{left, right, left, right}}, 3.0);
  const RoverConfig& c = d.rover.config();
  // Kinematics without slip: v = r (wl + wr) / 2, w = r (wr - wl) / (2 l). Skid
  // steering slips sideways when turning, so the yaw rate falls short of the
  // kinematic one; it turns left (CCW, positive) all the same.
  const double kinematic_w = c.wheel_radius_m * (right - left) / (2.0 * c.half_track_m);
  const BodyTwist m = d.body_rates();
  EXPECT_GT(m.w_radps, 0.1 * kinematic_w);
  EXPECT_LT(m.w_radps, kinematic_w * 1.05);
  EXPECT_GT(m.v_mps, 0.0);
  EXPECT_LT(m.v_mps, c.wheel_radius_m * 0.5 * (left + right) * 1.05);
  EXPECT_GT(d.rover.state().position_m.y(), 0.0);
}

TEST(RoverWheels, SpeedsAreClampedAndRateLimited) {
  {
    Drive d;
    const double max = d.rover.config().max_wheel_speed_radps;
    d.run(command::Wheels{{3.0 * max, -3.0 * max, 0.5 * max, -0.5 * max}}, 0.1);
    const auto& targets = d.rover.wheel_commands_radps();
    EXPECT_EQ(targets[Rover::front_left], max);
    EXPECT_EQ(targets[Rover::front_right], -max);
    EXPECT_EQ(targets[Rover::rear_left], 0.5 * max);
    EXPECT_EQ(targets[Rover::rear_right], -0.5 * max);
  }
  {
    RoverConfig config;
    config.max_wheel_accel_radps2 = 4.0;
    Drive d(config);
    const int steps = 10;
    d.run(command::Wheels{{8.0, 8.0, -8.0, 1.0}}, steps * d.scene.world.physics_step_s);
    // From rest, at most max_accel dt per step.
    const double reach = 4.0 * steps * d.scene.world.physics_step_s;
    const auto& targets = d.rover.wheel_commands_radps();
    EXPECT_NEAR(targets[Rover::front_left], reach, 1e-12);
    EXPECT_NEAR(targets[Rover::front_right], reach, 1e-12);
    EXPECT_NEAR(targets[Rover::rear_left], -reach, 1e-12);
    EXPECT_NEAR(targets[Rover::rear_right], std::min(1.0, reach), 1e-12);
  }
}

TEST(RoverWheels, HoldAndTwistTakeOverAfterwards) {
  Drive d;
  d.run(command::Wheels{{5.0, 5.0, 5.0, 5.0}}, 2.0);
  d.run(command::Hold{}, 2.0);
  EXPECT_TRUE(d.rover.stable());
  d.run(command::Twist{0.5, 0.0}, 3.0);
  EXPECT_NEAR(d.body_rates().v_mps, 0.5, 0.05);
}

TEST(LowLevelCommands, RoverRefusesTheQuadrotorsCommandsAndNonFiniteValues) {
  Drive d;
  const auto refuses = [&](const Command& c, const std::string& message) {
    SCOPED_TRACE(std::string(command_name(c)));
    try {
      d.rover.command(c);
      ADD_FAILURE() << "accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_THAT(e.what(), HasSubstr(message));
    }
  };
  refuses(command::Altitude{2.0}, "cannot follow an altitude command");
  refuses(command::Velocity{{1.0, 0.0, 0.0}, 0.0}, "cannot follow a quadrotor's velocity command");
  refuses(command::AttitudeThrust{0.0, 0.1, 0.0, 10.0}, "cannot follow a quadrotor's attitude_thrust command");
  refuses(command::Rotors{{600.0, 600.0, 600.0, 600.0}}, "cannot follow a quadrotor's rotors command");
  refuses(command::Wheels{{1.0, kNaN, 1.0, 1.0}}, "wheels: non-finite");
  refuses(command::Wheels{{1.0, 1.0, 1.0, -kInf}}, "wheels: non-finite");
}

}  // namespace
}  // namespace campo
