#include "scene/generators.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>
#include <stdexcept>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace campo {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

/// Exact equality of everything a generator sets, poses bit for bit.
void expect_identical(const std::vector<Shape>& a, const std::vector<Shape>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    SCOPED_TRACE(a[i].alias);
    EXPECT_EQ(a[i].alias, b[i].alias);
    EXPECT_EQ(a[i].type, b[i].type);
    EXPECT_EQ(std::memcmp(a[i].pose.matrix().data(), b[i].pose.matrix().data(), sizeof(double) * 16), 0);
    EXPECT_EQ(a[i].size_m, b[i].size_m);
    EXPECT_EQ(a[i].radius_m, b[i].radius_m);
    EXPECT_EQ(a[i].height_m, b[i].height_m);
    EXPECT_EQ(a[i].color.r, b[i].color.r);
    EXPECT_EQ(a[i].color.g, b[i].color.g);
    EXPECT_EQ(a[i].color.b, b[i].color.b);
  }
}

bool alias_has(const Shape& shape, const std::string& part) { return shape.alias.find(part) != std::string::npos; }

std::vector<Shape> select(const std::vector<Shape>& shapes, const std::string& part) {
  std::vector<Shape> out;
  std::copy_if(shapes.begin(), shapes.end(), std::back_inserter(out),
               [&](const Shape& s) { return alias_has(s, part); });
  return out;
}

/// World x, y of the four footprint corners of a (possibly yawed) cuboid.
std::vector<Eigen::Vector2d> footprint(const Shape& box) {
  std::vector<Eigen::Vector2d> corners;
  for (const double sx : {-0.5, 0.5}) {
    for (const double sy : {-0.5, 0.5}) {
      corners.push_back((box.pose * Eigen::Vector3d(sx * box.size_m.x(), sy * box.size_m.y(), 0.0)).head<2>());
    }
  }
  return corners;
}

// --- rolling terrain --------------------------------------------------------

RollingTerrainConfig small_terrain(std::uint64_t seed) {
  RollingTerrainConfig config;
  config.size_m = {60.0, 40.0};
  config.spacing_m = 0.5;
  config.amplitude_m = 2.5;
  config.wavelength_m = 15.0;
  config.waves = 5;
  config.seed = seed;
  return config;
}

TEST(GeneratorsRollingTerrain, SameSeedGivesSameBitsOtherSeedDiffers) {
  const HeightGrid a = make_rolling_terrain(small_terrain(7));
  const HeightGrid b = make_rolling_terrain(small_terrain(7));
  const HeightGrid c = make_rolling_terrain(small_terrain(8));
  ASSERT_EQ(a.heights_m.size(), b.heights_m.size());
  EXPECT_EQ(std::memcmp(a.heights_m.data(), b.heights_m.data(), a.heights_m.size() * sizeof(double)), 0);
  ASSERT_EQ(a.heights_m.size(), c.heights_m.size());
  EXPECT_NE(a.heights_m, c.heights_m);
}

TEST(GeneratorsRollingTerrain, PeakIsExactlyTheAmplitude) {
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    const HeightGrid grid = make_rolling_terrain(small_terrain(seed));
    EXPECT_EQ(std::max(grid.max_height_m(), -grid.min_height_m()), 2.5) << "seed " << seed;
  }
}

TEST(GeneratorsRollingTerrain, VertexCountIsRoundedSizeOverSpacingPlusOne) {
  RollingTerrainConfig config;
  config.size_m = {100.0, 50.0};
  config.spacing_m = 0.5;
  const HeightGrid even = make_rolling_terrain(config);
  EXPECT_EQ(even.cols, 201);
  EXPECT_EQ(even.rows, 101);
  EXPECT_EQ(even.spacing_x_m, 0.5);
  EXPECT_EQ(even.heights_m.size(), 201u * 101u);

  // 10.2 / 0.5 = 20.4 cells: 20 cells, stretched to span the size exactly.
  config.size_m = {10.0, 10.2};
  const HeightGrid stretched = make_rolling_terrain(config);
  EXPECT_EQ(stretched.cols, 21);
  EXPECT_EQ(stretched.rows, 21);
  EXPECT_DOUBLE_EQ(stretched.size_y_m(), 10.2);
}

