#include "planners/fast_atan.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <limits>
#include <numbers>
#include <utility>
#include <vector>

#include "campo/random.hpp"
#include "tests/test_units.hpp"

namespace campo {
namespace {

using namespace campo::test_units;
constexpr double kBound = 6.0e-9;  // the file comment states 5.8e-9
constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

/// The largest error seen over some inputs, against std::atan2 in double of
/// the very float inputs (so the inputs' rounding to float is not counted).
struct Errors {
  double max = 0.0;
  void add(float y, float x) {
    max = std::max(max, std::abs(fast_atan2(y, x) - std::atan2(static_cast<double>(y), static_cast<double>(x))));
  }
};

float float_from_bits(std::uint32_t bits) {
  float f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

// ------------------------------------------------------------ the error bound

TEST(FastAtan, WithinTheBoundAroundTheCircleAtManyRadii) {
  constexpr int kAngles = 4'000'000;
  for (const double radius : {1e-3, 0.37, 1.0, 29.0, 1e3}) {
    Errors errors;
    for (int i = 0; i < kAngles; ++i) {
      const double angle = -kPi + 2.0 * kPi * (i + 0.5) / kAngles;
      errors.add(static_cast<float>(radius * std::sin(angle)), static_cast<float>(radius * std::cos(angle)));
    }
    EXPECT_LE(errors.max, kBound) << "radius " << radius;
  }
}

TEST(FastAtan, WithinTheBoundForRandomPointsOfWideMagnitudes) {
  Rng rng(20261128);
  Errors errors;
  for (int i = 0; i < 2'000'000; ++i) {
    const double y = std::pow(10.0, rng.uniform(-6.0, 6.0)) * (rng.bernoulli(0.5) ? 1.0 : -1.0);
    const double x = std::pow(10.0, rng.uniform(-6.0, 6.0)) * (rng.bernoulli(0.5) ? 1.0 : -1.0);
    errors.add(static_cast<float>(y), static_cast<float>(x));
  }
  EXPECT_LE(errors.max, kBound);
}

TEST(FastAtan, WithinTheBoundForRandomFiniteFloatsOfAnyExponent) {
  // Random bit patterns: subnormals, FLT_MAX-sized and everything between,
  // ratios far beyond any float (the work is in double).
  Rng rng(7);
  Errors errors;
  int tried = 0;
  while (tried < 2'000'000) {
    const float y = float_from_bits(static_cast<std::uint32_t>(rng.uniform_int(0, 0xffffffff)));
    const float x = float_from_bits(static_cast<std::uint32_t>(rng.uniform_int(0, 0xffffffff)));
    if (!std::isfinite(y) || !std::isfinite(x)) continue;
    errors.add(y, x);
    ++tried;
  }
  EXPECT_LE(errors.max, kBound);
}

TEST(FastAtan, WithinTheBoundNearTheDiagonalsAndTheAxes) {
  // Every float ratio near 1 (where the angle switches from atan(|y| / |x|)
  // to pi/2 - atan(|x| / |y|)) and near 0 and 1e-30 (along the axes), in all
  // eight octants.
  Errors errors;
  for (const float centre : {1.0f, 1.0e-30f, 0.0f}) {
    float t = centre;
    for (int i = 0; i < 20000; ++i) t = std::nextafter(t, -1.0f);
    for (int i = 0; i < 40000; ++i, t = std::nextafter(t, 2.0f)) {
      for (const float sy : {1.0f, -1.0f}) {
        for (const float sx : {1.0f, -1.0f}) {
          errors.add(sy * t, sx * 1.0f);
          errors.add(sy * 1.0f, sx * t);
        }
      }
    }
  }
  EXPECT_LE(errors.max, kBound);
}

// ------------------------------------------------------------ special values

TEST(FastAtan, ZerosAxesAndInfinitiesAreStdAtan2s) {
  // Wherever an input is a zero or an infinity the angle is a multiple of
  // pi/4: std::atan2's to the last bits or two, its sign (of zero too) exactly.
  const std::vector<float> specials = {0.0f, -0.0f, kInf, -kInf};
  const std::vector<float> others = {0.0f,   -0.0f, 1.0f, -1.0f, 3.5e-7f, -2.0e30f,
                                     std::numeric_limits<float>::denorm_min(), -std::numeric_limits<float>::max(),
                                     kInf,   -kInf};
  for (const float s : specials) {
    for (const float o : others) {
      for (const auto& [y, x] : {std::pair{s, o}, std::pair{o, s}}) {
        const double expected = std::atan2(static_cast<double>(y), static_cast<double>(x));
        const double actual = fast_atan2(y, x);
        EXPECT_NEAR(actual, expected, 1e-15) << "atan2(" << y << ", " << x << ")";
        EXPECT_EQ(std::signbit(actual), std::signbit(expected)) << "atan2(" << y << ", " << x << ")";
      }
    }
  }
}

TEST(FastAtan, HandWrittenQuadrantValues) {
  EXPECT_EQ(fast_atan2(0.0f, 1.0f), 0.0);
  EXPECT_FALSE(std::signbit(fast_atan2(0.0f, 0.0f)));
  EXPECT_TRUE(std::signbit(fast_atan2(-0.0f, 0.0f)));
  EXPECT_NEAR(fast_atan2(0.0f, -0.0f), kPi, 1e-15);
  EXPECT_NEAR(fast_atan2(-0.0f, -0.0f), -kPi, 1e-15);
  EXPECT_NEAR(fast_atan2(0.0f, -5.0f), kPi, 1e-15);
  EXPECT_NEAR(fast_atan2(-0.0f, -5.0f), -kPi, 1e-15);
  EXPECT_NEAR(fast_atan2(2.0f, 0.0f), kPi / 2, 1e-15);
  EXPECT_NEAR(fast_atan2(-2.0f, -0.0f), -kPi / 2, 1e-15);
  EXPECT_NEAR(fast_atan2(7.0f, 7.0f), kPi / 4, kBound);
  EXPECT_NEAR(fast_atan2(-7.0f, -7.0f), -3 * kPi / 4, kBound);
  // 150 and -60 degrees, to the float inputs' rounding (about 3e-8 rad).
  EXPECT_NEAR(fast_atan2(1.0f, -1.7320508f), 5 * kPi / 6, 1e-7);
  EXPECT_NEAR(fast_atan2(-1.7320508f, 1.0f), -kPi / 3, 1e-7);
}

TEST(FastAtan, NanInGivesNanOut) {
  for (const float other : {0.0f, -0.0f, 1.0f, -1.0f, 1e30f, kInf, -kInf, kNaN}) {
    EXPECT_TRUE(std::isnan(fast_atan2(kNaN, other))) << other;
    EXPECT_TRUE(std::isnan(fast_atan2(other, kNaN))) << other;
  }
}

// ------------------------------------------------------------ symmetries

TEST(FastAtan, OddInYAndMirroredInX) {
  Rng rng(11);
  for (int i = 0; i < 200'000; ++i) {
    const float y = static_cast<float>(std::pow(10.0, rng.uniform(-4.0, 4.0)));
    const float x = static_cast<float>(std::pow(10.0, rng.uniform(-4.0, 4.0)));
    const double a = fast_atan2(y, x);  // first quadrant
    ASSERT_GE(a, 0.0);
    ASSERT_LE(a, kPi / 2);
    // Odd in y, exactly (the sign is put on last).
    ASSERT_EQ(fast_atan2(-y, x), -a);
    ASSERT_EQ(fast_atan2(-y, -x), -fast_atan2(y, -x));
    // Mirrored in x: pi - a, each quadrant in its own range.
    const double b = fast_atan2(y, -x);
    ASSERT_GE(b, kPi / 2);
    ASSERT_LE(b, kPi);
    ASSERT_NEAR(b, kPi - a, 1e-15);
    // Swapped: pi/2 - a.
    ASSERT_NEAR(fast_atan2(x, y), kPi / 2 - a, 2 * kBound);
  }
}

}  // namespace
}  // namespace campo
