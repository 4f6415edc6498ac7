#include "planners/follow_the_gap.hpp"

#include <array>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "campo/random.hpp"
#include "tests/test_units.hpp"

namespace campo {
namespace {

using namespace campo::test_units;
constexpr int kBeams = 181;      // planar180: +90 deg .. -90 deg, beam i at 90 - i deg
constexpr float kNoHit = 20.0f;  // planar180 reads its maximum where nothing is hit

int beam_at(double azimuth_deg) { return static_cast<int>(std::lround(90.0 - azimuth_deg)); }
double scan_angle(int beam) { return (90.0 - beam) * kDeg; }

// A scan of the robot turned `heading_deg` left in a world whose range at
// each world azimuth (deg) is `range_at`.
template <class RangeAt>
std::vector<float> scan_of(RangeAt range_at, double heading_deg = 0.0) {
  std::vector<float> ranges(kBeams);
  for (int i = 0; i < kBeams; ++i) ranges[i] = static_cast<float>(range_at(90.0 - i + heading_deg));
  return ranges;
}

bool inside(double azimuth_deg, const std::vector<std::pair<double, double>>& intervals_deg) {
  for (const auto& [lo, hi] : intervals_deg) {
    if (azimuth_deg >= lo - 1e-9 && azimuth_deg <= hi + 1e-9) return true;
  }
  return false;
}

// A straight wall `distance_m` ahead (range d / cos azimuth, no return where
// it would lie beyond 20 m) with openings given as azimuth ranges in degrees.
std::vector<float> wall_scan(double distance_m, const std::vector<std::pair<double, double>>& openings_deg) {
  return scan_of([&](double azimuth_deg) {
    const double r = distance_m / std::cos(azimuth_deg * kDeg);
    return inside(azimuth_deg, openings_deg) || std::abs(azimuth_deg) >= 90.0 || r >= kNoHit ? kNoHit : r;
  });
}

// 003's gaps as §3.6 prints them (every unblocked run between range steps,
// only the nearest reading grown): the synthetic openings below are slits a
// point robot takes, narrower than a rover.
constexpr FollowTheGapConfig k003{.free_range_m = 0.0, .grow_gap_edges = false};
// 003's gaps with the point-robot approach of §2.4.2 on their edges.
constexpr FollowTheGapConfig k003Grown{.free_range_m = 0.0};

FollowTheGapStep step_on(const std::vector<float>& ranges, double goal_bearing_rad,
                         const FollowTheGapConfig& config = k003) {
  FollowTheGapState state;
  return follow_the_gap_step(config, state, PlanarScanView{ranges}, goal_bearing_rad, 0.0);
}

const ScanGap& chosen(const FollowTheGapStep& step) { return step.gaps.at(static_cast<std::size_t>(step.chosen)); }

TEST(FollowTheGap, InactiveWhenEverythingIsBeyondTheActivationRange) {
  std::vector<float> ranges(kBeams, 3.6f);
  ranges[40] = 3.51f;
  FollowTheGapState state{true, 0.3, 0.1};
  const FollowTheGapStep step = follow_the_gap_step(k003, state, PlanarScanView{ranges}, 0.25, 0.0);
  EXPECT_FALSE(step.active);
  EXPECT_EQ(step.heading_rad, 0.25);
  EXPECT_EQ(step.chosen, -1);
  EXPECT_TRUE(step.gaps.empty());
  EXPECT_EQ(step.nearest_beam, 40);
  EXPECT_FALSE(state.has_previous);  // the obstacle is behind us: forget the old choice
  EXPECT_FALSE(step_on(std::vector<float>(kBeams, kNoHit), 0.0).active);
}

TEST(FollowTheGap, ActiveBelowTheActivationRange) {
  std::vector<float> ranges(kBeams, kNoHit);
  ranges[100] = 3.49f;
  const FollowTheGapStep step = step_on(ranges, 0.0);
  EXPECT_TRUE(step.active);
  EXPECT_EQ(step.nearest_beam, 100);
  EXPECT_FLOAT_EQ(step.nearest_range_m, 3.49f);
}

TEST(FollowTheGap, NoReturnsSaturateToMaxPlusOneMetre) {
  std::vector<float> ranges(kBeams, kNoHit);
  ranges[0] = std::numeric_limits<float>::quiet_NaN();
  ranges[1] = std::numeric_limits<float>::infinity();
  ranges[2] = 25.0f;
  ranges[3] = 19.5f;
  ranges[90] = 2.0f;
  const FollowTheGapStep step = step_on(ranges, 0.0);
  ASSERT_TRUE(step.active);
  for (int i : {0, 1, 2, 4, 180}) EXPECT_EQ(step.ranges_m[i], 21.0f) << i;
  EXPECT_EQ(step.ranges_m[3], 19.5f);
}

TEST(FollowTheGap, BubbleHalfWidthIsRadiusOverRangeTimesIncrement) {
  // 0.8 / (2 * pi / 180) = 22.9 -> 23 sectors; exact quotients stay exact.
  EXPECT_EQ(bubble_half_width(0.8, 2.0, kDeg), 23);
  EXPECT_EQ(bubble_half_width(0.8, 2.0, -kDeg), 23);
  EXPECT_EQ(bubble_half_width(20.0 * kDeg, 2.0, kDeg), 10);
  EXPECT_EQ(bubble_half_width(0.5, 3.0, 0.5 * kDeg), 20);  // 0.5 / (3 * 0.00873) = 19.1
}

TEST(FollowTheGap, BubbleZeroesExactlyNSectorsEachSideOfTheNearestReading) {
  std::vector<float> ranges(kBeams, kNoHit);
  ranges[90] = 2.0f;  // straight ahead
  FollowTheGapConfig config = k003;
  config.bubble_radius_m = 0.8;  // N = 23
  const FollowTheGapStep step = step_on(ranges, 0.0, config);
  ASSERT_TRUE(step.active);
  EXPECT_EQ(step.bubble_half_width, 23);
  EXPECT_EQ(step.bubble_first_beam, 67);
  EXPECT_EQ(step.bubble_last_beam, 113);
  for (int i = 0; i < kBeams; ++i) EXPECT_EQ(step.ranges_m[i] == 0.0f, i >= 67 && i <= 113) << i;
  // The rest splits at the bubble into two gaps.
  ASSERT_EQ(step.gaps.size(), 2u);
  EXPECT_EQ(step.gaps[0].first_beam, 0);
  EXPECT_EQ(step.gaps[0].last_beam, 66);
  EXPECT_EQ(step.gaps[1].first_beam, 114);
  EXPECT_EQ(step.gaps[1].last_beam, 180);
}

TEST(FollowTheGap, BubbleIsClippedAtTheEdgeOfTheScan) {
  std::vector<float> ranges(kBeams, kNoHit);
  ranges[5] = 1.0f;
  const FollowTheGapStep step = step_on(ranges, 0.0);
  EXPECT_EQ(step.bubble_half_width, 46);  // 0.8 / (1 * pi / 180) = 45.8
  EXPECT_EQ(step.bubble_first_beam, 0);
  EXPECT_EQ(step.bubble_last_beam, 51);
}

TEST(FollowTheGap, NothingLeftWhenTheBubbleCoversTheScan) {
  std::vector<float> ranges(kBeams, kNoHit);
  ranges[90] = 0.1f;  // N = 459
  const FollowTheGapStep step = step_on(ranges, 0.3);
  EXPECT_TRUE(step.active);
  EXPECT_TRUE(step.gaps.empty());
  EXPECT_EQ(step.chosen, -1);
  EXPECT_EQ(step.heading_rad, 0.3);
}

TEST(FollowTheGap, RangeStepsSplitGaps) {
  std::vector<float> ranges(kBeams, 10.0f);
  for (int i = 120; i < kBeams; ++i) ranges[i] = 10.9f;  // below the 1 m threshold: same gap
  for (int i = 0; i < 30; ++i) ranges[i] = 5.0f;         // a 5 m step: new gap
  ranges[90] = 3.0f;
  const FollowTheGapStep step = step_on(ranges, 0.0);
  ASSERT_EQ(step.gaps.size(), 3u);
  EXPECT_EQ(step.gaps[0].last_beam, 29);
  EXPECT_EQ(step.gaps[1].first_beam, 30);
  EXPECT_EQ(step.gaps[2].last_beam, 180);
}

TEST(FollowTheGap, WallWithOneOpeningPicksTheOpening) {
  // Wall 3 m ahead, opening between 20 and 30 deg to the left (beams 60-70).
  const std::vector<float> ranges = wall_scan(3.0, {{20.0, 30.0}});
  const FollowTheGapStep step = step_on(ranges, 0.0);
  ASSERT_TRUE(step.active);
  EXPECT_EQ(step.nearest_beam, 90);
  EXPECT_EQ(step.bubble_half_width, 16);  // 0.8 / (3 pi / 180) = 15.3
  const ScanGap& gap = chosen(step);
  EXPECT_EQ(gap.first_beam, beam_at(30.0));
  EXPECT_EQ(gap.last_beam, beam_at(20.0));
  // Hand-computed: ends both at 21 m, 10 deg apart; d_gap = 21 / 20.
  EXPECT_NEAR(gap.width_m, 2.0 * 21.0 * std::sin(5.0 * kDeg), 1e-4);
  EXPECT_NEAR(gap.mean_range, 1.05, 1e-6);
  EXPECT_NEAR(gap.center_rad, 25.0 * kDeg, 1e-12);
  // phi = ((a / d_min) 25 deg + 0) / (a / d_min + 1) with a = 1 m, d_min = 3 m: 6.25 deg.
  EXPECT_NEAR(gap.heading_rad, 6.25 * kDeg, 1e-6);
  EXPECT_NEAR(gap.score, gap.width_m * 1.05 + (M_PI - 6.25 * kDeg), 1e-4);
  EXPECT_DOUBLE_EQ(step.heading_rad, gap.heading_rad);
}

TEST(FollowTheGap, NearerObstaclesPullTheHeadingTowardTheGapCentre) {
  // Opening centred on 40 deg; a = 1 m. Wall at 3 m: a / d_min = 1/3, phi =
  // (40/3) / (4/3) = 10 deg; at 2 m: a / d_min = 1/2, phi = 20 / 1.5 = 13.3 deg.
  const std::vector<std::pair<double, double>> opening{{35.0, 45.0}};
  EXPECT_NEAR(step_on(wall_scan(3.0, opening), 0.0).heading_rad, 10.0 * kDeg, 1e-6);
  EXPECT_NEAR(step_on(wall_scan(2.0, opening), 0.0).heading_rad, 40.0 / 3.0 * kDeg, 1e-6);
  // a = 0 follows the goal; a large a heads for the centre.
  FollowTheGapConfig config = k003;
  config.alpha_m = 0.0;
  EXPECT_NEAR(step_on(wall_scan(3.0, opening), 0.0, config).heading_rad, 0.0, 1e-12);
  config.alpha_m = 1e6;
  EXPECT_NEAR(step_on(wall_scan(3.0, opening), 0.0, config).heading_rad, 40.0 * kDeg, 1e-5);
}

TEST(FollowTheGap, TwoOpeningsPrefersTheWiderOne) {
  // 10 deg on the left, 20 deg on the right, centred as far from the goal ahead.
  const std::vector<float> ranges = wall_scan(3.0, {{30.0, 40.0}, {-45.0, -25.0}});
  const ScanGap gap = chosen(step_on(ranges, 0.0));
  EXPECT_EQ(gap.first_beam, beam_at(-25.0));
  EXPECT_EQ(gap.last_beam, beam_at(-45.0));
}

TEST(FollowTheGap, GoalOnOneSidePicksTheOpeningOnThatSide) {
  const std::vector<float> ranges = wall_scan(3.0, {{20.0, 30.0}, {-30.0, -20.0}});
  EXPECT_GT(chosen(step_on(ranges, 60.0 * kDeg)).center_rad, 0.0);
  EXPECT_LT(chosen(step_on(ranges, -60.0 * kDeg)).center_rad, 0.0);
  // A wider opening on the other side wins with the default weights, loses
  // when k2 weighs alignment with the goal enough more.
  const std::vector<float> wide_right = wall_scan(3.0, {{20.0, 30.0}, {-40.0, -20.0}});
  EXPECT_LT(chosen(step_on(wide_right, 60.0 * kDeg)).center_rad, 0.0);
  FollowTheGapConfig config = k003;
  config.k_heading = 30.0;
  EXPECT_GT(chosen(step_on(wide_right, 60.0 * kDeg, config)).center_rad, 0.0);
}

TEST(FollowTheGap, HysteresisKeepsTheChoiceUntilAnotherGapIsClearlyBetter) {
  // Two equal openings symmetric about the goal (Fig. 44).
  const std::vector<float> ranges = wall_scan(3.0, {{20.0, 30.0}, {-30.0, -20.0}});
  const PlanarScanView scan{ranges};
  FollowTheGapConfig config = k003;
  config.hysteresis_bonus = 0.2;
  FollowTheGapState state;
  // Goal slightly right: the right opening wins and is remembered.
  const FollowTheGapStep first = follow_the_gap_step(config, state, scan, -0.02, 0.0);
  EXPECT_LT(chosen(first).center_rad, 0.0);
  EXPECT_FALSE(chosen(first).previous);
  ASSERT_TRUE(state.has_previous);
  // Goal slightly left: the left one scores a little more, within the bonus.
  const FollowTheGapStep second = follow_the_gap_step(config, state, scan, 0.02, 0.0);
  EXPECT_LT(chosen(second).center_rad, 0.0);
  EXPECT_TRUE(chosen(second).previous);
  // Without the state the left one would have won.
  EXPECT_GT(chosen(step_on(ranges, 0.02, config)).center_rad, 0.0);
  // Goal well to the left: the left opening beats the bonus.
  const FollowTheGapStep third = follow_the_gap_step(config, state, scan, 0.5, 0.0);
  EXPECT_GT(chosen(third).center_rad, 0.0);
  EXPECT_FALSE(chosen(third).previous);
  // And is kept in turn.
  const FollowTheGapStep fourth = follow_the_gap_step(config, state, scan, -0.02, 0.0);
  EXPECT_GT(chosen(fourth).center_rad, 0.0);
}

TEST(FollowTheGap, HysteresisFollowsTheGapWhileTheRobotTurns) {
  // A ring of wall 5 m away with openings at world azimuths 20-30 and
  // -30 - -20 deg and a post 3 m ahead; the robot turns 10 deg left between
  // scans, so in its frame everything moves 10 deg (10 beams) right.
  const auto world = [](double azimuth_deg) {
    if (inside(azimuth_deg, {{20.0, 30.0}, {-30.0, -20.0}})) return static_cast<double>(kNoHit);
    return std::abs(azimuth_deg) < 0.5 ? 3.0 : 5.0;
  };
  FollowTheGapConfig config = k003;
  config.hysteresis_bonus = 0.2;
  FollowTheGapState state;
  const FollowTheGapStep before = follow_the_gap_step(config, state, PlanarScanView{scan_of(world)}, -0.02, 0.0);
  EXPECT_EQ(chosen(before).first_beam, beam_at(-20.0));
  // Goal now 0.02 rad left of world azimuth 0: alone, the left opening would win.
  const std::vector<float> turned = scan_of(world, 10.0);
  const double goal = 0.02 - 10.0 * kDeg;
  EXPECT_EQ(chosen(step_on(turned, goal, config)).first_beam, beam_at(20.0));
  const FollowTheGapStep after = follow_the_gap_step(config, state, PlanarScanView{turned}, goal, 10.0 * kDeg);
  const ScanGap& gap = chosen(after);
  EXPECT_TRUE(gap.previous);
  EXPECT_EQ(gap.first_beam, beam_at(-30.0));  // world -20 deg seen from 10 deg left
  EXPECT_EQ(gap.last_beam, beam_at(-40.0));
}

TEST(FollowTheGap, SmallRangeNoiseDoesNotFlipTheChoice) {
  // Noise of 3 cm moves the nearest reading (and the bubble) by several beams
  // along the wall but leaves the wider opening, beams 115-135, the choice.
  const std::vector<float> clean = wall_scan(3.0, {{30.0, 40.0}, {-45.0, -25.0}});
  const ScanGap expected = chosen(step_on(clean, 0.0));
  ASSERT_EQ(expected.first_beam, beam_at(-25.0));
  ASSERT_EQ(expected.last_beam, beam_at(-45.0));
  Rng rng(42);
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<float> noisy = clean;
    for (float& r : noisy) {
      if (r < kNoHit) r = static_cast<float>(std::min(19.99, r + rng.normal(0.0, 0.03)));
    }
    const ScanGap gap = chosen(step_on(noisy, 0.0));
    EXPECT_GE(gap.first_beam, expected.first_beam) << "trial " << trial;
    EXPECT_EQ(gap.last_beam, expected.last_beam) << "trial " << trial;
  }
}


// ---------------------------------------------------------------- free-space gaps (campo)

TEST(FollowTheGap, FreeDistanceOfADiscAlongARay) {
  EXPECT_DOUBLE_EQ(free_distance(2.0, 0.0, 0.5), 1.5);
  // 10 deg off: 2 cos 10 - sqrt(0.5^2 - (2 sin 10)^2).
  const double lateral = 2.0 * std::sin(10.0 * kDeg);
  EXPECT_NEAR(free_distance(2.0, 10.0 * kDeg, 0.5), 2.0 * std::cos(10.0 * kDeg) - std::sqrt(0.25 - lateral * lateral), 1e-12);
  EXPECT_TRUE(std::isinf(free_distance(2.0, 20.0 * kDeg, 0.5)));  // 0.68 m off the line
  EXPECT_TRUE(std::isinf(free_distance(2.0, M_PI, 0.5)));         // behind
  EXPECT_EQ(free_distance(0.4, 30.0 * kDeg, 0.5), 0.0);           // already touching
}

// Range along a ray from the sensor (x forward, y left) to the nearest of
// axis-aligned boxes {x0, x1, y0, y1}, kNoHit where it hits none.
float box_range(double azimuth_deg, const std::vector<std::array<double, 4>>& boxes) {
  const double dx = std::cos(azimuth_deg * kDeg), dy = std::sin(azimuth_deg * kDeg);
  double best = kNoHit;
  for (const auto& [x0, x1, y0, y1] : boxes) {
    double lo = 0.0, hi = kNoHit;
    for (const auto& [d, a, b] : {std::array{dx, x0, x1}, std::array{dy, y0, y1}}) {
      if (std::abs(d) < 1e-12) {
        if (a > 0.0 || b < 0.0) hi = -1.0;
        continue;
      }
      const double t0 = a / d, t1 = b / d;
      lo = std::max(lo, std::min(t0, t1));
      hi = std::min(hi, std::max(t0, t1));
    }
    if (lo <= hi) best = std::min(best, lo);
  }
  return static_cast<float>(best);
}

// Between two canopy walls 1.7 m either side (a 3.4 m inter-row), a box 3 m
// ahead from 0.3 m right of the centre line to 1.0 m right: the passage, 2 m
// wide, is on the left (a 0.8 m disc fits 0.5-0.9 m left of the centre line).
std::vector<float> inter_row_with_box() {
  const std::vector<std::array<double, 4>> scene{
      {-1.0, 30.0, 1.7, 2.3}, {-1.0, 30.0, -2.3, -1.7}, {3.0, 3.75, -1.0, -0.3}};
  return scan_of([&](double azimuth_deg) { return box_range(azimuth_deg, scene); });
}

TEST(FollowTheGap, FreeSpaceGapsFindThePassageBesideABoxBetweenRows) {
  const std::vector<float> ranges = inter_row_with_box();
  const FollowTheGapStep step = step_on(ranges, 0.0, FollowTheGapConfig{});
  ASSERT_TRUE(step.active);
  // One gap: the passage. The canopy walls seen at a grazing angle are no gaps.
  ASSERT_EQ(step.gaps.size(), 1u);
  const ScanGap& gap = chosen(step);
  EXPECT_GT(scan_angle(gap.last_beam), 0.0);
  // The goal straight ahead, behind the box, is outside the gap: the heading
  // is held at the gap's edge rather than blended onto the box.
  EXPECT_NEAR(step.heading_rad, scan_angle(gap.last_beam), 1e-12);
  // Along that heading a 0.8 m disc clears the box's corner at (3, -0.3)...
  const double off = step.heading_rad - std::atan2(-0.3, 3.0);
  EXPECT_GE(std::hypot(3.0, 0.3) * std::sin(off), 0.8);
  // ...where 003's gaps split the walls into runs at every range step.
  EXPECT_GT(step_on(ranges, 0.0).gaps.size(), 5u);
}

// Between vine rows, 003's gaps as printed: the bubble grows the canopy
// beside the rover (the nearest reading), not the box, so the box's face and
// the slit past its corner, which only a point fits, are gaps, and the blended
// heading points at the box. With the gaps' edges grown by R no chosen
// heading passes the box's corner nearer than R.
TEST(FollowTheGap, With003GapsGrownAtTheirEdgesTheHeadingClearsTheBoxByR) {
  const std::vector<float> ranges = inter_row_with_box();
  const double corner = std::atan2(-0.3, 3.0);  // the box's near left corner, 3 m ahead, 0.3 m right
  const auto clearance = [&](double heading) { return std::hypot(3.0, 0.3) * std::sin(heading - corner); };
  const FollowTheGapStep printed = step_on(ranges, 0.0, k003);
  ASSERT_GE(printed.chosen, 0);
  EXPECT_LT(clearance(printed.heading_rad), 0.8);  // straight on, 0.3 m from the corner
  const FollowTheGapStep grown = step_on(ranges, 0.0, k003Grown);
  ASSERT_GE(grown.chosen, 0);
  EXPECT_GE(clearance(grown.heading_rad), 0.8 - 1e-9);
  // Every gap left keeps its heading inside its beams and R off each range-step edge.
  for (const ScanGap& g : grown.gaps) {
    EXPECT_LE(g.heading_rad, scan_angle(g.first_beam) + 1e-12);
    EXPECT_GE(g.heading_rad, scan_angle(g.last_beam) - 1e-12);
  }
  // Fewer gaps: the single beams along the canopy walls between range steps are gone.
  EXPECT_LT(grown.gaps.size(), printed.gaps.size());
}

TEST(FollowTheGap, FreeSpaceRejectsAnOpeningNarrowerThanTheRover) {
  // A wall 3 m ahead with a 0.6 m slit straight ahead (point robots pass, a 1.6 m disc does not)...
  const double slit_deg = std::atan(0.3 / 3.0) / kDeg;
  const FollowTheGapStep narrow = step_on(wall_scan(3.0, {{-slit_deg, slit_deg}}), 0.0, FollowTheGapConfig{});
  for (const ScanGap& g : narrow.gaps) EXPECT_GT(std::abs(g.center_rad), 45.0 * kDeg) << g.first_beam;
  // ...and a 3 m opening, which it does: the gap through it spans the
  // directions keeping the disc 0.8 m off both edges, about 13 deg each side
  // (the bubble, ceil(R / (d_min dalpha)) sectors, may take one beam more on the nearest edge's side).
  const double wide_deg = std::atan(1.5 / 3.0) / kDeg;
  const FollowTheGapStep wide = step_on(wall_scan(3.0, {{-wide_deg, wide_deg}}), 0.0, FollowTheGapConfig{});
  bool through = false;
  for (const ScanGap& g : wide.gaps) {
    if (g.first_beam > beam_at(0.0) || g.last_beam < beam_at(0.0)) continue;
    through = true;
    EXPECT_GE(g.first_beam, beam_at(13.0));
    EXPECT_LE(g.first_beam, beam_at(12.0));
    EXPECT_LE(g.last_beam, beam_at(-13.0));
    EXPECT_GE(g.last_beam, beam_at(-12.0));
  }
  EXPECT_TRUE(through);
}

}  // namespace
}  // namespace campo