TEST(GeneratorsRollingTerrain, SlopeIsBoundedByTheShortestWavelength) {
  // Bernstein: a sum of waves no shorter than 0.7 wavelength has slope at most
  // 2 pi / (0.7 wavelength) times its peak; 10 % covers the peak between samples.
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const RollingTerrainConfig config = small_terrain(seed);
    const HeightGrid grid = make_rolling_terrain(config);
    const double bound = 2.0 * std::numbers::pi * config.amplitude_m / (0.7 * config.wavelength_m) * 1.1;
    double steepest = 0.0;
    for (int r = 0; r < grid.rows; ++r) {
      for (int c = 0; c < grid.cols; ++c) {
        if (c + 1 < grid.cols) steepest = std::max(steepest, std::abs(grid.at(c + 1, r) - grid.at(c, r)) / grid.spacing_x_m);
        if (r + 1 < grid.rows) steepest = std::max(steepest, std::abs(grid.at(c, r + 1) - grid.at(c, r)) / grid.spacing_y_m);
      }
    }
    EXPECT_LE(steepest, bound) << "seed " << seed;
    EXPECT_GT(steepest, 0.0);
  }
}

TEST(GeneratorsRollingTerrain, RejectsBadConfig) {
  RollingTerrainConfig config;
  config.waves = 0;
  EXPECT_THAT([&] { make_rolling_terrain(config); },
              ThrowsMessage<std::invalid_argument>(HasSubstr("waves must be in [1, 32], got 0")));
  config = {};
  config.spacing_m = 0.0;
  EXPECT_THAT([&] { make_rolling_terrain(config); },
              ThrowsMessage<std::invalid_argument>(HasSubstr("spacing must be finite and > 0")));
  config = {};
  config.size_m = {1e5, 1e5};
  config.spacing_m = 1.0;
  EXPECT_THAT([&] { make_rolling_terrain(config); },
              ThrowsMessage<std::invalid_argument>(HasSubstr("more than 16777216 vertices")));
}

// --- trees ------------------------------------------------------------------

double hills(double x, double y) { return 0.8 * std::sin(0.3 * x) + 0.2 * y; }

TreesConfig forest(std::uint64_t seed) {
  TreesConfig config;
  config.area_min_m = {-15.0, -15.0};
  config.area_max_m = {15.0, 15.0};
  config.count = 40;
  config.min_spacing_m = 2.0;
  config.keep_out = {{0.0, 0.0, 5.0}, {10.0, -10.0, 3.0}};
  config.seed = seed;
  return config;
}

TEST(GeneratorsTrees, SameSeedGivesSameShapesOtherSeedDiffers) {
  const auto a = make_trees(forest(3), "forest", hills);
  expect_identical(a, make_trees(forest(3), "forest", hills));
  const auto c = make_trees(forest(4), "forest", hills);
  ASSERT_EQ(a.size(), c.size());
  EXPECT_NE(a[0].pose.translation(), c[0].pose.translation());
}

TEST(GeneratorsTrees, CountSpacingAreaAndKeepOut) {
  const TreesConfig config = forest(5);
  const auto shapes = make_trees(config, "forest", hills);
  ASSERT_EQ(shapes.size(), 80u);
  EXPECT_EQ(shapes[0].alias, "forest/tree0/trunk");
  EXPECT_EQ(shapes[1].alias, "forest/tree0/crown");
  EXPECT_EQ(shapes[79].alias, "forest/tree39/crown");
  const auto trunks = select(shapes, "/trunk");
  ASSERT_EQ(trunks.size(), 40u);
  for (std::size_t i = 0; i < trunks.size(); ++i) {
    const Eigen::Vector2d p = trunks[i].pose.translation().head<2>();
    EXPECT_GE(p.x(), -15.0);
    EXPECT_LT(p.x(), 15.0);
    EXPECT_GE(p.y(), -15.0);
    EXPECT_LT(p.y(), 15.0);
    for (const auto& k : config.keep_out) EXPECT_GE((p - k.head<2>()).norm(), k.z()) << trunks[i].alias;
    for (std::size_t j = i + 1; j < trunks.size(); ++j) {
      EXPECT_GE((p - trunks[j].pose.translation().head<2>()).norm(), 2.0) << trunks[i].alias << " " << trunks[j].alias;
    }
  }
}

