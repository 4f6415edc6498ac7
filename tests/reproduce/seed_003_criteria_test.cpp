// Seed 003's criteria on measured-like data: every verdict each can give,
// failure included, through judge() as the report uses them.
#include "reproduce/seed_003_criteria.hpp"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "reproduce/report.hpp"

namespace campo {
namespace {

Verdict verdict_of(std::optional<bool> holds, bool departures, bool cause_known) {
  return judge(ClaimKind::thesis_result, holds, departures, cause_known);
}

TEST(Seed003Criteria, Fig45EveryDrawReachedCleanlyOrNot) {
  // 20 draws as measured on 4 m rows: all reached, one without an avoidance.
  std::vector<RunOutcome> runs(19, RunOutcome{true, 0, 12.5});
  runs.push_back({true, 0, 0.0});
  const OutcomeCounts c = count_outcomes(runs);
  EXPECT_EQ(c.runs, 20);
  EXPECT_EQ(c.reached_clean, 20);
  EXPECT_EQ(c.avoided, 19);
  EXPECT_EQ(c.with_avoidance, 19);
  EXPECT_EQ(every_run_reaches_without_collision(runs), true);
  EXPECT_EQ(verdict_of(every_run_reaches_without_collision(runs), false, false), Verdict::reproduced);
  EXPECT_EQ(verdict_of(every_run_reaches_without_collision(runs), true, false), Verdict::reproduced_with_departures);
  // One draw with a scrape: the criterion fails, whether or not the cause is shown.
  runs[3].collisions = 1;
  EXPECT_EQ(count_outcomes(runs).collision_free, 19);
  EXPECT_EQ(every_run_reaches_without_collision(runs), false);
  EXPECT_EQ(verdict_of(every_run_reaches_without_collision(runs), true, true), Verdict::deviates);
  EXPECT_EQ(verdict_of(every_run_reaches_without_collision(runs), true, false), Verdict::not_reproduced);
  EXPECT_EQ(verdict_of(every_run_reaches_without_collision({}), true, true), Verdict::not_reproduced);
}

TEST(Seed003Criteria, TrappedRunFailsNoLocalMinimum) {
  std::vector<RunOutcome> runs{{true, 0, 30.0, false}, {true, 0, 424.8, false}};
  EXPECT_EQ(never_trapped(runs), true);
  runs.push_back({false, 1, 10.0, false});  // a collision is not a trap
  EXPECT_EQ(never_trapped(runs), true);
  runs.push_back({false, 0, 292.4, true});  // timed out standing behind a box
  EXPECT_EQ(never_trapped(runs), false);
  EXPECT_EQ(verdict_of(never_trapped(runs), true, true), Verdict::deviates);
  EXPECT_EQ(never_trapped({}), std::nullopt);
  // A rover that stood from 7.6 s to 190.6 s, sampled every 0.1 s.
  std::vector<double> t, v;
  for (int i = 0; i <= 3000; ++i) {
    t.push_back(0.1 * i);
    v.push_back(t.back() >= 7.6 && t.back() <= 190.6 ? 0.001 : 0.5);
  }
  EXPECT_NEAR(longest_standstill_s(t, v, 0.02), 183.0, 0.11);
  EXPECT_EQ(longest_standstill_s(t, std::vector<double>(t.size(), 1.0), 0.02), 0.0);
}

TEST(Seed003Criteria, Fig46SwitchRightThenLeftAndSafePassage) {
  const std::vector<double> thesis_like{-21.0, -18.0, 57.6, 40.0, 10.0};
  EXPECT_EQ(gap_sides(thesis_like), (std::vector<int>{-1, 1}));
  EXPECT_TRUE(switches_right_then_left(thesis_like));
  EXPECT_FALSE(switches_right_then_left({30.0, -20.0}));  // left first
  EXPECT_FALSE(switches_right_then_left({-30.0, -20.0}));  // never switched
  EXPECT_FALSE(switches_right_then_left({}));
  std::vector<CrossingRun> runs{{thesis_like, {true, 0, 3.5}}, {{40.0}, {true, 0, 2.0}}};
  EXPECT_EQ(fig46_switches(runs), 1);
  EXPECT_EQ(fig46_holds(runs), true);
  EXPECT_EQ(verdict_of(fig46_holds(runs), true, false), Verdict::reproduced_with_departures);
  runs[1].outcome.collisions = 1;  // a run that hits the walker
  EXPECT_EQ(fig46_holds(runs), false);
  EXPECT_EQ(verdict_of(fig46_holds(runs), true, false), Verdict::not_reproduced);
  runs = {{{40.0}, {true, 0, 2.0}}};  // safe, but the switch never occurs
  EXPECT_EQ(fig46_holds(runs), false);
  EXPECT_EQ(fig46_holds({}), std::nullopt);
}

TEST(Seed003Criteria, HysteresisNeedsIndecisionWithoutTheBonusAndNoneWithIt) {
  EXPECT_EQ(steering_reversals({10.0, 12.0, -8.0, 1.0, -9.0, 9.0}, 2.0), 2);
  EXPECT_EQ(steering_reversals({10.0, 0.5, -0.5, 10.0}, 2.0), 0);
  // Measured: the chosen gap's centre 75° left, 11° after the obstacle, one scan back at 60°, then 13°: two flips.
  EXPECT_EQ(gap_flips({75.0, 74.0, 73.0, 11.0, 12.0, 60.0, 13.0, 12.0, 6.0, -2.0}, 20.0), 2);
  EXPECT_EQ(gap_flips({75.0, 73.0, 11.0, 12.0, 6.0, -2.0}, 20.0), 0);  // one change, kept
  EXPECT_EQ(gap_flips({}, 20.0), 0);
  EXPECT_EQ(hysteresis_holds({0, 5, 1}, {0, 1, 1}, 3), true);
  EXPECT_EQ(verdict_of(hysteresis_holds({0, 5, 1}, {0, 1, 1}, 3), true, false), Verdict::reproduced_with_departures);
  EXPECT_EQ(hysteresis_holds({0, 5, 1}, {0, 4, 1}, 3), false);  // the bonus did not help
  EXPECT_EQ(hysteresis_holds({1, 1, 1}, {1, 1, 1}, 3), false);  // no indecision to resolve
  EXPECT_EQ(verdict_of(hysteresis_holds({1, 1, 1}, {1, 1, 1}, 3), true, false), Verdict::not_reproduced);
  EXPECT_EQ(hysteresis_holds({}, {1}, 3), std::nullopt);
}

// A route north along x = 0 for 10 m, a half circle of radius 2 round (2, 10), south along x = 4.
std::vector<Eigen::Vector2d> u_turn_route() {
  std::vector<Eigen::Vector2d> route;
  for (int i = 0; i <= 100; ++i) route.emplace_back(0.0, 0.1 * i);
  for (int i = 1; i < 63; ++i) {
    const double a = M_PI - i * M_PI / 63.0;
    route.emplace_back(2.0 + 2.0 * std::cos(a), 10.0 + 2.0 * std::sin(a));
  }
  for (int i = 0; i <= 100; ++i) route.emplace_back(4.0, 10.0 - 0.1 * i);
  return route;
}

TEST(Seed003Criteria, SignedCrossTrackAndCurvature) {
  const std::vector<Eigen::Vector2d> route = u_turn_route();
  EXPECT_NEAR(signed_cross_track({-0.3, 5.0}, route), 0.3, 1e-12);   // west of a northward leg: left
  EXPECT_NEAR(signed_cross_track({0.2, 5.0}, route), -0.2, 1e-12);
  EXPECT_NEAR(signed_cross_track({4.2, 5.0}, route), 0.2, 1e-12);    // east of the southward leg: left
  const std::vector<double> k = route_curvature(route);
  EXPECT_NEAR(k[50], 0.0, 1e-12);
  EXPECT_NEAR(k[130], -0.5, 0.01);  // a right turn of radius 2 m
}

TEST(Seed003Criteria, TrackingSlowsInCurvesAndStaysInTheRow) {
  const std::vector<Eigen::Vector2d> route = u_turn_route();
  std::vector<Eigen::Vector2d> track;
  std::vector<double> speed;
  for (std::size_t i = 0; i < route.size(); ++i) {
    track.push_back(route[i] + Eigen::Vector2d(0.05, 0.0));
    speed.push_back(i > 100 && i < 163 ? 0.6 : 1.0);  // the arc's points
  }
  const SpeedByCurvature s = speed_by_curvature(track, speed, route, 0.05, 0.2);
  EXPECT_GT(s.straight_samples, 150);
  EXPECT_GT(s.curve_samples, 40);
  EXPECT_NEAR(s.straight_mps, 1.0, 1e-12);
  EXPECT_NEAR(s.curve_mps, 0.6, 1e-12);
  EXPECT_EQ(tracking_holds(0.36, 1.2, s), true);
  EXPECT_EQ(verdict_of(tracking_holds(0.36, 1.2, s), false, false), Verdict::reproduced);
  EXPECT_EQ(tracking_holds(1.3, 1.2, s), false);  // left its inter-row
  speed.assign(speed.size(), 1.0);               // no slowing in the curve
  EXPECT_EQ(tracking_holds(0.36, 1.2, speed_by_curvature(track, speed, route, 0.05, 0.2)), false);
  EXPECT_EQ(tracking_holds(0.36, 1.2, SpeedByCurvature{}), std::nullopt);
}

TEST(Seed003Criteria, RejoinFromAStartOffTheRoute) {
  const std::vector<Eigen::Vector2d> route = u_turn_route();
  std::vector<Eigen::Vector2d> track;
  for (int i = 0; i <= 40; ++i) track.emplace_back(1.0 - 0.025 * i, 0.1 * i);  // converges over ~4.1 m
  const std::optional<double> d = distance_to_rejoin_m(track, route, 0.1001);
  ASSERT_TRUE(d);
  EXPECT_NEAR(*d, 36 * std::hypot(0.025, 0.1), 1e-9);
  EXPECT_FALSE(distance_to_rejoin_m({{1.0, 0.0}, {1.0, 5.0}}, route, 0.1));
  EXPECT_EQ(every_run_rejoins({d, d}, {{true, 0, 0.0}, {true, 0, 0.0}}), true);
  EXPECT_EQ(every_run_rejoins({d, std::nullopt}, {{true, 0, 0.0}, {true, 0, 0.0}}), false);
  EXPECT_EQ(every_run_rejoins({d}, {{false, 0, 0.0}}), false);
  EXPECT_EQ(every_run_rejoins({}, {}), std::nullopt);
}

TEST(Seed003Criteria, LookaheadOscillatesWhenSmallAndCutsCornersWhenLarge) {
  EXPECT_EQ(oscillations({0.0, 0.03, 0.01, -0.03, -0.01, 0.04, 0.005, -0.005}, 0.02), 2);
  // A track that follows the U-turn misses its arc by nothing; one that cuts straight across at y = 10 by 2 m.
  const std::vector<Eigen::Vector2d> route = u_turn_route();
  EXPECT_NEAR(curve_miss_m(route, route, 0.3), 0.0, 1e-12);
  std::vector<Eigen::Vector2d> cut;
  for (int i = 0; i <= 40; ++i) cut.emplace_back(0.1 * i, 10.0);
  EXPECT_NEAR(curve_miss_m(route, cut, 0.3), 2.0, 0.01);
  EXPECT_EQ(curve_miss_m(route, {{0.0, 0.0}}, 5.0), 0.0);  // no point that curved
  const std::vector<LookaheadRun> runs{{0.3, 9, 0.05}, {1.5, 0, 0.3}, {6.0, 0, 1.4}};
  EXPECT_EQ(lookahead_holds(runs, 1.5), true);
  EXPECT_EQ(verdict_of(lookahead_holds(runs, 1.5), false, false), Verdict::reproduced);
  EXPECT_EQ(lookahead_holds({{0.3, 0, 0.05}, {1.5, 0, 0.3}, {6.0, 0, 1.4}}, 1.5), false);  // no oscillation
  EXPECT_EQ(lookahead_holds({{0.3, 9, 0.05}, {1.5, 0, 0.3}, {6.0, 0, 0.2}}, 1.5), false);  // no corner cutting
  EXPECT_EQ(lookahead_holds({{1.5, 0, 0.3}, {6.0, 0, 1.4}}, 1.5), std::nullopt);
}

TEST(Seed003Criteria, DubinsGeometryOfStraightsAndArcs) {
  const std::vector<Eigen::Vector2d> route = u_turn_route();
  const std::vector<Segment2> rows{{{0.0, 0.0}, {0.0, 10.0}}, {{4.0, 10.0}, {4.0, 0.0}}};
  EXPECT_LT(max_distance_to_geometry(route, rows, {{{2.0, 10.0}, 2.0}}), 1e-9);
  // An arc of the wrong radius (a rounded corner of 1.5 m) is 0.5 m off.
  EXPECT_NEAR(max_distance_to_geometry(route, rows, {{{2.0, 10.0}, 1.5}}), 0.5, 1e-9);
}

}  // namespace
}  // namespace campo
