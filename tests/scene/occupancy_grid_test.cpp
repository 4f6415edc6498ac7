#include "scene/occupancy_grid.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "campo/random.hpp"
#include "campo/scene.hpp"
#include "campo/scene_loader.hpp"

namespace campo {
namespace {

Shape make_shape(ShapeType type, const Eigen::Vector3d& centre, const std::string& alias) {
  Shape shape;
  shape.alias = alias;
  shape.type = type;
  shape.pose = Eigen::Isometry3d::Identity();
  shape.pose.translation() = centre;
  return shape;
}

Shape ground_plane(double z = 0.0) { return make_shape(ShapeType::plane, {0.0, 0.0, z}, "ground"); }

Shape cuboid(const Eigen::Vector3d& centre, const Eigen::Vector3d& size, double yaw_rad = 0.0) {
  Shape s = make_shape(ShapeType::cuboid, centre, "box");
  s.size_m = size;
  s.pose.linear() = Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return s;
}

/// Cells with any of their nine half-cell lattice points (corners, edge
/// midpoints, centre) strictly inside a footprint, as the expectation.
std::vector<std::uint8_t> expected_cells(const OccupancyGrid& grid,
                                         const std::function<bool(const Eigen::Vector2d&)>& inside) {
  std::vector<std::uint8_t> cells(grid.occupied.size(), 0);
  for (int row = 0; row < grid.rows; ++row) {
    for (int col = 0; col < grid.cols; ++col) {
      bool hit = false;
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          hit = hit || inside(grid.centre_of(col, row) + 0.5 * grid.resolution_m * Eigen::Vector2d(dx, dy));
        }
      }
      cells[static_cast<std::size_t>(row) * grid.cols + col] = hit ? 1 : 0;
    }
  }
  return cells;
}

/// Footprints shrink by this in the expectations: lattice points on a
/// shape's side (up to rounding) count as outside, as in the grid.
constexpr double kIn = 1e-7;

int count(const std::vector<std::uint8_t>& cells) { return static_cast<int>(std::count(cells.begin(), cells.end(), 1)); }

TEST(OccupancyGrid, CellOfAndCentreOfAreInverse) {
  OccupancyGrid grid;
  grid.cols = 10;
  grid.rows = 5;
  grid.resolution_m = 0.25;
  grid.origin_m = {-1.0, 2.0};
  grid.occupied.assign(50, 0);
  EXPECT_EQ(grid.cell_of({-1.0, 2.0}), Eigen::Vector2i(0, 0));
  EXPECT_EQ(grid.cell_of({-0.76, 2.26}), Eigen::Vector2i(0, 1));
  EXPECT_EQ(grid.cell_of({-1.01, 1.99}), Eigen::Vector2i(-1, -1));
  EXPECT_TRUE(grid.centre_of(3, 4).isApprox(Eigen::Vector2d(-0.125, 3.125)));
  EXPECT_EQ(grid.cell_of(grid.centre_of(7, 2)), Eigen::Vector2i(7, 2));
  EXPECT_FALSE(grid.is_occupied(9, 4));
  EXPECT_TRUE(grid.is_occupied(10, 4));  // outside counts as occupied
  EXPECT_TRUE(grid.is_occupied(Eigen::Vector2d(-2.0, 2.5)));
}