TEST(GeneratorsTrees, TrunksStandOnTheGroundUnderSphereCrowns) {
  const TreesConfig config = forest(6);
  const auto shapes = make_trees(config, "forest", hills);
  for (std::size_t i = 0; i < shapes.size(); i += 2) {
    const Shape& trunk = shapes[i];
    const Shape& crown = shapes[i + 1];
    SCOPED_TRACE(trunk.alias);
    ASSERT_EQ(trunk.type, ShapeType::cylinder);
    ASSERT_EQ(crown.type, ShapeType::sphere);
    const Eigen::Vector3d p = trunk.pose.translation();
    const double ground = hills(p.x(), p.y());
    const double base = p.z() - 0.5 * trunk.height_m;
    const double top = p.z() + 0.5 * trunk.height_m;
    EXPECT_NEAR(base, ground - 0.2, 1e-9);
    EXPECT_GT(top, ground + 1.9);
    EXPECT_GE(trunk.radius_m, 0.15);
    EXPECT_LE(trunk.radius_m, 0.3);
    EXPECT_GE(crown.radius_m, 0.8);
    EXPECT_LE(crown.radius_m, 1.6);
    EXPECT_EQ(crown.pose.translation().head<2>(), p.head<2>());
    EXPECT_NEAR(crown.pose.translation().z(), top + 0.6 * crown.radius_m, 1e-9);
    // Brown trunk, green crown.
    EXPECT_GT(trunk.color.r, trunk.color.b);
    EXPECT_GT(crown.color.g, crown.color.r);
    EXPECT_TRUE(trunk.source.empty());
  }
}

TEST(GeneratorsTrees, ConeCrownStartsAtSevenTenthsOfTheTrunk) {
  TreesConfig config = forest(7);
  config.crown = CrownShape::cone;
  config.crown_height_ratio = 2.5;
  const auto shapes = make_trees(config, "pines", hills);
  for (std::size_t i = 0; i < shapes.size(); i += 2) {
    const Shape& trunk = shapes[i];
    const Shape& crown = shapes[i + 1];
    ASSERT_EQ(crown.type, ShapeType::cone);
    const Eigen::Vector3d p = trunk.pose.translation();
    const double ground = hills(p.x(), p.y());
    const double trunk_height = trunk.height_m - 0.2;
    EXPECT_NEAR(crown.height_m, 2.5 * crown.radius_m, 1e-12);
    EXPECT_NEAR(crown.pose.translation().z() - 0.5 * crown.height_m, ground + 0.7 * trunk_height, 1e-9);
  }
}

TEST(GeneratorsTrees, ImpossiblePlacementThrows) {
  TreesConfig config;
  config.area_min_m = {0.0, 0.0};
  config.area_max_m = {5.0, 5.0};
  config.count = 100;
  config.min_spacing_m = 2.0;
  EXPECT_THAT([&] { make_trees(config, "t", hills); },
              ThrowsMessage<std::runtime_error>(AllOf(HasSubstr("could not place 100 trees with min spacing 2 m"),
                                                      HasSubstr("in area [0, 5] x [0, 5] m; placed "))));
}

TEST(GeneratorsTrees, ZeroTreesAndBadConfig) {
  TreesConfig config;
  config.count = 0;
  EXPECT_TRUE(make_trees(config, "t", hills).empty());
  config.trunk_radius_m = {0.3, 0.1};
  EXPECT_THAT([&] { make_trees(config, "t", hills); },
              ThrowsMessage<std::invalid_argument>(HasSubstr("trunk_radius must be a range")));
}

