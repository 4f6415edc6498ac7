#include "planners/pure_pursuit.hpp"
#include "tests/test_units.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

namespace campo {
namespace {

using Path = std::vector<Eigen::Vector2d>;

using namespace campo::test_units;

void expect_near(const Eigen::Vector2d& actual, const Eigen::Vector2d& expected, double tolerance = 1e-9) {
  EXPECT_NEAR(actual.x(), expected.x(), tolerance);
  EXPECT_NEAR(actual.y(), expected.y(), tolerance);
}

PurePursuitConfig lookahead(double radius_m) {
  PurePursuitConfig config;
  config.lookahead_m = radius_m;
  return config;
}

// Distance from p to the polyline: the cross-track error.
double cross_track(const Eigen::Vector2d& p, const Path& path) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 1 < path.size(); ++i) {
    const Eigen::Vector2d d = path[i + 1] - path[i];
    const double t = std::clamp((p - path[i]).dot(d) / d.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (p - (path[i] + t * d)).norm());
  }
  return best;
}

// ------------------------------------------- circle-segment crossings (Fig. 37)

TEST(PurePursuitCrossing, NoIntersection) { EXPECT_FALSE(circle_segment_goal({0, 0}, 1.0, {2, -1}, {2, 1})); }

TEST(PurePursuitCrossing, OneHitInsideTheSegment) {
  // The line y = 0 crosses the unit circle at x = +-1; only x = 1 lies on the segment.
  const auto goal = circle_segment_goal({0, 0}, 1.0, {0, 0}, {3, 0});
  ASSERT_TRUE(goal);
  expect_near(*goal, {1, 0});
}

TEST(PurePursuitCrossing, TwoHitsTakeTheOneNearerTheSegmentEnd) {
  // y = 0.6 crosses the unit circle at x = +-0.8.
  const auto forward = circle_segment_goal({0, 0}, 1.0, {-3, 0.6}, {3, 0.6});
  ASSERT_TRUE(forward);
  expect_near(*forward, {0.8, 0.6});
  const auto backward = circle_segment_goal({0, 0}, 1.0, {3, 0.6}, {-3, 0.6});
  ASSERT_TRUE(backward);
  expect_near(*backward, {-0.8, 0.6});
}

TEST(PurePursuitCrossing, HitsOutsideTheSegmentAreIgnored) {
  // The line crosses at x = +-1, both outside [2, 4].
  EXPECT_FALSE(circle_segment_goal({0, 0}, 1.0, {2, 0}, {4, 0}));
  // Translated circle: centre (5, 5), crossings at (5 +- 1, 5), segment x in [6.5, 9].
  EXPECT_FALSE(circle_segment_goal({5, 5}, 1.0, {6.5, 5}, {9, 5}));
}

TEST(PurePursuitCrossing, TangentSegmentTouchesOnce) {
  const auto goal = circle_segment_goal({0, 0}, 1.0, {-1, 1}, {1, 1});
  ASSERT_TRUE(goal);
  expect_near(*goal, {0, 1});
}

TEST(PurePursuitCrossing, DegenerateSegmentHasNoCrossing) {
  EXPECT_FALSE(circle_segment_goal({0, 0}, 1.0, {1, 0}, {1, 0}));
}

// ------------------------------------------------------------- goal selection

TEST(PurePursuit, OneSegmentGoalIsTheLookaheadPointAhead) {
  PurePursuitState state;
  const Path path{{0, 0}, {10, 0}};
  const PurePursuitStep step = pure_pursuit_step(lookahead(1.5), state, {2, 0}, 0.0, path);
  EXPECT_EQ(step.source, GoalSource::intersection);
  EXPECT_EQ(step.index, 0);
  expect_near(step.goal, {3.5, 0});
  EXPECT_NEAR(step.turn_error_rad, 0.0, 1e-12);
  EXPECT_FALSE(step.end_reached);
}

