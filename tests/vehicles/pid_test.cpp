#include "vehicles/pid.hpp"

#include <gtest/gtest.h>

namespace campo {
namespace {

TEST(Pid, ProportionalOnly) {
  Pid pid({2.0, 0.0, 0.0});
  EXPECT_DOUBLE_EQ(pid.update(1.5, 0.01), 3.0);
  EXPECT_DOUBLE_EQ(pid.update(-0.5, 0.01), -1.0);
}

TEST(Pid, IntegralAccumulatesTheTerm) {
  Pid pid({0.0, 4.0, 0.0});
  for (int i = 0; i < 10; ++i) pid.update(0.5, 0.1);
  // I = ki * sum(e dt) = 4 * 0.5 * 1.0.
  EXPECT_NEAR(pid.integral(), 2.0, 1e-12);
  EXPECT_NEAR(pid.update(0.0, 0.1), 2.0, 1e-12);
}

TEST(Pid, IntegralTermIsClampedToItsLimit) {
  Pid pid({0.0, 10.0, 0.0, 0.7, 100.0});
  for (int i = 0; i < 1000; ++i) pid.update(1.0, 0.01);
  EXPECT_DOUBLE_EQ(pid.integral(), 0.7);
  for (int i = 0; i < 1000; ++i) pid.update(-1.0, 0.01);
  EXPECT_DOUBLE_EQ(pid.integral(), -0.7);
}

TEST(Pid, OutputIsClamped) {
  Pid pid({10.0, 0.0, 0.0, 1.0, 2.5});
  EXPECT_DOUBLE_EQ(pid.update(1.0, 0.01), 2.5);
  EXPECT_DOUBLE_EQ(pid.update(-1.0, 0.01), -2.5);
}

TEST(Pid, NoWindupWhileSaturated) {
  // A large integral limit, so that only conditional integration stops windup.
  const PidConfig config{0.1, 2.0, 0.0, 1000.0, 1.0};
  Pid pid(config);
  // Long saturation: the error stays at +5 for 100 s (output pinned at +1);
  // the integral stops where it saturates the output with P = 0.5.
  for (int i = 0; i < 10000; ++i) pid.update(5.0, 0.01);
  EXPECT_NEAR(pid.integral(), 0.5, 0.02);
  // Reversing the error must drive the output negative within a bounded time:
  // the integral has at most output_limit to unwind at ki |e| per second.
  int steps = 0;
  while (pid.update(-0.5, 0.01) >= 0.0) {
    ++steps;
    ASSERT_LT(steps, 100) << "integral wound up";
  }
  // The same with an unlimited-windup reference would take 1000 / (2 * 0.5) = 1000 s.
  EXPECT_LT(steps * 0.01, 1.0);
}

TEST(Pid, IntegratesOutOfSaturation) {
  // Saturated high, but an error of the opposite sign still moves the integral.
  Pid pid({10.0, 1.0, 0.0, 5.0, 1.0});
  for (int i = 0; i < 100; ++i) pid.update(1.0, 0.01);
  const double before = pid.integral();
  pid.update(-0.01, 0.01);
  EXPECT_LT(pid.integral(), before);
}

TEST(Pid, DerivativeOnErrorByDifference) {
  Pid pid({0.0, 0.0, 0.5});
  EXPECT_DOUBLE_EQ(pid.update(1.0, 0.1), 0.0);  // no previous error yet
  EXPECT_NEAR(pid.update(1.2, 0.1), 0.5 * 0.2 / 0.1, 1e-12);
}

TEST(Pid, DerivativeOnMeasurementIgnoresSetpointJumps) {
  Pid pid({0.0, 0.0, 0.5});
  EXPECT_DOUBLE_EQ(pid.update(0.0, 0.1, 0.0), 0.0);
  // The error jumps (a new setpoint) but the measurement is still: no kick.
  EXPECT_DOUBLE_EQ(pid.update(10.0, 0.1, 0.0), 0.0);
  // The measurement rising at 2 units/s damps: D = -kd * 2.
  EXPECT_DOUBLE_EQ(pid.update(10.0, 0.1, 2.0), -1.0);
}

TEST(Pid, ResetForgetsIntegralAndPreviousError) {
  Pid pid({1.0, 1.0, 1.0});
  pid.update(1.0, 0.1);
  pid.update(2.0, 0.1);
  pid.reset();
  EXPECT_DOUBLE_EQ(pid.integral(), 0.0);
  // As after construction: P + I of one step, no derivative.
  EXPECT_DOUBLE_EQ(pid.update(3.0, 0.1), 3.0 + 0.3);
}

}  // namespace
}  // namespace campo