TEST(GeneratorsTrees, RejectsGroundWithoutHeight) {
  const auto no_ground = [](double, double) { return std::nan(""); };
  EXPECT_THAT([&] { make_trees(forest(1), "t", no_ground); },
              ThrowsMessage<std::runtime_error>(HasSubstr("is not finite")));
}

// --- vineyard ---------------------------------------------------------------

VineyardConfig small_vineyard(std::uint64_t seed) {
  VineyardConfig config;
  config.field_size_m = {60.0, 40.0};
  config.row_count = 8;
  config.row_spacing_m = 3.0;
  config.headland_m = 5.0;  // rows 30 m long
  config.post_spacing_m = 5.0;
  config.obstacle_count = 30;
  config.seed = seed;
  return config;
}

TEST(GeneratorsVineyard, ExpectedCounts) {
  const auto shapes = make_vineyard(small_vineyard(1), "vy");
  // 30 m rows with posts every 5 m including both ends: 7 per row.
  EXPECT_EQ(select(shapes, "/post").size(), 8u * 7u);
  EXPECT_EQ(select(shapes, "/canopy").size(), 8u);
  EXPECT_EQ(select(shapes, "/fence/").size(), 4u);
  EXPECT_EQ(select(shapes, "/obstacle").size(), 30u);
  EXPECT_EQ(shapes.size(), 56u + 8u + 4u + 30u);
  EXPECT_EQ(shapes.front().alias, "vy/row0/post0");
  EXPECT_EQ(shapes.back().alias, "vy/obstacle29");
}

TEST(GeneratorsVineyard, SameSeedGivesSameShapesOtherSeedMovesObstacles) {
  const auto a = make_vineyard(small_vineyard(1), "vy");
  expect_identical(a, make_vineyard(small_vineyard(1), "vy"));
  const auto b = make_vineyard(small_vineyard(2), "vy");
  EXPECT_NE(select(a, "/obstacle")[0].pose.translation(), select(b, "/obstacle")[0].pose.translation());
}

TEST(GeneratorsVineyard, RowsAreEquispacedCentredAndPostedAtBothEnds) {
  const VineyardConfig config = small_vineyard(1);
  const auto shapes = make_vineyard(config, "vy");
  const auto canopies = select(shapes, "/canopy");
  for (std::size_t i = 0; i < canopies.size(); ++i) {
    const Shape& canopy = canopies[i];
    EXPECT_NEAR(canopy.pose.translation().x(), (i - 3.5) * 3.0, 1e-12);
    EXPECT_EQ(canopy.pose.translation().y(), 0.0);
    EXPECT_NEAR(canopy.pose.translation().z() - 0.5 * canopy.size_m.z(), 0.6, 1e-12);
    EXPECT_NEAR(canopy.pose.translation().z() + 0.5 * canopy.size_m.z(), 1.8, 1e-12);
    EXPECT_EQ(canopy.size_m.x(), 0.6);
    EXPECT_EQ(canopy.size_m.y(), 30.0);
    const auto posts = select(shapes, "/row" + std::to_string(i) + "/post");
    ASSERT_EQ(posts.size(), 7u);
    EXPECT_NEAR(posts.front().pose.translation().y(), -15.0, 1e-12);
    EXPECT_NEAR(posts.back().pose.translation().y(), 15.0, 1e-12);
    for (const Shape& post : posts) {
      EXPECT_EQ(post.pose.translation().x(), canopy.pose.translation().x());
      EXPECT_NEAR(post.pose.translation().z(), 0.5 * post.height_m, 1e-12);
    }
  }
}

