#include "planners/dubins.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "campo/random.hpp"
#include "tests/test_units.hpp"

namespace campo::dubins {
namespace {

using namespace campo::test_units;
constexpr double kTol = 1e-9;

Pose2 pose_deg(double x_m, double y_m, double heading_deg) { return {x_m, y_m, heading_deg * kPi / 180.0}; }

double angle_difference(double a, double b) { return std::remainder(a - b, 2.0 * kPi); }

void expect_pose_near(const Pose2& actual, const Pose2& expected) {
  EXPECT_NEAR(actual.x_m, expected.x_m, kTol);
  EXPECT_NEAR(actual.y_m, expected.y_m, kTol);
  EXPECT_NEAR(angle_difference(actual.heading_rad, expected.heading_rad), 0.0, kTol);
}

void expect_segments(const Path& path, std::array<double, 3> expected_m) {
  for (std::size_t i = 0; i < 3; ++i) EXPECT_NEAR(path.segment_lengths_m[i], expected_m[i], kTol) << "segment " << i;
}

/// The word with L and R swapped (a mirror image of the path).
Word mirrored(Word word) {
  switch (word) {
    case Word::LSL: return Word::RSR;
    case Word::RSR: return Word::LSL;
    case Word::LSR: return Word::RSL;
    case Word::RSL: return Word::LSR;
    case Word::RLR: return Word::LRL;
    case Word::LRL: return Word::RLR;
  }
  return word;
}

/// The word of the same path driven backwards with the heading turned round:
/// segments in reverse order, each arc turning the other way.
Word reversed(Word word) {
  const std::string letters(to_string(word));
  return mirrored(*std::find_if(kWords.begin(), kWords.end(), [&](Word w) {
    return to_string(w) == std::string(letters.rbegin(), letters.rend());
  }));
}

/// Seeded pose pairs and radii: positions within +-10 m and radii 0.5-4 m, so
/// that all six words are often feasible.
struct Problem {
  Pose2 from, to;
  double radius_m;
};
std::vector<Problem> random_problems(std::size_t count) {
  Rng rng(20260515);
  std::vector<Problem> problems;
  for (std::size_t i = 0; i < count; ++i) {
    const auto pose = [&] { return Pose2{rng.uniform(-10, 10), rng.uniform(-10, 10), rng.uniform(-kPi, kPi)}; };
    const Pose2 from = pose();
    const Pose2 to = pose();
    problems.push_back({from, to, rng.uniform(0.5, 4.0)});
  }
  return problems;
}

double distance(const Pose2& a, const Pose2& b) { return std::hypot(b.x_m - a.x_m, b.y_m - a.y_m); }

// ------------------------------------------------------------- hand-worked

TEST(DubinsWords, NamesAreTheSegmentLetters) {
  EXPECT_EQ(to_string(Word::LSL), "LSL");
  EXPECT_EQ(to_string(Word::RSR), "RSR");
  EXPECT_EQ(to_string(Word::LSR), "LSR");
  EXPECT_EQ(to_string(Word::RSL), "RSL");
  EXPECT_EQ(to_string(Word::RLR), "RLR");
  EXPECT_EQ(to_string(Word::LRL), "LRL");
}

TEST(DubinsWords, StraightLineIsLslWithNoArcs) {
  // Both poses on one line, same heading: 10 m straight. LSL, RSR, LSR, RSL
  // all degenerate to it; the circles are 10 r apart (> 4 r), so no CCC.
  const Pose2 from = pose_deg(0, 0, 0);
  const Pose2 to = pose_deg(10, 0, 0);
  const Path shortest = shortest_path(from, to, 1.0);
  EXPECT_EQ(shortest.word, Word::LSL);
  expect_segments(shortest, {0, 10, 0});
  for (Word word : {Word::RSR, Word::LSR, Word::RSL}) EXPECT_NEAR(path(from, to, 1.0, word)->length_m(), 10, kTol);
  EXPECT_FALSE(path(from, to, 1.0, Word::RLR));
  EXPECT_FALSE(path(from, to, 1.0, Word::LRL));

  // The same along a slanted line: rounding must not turn a zero arc into a full circle.
  const Pose2 slanted = pose_deg(1, 2, 30);
  const Pose2 ahead{1 + 10 * std::cos(kPi / 6), 2 + 10 * std::sin(kPi / 6), kPi / 6};
  const Path run = shortest_path(slanted, ahead, 3.0);
  EXPECT_EQ(run.word, Word::LSL);
  expect_segments(run, {0, 10, 0});
}

TEST(DubinsWords, UTurnIsAHalfCircle) {
  // Heading north at the origin, back south 2 r to the west (r = 2.5 m): one
  // left half circle around (-r, 0), length pi r (LSL with the circles coinciding).
  const double r = 2.5;
  const Path left = shortest_path(pose_deg(0, 0, 90), pose_deg(-2 * r, 0, -90), r);
  EXPECT_EQ(left.word, Word::LSL);
  expect_segments(left, {kPi * r, 0, 0});
  // Mirrored to the east: a right half circle.
  const Path right = shortest_path(pose_deg(0, 0, 90), pose_deg(2 * r, 0, -90), r);
  EXPECT_EQ(right.word, Word::RSR);
  expect_segments(right, {kPi * r, 0, 0});
}

TEST(DubinsWords, LslHalfCircleThenStraight) {
  // r = 2: heading east at the origin, a left half circle around (0, 2) ends
  // at (0, 4) heading west, then 5 m straight to (-5, 4): 2 pi + 5.
  const Path p = shortest_path(pose_deg(0, 0, 0), pose_deg(-5, 4, 180), 2.0);
  EXPECT_EQ(p.word, Word::LSL);
  expect_segments(p, {2 * kPi, 5, 0});
  EXPECT_NEAR(p.length_m(), 2 * kPi + 5, kTol);
}

TEST(DubinsWords, RsrAndLslQuarterTurnsAroundAStraight) {
  // r = 1: heading north at the origin, a right quarter circle around (1, 0)
  // reaches (1, 1) heading east, 2 m straight to (3, 1), a right quarter
  // around (3, 0) ends at (4, 0) heading south: pi / 2 + 2 + pi / 2.
  const Path right = shortest_path(pose_deg(0, 0, 90), pose_deg(4, 0, -90), 1.0);
  EXPECT_EQ(right.word, Word::RSR);
  expect_segments(right, {kPi / 2, 2, kPi / 2});
  // The mirror image to the west turns left.
  const Path left = shortest_path(pose_deg(0, 0, 90), pose_deg(-4, 0, -90), 1.0);
  EXPECT_EQ(left.word, Word::LSL);
  expect_segments(left, {kPi / 2, 2, kPi / 2});
}

TEST(DubinsWords, LsrAndRslLaneChange) {
  // r = 1: heading east at the origin, a left quarter around (0, 1) reaches
  // (1, 1) heading north, 3 m straight to (1, 4), a right quarter around
  // (2, 4) ends at (2, 5) heading east. The circle centres (0, 1) and (2, 4)
  // are sqrt(13) apart, and the inner tangent sqrt(13 - 4) = 3 leaves at
  // atan(3/2) + atan(2/3) = 90 deg: pi / 2 + 3 + pi / 2.
  const Path lsr = shortest_path(pose_deg(0, 0, 0), pose_deg(2, 5, 0), 1.0);
  EXPECT_EQ(lsr.word, Word::LSR);
  expect_segments(lsr, {kPi / 2, 3, kPi / 2});
  // Mirrored across the x axis: right first.
  const Path rsl = shortest_path(pose_deg(0, 0, 0), pose_deg(2, -5, 0), 1.0);
  EXPECT_EQ(rsl.word, Word::RSL);
  expect_segments(rsl, {kPi / 2, 3, kPi / 2});
}

TEST(DubinsWords, TurningBackOnTheSpotIsThreeArcs) {
  // r = 1, from (0, 0) heading north back to (0, 0) heading south. The left
  // circles are centred at (-1, 0) and (1, 0); a right circle centred at
  // (0, sqrt 3) touches both (an equilateral triangle of side 2). Left 60 deg
  // to (-1/2, sqrt3/2), right 300 deg round the top to (1/2, sqrt3/2), left
  // 60 deg back to the origin: LRL = pi/3 + 5pi/3 + pi/3 = 7pi/3. RLR is its
  // mirror image, just as long, and first in enum order. Every CSC is
  // longer: LSL and RSR need 3 pi + 2; LSR and RSL have their circles
  // overlapping (infeasible).
  const Pose2 from = pose_deg(0, 0, 90);
  const Pose2 to = pose_deg(0, 0, -90);
  const std::optional<Path> lrl = path(from, to, 1.0, Word::LRL);
  ASSERT_TRUE(lrl);
  expect_segments(*lrl, {kPi / 3, 5 * kPi / 3, kPi / 3});
  EXPECT_NEAR(lrl->pose_at(kPi / 3).x_m, -0.5, kTol);
  EXPECT_NEAR(lrl->pose_at(kPi / 3).y_m, std::sqrt(3.0) / 2, kTol);
  // Half way, 60 + 150 deg along: the top of the middle circle, heading east.
  expect_pose_near(lrl->pose_at(7 * kPi / 6), {0, std::sqrt(3.0) + 1, 0});
  const Path shortest = shortest_path(from, to, 1.0);
  EXPECT_EQ(shortest.word, Word::RLR);
  expect_segments(shortest, {kPi / 3, 5 * kPi / 3, kPi / 3});
  EXPECT_NEAR(path(from, to, 1.0, Word::LSL)->length_m(), 3 * kPi + 2, kTol);
  EXPECT_NEAR(path(from, to, 1.0, Word::RSR)->length_m(), 3 * kPi + 2, kTol);
  EXPECT_FALSE(path(from, to, 1.0, Word::LSR));
  EXPECT_FALSE(path(from, to, 1.0, Word::RSL));
}

TEST(DubinsWords, CccWithUnequalEndArcs) {
  // The circles of the previous case, but the start 30 deg below the x axis
  // on the left circle around (-1, 0): (-1 + sqrt3/2, -1/2) heading 60 deg.
  // LRL: left 90 deg up to the tangent point, right 300 deg, left 60 deg:
  // pi/2 + 5pi/3 + pi/3. Scaled by r = 2.
  const double r = 2.0;
  const Pose2 from{r * (-1 + std::sqrt(3.0) / 2), -r / 2, kPi / 3};
  const std::optional<Path> lrl = path(from, pose_deg(0, 0, -90), r, Word::LRL);
  ASSERT_TRUE(lrl);
  expect_segments(*lrl, {r * kPi / 2, r * 5 * kPi / 3, r * kPi / 3});
  // Mirrored across the x axis it is RLR.
  const std::optional<Path> rlr = path({from.x_m, -from.y_m, -from.heading_rad}, pose_deg(0, 0, 90), r, Word::RLR);
  ASSERT_TRUE(rlr);
  expect_segments(*rlr, {r * kPi / 2, r * 5 * kPi / 3, r * kPi / 3});
}

TEST(DubinsWords, IdenticalPosesGiveAnEmptyPath) {
  const Pose2 here = pose_deg(3, -4, 123);
  const Path p = shortest_path(here, here, 1.5);
  EXPECT_NEAR(p.length_m(), 0.0, kTol);
  const std::vector<Pose2> poses = sample(p, 0.1);
  ASSERT_EQ(poses.size(), 1u);
  expect_pose_near(poses[0], here);
}

TEST(DubinsInputs, RejectsBadRadiusStepAndNonFinitePoses) {
  const Pose2 a = pose_deg(0, 0, 0);
  const Pose2 b = pose_deg(5, 5, 90);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (double r : {0.0, -1.0, nan, inf}) {
    EXPECT_THROW(shortest_path(a, b, r), std::invalid_argument);
    EXPECT_THROW(path(a, b, r, Word::LSL), std::invalid_argument);
  }
  EXPECT_THROW(shortest_path({nan, 0, 0}, b, 1.0), std::invalid_argument);
  EXPECT_THROW(shortest_path(a, {0, 0, inf}, 1.0), std::invalid_argument);
  const std::vector<Pose2> waypoints{a, b};
  EXPECT_THROW(route(waypoints, -2.0), std::invalid_argument);
  const Path p = shortest_path(a, b, 1.0);
  for (double step : {0.0, -0.1, nan, inf}) EXPECT_THROW(sample(p, step), std::invalid_argument);
  try {
    shortest_path(a, b, -2.0);
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("turning radius"), std::string::npos);
  }
}

// ---------------------------------------------------- seeded random problems

TEST(DubinsInvariants, EveryFeasibleWordEndsAtTheGoal) {
  std::array<int, 6> feasible{};
  for (const Problem& q : random_problems(3000)) {
    for (Word word : kWords) {
      const std::optional<Path> p = path(q.from, q.to, q.radius_m, word);
      if (!p) continue;
      ++feasible[static_cast<std::size_t>(word)];
      SCOPED_TRACE(std::string(to_string(word)));
      for (double length : p->segment_lengths_m) EXPECT_GE(length, 0.0);
      EXPECT_GE(p->length_m(), distance(q.from, q.to) - kTol);
      expect_pose_near(p->pose_at(p->length_m()), q.to);
      expect_pose_near(p->pose_at(0.0), q.from);
    }
  }
  // CSC words exist for all but overlapping circles; CCC only for near poses.
  EXPECT_EQ(feasible[0], 3000);
  EXPECT_EQ(feasible[1], 3000);
  for (int count : feasible) EXPECT_GT(count, 300);
}

TEST(DubinsInvariants, ShortestIsNoLongerThanAnyWord) {
  for (const Problem& q : random_problems(3000)) {
    const Path shortest = shortest_path(q.from, q.to, q.radius_m);
    EXPECT_GE(shortest.length_m(), distance(q.from, q.to) - kTol);
    expect_pose_near(shortest.pose_at(shortest.length_m()), q.to);
    for (Word word : kWords) {
      if (const std::optional<Path> p = path(q.from, q.to, q.radius_m, word)) {
        EXPECT_LE(shortest.length_m(), p->length_m() + kTol) << to_string(word);
      }
    }
  }
}

TEST(DubinsInvariants, SamplesAreContinuousAndIncludeBothEnds) {
  const double step = 0.3;
  for (const Problem& q : random_problems(300)) {
    const Path p = shortest_path(q.from, q.to, q.radius_m);
    const std::vector<Pose2> poses = sample(p, step);
    ASSERT_GE(poses.size(), 2u);
    EXPECT_EQ(poses.front().x_m, q.from.x_m);
    EXPECT_EQ(poses.front().y_m, q.from.y_m);
    const Pose2 end = p.pose_at(p.length_m());
    EXPECT_EQ(poses.back().x_m, end.x_m);
    EXPECT_EQ(poses.back().y_m, end.y_m);
    expect_pose_near(poses.back(), q.to);
    EXPECT_EQ(poses.size(), static_cast<std::size_t>(std::ceil(p.length_m() / step)) + 1);
    for (std::size_t i = 1; i < poses.size(); ++i) {
      EXPECT_LE(distance(poses[i - 1], poses[i]), step + kTol);
      EXPECT_LE(std::abs(angle_difference(poses[i].heading_rad, poses[i - 1].heading_rad)), step / q.radius_m + kTol);
      EXPECT_GE(poses[i].heading_rad, -kPi);
      EXPECT_LT(poses[i].heading_rad, kPi);
    }
  }
}

TEST(DubinsSymmetry, ReversedProblemHasTheSameLength) {
  // Driving the path backwards with the heading turned round is a forward
  // path from (to, heading + pi) to (from, heading + pi) of the same length.
  const auto turned = [](const Pose2& p) { return Pose2{p.x_m, p.y_m, p.heading_rad + kPi}; };
  for (const Problem& q : random_problems(1000)) {
    const Pose2 from = turned(q.to);
    const Pose2 to = turned(q.from);
    EXPECT_NEAR(shortest_path(from, to, q.radius_m).length_m(), shortest_path(q.from, q.to, q.radius_m).length_m(),
                kTol);
    for (Word word : kWords) {
      const std::optional<Path> forward = path(q.from, q.to, q.radius_m, word);
      const std::optional<Path> backward = path(from, to, q.radius_m, reversed(word));
      ASSERT_EQ(forward.has_value(), backward.has_value()) << to_string(word);
      if (forward) {
        EXPECT_NEAR(forward->length_m(), backward->length_m(), kTol) << to_string(word);
      }
    }
  }
}

TEST(DubinsSymmetry, MirrorAcrossTheXAxisSwapsLeftAndRight) {
  const auto mirror = [](const Pose2& p) { return Pose2{p.x_m, -p.y_m, -p.heading_rad}; };
  for (const Problem& q : random_problems(1000)) {
    const Pose2 from = mirror(q.from);
    const Pose2 to = mirror(q.to);
    EXPECT_NEAR(shortest_path(from, to, q.radius_m).length_m(), shortest_path(q.from, q.to, q.radius_m).length_m(),
                kTol);
    for (Word word : kWords) {
      const std::optional<Path> original = path(q.from, q.to, q.radius_m, word);
      const std::optional<Path> image = path(from, to, q.radius_m, mirrored(word));
      ASSERT_EQ(original.has_value(), image.has_value()) << to_string(word);
      if (!original) continue;
      for (std::size_t i = 0; i < 3; ++i) {
        EXPECT_NEAR(original->segment_lengths_m[i], image->segment_lengths_m[i], kTol) << to_string(word);
      }
    }
  }
}

// ------------------------------------------------------------------ routes

TEST(DubinsRoute, VineyardRowsAreStraightsAndRowSwitchesAreArcs) {
  // Three 40 m rows 3 m apart, driven alternately east and west; r = 1.5 m,
  // so each row switch is a half circle of length 1.5 pi.
  const double r = 1.5;
  const std::vector<Pose2> waypoints{pose_deg(0, 0, 0),    pose_deg(40, 0, 0), pose_deg(40, 3, 180),
                                     pose_deg(0, 3, 180), pose_deg(0, 6, 0),  pose_deg(40, 6, 0)};
  const std::vector<Path> paths = route(waypoints, r);
  ASSERT_EQ(paths.size(), 5u);
  for (std::size_t i = 0; i < paths.size(); ++i) {
    SCOPED_TRACE(i);
    const std::string letters(to_string(paths[i].word));
    ASSERT_EQ(letters[1], 'S');
    if (i % 2 == 0) {
      expect_segments(paths[i], {0, 40, 0});  // along a row
    } else {
      EXPECT_NEAR(paths[i].segment_lengths_m[1], 0.0, kTol);  // row switch
      EXPECT_NEAR(paths[i].length_m(), kPi * r, kTol);
    }
  }
  EXPECT_EQ(paths[1].word, Word::LSL);  // east then north then west: left
  EXPECT_EQ(paths[3].word, Word::RSR);  // west then north then east: right

  const double step = 0.5;
  const std::vector<Pose2> poses = sample_route(paths, step);
  std::size_t expected = 1;
  for (const Path& p : paths) expected += sample(p, step).size() - 1;
  EXPECT_EQ(poses.size(), expected);
  expect_pose_near(poses.front(), waypoints.front());
  expect_pose_near(poses.back(), waypoints.back());
  for (std::size_t i = 1; i < poses.size(); ++i) {
    EXPECT_GT(distance(poses[i - 1], poses[i]), 0.1);  // no junction twice
    EXPECT_LE(distance(poses[i - 1], poses[i]), step + kTol);
  }
}

TEST(DubinsRoute, FewerThanTwoWaypointsGiveNoPaths) {
  EXPECT_TRUE(route({}, 1.0).empty());
  const std::vector<Pose2> one{pose_deg(1, 2, 3)};
  EXPECT_TRUE(route(one, 1.0).empty());
  EXPECT_TRUE(sample_route({}, 0.5).empty());
}

}  // namespace
}  // namespace campo::dubins
