// The sweep's progress line: counts, pace and time left.
#include "sweep/progress.hpp"

#include <gtest/gtest.h>

namespace campo {
namespace {

TEST(SweepProgress, DurationsReadLikeAClock) {
  EXPECT_EQ(format_duration(0.4), "0s");
  EXPECT_EQ(format_duration(59.6), "1m00s");
  EXPECT_EQ(format_duration(245.0), "4m05s");
  EXPECT_EQ(format_duration(3720.0), "1h02m");
}

TEST(SweepProgress, EtaIsTheRemainingRunsAtThePaceSoFar) {
  EXPECT_FALSE(eta_s({.total = 10, .done = 0, .elapsed_s = 5.0}).has_value());
  EXPECT_DOUBLE_EQ(*eta_s({.total = 10, .done = 4, .elapsed_s = 8.0}), 12.0);
  EXPECT_DOUBLE_EQ(*eta_s({.total = 10, .done = 10, .elapsed_s = 8.0}), 0.0);
}

TEST(SweepProgress, BarAndLineShowCountsPaceAndEta) {
  const SweepProgress p{.total = 100, .done = 25, .failed = 2, .running = 2, .elapsed_s = 30.0};
  EXPECT_EQ(progress_bar(p, 20),
            "[#####...............] 25/100 done, 2 failed, 2 running | 50.0 runs/min | ETA 1m30s");
  EXPECT_EQ(progress_line(p), "progress: 25/100 done, 2 failed, 2 running | 50.0 runs/min | ETA 1m30s");
  EXPECT_EQ(progress_bar({.total = 3}, 4), "[....] 0/3 done, 0 failed, 0 running | ETA --");
}

}  // namespace
}  // namespace campo
