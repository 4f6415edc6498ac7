#include "planners/path_smoothing.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "planners/rrt_star.hpp"

namespace campo {
namespace {

/// 20 m x 20 m of 0.1 m cells, with the given boxes (x0, y0, x1, y1) occupied.
OccupancyGrid field(const std::vector<Eigen::Vector4d>& boxes) {
  OccupancyGrid grid;
  grid.cols = grid.rows = 200;
  grid.resolution_m = 0.1;
  grid.occupied.assign(200 * 200, 0);
  for (int row = 0; row < grid.rows; ++row) {
    for (int col = 0; col < grid.cols; ++col) {
      const Eigen::Vector2d c = grid.centre_of(col, row);
      for (const Eigen::Vector4d& b : boxes) {
        if (c.x() > b[0] && c.x() < b[2] && c.y() > b[1] && c.y() < b[3]) {
          grid.occupied[static_cast<std::size_t>(row) * grid.cols + col] = 1;
        }
      }
    }
  }
  return grid;
}

double length(const std::vector<Eigen::Vector2d>& path) {
  double total = 0.0;
  for (std::size_t i = 1; i < path.size(); ++i) total += (path[i] - path[i - 1]).norm();
  return total;
}

void expect_free(const OccupancyGrid& grid, const std::vector<Eigen::Vector2d>& path) {
  for (std::size_t i = 1; i < path.size(); ++i) EXPECT_TRUE(grid.segment_free(path[i - 1], path[i])) << i;
}

/// Largest heading change per metre at the output's interior points (the
/// turn at a point over the mean length of its two segments), skipping the
/// given sharp corner points.
double max_curvature(const std::vector<Eigen::Vector2d>& points, const std::vector<Eigen::Vector2d>& sharp = {}) {
  double worst = 0.0;
  for (std::size_t i = 1; i + 1 < points.size(); ++i) {
    bool skip = false;
    for (const Eigen::Vector2d& s : sharp) skip = skip || (points[i] - s).norm() < 1e-9;
    if (skip) continue;
    const Eigen::Vector2d a = points[i] - points[i - 1];
    const Eigen::Vector2d b = points[i + 1] - points[i];
    const double turn = std::abs(std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b)));
    worst = std::max(worst, turn / (0.5 * (a.norm() + b.norm())));
  }
  return worst;
}

TEST(PathSmoothing, ShortcutStraightensAStaircaseAroundAnObstacle) {
  const OccupancyGrid grid = field({{8.0, 0.0, 10.0, 9.0}});
  // A grid-like staircase from (1, 1) up to (1, 12), then right and down to (18, 1).
  std::vector<Eigen::Vector2d> path;
  for (int k = 0; k <= 11; ++k) path.push_back({1.05 + 0.1 * (k % 2), 1.05 + k});
  for (int k = 1; k <= 17; ++k) path.push_back({1.05 + k, 12.05 - 0.5 * (k > 9 ? k - 9 : 0)});
  path.push_back({18.05, 1.05});
  const std::vector<Eigen::Vector2d> shortcut = shortcut_path(grid, path);
  expect_free(grid, shortcut);
  EXPECT_EQ(shortcut.front(), path.front());
  EXPECT_EQ(shortcut.back(), path.back());
  EXPECT_LT(shortcut.size(), 6u);
  EXPECT_LT(length(shortcut), length(path));
}

// Two 90 degree corners round an L-shaped wall: fillets of the widest radius
// that fits, heading changing no faster than 1 / radius.
TEST(PathSmoothing, FilletsRoundCornersAtNoLessThanTheMinimumRadius) {
  const OccupancyGrid grid = field({{4.0, 4.0, 16.0, 16.0}});
  const std::vector<Eigen::Vector2d> waypoints = {{2.0, 2.0}, {18.0, 2.0}, {18.0, 18.0}, {2.0, 18.0}};
  PathSmoothingConfig config;
  config.min_turning_radius_m = 1.0;
  config.max_turning_radius_m = 3.0;
  const SmoothedPath smoothed = fillet_corners(grid, waypoints, config);
  ASSERT_EQ(smoothed.fillets.size(), 2u);
  EXPECT_EQ(smoothed.sharp_corners, 0);
  for (const Fillet& f : smoothed.fillets) {
    EXPECT_GE(f.radius_m, config.min_turning_radius_m);
    EXPECT_NEAR(f.turn_rad, std::numbers::pi / 2, 1e-12);  // counter-clockwise
    EXPECT_NEAR((f.entry_m - f.centre_m).norm(), f.radius_m, 1e-9);
    EXPECT_NEAR((f.exit_m - f.centre_m).norm(), f.radius_m, 1e-9);
  }
  // The widest radius tried fits: the 3 m arc clears the square's corner.
  EXPECT_DOUBLE_EQ(smoothed.fillets[0].radius_m, 3.0);
  expect_free(grid, smoothed.points_m);
  EXPECT_LE(length(smoothed.points_m), length(waypoints));
  EXPECT_NEAR(smoothed.length_m, length(smoothed.points_m), 1e-9);
  EXPECT_LE(max_curvature(smoothed.points_m), 1.02 / config.min_turning_radius_m);
  for (std::size_t i = 1; i < smoothed.points_m.size(); ++i) {
    EXPECT_LE((smoothed.points_m[i] - smoothed.points_m[i - 1]).norm(), config.step_m + 1e-9);
  }
  EXPECT_EQ(smoothed.points_m.front(), waypoints.front());
  EXPECT_EQ(smoothed.points_m.back(), waypoints.back());
}