// Every obstacle lies between two canopies with 0.3 m clearance on both
// sides, and a passage at least `passage_m` wide on one side.
void expect_obstacles_between_rows(const VineyardConfig& config, double passage_m) {
  const auto shapes = make_vineyard(config, "vy");
  const auto canopies = select(shapes, "/canopy");
  const auto obstacles = select(shapes, "/obstacle");
  ASSERT_EQ(obstacles.size(), static_cast<std::size_t>(config.obstacle_count));
  for (const Shape& obstacle : obstacles) {
    SCOPED_TRACE(obstacle.alias);
    for (int k = 0; k < 3; ++k) {
      EXPECT_GE(obstacle.size_m[k], config.obstacle_size_m[0]);
      EXPECT_LE(obstacle.size_m[k], config.obstacle_size_m[1]);
    }
    EXPECT_NEAR(obstacle.pose.translation().z(), 0.5 * obstacle.size_m.z(), 1e-12);
    const auto corners = footprint(obstacle);
    // The gap this obstacle is in: between the canopies on either side of its centre.
    const double cx = obstacle.pose.translation().x();
    const auto right = std::find_if(canopies.begin(), canopies.end(),
                                    [&](const Shape& c) { return c.pose.translation().x() > cx; });
    ASSERT_NE(right, canopies.begin());
    ASSERT_NE(right, canopies.end());
    const double left_side = std::prev(right)->pose.translation().x() + 0.5 * config.canopy_width_m;
    const double right_side = right->pose.translation().x() - 0.5 * config.canopy_width_m;
    double min_x = right_side, max_x = left_side;
    for (const Eigen::Vector2d& corner : corners) {
      EXPECT_GE(corner.x(), left_side + 0.3 - 1e-9);
      EXPECT_LE(corner.x(), right_side - 0.3 + 1e-9);
      EXPECT_GE(corner.y(), -15.0 - 1e-9);
      EXPECT_LE(corner.y(), 15.0 + 1e-9);
      min_x = std::min(min_x, corner.x());
      max_x = std::max(max_x, corner.x());
    }
    EXPECT_GE(std::max(min_x - left_side, right_side - max_x), passage_m - 1e-9);
  }
}

TEST(GeneratorsVineyard, ObstaclesLieBetweenRowsClearOfCanopies) {
  expect_obstacles_between_rows(small_vineyard(9), 0.3);
}

// 3 m rows with 0.6 m canopies leave 2.4 m: 0.8 m boxes (1.13 m across when
// yawed) + 0.3 m clearance fit a 0.95 m passage on the other side.
TEST(GeneratorsVineyard, ObstaclesLeaveThePassageAskedFor) {
  VineyardConfig config = small_vineyard(4);
  config.obstacle_passage_m = 0.95;
  expect_obstacles_between_rows(config, 0.95);
  config.obstacle_passage_m = 1.2;
  EXPECT_THAT([&] { make_vineyard(config, "v"); },
              ThrowsMessage<std::invalid_argument>(HasSubstr("a passage of 1.2 m on the other")));
}