TEST(PurePursuit, SeveralSegmentsHitTakesTheFirstValidPoint) {
  // Fig. 38, a hairpin: the circle of radius 2 around (1, 0) crosses the
  // first leg at (3, 0) and the return leg at (1 + sqrt 3, 1); taking the
  // latter would cut the bend.
  PurePursuitState state;
  const Path path{{0, 0}, {4, 0}, {4, 1}, {0, 1}};
  ASSERT_TRUE(circle_segment_goal({1, 0}, 2.0, path[2], path[3]));
  const PurePursuitStep step = pure_pursuit_step(lookahead(2.0), state, {1, 0}, 0.0, path);
  EXPECT_EQ(step.source, GoalSource::intersection);
  EXPECT_EQ(step.index, 0);
  expect_near(step.goal, {3, 0});
}

TEST(PurePursuit, DoesNotGoBackAlongThePath) {
  // Fig. 39: the robot at (3, 0), near waypoint 1, lastFoundIndex still 0.
  // The circle crosses the first segment only at (1, 0), behind the robot
  // (farther from waypoint 1 than the robot), so the search goes on to the
  // second segment: (4, sqrt 3).
  PurePursuitState state;
  const Path path{{0, 0}, {4, 0}, {4, 4}};
  const PurePursuitStep step = pure_pursuit_step(lookahead(2.0), state, {3, 0}, 0.0, path);
  EXPECT_EQ(step.source, GoalSource::intersection);
  EXPECT_EQ(step.index, 1);
  EXPECT_EQ(state.last_found_index, 1);
  expect_near(step.goal, {4, std::sqrt(3.0)});
  EXPECT_NEAR(step.turn_error_rad, std::atan2(std::sqrt(3.0), 1.0), 1e-12);
}

TEST(PurePursuit, NoCrossingFallsBackToTheLastFoundWaypoint) {
  PurePursuitState state{1};
  const Path path{{0, 0}, {4, 0}, {4, 4}};
  const PurePursuitStep step = pure_pursuit_step(lookahead(1.0), state, {10, 10}, 0.0, path);
  EXPECT_EQ(step.source, GoalSource::waypoint);
  EXPECT_EQ(step.index, 1);
  expect_near(step.goal, {4, 0});
  EXPECT_EQ(state.last_found_index, 1);
}

TEST(PurePursuit, StartAwayFromThePathHeadsToTheFirstWaypoint) {
  PurePursuitState state;
  const Path path{{0, 0}, {4, 0}, {4, 4}};
  const PurePursuitStep step = pure_pursuit_step(lookahead(1.0), state, {-3, -4}, M_PI / 2, path);
  EXPECT_EQ(step.source, GoalSource::waypoint);
  EXPECT_EQ(step.index, 0);
  expect_near(step.goal, {0, 0});
  EXPECT_NEAR(step.turn_error_rad, std::atan2(4.0, 3.0) - M_PI / 2, 1e-12);
}

TEST(PurePursuit, LastFoundIndexNeverGoesBack) {
  // lastFoundIndex 1: the first segment, which the circle crosses at (3, 0),
  // is not searched again; the second is out of reach, so the goal is waypoint 1.
  PurePursuitState state{1};
  const Path path{{0, 0}, {4, 0}, {4, 4}};
  const PurePursuitStep step = pure_pursuit_step(lookahead(2.0), state, {1, 0}, 0.0, path);
  EXPECT_EQ(step.source, GoalSource::waypoint);
  expect_near(step.goal, {4, 0});
  EXPECT_EQ(state.last_found_index, 1);
}

TEST(PurePursuit, LastFoundIndexAdvancesMonotonicallyAlongThePath) {
  PurePursuitState state;
  const Path path{{0, 0}, {3, 0}, {3, 3}, {6, 3}, {6, 6}};
  // Positions along the path, each a little ahead of the last.
  std::vector<int> indices;
  for (std::size_t i = 0; i + 1 < path.size(); ++i) {
    for (double t = 0.0; t < 1.0; t += 0.1) {
      const Eigen::Vector2d p = path[i] + t * (path[i + 1] - path[i]);
      indices.push_back(pure_pursuit_step(lookahead(1.0), state, p, 0.0, path).index);
    }
  }
  EXPECT_TRUE(std::is_sorted(indices.begin(), indices.end()));
  EXPECT_EQ(indices.front(), 0);
  EXPECT_GE(indices.back(), 3);
  // Positions revisited from the start do not bring it back.
  const int reached = state.last_found_index;
  pure_pursuit_step(lookahead(1.0), state, path[0], 0.0, path);
  EXPECT_EQ(state.last_found_index, reached);
}