TEST(PathSmoothing, ObstaclesNearTheCornerShrinkTheFilletOrKeepItSharp) {
  const std::vector<Eigen::Vector2d> waypoints = {{2.0, 2.0}, {10.0, 2.0}, {10.0, 10.0}};
  PathSmoothingConfig config;
  config.min_turning_radius_m = 1.0;
  config.max_turning_radius_m = 5.0;
  // A post where the 5 m fillet would pass (its middle is at (8.54, 3.46));
  // tighter fillets pass between the post and the corner.
  const OccupancyGrid post = field({{8.3, 3.2, 8.8, 3.7}});
  const SmoothedPath shrunk = fillet_corners(post, waypoints, config);
  ASSERT_EQ(shrunk.fillets.size(), 1u);
  EXPECT_LT(shrunk.fillets[0].radius_m, 5.0);
  EXPECT_GE(shrunk.fillets[0].radius_m, 1.0);
  expect_free(post, shrunk.points_m);
  // A block filling the inside of the corner 0.2 m from the path: every
  // fillet of 1 m or more cuts into it, so the corner stays sharp.
  const OccupancyGrid tight = field({{5.0, 2.3, 9.8, 9.0}});
  ASSERT_TRUE(tight.segment_free(waypoints[0], waypoints[1]));
  const SmoothedPath sharp = fillet_corners(tight, waypoints, config);
  EXPECT_TRUE(sharp.fillets.empty());
  EXPECT_EQ(sharp.sharp_corners, 1);
  expect_free(tight, sharp.points_m);
  EXPECT_NEAR(length(sharp.points_m), 16.0, 1e-9);
  // Segments too short for the minimum radius: sharp as well.
  const std::vector<Eigen::Vector2d> short_legs = {{2.0, 2.0}, {2.5, 2.0}, {2.5, 2.5}};
  EXPECT_EQ(fillet_corners(field({}), short_legs, config).sharp_corners, 1);
}

TEST(PathSmoothing, SmoothsAnRrtStarPathIntoADrivableOne) {
  const OccupancyGrid grid = inflate(field({{0.0, 9.5, 14.0, 10.5}, {5.0, 14.0, 6.0, 17.0}}), 0.3);
  RrtStarConfig rrt;
  rrt.seed = 3;
  rrt.max_iterations = 3000;
  const RrtStarResult tree = rrt_star(grid, {2.0, 2.0}, {3.0, 18.0}, rrt);
  ASSERT_EQ(tree.status, RrtStarStatus::solved);
  PathSmoothingConfig config;
  config.min_turning_radius_m = 1.5;
  const SmoothedPath smoothed = smooth_path(grid, tree.path_m, config);
  EXPECT_LT(smoothed.waypoints_m.size(), tree.path_m.size());
  expect_free(grid, smoothed.points_m);
  EXPECT_LE(smoothed.length_m, tree.cost_m + 1e-9);
  EXPECT_EQ(smoothed.points_m.front(), tree.path_m.front());
  EXPECT_EQ(smoothed.points_m.back(), tree.path_m.back());
  std::vector<Eigen::Vector2d> sharp;
  for (std::size_t c = 1; c + 1 < smoothed.waypoints_m.size(); ++c) {
    bool rounded = false;
    for (const Fillet& f : smoothed.fillets) rounded = rounded || f.corner == c;
    if (!rounded) sharp.push_back(smoothed.waypoints_m[c]);
  }
  EXPECT_EQ(static_cast<int>(sharp.size()), smoothed.sharp_corners);
  EXPECT_LE(max_curvature(smoothed.points_m, sharp), 1.02 / config.min_turning_radius_m);
}

TEST(PathSmoothing, RejectsBadConfigs) {
  PathSmoothingConfig config;
  config.max_turning_radius_m = 0.5;  // below the minimum
  EXPECT_THROW(validate(config), std::invalid_argument);
  config = {};
  config.radius_ratio = 1.0;
  EXPECT_THROW(validate(config), std::invalid_argument);
  const std::vector<Eigen::Vector2d> one = {{1.0, 1.0}};
  EXPECT_EQ(smooth_path(field({}), one).points_m, one);
}

}  // namespace
}  // namespace campo