// One shape of each kind between the ground and the vehicle's height, each
// checked cell by cell against its footprint written out by hand.
TEST(OccupancyGrid, ShapesInTheHeightBandAreRasterizedCellExactly) {
  Scene scene;
  scene.shapes.push_back(ground_plane());
  scene.shapes.push_back(cuboid({2.0, 3.0, 0.25}, {1.0, 0.6, 0.5}));
  Shape cylinder = make_shape(ShapeType::cylinder, {-2.0, -1.0, 1.0}, "cylinder");
  cylinder.radius_m = 0.5;
  cylinder.height_m = 2.0;
  scene.shapes.push_back(cylinder);
  OccupancyConfig config;  // 0.1 m cells, band [0.05, 1.0] m
  const OccupancyGrid grid = build_occupancy_grid(scene, config);

  // Bounds: footprints x in [-2.5, 2.5], y in [-1.5, 3.3], plus 1 m.
  EXPECT_NEAR(grid.origin_m.x(), -3.5, 1e-9);
  EXPECT_NEAR(grid.origin_m.y(), -2.5, 1e-9);
  EXPECT_EQ(grid.cols, 70);
  EXPECT_EQ(grid.rows, 68);
  const auto expected = expected_cells(grid, [](const Eigen::Vector2d& p) {
    const bool in_box = std::abs(p.x() - 2.0) < 0.5 - kIn && std::abs(p.y() - 3.0) < 0.3 - kIn;
    const bool in_cylinder = (p - Eigen::Vector2d(-2.0, -1.0)).norm() < 0.5 - kIn;
    return in_box || in_cylinder;
  });
  EXPECT_EQ(grid.occupied, expected);
  // The box's sides lie on cell edges: exactly its 10 x 6 cells.
  EXPECT_EQ(count(grid.occupied) - 60, count(expected_cells(grid, [](const Eigen::Vector2d& p) {
              return (p - Eigen::Vector2d(-2.0, -1.0)).norm() < 0.5 - kIn;
            })));
  EXPECT_TRUE(grid.is_occupied(Eigen::Vector2d(1.55, 2.75)));
  EXPECT_FALSE(grid.is_occupied(Eigen::Vector2d(1.45, 2.75)));
  EXPECT_FALSE(grid.is_occupied(Eigen::Vector2d(2.45, 3.35)));
}

// A post as thin as a cell, centred on a cell corner, and a wall as thick as
// a cell, centred on a cell edge, still show up.
TEST(OccupancyGrid, ThinObstaclesOffTheCellCentresDoNotVanish) {
  Scene scene;
  Shape post = make_shape(ShapeType::cylinder, {1.0, 1.0, 0.5}, "post");
  post.radius_m = 0.05;
  scene.shapes.push_back(post);
  scene.shapes.push_back(cuboid({3.0, 1.0, 0.5}, {0.1, 2.0, 1.0}));
  const OccupancyGrid grid = build_occupancy_grid(scene);
  EXPECT_EQ(count(grid.occupied), 4 + 2 * 20);
  EXPECT_TRUE(grid.is_occupied(Eigen::Vector2d(0.95, 0.95)));
  EXPECT_TRUE(grid.is_occupied(Eigen::Vector2d(1.05, 1.05)));
  EXPECT_TRUE(grid.is_occupied(Eigen::Vector2d(2.95, 1.0)));
  EXPECT_TRUE(grid.is_occupied(Eigen::Vector2d(3.05, 1.0)));
}

TEST(OccupancyGrid, OverhangsAboveTheVehicleAndSlabsBelowTheClearanceAreLeftOut) {
  Scene scene;
  scene.shapes.push_back(ground_plane());
  scene.shapes.push_back(cuboid({0.0, 0.0, 0.25}, {0.4, 0.4, 0.5}));  // seen
  scene.shapes.push_back(cuboid({3.0, 0.0, 1.6}, {1.0, 1.0, 0.8}));   // z in [1.2, 2.0]: above
  scene.shapes.push_back(cuboid({0.0, 3.0, 0.015}, {1.0, 1.0, 0.03})); // z in [0, 0.03]: terrain
  Shape dynamic = cuboid({-3.0, 0.0, 0.5}, {0.4, 0.4, 1.0});
  dynamic.is_static = false;
  dynamic.mass_kg = 1.0;
  scene.shapes.push_back(dynamic);
  Mover mover;
  mover.shape = cuboid({0.0, -3.0, 0.5}, {0.4, 0.4, 1.0});
  mover.path_m = {{0.0, -3.0, 0.5}, {1.0, -3.0, 0.5}};
  scene.movers.push_back(mover);

  const OccupancyGrid grid = build_occupancy_grid(scene);
  const auto expected = expected_cells(grid, [](const Eigen::Vector2d& p) {
    return std::abs(p.x()) < 0.2 - kIn && std::abs(p.y()) < 0.2 - kIn;
  });
  EXPECT_EQ(grid.occupied, expected);
  EXPECT_EQ(count(grid.occupied), 16);
}

