#include "vehicles/quadrotor_controller.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include <gtest/gtest.h>

#include "vehicles/quadrotor.hpp"
#include "tests/test_units.hpp"

namespace campo {
namespace {

using namespace campo::test_units;

QuadrotorModel preset_model() { return model_of(QuadrotorConfig{}, {0.0, 0.0, -9.81}); }

Eigen::Matrix4d preset_allocation() {
  const QuadrotorModel m = preset_model();
  return allocation_matrix(m.arm_length_m, m.thrust_coefficient, m.torque_coefficient);
}

TEST(QuadrotorMixer, RotorsSitOnTheDiagonalsOfAnXFrame) {
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector3d r = rotor_position(i, 0.225);
    EXPECT_NEAR(r.norm(), 0.225, 1e-12);
    EXPECT_NEAR(std::abs(r.x()), std::abs(r.y()), 1e-12);
    EXPECT_EQ(r.z(), 0.0);
  }
  EXPECT_GT(rotor_position(0, 1.0).x(), 0.0);  // front-left
  EXPECT_GT(rotor_position(0, 1.0).y(), 0.0);
  EXPECT_LT(rotor_position(2, 1.0).x(), 0.0);  // rear-right
  EXPECT_LT(rotor_position(2, 1.0).y(), 0.0);
  // Diagonal pairs spin the same way, neighbours opposite.
  EXPECT_EQ(kRotorTorqueSign[0], kRotorTorqueSign[2]);
  EXPECT_EQ(kRotorTorqueSign[1], kRotorTorqueSign[3]);
  EXPECT_EQ(kRotorTorqueSign[0], -kRotorTorqueSign[1]);
}

TEST(QuadrotorMixer, AllocationMatchesForcesAtTheRotors) {
  const QuadrotorModel m = preset_model();
  const Eigen::Matrix4d a = preset_allocation();
  const Eigen::Vector4d squared(3.1e5, 4.2e5, 2.7e5, 3.9e5);
  // The wrench the physics applies: thrust at each rotor position plus drag torques.
  double thrust = 0.0;
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector3d force(0.0, 0.0, m.thrust_coefficient * squared(i));
    thrust += force.z();
    torque += rotor_position(i, m.arm_length_m).cross(force);
    torque.z() += kRotorTorqueSign[static_cast<std::size_t>(i)] * m.torque_coefficient * squared(i);
  }
  const Eigen::Vector4d wrench = a * squared;
  EXPECT_NEAR(wrench(0), thrust, 1e-12);
  EXPECT_NEAR((wrench.tail<3>() - torque).norm(), 0.0, 1e-12);
}

TEST(QuadrotorMixer, RoundTripRecoversThrustAndTorques) {
  const QuadrotorModel m = preset_model();
  const Eigen::Matrix4d a = preset_allocation();
  const double min_sq = std::pow(m.min_rotor_speed_radps, 2);
  const double max_sq = std::pow(m.max_rotor_speed_radps, 2);
  // Wrenches the rotors can realise without hitting a speed limit.
  const double thrusts[] = {10.0, 14.7, 25.0};
  const Eigen::Vector3d torques[] = {{0.0, 0.0, 0.0}, {0.3, -0.2, 0.02}, {-0.5, 0.4, -0.03}};
  for (const double thrust : thrusts) {
    for (const Eigen::Vector3d& torque : torques) {
      const Eigen::Vector4d squared = mix(a.inverse(), thrust, torque, min_sq, max_sq);
      ASSERT_GT(squared.minCoeff(), min_sq);
      ASSERT_LT(squared.maxCoeff(), max_sq);
      const Eigen::Vector4d wrench = a * squared;
      EXPECT_NEAR(wrench(0), thrust, 1e-9);
      EXPECT_NEAR((wrench.tail<3>() - torque).norm(), 0.0, 1e-9) << thrust;
    }
  }
}