TEST(PurePursuit, RestOfThePathInsideTheCircleAimsAtTheEnd) {
  // Dense samples near the end: once they are all within the lookahead, the
  // goal is the last point, not a waypoint the robot is about to pass.
  PurePursuitState state{7};
  Path path;
  for (int i = 0; i <= 10; ++i) path.emplace_back(0.1 * i, 0.0);
  const PurePursuitStep step = pure_pursuit_step(lookahead(1.5), state, {0.75, 0.0}, 0.0, path);
  EXPECT_EQ(step.source, GoalSource::waypoint);
  EXPECT_EQ(step.index, 10);
  expect_near(step.goal, {1.0, 0.0});
}

TEST(PurePursuit, EndReachedWithinToleranceOfTheLastPointStops) {
  PurePursuitConfig config = lookahead(1.0);
  config.goal_tolerance_m = 0.3;
  const Path path{{0, 0}, {4, 0}};
  PurePursuitState state;
  const PurePursuitStep near = pure_pursuit_step(config, state, {3.8, 0.1}, 0.0, path);
  EXPECT_TRUE(near.end_reached);
  EXPECT_EQ(near.speed_m_s, 0.0);
  EXPECT_EQ(near.yaw_rate_rad_s, 0.0);
  PurePursuitState fresh;
  EXPECT_FALSE(pure_pursuit_step(config, fresh, {3.5, 0.0}, 0.0, path).end_reached);
}

TEST(PurePursuit, EndOfALoopIsNotReachedAtTheStart) {
  // A closed loop ends where it starts; only the last segment counts.
  PurePursuitState state;
  const Path loop{{0, 0}, {5, 0}, {5, 5}, {0, 5}, {0, 0}};
  EXPECT_FALSE(pure_pursuit_step(lookahead(1.0), state, {0, 0}, 0.0, loop).end_reached);
}

TEST(PurePursuit, EmptyPathThrows) {
  PurePursuitState state;
  EXPECT_THROW(pure_pursuit_step(lookahead(1.0), state, {0, 0}, 0.0, Path{}), std::invalid_argument);
}

// ------------------------------------------------------------------ control law

TEST(PurePursuitWrap, TurnErrorLiesInMinusPiToPi) {
  EXPECT_NEAR(wrap_to_pi(358.0 * kDeg), -2.0 * kDeg, 1e-12);
  EXPECT_NEAR(wrap_to_pi(-358.0 * kDeg), 2.0 * kDeg, 1e-12);
  EXPECT_DOUBLE_EQ(wrap_to_pi(M_PI), M_PI);
  EXPECT_DOUBLE_EQ(wrap_to_pi(-M_PI), M_PI);
  EXPECT_DOUBLE_EQ(wrap_to_pi(3.0 * M_PI), M_PI);
  EXPECT_NEAR(wrap_to_pi(0.5 + 4.0 * M_PI), 0.5, 1e-12);
}

TEST(PurePursuitWrap, HeadingOneDegreeTargetAt359TurnsTwoDegreesClockwise) {
  // 003 §3.4: heading 1 deg, goal at 359 deg: turn -2 deg, not +358 deg.
  PurePursuitState state;
  const Eigen::Vector2d goal_direction(std::cos(359.0 * kDeg), std::sin(359.0 * kDeg));
  const Path path{Eigen::Vector2d(0, 0), 100.0 * goal_direction};
  const PurePursuitStep step = pure_pursuit_step(lookahead(1.0), state, {0, 0}, 1.0 * kDeg, path);
  EXPECT_NEAR(step.turn_error_rad, -2.0 * kDeg, 1e-9);
  EXPECT_LT(step.yaw_rate_rad_s, 0.0);
}

TEST(PurePursuitWrap, GoalStraightBehindGivesPlusPi) {
  PurePursuitState state;
  const Path path{{0, 0}, {-10, 0}};
  const PurePursuitStep step = pure_pursuit_step(lookahead(1.0), state, {0, 0}, 0.0, path);
  EXPECT_DOUBLE_EQ(step.turn_error_rad, M_PI);
}