TEST(OccupancyGrid, SpheresConesAndTiltedShapesUseTheirSectionInTheBand) {
  Scene scene;
  scene.shapes.push_back(ground_plane());
  // Sphere reaching down to 0.8 m: inside the band (below 1 m) where
  // 1.3 - sqrt(0.25 - rho^2) < 1, i.e. rho < 0.4.
  Shape sphere = make_shape(ShapeType::sphere, {4.0, 0.0, 1.3}, "sphere");
  sphere.radius_m = 0.5;
  scene.shapes.push_back(sphere);
  // Cone, base radius 0.6 on the ground, apex at 2 m: its top 2 - rho / 0.3
  // is above the 0.05 m clearance where rho < 0.585.
  Shape cone = make_shape(ShapeType::cone, {0.0, 0.0, 1.0}, "cone");
  cone.radius_m = 0.6;
  cone.height_m = 2.0;
  scene.shapes.push_back(cone);
  // A log: cylinder lying along x, radius 0.3, on the ground.
  Shape log = make_shape(ShapeType::cylinder, {0.0, 3.0, 0.3}, "log");
  log.radius_m = 0.3;
  log.height_m = 2.0;
  log.pose.linear() = Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();
  scene.shapes.push_back(log);
  // A box turned by 30 degrees.
  const double yaw = std::numbers::pi / 6;
  scene.shapes.push_back(cuboid({-4.0, 0.0, 0.5}, {1.2, 0.5, 1.0}, yaw));

  const OccupancyGrid grid = build_occupancy_grid(scene);
  const auto expected = expected_cells(grid, [&](const Eigen::Vector2d& p) {
    const bool in_sphere = (p - Eigen::Vector2d(4.0, 0.0)).norm() < 0.4 - kIn;
    const bool in_cone = p.norm() < 0.585 - kIn;
    const bool in_log = std::abs(p.x()) < 1.0 - kIn && std::abs(p.y() - 3.0) < 0.3 - kIn;
    const Eigen::Vector2d q = Eigen::Rotation2Dd(-yaw) * (p - Eigen::Vector2d(-4.0, 0.0));
    const bool in_box = std::abs(q.x()) < 0.6 - kIn && std::abs(q.y()) < 0.25 - kIn;
    return in_sphere || in_cone || in_log || in_box;
  });
  EXPECT_EQ(grid.occupied, expected);
}

TEST(OccupancyGrid, TheBandFollowsTheGround) {
  Scene scene;
  scene.shapes.push_back(ground_plane(0.4));
  scene.shapes.push_back(cuboid({0.0, 0.0, 0.25}, {0.4, 0.4, 0.5}));  // top 0.5 > 0.4 + 0.05
  scene.shapes.push_back(cuboid({2.0, 0.0, 0.2}, {0.4, 0.4, 0.4}));   // top 0.4: under the ground
  const OccupancyGrid grid = build_occupancy_grid(scene);
  EXPECT_TRUE(grid.is_occupied(Eigen::Vector2d(0.0, 0.0)));
  EXPECT_FALSE(grid.is_occupied(Eigen::Vector2d(2.0, 0.0)));
  EXPECT_EQ(count(grid.occupied), 16);
}