TEST(GeneratorsVineyard, FenceEnclosesEverything) {
  const VineyardConfig config = small_vineyard(4);
  const auto shapes = make_vineyard(config, "vy");
  const auto fence = select(shapes, "/fence/");
  ASSERT_EQ(fence.size(), 4u);
  for (const Shape& wall : fence) {
    EXPECT_NEAR(wall.size_m.z(), config.fence_height_m, 1e-12);
    EXPECT_NEAR(wall.pose.translation().z(), 0.5 * config.fence_height_m, 1e-12);
  }
  // Inner faces of the walls.
  const double inner_x = 0.5 * config.field_size_m.x() - 0.5 * config.fence_thickness_m;
  const double inner_y = 0.5 * config.field_size_m.y() - 0.5 * config.fence_thickness_m;
  const auto north = select(shapes, "/fence/north")[0];
  const auto east = select(shapes, "/fence/east")[0];
  EXPECT_NEAR(north.pose.translation().y() - 0.5 * north.size_m.y(), inner_y, 1e-12);
  EXPECT_GE(north.size_m.x(), config.field_size_m.x());
  EXPECT_NEAR(east.pose.translation().x() - 0.5 * east.size_m.x(), inner_x, 1e-12);
  EXPECT_GE(east.size_m.y(), config.field_size_m.y());
  for (const Shape& shape : shapes) {
    if (alias_has(shape, "/fence/")) continue;
    const Eigen::Vector3d p = shape.pose.translation();
    const Eigen::Vector2d half = shape.type == ShapeType::cylinder ? Eigen::Vector2d(shape.radius_m, shape.radius_m)
                                                                   : Eigen::Vector2d(0.5 * shape.size_m.head<2>());
    std::vector<Eigen::Vector2d> extremes = shape.type == ShapeType::cuboid && alias_has(shape, "/obstacle")
                                                ? footprint(shape)
                                                : std::vector<Eigen::Vector2d>{p.head<2>() - half, p.head<2>() + half};
    for (const Eigen::Vector2d& e : extremes) {
      EXPECT_LT(std::abs(e.x()), inner_x) << shape.alias;
      EXPECT_LT(std::abs(e.y()), inner_y) << shape.alias;
    }
  }
}

TEST(GeneratorsVineyard, RejectsImpossibleGeometry) {
  VineyardConfig config;
  config.row_count = 40;  // 117.6 m of rows in a 100 m field
  EXPECT_THAT([&] { make_vineyard(config, "v"); },
              ThrowsMessage<std::invalid_argument>(HasSubstr("40 rows at 3 m spacing span 117.6 m")));
  config = {};
  config.canopy_width_m = 3.5;
  EXPECT_THAT([&] { make_vineyard(config, "v"); },
              ThrowsMessage<std::invalid_argument>(HasSubstr("must be narrower than the row spacing 3 m")));
  config = {};
  config.headland_m = 50.0;
  EXPECT_THAT([&] { make_vineyard(config, "v"); },
              ThrowsMessage<std::invalid_argument>(HasSubstr("leave no room for rows")));
  config = {};
  config.obstacle_size_m = {1.0, 2.0};
  EXPECT_THAT([&] { make_vineyard(config, "v"); },
              ThrowsMessage<std::invalid_argument>(HasSubstr("cannot hold obstacles up to 2 m")));
  config = {};
  config.row_count = 1;
  EXPECT_THAT([&] { make_vineyard(config, "v"); },
              ThrowsMessage<std::invalid_argument>(HasSubstr("need at least 2 rows")));
  config.obstacle_count = 0;
  EXPECT_EQ(make_vineyard(config, "v").size(), 18u + 1u + 4u);
  // 2.1 / 0.7 is 3.0000000000000004 in doubles: still 3 gaps, 4 posts.
  config.field_size_m = {10.0, 2.1};
  config.headland_m = 0.0;
  config.post_spacing_m = 0.7;
  EXPECT_EQ(select(make_vineyard(config, "v"), "/post").size(), 4u);
  config = {};
  config.canopy_bottom_m = 2.0;
  EXPECT_THAT([&] { make_vineyard(config, "v"); },
              ThrowsMessage<std::invalid_argument>(HasSubstr("0 <= canopy_bottom < canopy_top")));
}

// --- grid obstacles ---------------------------------------------------------

GridObstaclesConfig map_001() {
  GridObstaclesConfig config;
  config.origin_m = {-75.0, -75.0};
  config.cell_size_m = 1.5;
  return config;
}

TEST(GeneratorsGridObstacles, CellCentres) {
  const GridObstaclesConfig config = map_001();
  EXPECT_EQ(grid_cell_center(config, 1, 1), Eigen::Vector2d(-74.25, -74.25));
  EXPECT_EQ(grid_cell_center(config, 100, 100), Eigen::Vector2d(74.25, 74.25));
  // Rows count northward (y), columns eastward (x).
  EXPECT_EQ(grid_cell_center(config, 2, 5), Eigen::Vector2d(-75.0 + 4.5 * 1.5, -75.0 + 1.5 * 1.5));
  EXPECT_THAT([&] { grid_cell_center(config, 0, 5); },
              ThrowsMessage<std::invalid_argument>(HasSubstr("cell (0, 5) is outside the 100 x 100 grid")));
  EXPECT_THROW(grid_cell_center(config, 1, 101), std::invalid_argument);
}

