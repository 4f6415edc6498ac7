#include "campo/random.hpp"

#include <cmath>
#include <set>

#include <gtest/gtest.h>

namespace campo {
namespace {

TEST(Random, SameSeedSameStreamEverywhere) {
  // The C++ standard fixes mt19937_64's 10000th output for the default seed;
  // uniform01 is that value's top 53 bits, so the stream is portable.
  std::mt19937_64 reference(5489u);
  reference.discard(9999);
  const std::uint64_t ten_thousandth = reference();
  ASSERT_EQ(ten_thousandth, 9981545732273789042ULL);
  Rng rng(5489u);
  double last = 0.0;
  for (int i = 0; i < 10000; ++i) last = rng.uniform01();
  EXPECT_EQ(last, static_cast<double>(ten_thousandth >> 11) * 0x1.0p-53);
}

TEST(Random, UniformAndNormalStatistics) {
  Rng rng(42);
  const int n = 200000;
  double sum = 0, sum2 = 0, usum = 0;
  for (int i = 0; i < n; ++i) {
    const double x = rng.normal(3.0, 2.0);
    sum += x;
    sum2 += x * x;
    const double u = rng.uniform(-1.0, 5.0);
    ASSERT_GE(u, -1.0);
    ASSERT_LT(u, 5.0);
    usum += u;
  }
  const double mean = sum / n, var = sum2 / n - mean * mean;
  EXPECT_NEAR(mean, 3.0, 4 * 2.0 / std::sqrt(n));
  EXPECT_NEAR(std::sqrt(var), 2.0, 0.02);
  EXPECT_NEAR(usum / n, 2.0, 4 * 6.0 / std::sqrt(12.0 * n));
}

TEST(Random, UniformIntCoversItsRange) {
  Rng rng(7);
  std::set<std::int64_t> seen;
  for (int i = 0; i < 1000; ++i) {
    const auto v = rng.uniform_int(-2, 3);
    ASSERT_GE(v, -2);
    ASSERT_LE(v, 3);
    seen.insert(v);
  }
  EXPECT_EQ(seen.size(), 6u);
}

TEST(Random, DerivedSeedsDiffer) {
  std::set<std::uint64_t> seeds;
  for (std::uint64_t s = 0; s < 20; ++s) {
    for (std::uint64_t label = 0; label < 20; ++label) seeds.insert(Rng::derive_seed(s, label));
  }
  EXPECT_EQ(seeds.size(), 400u);
  EXPECT_EQ(Rng::derive_seed(3, 4), Rng::derive_seed(3, 4));
}

}  // namespace
}  // namespace campo
