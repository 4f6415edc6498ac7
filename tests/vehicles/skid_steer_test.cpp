#include "vehicles/skid_steer.hpp"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

namespace campo {
namespace {

constexpr SkidSteerGeometry kGeometry{0.2, 0.3};

TEST(SkidSteer, InverseThenForwardKinematicsIsTheIdentity) {
  for (const BodyTwist t : {BodyTwist{1.0, 0.0}, BodyTwist{0.0, 0.8}, BodyTwist{-0.4, 0.3},
                            BodyTwist{0.7, -1.2}, BodyTwist{0.0, 0.0}}) {
    const BodyTwist back = twist_from_wheel_speeds(wheel_speeds_from_twist(t, kGeometry), kGeometry);
    EXPECT_NEAR(back.v_mps, t.v_mps, 1e-12);
    EXPECT_NEAR(back.w_radps, t.w_radps, 1e-12);
  }
}

TEST(SkidSteer, CounterClockwiseTurnSpinsTheRightWheelsFaster) {
  // w_right = v/r + w*l/r, w_left = v/r - w*l/r (ENU, yaw CCW positive).
  const WheelSpeeds w = wheel_speeds_from_twist({1.0, 0.5}, kGeometry);
  EXPECT_DOUBLE_EQ(w.right_radps, 1.0 / 0.2 + 0.5 * 0.3 / 0.2);
  EXPECT_DOUBLE_EQ(w.left_radps, 1.0 / 0.2 - 0.5 * 0.3 / 0.2);
  const WheelSpeeds spin = wheel_speeds_from_twist({0.0, 1.0}, kGeometry);
  EXPECT_DOUBLE_EQ(spin.left_radps, -spin.right_radps);
  EXPECT_GT(spin.right_radps, 0.0);
}

TEST(SkidSteer, SaturationKeepsTheCurvature) {
  const WheelSpeeds w = saturate({4.0, 12.0}, 6.0);
  EXPECT_DOUBLE_EQ(w.right_radps, 6.0);
  EXPECT_DOUBLE_EQ(w.left_radps, 2.0);
  const WheelSpeeds inside = saturate({-3.0, 5.0}, 6.0);
  EXPECT_DOUBLE_EQ(inside.left_radps, -3.0);
  EXPECT_DOUBLE_EQ(inside.right_radps, 5.0);
  const WheelSpeeds reverse = saturate({-9.0, -3.0}, 6.0);
  EXPECT_DOUBLE_EQ(reverse.left_radps, -6.0);
  EXPECT_DOUBLE_EQ(reverse.right_radps, -2.0);
}

TEST(SkidSteer, RateLimitRespectsTheAccelerationLimitAndArrives) {
  const double dt = 0.01;
  const double max_accel = 5.0;
  WheelSpeeds w;
  const WheelSpeeds target{3.0, -1.0};
  int steps = 0;
  while ((w.left_radps != target.left_radps || w.right_radps != target.right_radps) && steps < 1000) {
    const WheelSpeeds next = rate_limit(w, target, max_accel, dt);
    EXPECT_LE(std::abs(next.left_radps - w.left_radps), max_accel * dt + 1e-12);
    EXPECT_LE(std::abs(next.right_radps - w.right_radps), max_accel * dt + 1e-12);
    w = next;
    ++steps;
  }
  // The larger change takes 3 / (5 * 0.01) = 60 steps (61 with rounding).
  EXPECT_GE(steps, 60);
  EXPECT_LE(steps, 61);
}

TEST(SkidSteer, RateLimitOffPassesTheTargetThrough) {
  const WheelSpeeds w = rate_limit({0.0, 0.0}, {8.0, -8.0}, 0.0, 0.01);
  EXPECT_EQ(w.left_radps, 8.0);
  EXPECT_EQ(w.right_radps, -8.0);
}

TEST(SkidSteer, OdometryDrivesStraightAlongTheHeading) {
  PlanarPose p{1.0, 2.0, std::numbers::pi / 6};
  const WheelSpeeds w = wheel_speeds_from_twist({0.5, 0.0}, kGeometry);
  for (int i = 0; i < 100; ++i) p = integrate_odometry(p, w, kGeometry, 0.04);
  EXPECT_NEAR(p.x_m, 1.0 + 2.0 * std::cos(std::numbers::pi / 6), 1e-12);
  EXPECT_NEAR(p.y_m, 2.0 + 2.0 * std::sin(std::numbers::pi / 6), 1e-12);
  EXPECT_NEAR(p.yaw_rad, std::numbers::pi / 6, 1e-12);
}

TEST(SkidSteer, OdometryIntegratesArcsExactly) {
  // A quarter circle of radius v/w = 2 m from the origin heading +x ends at (2, 2) heading +y,
  // in one step or in many.
  const WheelSpeeds w = wheel_speeds_from_twist({1.0, 0.5}, kGeometry);
  const double duration = (std::numbers::pi / 2) / 0.5;
  const PlanarPose one = integrate_odometry({}, w, kGeometry, duration);
  PlanarPose many;
  for (int i = 0; i < 1000; ++i) many = integrate_odometry(many, w, kGeometry, duration / 1000);
  for (const PlanarPose& p : {one, many}) {
    EXPECT_NEAR(p.x_m, 2.0, 1e-9);
    EXPECT_NEAR(p.y_m, 2.0, 1e-9);
    EXPECT_NEAR(p.yaw_rad, std::numbers::pi / 2, 1e-9);
  }
}

TEST(SkidSteer, OdometryTurnsInPlaceAndWrapsTheHeading) {
  const WheelSpeeds w = wheel_speeds_from_twist({0.0, 1.0}, kGeometry);
  const PlanarPose p = integrate_odometry({3.0, -1.0, 3.0}, w, kGeometry, 0.5);
  EXPECT_DOUBLE_EQ(p.x_m, 3.0);
  EXPECT_DOUBLE_EQ(p.y_m, -1.0);
  EXPECT_NEAR(p.yaw_rad, 3.5 - 2 * std::numbers::pi, 1e-12);
}

}  // namespace
}  // namespace campo