TEST(OccupancyGrid, BoundsCoverTheVehiclesMissionAndRejectBadConfigs) {
  Scene scene;
  scene.shapes.push_back(cuboid({0.0, 0.0, 0.25}, {0.4, 0.4, 0.5}));
  VehicleDef rover;
  rover.type = VehicleType::rover;
  rover.pose.translation() = Eigen::Vector3d(-5.0, 0.0, 0.0);
  rover.mission.push_back({Eigen::Vector3d(7.03, 2.0, 0.0), std::nullopt});
  scene.vehicles.push_back(rover);
  OccupancyConfig config;
  config.resolution_m = 0.5;
  config.margin_m = 0.0;
  const OccupancyGrid grid = build_occupancy_grid(scene, config);
  EXPECT_DOUBLE_EQ(grid.origin_m.x(), -5.0);
  EXPECT_DOUBLE_EQ(grid.origin_m.y(), -0.5);
  EXPECT_EQ(grid.cols, 25);  // to 7.5 >= 7.03
  EXPECT_EQ(grid.rows, 5);   // to 2.0
  EXPECT_EQ(build_occupancy_grid(Scene{}).cols, 0);

  config.resolution_m = 0.0;
  EXPECT_THROW(build_occupancy_grid(scene, config), std::invalid_argument);
  config.resolution_m = 1e-4;
  config.max_cells = 1000;
  EXPECT_THROW(build_occupancy_grid(scene, config), std::invalid_argument);
}

OccupancyGrid random_grid(int cols, int rows, double resolution, double fill, std::uint64_t seed) {
  OccupancyGrid grid;
  grid.cols = cols;
  grid.rows = rows;
  grid.resolution_m = resolution;
  grid.origin_m = {-1.3, 0.7};
  grid.occupied.resize(static_cast<std::size_t>(cols) * rows);
  Rng rng(seed);
  for (auto& cell : grid.occupied) cell = rng.bernoulli(fill) ? 1 : 0;
  return grid;
}

TEST(OccupancyGrid, InflationMatchesBruteForceDistances) {
  const OccupancyGrid grid = random_grid(60, 45, 0.1, 0.01, 7);
  // Radii between and exactly at cell distances (1, sqrt 2, 2, sqrt 5 cells).
  for (const double radius : {0.1, std::sqrt(2.0) * 0.1, 0.17, 0.2, std::sqrt(5.0) * 0.1, 0.33, 0.75}) {
    SCOPED_TRACE(radius);
    const OccupancyGrid inflated = inflate(grid, radius);
    ASSERT_EQ(inflated.occupied.size(), grid.occupied.size());
    for (int row = 0; row < grid.rows; ++row) {
      for (int col = 0; col < grid.cols; ++col) {
        bool near = false;
        for (int r = 0; r < grid.rows && !near; ++r) {
          for (int c = 0; c < grid.cols && !near; ++c) {
            near = grid.is_occupied(c, r) && (grid.centre_of(c, r) - grid.centre_of(col, row)).norm() <= radius + 1e-9;
          }
        }
        ASSERT_EQ(inflated.is_occupied(col, row), near) << col << ", " << row;
      }
    }
  }
  EXPECT_EQ(inflate(grid, 0.0).occupied, grid.occupied);
  EXPECT_THROW(inflate(grid, -0.1), std::invalid_argument);
}