TEST(QuadrotorMixer, SaturationDropsYawFirstAndKeepsRollPitch) {
  const QuadrotorModel m = preset_model();
  const Eigen::Matrix4d a = preset_allocation();
  const double min_sq = std::pow(m.min_rotor_speed_radps, 2);
  const double max_sq = std::pow(m.max_rotor_speed_radps, 2);
  // Far more yaw torque than the rotors can give at hover thrust.
  const Eigen::Vector3d torque(0.2, -0.1, 5.0);
  const Eigen::Vector4d squared = mix(a.inverse(), 14.7, torque, min_sq, max_sq);
  EXPECT_GE(squared.minCoeff(), min_sq);
  EXPECT_LE(squared.maxCoeff(), max_sq);
  const Eigen::Vector4d wrench = a * squared;
  EXPECT_NEAR(wrench(0), 14.7, 1e-9);
  EXPECT_NEAR(wrench(1), 0.2, 1e-9);
  EXPECT_NEAR(wrench(2), -0.1, 1e-9);
  EXPECT_GT(wrench(3), 0.0);
  EXPECT_LT(wrench(3), 5.0);
}

TEST(QuadrotorMixer, SaturationScalesExcessRollAndShiftsThrust) {
  const QuadrotorModel m = preset_model();
  const Eigen::Matrix4d a = preset_allocation();
  const double min_sq = std::pow(m.min_rotor_speed_radps, 2);
  const double max_sq = std::pow(m.max_rotor_speed_radps, 2);
  // More roll torque than the full motor range gives.
  const Eigen::Vector4d squared = mix(a.inverse(), 30.0, {50.0, 0.0, 0.0}, min_sq, max_sq);
  EXPECT_GE(squared.minCoeff(), min_sq);
  EXPECT_LE(squared.maxCoeff(), max_sq);
  const Eigen::Vector4d wrench = a * squared;
  EXPECT_GT(wrench(1), 0.0);
  EXPECT_NEAR(wrench(2), 0.0, 1e-9);
  // All of the range goes to roll: two rotors at the top, two at the bottom.
  EXPECT_NEAR(squared.maxCoeff() - squared.minCoeff(), max_sq - min_sq, 1e-6);
}

TEST(QuadrotorAttitude, FromThrustAndYaw) {
  const Eigen::Quaterniond level = attitude_from_thrust({0.0, 0.0, 3.0}, kPi / 2);
  EXPECT_NEAR((level * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitY()).norm(), 0.0, 1e-12);
  EXPECT_NEAR((level * Eigen::Vector3d::UnitZ() - Eigen::Vector3d::UnitZ()).norm(), 0.0, 1e-12);

  const Eigen::Vector3d tilted(1.0, 0.0, 2.0);
  const Eigen::Quaterniond q = attitude_from_thrust(tilted, 0.3);
  EXPECT_NEAR((q * Eigen::Vector3d::UnitZ() - tilted.normalized()).norm(), 0.0, 1e-12);
  VehicleState s;
  s.orientation = q;
  EXPECT_NEAR(s.yaw_rad(), 0.3, 1e-12);
}

TEST(QuadrotorAttitude, ErrorIsTheBodyRotationVector) {
  const Eigen::Quaterniond current(Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ()));
  const Eigen::Quaterniond small = current * Eigen::Quaterniond(Eigen::AngleAxisd(0.01, Eigen::Vector3d::UnitX()));
  const Eigen::Vector3d e = attitude_error(current, small);
  EXPECT_NEAR(e.x(), 0.01, 1e-6);
  EXPECT_NEAR(e.y(), 0.0, 1e-12);
  EXPECT_NEAR(e.z(), 0.0, 1e-12);
  // The short way round: a 350-degree yaw is a 10-degree turn the other way.
  const Eigen::Quaterniond far(Eigen::AngleAxisd(0.4 + 350.0 * kPi / 180.0, Eigen::Vector3d::UnitZ()));
  EXPECT_NEAR(attitude_error(current, far).z(), -10.0 * kPi / 180.0, 1e-12);
}

TEST(QuadrotorAttitude, HeadingChangeDoesNotDisturbTheTilt) {
  // Level now; wanted: 10 degrees of pitch and a half turn of heading.
  const Eigen::Quaterniond level = Eigen::Quaterniond::Identity();
  const Eigen::Vector3d thrust(std::sin(10.0 * kPi / 180.0), 0.0, std::cos(10.0 * kPi / 180.0));
  const Eigen::Vector3d e = attitude_error(level, attitude_from_thrust(thrust, 3.0));
  // The tilt part is a pure pitch of 10 degrees toward +x, whatever the heading.
  EXPECT_NEAR(e.x(), 0.0, 1e-12);
  EXPECT_NEAR(e.y(), 2.0 * std::sin(5.0 * kPi / 180.0), 1e-12);
  // The turn is about the tilted body z, so near (not exactly) the change of heading.
  EXPECT_NEAR(e.z(), 3.0, 0.01);
}