double sine_ground(double x, double y) { return std::sin(x / 5.0); }

TEST(GeneratorsGridObstacles, BoxCoversItsCellsExactly) {
  GridObstaclesConfig config = map_001();
  config.boxes = {{40, 45, 25, 30, 15.0}, {20, 22, 1, 100, 35.0}};
  const auto shapes = make_grid_obstacles(config, "city", sine_ground);
  ASSERT_EQ(shapes.size(), 2u);
  EXPECT_EQ(shapes[0].alias, "city/box0");
  EXPECT_EQ(shapes[1].alias, "city/box1");
  const Shape& block = shapes[0];
  EXPECT_EQ(block.type, ShapeType::cuboid);
  const Eigen::Vector3d p = block.pose.translation();
  EXPECT_NEAR(p.x() - 0.5 * block.size_m.x(), -75.0 + 24 * 1.5, 1e-9);
  EXPECT_NEAR(p.x() + 0.5 * block.size_m.x(), -75.0 + 30 * 1.5, 1e-9);
  EXPECT_NEAR(p.y() - 0.5 * block.size_m.y(), -75.0 + 39 * 1.5, 1e-9);
  EXPECT_NEAR(p.y() + 0.5 * block.size_m.y(), -75.0 + 45 * 1.5, 1e-9);
  // sin(x / 5) rises monotonically over x in [-39, -30]: extremes at the edges.
  EXPECT_NEAR(p.z() + 0.5 * block.size_m.z(), std::sin(-30.0 / 5.0) + 15.0, 1e-12);
  EXPECT_NEAR(p.z() - 0.5 * block.size_m.z(), std::sin(-39.0 / 5.0) - 1.0, 1e-12);
  // The wall spans the whole map west to east.
  const Shape& wall = shapes[1];
  EXPECT_NEAR(wall.pose.translation().x() - 0.5 * wall.size_m.x(), -75.0, 1e-9);
  EXPECT_NEAR(wall.pose.translation().x() + 0.5 * wall.size_m.x(), 75.0, 1e-9);
  // Its top is 35 m above the sampled crest of the sine (peak 1, missed by < 0.003).
  EXPECT_NEAR(wall.pose.translation().z() + 0.5 * wall.size_m.z(), 1.0 + 35.0, 0.003);
}

TEST(GeneratorsGridObstacles, TopFollowsAGroundPeakInsideTheBlock) {
  GridObstaclesConfig config;
  config.boxes = {{2, 3, 4, 7, 10.0}};  // x in [4.5, 10.5] holds the peak of 2 sin(x / 5) at 7.85
  const auto ground = [](double x, double y) { return 2.0 * std::sin(x / 5.0) + 0.1 * y; };
  const auto shapes = make_grid_obstacles(config, "g", ground);
  ASSERT_EQ(shapes.size(), 1u);
  const double top = shapes[0].pose.translation().z() + 0.5 * shapes[0].size_m.z();
  const double true_max = 2.0 + 0.1 * 4.5;
  // Sampling every half cell misses a peak by at most |f''| h^2 / 8.
  const double h = 0.75;
  EXPECT_LE(top, true_max + 10.0 + 1e-12);
  EXPECT_GE(top, true_max + 10.0 - (2.0 / 25.0) * h * h / 8.0);
}

