#include "planners/vfh_plus.hpp"
#include "tests/test_units.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include <gtest/gtest.h>

namespace campo {
namespace {

using namespace campo::test_units;

/// Free 10 m x 10 m grid of 0.1 m cells centred on the origin.
OccupancyGrid open_field() {
  OccupancyGrid grid;
  grid.cols = grid.rows = 100;
  grid.resolution_m = 0.1;
  grid.origin_m = {-5.0, -5.0};
  grid.occupied.assign(100 * 100, 0);
  return grid;
}

void occupy(OccupancyGrid& grid, const Eigen::Vector2d& point) {
  const Eigen::Vector2i c = grid.cell_of(point);
  grid.occupied[static_cast<std::size_t>(c.y()) * grid.cols + c.x()] = 1;
}

void occupy_box(OccupancyGrid& grid, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi) {
  for (double y = lo.y() + 0.05; y < hi.y(); y += 0.1) {
    for (double x = lo.x() + 0.05; x < hi.x(); x += 0.1) occupy(grid, {x, y});
  }
}

const Eigen::Vector2d kRobot(0.05, 0.05);  // a cell centre, so distances to cell centres are round

TEST(VfhPlusHistogram, ObstacleCellsCoverTheirEnlargedAngularSpan) {
  OccupancyGrid grid = open_field();
  occupy(grid, kRobot + Eigen::Vector2d(2.0, 0.0));  // bearing 0, d 2
  occupy(grid, kRobot + Eigen::Vector2d(0.0, 1.2));  // bearing 90 deg, d 1.2
  VfhPlusConfig config;  // 72 sectors of 5 deg, r_r + d_s = 0.6, window 3.5 m, a = 4
  config.robot_radius_m = 0.4;
  config.safety_distance_m = 0.1;
  const std::vector<double> polar = vfh_polar_histogram(grid, kRobot, config);
  ASSERT_EQ(polar.size(), 72u);
  // gamma = asin(0.5 / 2) = 14.48 deg: sectors -10..10 deg; m = 4 - (3 / 3.5^2) 2^2.
  const double m_far = 4.0 - 3.0 / 12.25 * 4.0;
  // gamma = asin(0.5 / 1.2) = 24.62 deg: sectors 70..110 deg.
  const double m_near = 4.0 - 3.0 / 12.25 * 1.44;
  for (int k = 0; k < 72; ++k) {
    SCOPED_TRACE(k);
    const bool far = k <= 2 || k >= 70;
    const bool near = k >= 14 && k <= 22;
    EXPECT_NEAR(polar[k], (far ? m_far : 0.0) + (near ? m_near : 0.0), 1e-9);
  }
  // Inside the enlargement radius the cell blocks a half plane.
  OccupancyGrid close = open_field();
  occupy(close, kRobot + Eigen::Vector2d(0.1, -0.3));  // bearing -71.57 deg
  const std::vector<double> half = vfh_polar_histogram(close, kRobot, config);
  for (int k = 0; k < 72; ++k) EXPECT_EQ(half[k] > 0.0, k >= 40 || k <= 3) << k;  // -161.57 .. 18.43 deg
}

TEST(VfhPlusHistogram, BinaryHistogramHasHysteresis) {
  const std::vector<double> polar = {0.2, 1.0, 2.0, 1.0, 0.5, 1.5};
  EXPECT_EQ(vfh_binary_histogram(polar, std::vector<std::uint8_t>{1, 1, 0, 0, 1, 0}, 0.5, 1.5),
            (std::vector<std::uint8_t>{0, 1, 1, 0, 1, 0}));
  // No previous histogram: in between counts as free.
  EXPECT_EQ(vfh_binary_histogram(polar, {}, 0.5, 1.5), (std::vector<std::uint8_t>{0, 0, 1, 0, 0, 0}));
}

// An obstacle 1.2 m to the left overlaps the left turning circle (centre 1 m
// to the left, radius 1 m, plus 0.5 m enlargement): every direction left of
// it is masked, though the binary histogram has them free.
TEST(VfhPlusMask, TurningCirclesMaskDirectionsBeyondBlockingObstacles) {
  OccupancyGrid grid = open_field();
  occupy(grid, kRobot + Eigen::Vector2d(0.0, 1.2));
  VfhPlusConfig config;
  config.robot_radius_m = 0.4;
  config.safety_distance_m = 0.1;
  config.min_turning_radius_m = 1.0;
  const VfhTurnLimits limits = vfh_turn_limits(grid, kRobot, 0.0, config);
  EXPECT_NEAR(limits.left_rad, 90.0 * kDeg, 1e-9);
  EXPECT_DOUBLE_EQ(limits.right_rad, -std::numbers::pi);
  const auto binary = vfh_binary_histogram(vfh_polar_histogram(grid, kRobot, config), {}, config.threshold_low,
                                           config.threshold_high);
  const auto masked = vfh_masked_histogram(binary, limits, 0.0);
  for (int k = 0; k < 72; ++k) {
    SCOPED_TRACE(k);
    if (k >= 14 && k <= 22) {
      EXPECT_EQ(binary[k], 1);  // the obstacle itself
    } else {
      EXPECT_EQ(binary[k], 0);
    }
    if (k == 36) continue;  // straight behind: on the boundary of both sides
    EXPECT_EQ(masked[k], (k >= 14 && k <= 35) ? 1 : 0);
  }
  // Heading north instead, the same cell is straight ahead and out of reach
  // of both turning circles' blocking distance: nothing masked.
  const VfhTurnLimits north = vfh_turn_limits(grid, kRobot, 90.0 * kDeg, config);
  EXPECT_DOUBLE_EQ(north.right_rad, -std::numbers::pi);
  EXPECT_DOUBLE_EQ(north.left_rad, std::numbers::pi);
}

TEST(VfhPlusOpenings, NarrowAndWideOpeningsAndTheirCandidates) {
  // 36 sectors of 10 deg: free 34, 35, 0, 1, 2 (narrow, wraps) and 10..29 (wide).
  std::vector<std::uint8_t> masked(36, 1);
  for (int k : {34, 35, 0, 1, 2}) masked[k] = 0;
  for (int k = 10; k <= 29; ++k) masked[k] = 0;
  const auto openings = vfh_openings(masked, 8);
  ASSERT_EQ(openings.size(), 2u);
  EXPECT_EQ(openings[0].right_sector, 10);
  EXPECT_EQ(openings[0].left_sector, 29);
  EXPECT_EQ(openings[0].sectors, 20);
  EXPECT_TRUE(openings[0].wide);
  EXPECT_EQ(openings[1].right_sector, 34);
  EXPECT_EQ(openings[1].left_sector, 2);
  EXPECT_EQ(openings[1].sectors, 5);
  EXPECT_FALSE(openings[1].wide);

  VfhPlusConfig config;
  config.sectors = 36;
  config.wide_opening_sectors = 8;
  const double target = 200.0 * kDeg;  // sector 20, inside [c_r, c_l] = [14, 25]
  const auto candidates = vfh_candidates(openings, 36, target, 0.0, std::nullopt, config);
  ASSERT_EQ(candidates.size(), 4u);
  EXPECT_NEAR(candidates[0].direction_rad, 140.0 * kDeg, 1e-9);                       // c_r
  EXPECT_NEAR(candidates[1].direction_rad, 250.0 * kDeg - 2 * std::numbers::pi, 1e-9);  // c_l
  EXPECT_NEAR(candidates[2].direction_rad, target - 2 * std::numbers::pi, 1e-9);        // c_t
  EXPECT_NEAR(candidates[3].direction_rad, 0.0, 1e-9);                                 // narrow centre
  // g = 5 D(c, target) + 2 D(c, heading) + 2 D(c, previous = heading), in sectors.
  EXPECT_NEAR(candidates[2].cost, 5 * 0 + 2 * 16 + 2 * 16, 1e-9);
  EXPECT_NEAR(candidates[3].cost, 5 * 16 + 0 + 0, 1e-9);
  EXPECT_TRUE(vfh_openings(std::vector<std::uint8_t>(36, 1), 8).empty());
}

TEST(VfhPlusStep, FollowsACorridor) {
  OccupancyGrid grid = open_field();
  occupy_box(grid, {-5.0, 1.5}, {5.0, 1.6});
  occupy_box(grid, {-5.0, -1.6}, {5.0, -1.5});
  VfhPlusState state;
  const VfhPlusResult result = vfh_plus_step(grid, kRobot, 0.0, {20.0, 0.05}, VfhPlusConfig{}, state);
  ASSERT_TRUE(result.direction_rad.has_value());
  EXPECT_NEAR(*result.direction_rad, 0.0, 2.5 * kDeg);
  EXPECT_EQ(state.binary, result.binary);
  EXPECT_EQ(state.direction_rad, result.direction_rad);
}

TEST(VfhPlusStep, SteersAroundASingleObstacleOnTheTargetsSide) {
  OccupancyGrid grid = open_field();
  occupy_box(grid, {1.8, -0.1}, {2.2, 0.2});  // rows -0.05 .. 0.15: symmetric about the robot
  const VfhPlusConfig config;
  for (const double side : {1.0, -1.0}) {
    SCOPED_TRACE(side);
    VfhPlusState state;
    const VfhPlusResult result = vfh_plus_step(grid, kRobot, 0.0, {10.0, 0.05 + side * 0.5}, config, state);
    ASSERT_TRUE(result.direction_rad.has_value());
    const double direction = *result.direction_rad;
    EXPECT_GT(side * direction, 20.0 * kDeg);  // clear of the enlarged obstacle
    const int sector = static_cast<int>(std::lround(direction / (5.0 * kDeg)) + 72) % 72;
    EXPECT_EQ(result.masked[sector], 0);
  }
  // Target dead ahead: the previous direction breaks the tie.
  for (const double previous : {0.3, -0.3}) {
    VfhPlusState state;
    state.direction_rad = previous;
    const VfhPlusResult result = vfh_plus_step(grid, kRobot, 0.0, {10.0, 0.05}, config, state);
    ASSERT_TRUE(result.direction_rad.has_value());
    EXPECT_GT(*result.direction_rad * previous, 0.0);
  }
}

TEST(VfhPlusStep, BoxedInGivesNoDirectionAndKeepsThePreviousOne) {
  OccupancyGrid grid = open_field();
  occupy_box(grid, {-1.0, -1.0}, {1.0, -0.9});
  occupy_box(grid, {-1.0, 0.9}, {1.0, 1.0});
  occupy_box(grid, {-1.0, -1.0}, {-0.9, 1.0});
  occupy_box(grid, {0.9, -1.0}, {1.0, 1.0});
  VfhPlusState state;
  state.direction_rad = 0.25;
  const VfhPlusResult result = vfh_plus_step(grid, kRobot, 0.0, {4.0, 0.0}, VfhPlusConfig{}, state);
  EXPECT_FALSE(result.direction_rad.has_value());
  EXPECT_TRUE(result.candidates.empty());
  EXPECT_EQ(state.direction_rad, 0.25);
}

TEST(VfhPlusStep, RejectsWeightsThatOutvoteTheTarget) {
  VfhPlusConfig config;
  config.mu_target = 3.0;  // not > 2 + 2
  EXPECT_THROW(validate(config), std::invalid_argument);
  config = {};
  config.threshold_low = 2.0;
  config.threshold_high = 1.0;
  EXPECT_THROW(validate(config), std::invalid_argument);
  EXPECT_NO_THROW(validate(VfhPlusConfig{}));
}

}  // namespace
}  // namespace campo