TEST(QuadrotorShaping, CrossTrackFirstThenAlongWithinTheLimits) {
  const Eigen::Vector3d dir = Eigen::Vector3d::UnitX();
  // Along-track gets what the cross-track leaves.
  const Eigen::Vector3d v = cap_cross_first({5.0, 0.3, 0.0}, dir, 0.5);
  EXPECT_NEAR(v.y(), 0.3, 1e-12);
  EXPECT_NEAR(v.x(), 0.4, 1e-12);
  // Cross-track alone above the limit: capped, nothing along.
  const Eigen::Vector3d w = cap_cross_first({5.0, 2.0, 0.0}, dir, 0.5);
  EXPECT_NEAR(w.norm(), 0.5, 1e-12);
  EXPECT_NEAR(w.x(), 0.0, 1e-12);
  // The separate cap on the part along (a braking profile).
  const Eigen::Vector3d b = cap_cross_first({5.0, 0.1, 0.0}, dir, 0.5, 0.2);
  EXPECT_NEAR(b.x(), 0.2, 1e-12);
  EXPECT_NEAR(b.y(), 0.1, 1e-12);
  EXPECT_NEAR(cap_cross_first({-1.0, 0.0, 0.0}, dir, 0.5, 0.2).x(), -0.2, 1e-12);
  // Within the limits nothing changes; no direction caps only the norm.
  EXPECT_EQ(cap_cross_first({0.1, 0.2, 0.0}, dir, 0.5), Eigen::Vector3d(0.1, 0.2, 0.0));
  EXPECT_NEAR(cap_cross_first({3.0, 4.0, 0.0}, Eigen::Vector3d::Zero(), 1.0).norm(), 1.0, 1e-12);
}

VehicleState hovering_at(const Eigen::Vector3d& p, double yaw = 0.0) {
  VehicleState s;
  s.position_m = p;
  s.orientation = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ());
  return s;
}

TEST(QuadrotorController, AtEquilibriumCommandsHoverSpeed) {
  const QuadrotorModel model = preset_model();
  const VehicleState s = hovering_at({1.0, 2.0, 3.0}, 0.7);
  QuadrotorController controller(QuadrotorControllerConfig{}, model, s);
  const RotorSpeeds w = controller.update(s, 1.0 / 240.0);
  for (const double speed : w) EXPECT_NEAR(speed, hover_rotor_speed(model), 1e-9);
}

TEST(QuadrotorController, RejectsTwistAndBadSpeeds) {
  QuadrotorController controller(QuadrotorControllerConfig{}, preset_model(), hovering_at({0, 0, 1}));
  EXPECT_THROW(controller.command(command::Twist{0.5, 0.1}, hovering_at({0, 0, 1})), std::invalid_argument);
  EXPECT_THROW(controller.command(command::GoTo{{1, 0, 1}, 0.0, true}, hovering_at({0, 0, 1})),
               std::invalid_argument);
}

TEST(QuadrotorController, ResendingTheSameCommandKeepsIntegrators) {
  // Integrating gains everywhere, so that a reset would show in the output.
  QuadrotorControllerConfig config;
  config.position.ki = 0.5;
  const QuadrotorModel model = preset_model();
  const VehicleState start = hovering_at({0.0, 0.0, 1.0});
  QuadrotorController once(config, model, start);
  QuadrotorController every_tick(config, model, start);
  const command::GoTo go{{3.0, 1.0, 1.5}, 0.6, true};
  once.command(go, start);
  every_tick.command(go, start);
  VehicleState s = start;
  for (int k = 0; k < 200; ++k) {
    // A state drifting off the line, so that every loop integrates.
    s.position_m += Eigen::Vector3d(0.002, -0.001, 0.0005);
    s.linear_velocity_mps = {0.1, -0.05, 0.02};
    if (k % 4 == 0) every_tick.command(go, s);
    const RotorSpeeds a = once.update(s, 1.0 / 240.0);
    const RotorSpeeds b = every_tick.update(s, 1.0 / 240.0);
    ASSERT_EQ(a, b) << "step " << k;
  }
  // A new target does change the behaviour.
  every_tick.command(command::GoTo{{-3.0, 1.0, 1.5}, 0.6, true}, s);
  EXPECT_NE(once.update(s, 1.0 / 240.0), every_tick.update(s, 1.0 / 240.0));
}

}  // namespace
}  // namespace campo