// Ground work of one generator is bounded whatever its blocks: 10000 blocks over a whole 10000 x 10000
// grid once cost 10000 x 257^2 ground queries (15-23 s); now they share kGridBoxGroundVisits.
TEST(GeneratorsGridObstacles, GroundSamplesStayWithinOneBudgetPerGenerator) {
  GridObstaclesConfig config;
  config.rows = config.cols = 10000;
  config.cell_size_m = 0.01;
  config.boxes.assign(10000, GridBox{1, 10000, 1, 10000, 2.0});
  const int n = grid_box_samples_per_side(config, 1);
  EXPECT_EQ(n, 19);  // floor(sqrt(2^22 / 10000)) - 1: 20 x 20 points a block
  long queries = 0;
  const auto counting = [&](double x, double y) {
    ++queries;
    return sine_ground(x, y);
  };
  const auto shapes = make_grid_obstacles(config, "g", counting, n);
  ASSERT_EQ(shapes.size(), 10000u);
  EXPECT_EQ(queries, 10000L * 20 * 20);
  EXPECT_LE(static_cast<double>(queries), kGridBoxGroundVisits);
  // Coarser, not wrong: the samples lie under the block (x in [0, 100] m, every 5.26 m), so the top stands
  // 2 m above a sampled crest of sin(x / 5), never above the true crest and here within 0.09 of it.
  const double top = shapes[0].pose.translation().z() + 0.5 * shapes[0].size_m.z();
  EXPECT_LE(top, 1.0 + 2.0 + 1e-12);
  EXPECT_GE(top, 0.91 + 2.0);
  // Three ground shapes per query: a third of the points.
  EXPECT_EQ(grid_box_samples_per_side(config, 3), 10);
  // Far beyond the budget (10^6 ground shapes): the corners, never fewer.
  EXPECT_EQ(grid_box_samples_per_side(config, 1000000), 1);
  // A flat ground needs the corners alone.
  EXPECT_EQ(grid_box_samples_per_side(config, 0), 1);
}

TEST(GeneratorsGridObstacles, SmallOrFewBlocksKeepEveryCornerAndCentre) {
  GridObstaclesConfig config;
  config.rows = config.cols = 10000;
  // 10000 blocks of 3 x 3 cells: 7 x 7 points each, well within the budget.
  config.boxes.assign(10000, GridBox{1, 3, 1, 3, 2.0});
  EXPECT_EQ(grid_box_samples_per_side(config, 1), kGridBoxGroundSamples);
  // A few blocks over the whole grid: 257 x 257 points each, as before the budget.
  config.boxes.assign(60, GridBox{1, 10000, 1, 10000, 2.0});
  EXPECT_EQ(grid_box_samples_per_side(config, 1), kGridBoxGroundSamples);
  // The budget binds only between the two: 64 large blocks plus many small ones.
  config.boxes.assign(64, GridBox{1, 10000, 1, 10000, 2.0});
  const int n = grid_box_samples_per_side(config, 1);
  EXPECT_LT(n, kGridBoxGroundSamples);
  EXPECT_LE(64.0 * (n + 1) * (n + 1), kGridBoxGroundVisits);
  EXPECT_GT(64.0 * (n + 2) * (n + 2), kGridBoxGroundVisits);  // the largest that fits
}

TEST(GeneratorsGridObstacles, RejectsBadBlocks) {
  GridObstaclesConfig config = map_001();
  config.boxes = {{1, 1, 1, 1, 5.0}, {10, 101, 1, 1, 5.0}};
  EXPECT_THAT([&] { make_grid_obstacles(config, "g", sine_ground); },
              ThrowsMessage<std::invalid_argument>(
                  HasSubstr("box 1: rows 10-101 must be an ascending range within 1-100")));
  config.boxes = {{5, 5, 9, 8, 5.0}};
  EXPECT_THAT([&] { make_grid_obstacles(config, "g", sine_ground); },
              ThrowsMessage<std::invalid_argument>(HasSubstr("box 0: cols 9-8")));
  config.boxes = {{5, 5, 8, 9, 0.0}};
  EXPECT_THAT([&] { make_grid_obstacles(config, "g", sine_ground); },
              ThrowsMessage<std::invalid_argument>(HasSubstr("box 0: height must be finite and > 0")));
}

}  // namespace
}  // namespace campo