TEST(PurePursuitControl, YawRateIsProportionalAndClamped) {
  PurePursuitConfig config = lookahead(1.0);
  config.turn_gain_per_s = 2.0;
  config.max_yaw_rate_rad_s = 1.0;
  const Path path{{0, 0}, {0, 10}};  // goal at (0, 1): straight left
  PurePursuitState a;
  EXPECT_NEAR(pure_pursuit_step(config, a, {0, 0}, M_PI / 2 - 0.1, path).yaw_rate_rad_s, 0.2, 1e-12);
  PurePursuitState b;
  EXPECT_DOUBLE_EQ(pure_pursuit_step(config, b, {0, 0}, 0.0, path).yaw_rate_rad_s, 1.0);
  PurePursuitState c;
  EXPECT_DOUBLE_EQ(pure_pursuit_step(config, c, {0, 0}, M_PI, path).yaw_rate_rad_s, -1.0);
}

TEST(PurePursuitControl, SlowsDownInCurvesButNotBelowTheMinimum) {
  PurePursuitConfig config = lookahead(1.0);
  config.max_speed_m_s = 1.0;
  config.min_speed_m_s = 0.2;
  config.slowdown_turn_error_rad = 1.0;
  const Path path{{0, 0}, {10, 0}};
  const auto speed = [&](double heading) {
    PurePursuitState state;
    return pure_pursuit_step(config, state, {0, 0}, heading, path).speed_m_s;
  };
  EXPECT_DOUBLE_EQ(speed(0.0), 1.0);
  EXPECT_NEAR(speed(0.5), 0.6, 1e-12);
  EXPECT_NEAR(speed(-0.5), 0.6, 1e-12);
  EXPECT_DOUBLE_EQ(speed(2.0), 0.2);
}

// ------------------------------------------------------------------ closed loop

struct LoopRun {
  double max_cross_track_m = 0.0;
  bool reached = false;
  int steps = 0;
};

// The kinematic unicycle x += v cos th dt, y += v sin th dt, th += w dt under pure pursuit.
LoopRun follow(const PurePursuitConfig& config, const Path& path, Eigen::Vector2d position, double heading,
               int max_steps) {
  constexpr double kDt = 0.05;
  PurePursuitState state;
  LoopRun run;
  for (; run.steps < max_steps; ++run.steps) {
    const PurePursuitStep step = pure_pursuit_step(config, state, position, heading, path);
    if (step.end_reached) {
      run.reached = true;
      break;
    }
    position += step.speed_m_s * kDt * Eigen::Vector2d(std::cos(heading), std::sin(heading));
    heading += step.yaw_rate_rad_s * kDt;
    run.max_cross_track_m = std::max(run.max_cross_track_m, cross_track(position, path));
  }
  return run;
}

TEST(PurePursuitClosedLoop, UnicycleFollowsAnLShapedPath) {
  const Path path{{0, 0}, {10, 0}, {10, 10}};
  const LoopRun run = follow(PurePursuitConfig{}, path, {0, 0}, 0.0, 2000);
  EXPECT_TRUE(run.reached);
  // Cutting the corner with a 1.5 m lookahead: about lookahead (1 - 1/sqrt 2) = 0.44 m.
  EXPECT_LT(run.max_cross_track_m, 0.6);
}

TEST(PurePursuitClosedLoop, UnicycleFollowsADenselySampledSquare) {
  // A closed square sampled every 0.1 m, like a discretised global path.
  const Eigen::Vector2d corners[] = {{0, 0}, {8, 0}, {8, 8}, {0, 8}, {0, 0}};
  Path path;
  for (int c = 0; c < 4; ++c) {
    for (int i = 0; i < 80; ++i) path.push_back(corners[c] + (corners[c + 1] - corners[c]) * (i / 80.0));
  }
  path.push_back(corners[4]);
  const LoopRun run = follow(PurePursuitConfig{}, path, {0, 0}, 0.0, 4000);
  EXPECT_TRUE(run.reached);
  EXPECT_LT(run.max_cross_track_m, 0.6);
}

TEST(PurePursuitClosedLoop, UnicycleStartingOffThePathJoinsIt) {
  const Path path{{0, 0}, {10, 0}, {10, 10}};
  const LoopRun run = follow(PurePursuitConfig{}, path, {-3, 2}, M_PI, 3000);
  EXPECT_TRUE(run.reached);
}

}  // namespace
}  // namespace campo