/// Whether the segment meets the closed square of a cell (Liang-Barsky clip).
bool touches(const OccupancyGrid& grid, int col, int row, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d lo = grid.origin_m + grid.resolution_m * Eigen::Vector2d(col, row);
  const Eigen::Vector2d hi = lo + Eigen::Vector2d::Constant(grid.resolution_m);
  double t0 = 0.0, t1 = 1.0;
  const Eigen::Vector2d d = b - a;
  for (int i = 0; i < 2; ++i) {
    if (d[i] == 0.0) {
      if (a[i] < lo[i] || a[i] > hi[i]) return false;
      continue;
    }
    double ta = (lo[i] - a[i]) / d[i], tb = (hi[i] - a[i]) / d[i];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  return t0 <= t1;
}

TEST(OccupancyGrid, SegmentFreeChecksExactlyTheCellsTheSegmentTouches) {
  const OccupancyGrid grid = random_grid(40, 30, 0.25, 0.03, 11);
  Rng rng(5);
  const Eigen::Vector2d lo = grid.origin_m;
  const Eigen::Vector2d hi = lo + grid.resolution_m * Eigen::Vector2d(grid.cols, grid.rows);
  int free_count = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const Eigen::Vector2d a(rng.uniform(lo.x(), hi.x()), rng.uniform(lo.y(), hi.y()));
    // Short segments too, so that many are free.
    const double reach = trial % 2 == 0 ? 1.0 : 12.0;
    const Eigen::Vector2d b = (a + Eigen::Vector2d(rng.uniform(-reach, reach), rng.uniform(-reach, reach)))
                                  .cwiseMax(lo + Eigen::Vector2d::Constant(1e-9))
                                  .cwiseMin(hi - Eigen::Vector2d::Constant(1e-9));
    bool exact_free = true;
    for (int row = 0; row < grid.rows && exact_free; ++row) {
      for (int col = 0; col < grid.cols && exact_free; ++col) {
        exact_free = !(grid.is_occupied(col, row) && touches(grid, col, row, a, b));
      }
    }
    ASSERT_EQ(grid.segment_free(a, b), exact_free) << a.transpose() << " -> " << b.transpose();
    ASSERT_EQ(grid.segment_free(b, a), exact_free);
    // Dense samples of a free segment all land in free cells.
    if (exact_free) {
      ++free_count;
      for (int k = 0; k <= 2000; ++k) ASSERT_FALSE(grid.is_occupied(Eigen::Vector2d(a + (b - a) * (k / 2000.0))));
    }
  }
  EXPECT_GT(free_count, 50);
}

TEST(OccupancyGrid, SegmentFreeBlocksCornerCuttingAndLeavingTheGrid) {
  OccupancyGrid grid;
  grid.cols = grid.rows = 4;
  grid.resolution_m = 1.0;
  grid.occupied.assign(16, 0);
  grid.occupied[1 * 4 + 2] = 1;  // (2, 1)
  grid.occupied[2 * 4 + 1] = 1;  // (1, 2)
  // Centre to centre through the corner (2, 2) shared by the two occupied cells.
  EXPECT_FALSE(grid.segment_free({1.5, 1.5}, {2.5, 2.5}));
  EXPECT_TRUE(grid.segment_free({0.5, 0.5}, {1.5, 1.5}));
  EXPECT_TRUE(grid.segment_free({0.5, 3.5}, {3.5, 3.5}));  // along a free row
  EXPECT_TRUE(grid.segment_free({0.5, 0.5}, {0.5, 0.5}));
  EXPECT_FALSE(grid.segment_free({3.5, 3.5}, {4.5, 3.5}));
  EXPECT_FALSE(grid.segment_free({0.5, 0.5}, {0.5, std::nan("")}));
}

// The bundled vineyard: 20 rows 4 m apart plus the fence, seen across the
// field half way along the rows, and only the fence in the headlands.
TEST(OccupancyGrid, VineyardCrossSectionShowsTheRowsAndTheFence) {
  const Scene scene = load_scene(std::string(CAMPO_SOURCE_DIR) + "/scenes/vineyard.json");
  const OccupancyGrid grid = build_occupancy_grid(scene);
  EXPECT_GT(static_cast<double>(grid.cols) * grid.rows, 1.0e6);
  const auto runs_across = [&](double y) {
    std::vector<double> starts;
    const int row = grid.cell_of({0.0, y}).y();
    for (int col = 0; col < grid.cols; ++col) {
      if (grid.is_occupied(col, row) && (col == 0 || !grid.is_occupied(col - 1, row))) {
        starts.push_back(grid.centre_of(col, row).x());
      }
    }
    return starts;
  };
  const std::vector<double> middle = runs_across(0.05);
  ASSERT_EQ(middle.size(), 22u);
  EXPECT_NEAR(middle.front(), -50.0, 0.1);  // west fence
  for (int i = 0; i < 20; ++i) EXPECT_NEAR(middle[i + 1], (i - 9.5) * 4.0 - 0.3, 0.1);  // canopy west edge
  EXPECT_NEAR(middle.back(), 50.0, 0.1);  // east fence
  EXPECT_EQ(runs_across(46.05).size(), 2u);
}

}  // namespace
}  // namespace campo
