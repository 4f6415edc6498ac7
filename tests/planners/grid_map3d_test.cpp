#include "planners/grid_map3d.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace campo {
namespace {

using grid::Cell;
using grid::CellState;

// Seed 001's grid with take-off ground at z = -1 m.
GridMap3d seed_001_map() {
  GridMap3dConfig config;
  config.ground_z_m = -1.0;
  return GridMap3d(config);
}

TEST(GridMap3d, ConvertsWorldPointsToCellsAndBack) {
  const GridMap3d map = seed_001_map();
  // x east -> column, y north -> row, z -> nearest level (level 2 at take-off ground).
  EXPECT_EQ(map.cell_of({23.25, 0.75, -0.7}), (Cell{15, 0, 2}));
  EXPECT_EQ(map.cell_of({1.6, 3.1, -1.0 + 42.0}), (Cell{1, 2, 8}));
  EXPECT_EQ(map.cell_of({0.0, 0.0, -1.0 - 14.0}), (Cell{0, 0, 0}));
  EXPECT_EQ(map.cell_of({0.0, 0.0, -1.0 + 3.4}), (Cell{0, 0, 2}));
  EXPECT_EQ(map.cell_of({0.0, 0.0, -1.0 + 3.6}), (Cell{0, 0, 3}));
  EXPECT_EQ(map.cell_of({-0.1, 150.1, 0.0}), (Cell{-1, 100, 2}));
  EXPECT_FALSE(map.contains(map.cell_of({-0.1, 5.0, 0.0})));
  EXPECT_TRUE((map.center({15, 0, 8}) - Eigen::Vector3d(23.25, 0.75, 41.0)).norm() < 1e-12);
  EXPECT_TRUE((map.center({0, 99, 0}) - Eigen::Vector3d(0.75, 149.25, -15.0)).norm() < 1e-12);
  for (const Cell c : {Cell{0, 0, 0}, Cell{37, 81, 5}, Cell{99, 99, 8}}) EXPECT_EQ(map.cell_of(map.center(c)), c);
}

TEST(GridMap3d, HitBlocksItsColumnBelowAndReturnsOnlyChanges) {
  GridMap3d map = seed_001_map();
  // A building roof 30 m above take-off ground: level round(30 / 7) + 2 = 6.
  const auto first = map.mark_hit({10.0, 20.0, -1.0 + 30.0});
  ASSERT_EQ(first.size(), 7u);
  for (int z = 0; z <= 6; ++z) {
    EXPECT_EQ(first[z].cell, (Cell{6, 13, z}));
    EXPECT_EQ(first[z].state, CellState::blocked);
    EXPECT_EQ(map.state({6, 13, z}), CellState::blocked);
  }
  EXPECT_EQ(map.state({6, 13, 7}), CellState::unknown);
  EXPECT_EQ(map.state({7, 13, 0}), CellState::unknown);
  // The same hit again, or a lower one, changes nothing; a higher one only the new levels.
  EXPECT_TRUE(map.mark_hit({10.0, 20.0, 29.0}).empty());
  EXPECT_TRUE(map.mark_hit({10.2, 20.3, 0.0}).empty());
  const auto higher = map.mark_hit({10.0, 20.0, -1.0 + 42.0});
  ASSERT_EQ(higher.size(), 2u);
  EXPECT_EQ(higher[0].cell, (Cell{6, 13, 7}));
  EXPECT_EQ(higher[1].cell, (Cell{6, 13, 8}));
  // Above the grid: the whole column; below it or outside its columns: nothing.
  EXPECT_EQ(map.mark_hit({0.0, 0.0, 200.0}).size(), 9u);
  EXPECT_TRUE(map.mark_hit({1.6, 0.0, -40.0}).empty());
  EXPECT_TRUE(map.mark_hit({151.0, 0.0, 0.0}).empty());
}

TEST(GridMap3d, HeightMapHoldsTheTopOfEachColumn) {
  GridMap3d map = seed_001_map();
  map.mark_hit({10.0, 20.0, -1.0 + 30.0});
  map.mark_hit({0.5, 0.5, -1.2});
  EXPECT_EQ(map.top_blocked_level(6, 13), 6);
  EXPECT_EQ(map.top_blocked_level(0, 0), 2);
  EXPECT_FALSE(map.top_blocked_level(1, 0).has_value());
  const std::vector<double> heights = map.height_map_m();
  ASSERT_EQ(heights.size(), 100u * 100u);
  EXPECT_DOUBLE_EQ(heights[13 * 100 + 6], -1.0 + 28.0);
  EXPECT_DOUBLE_EQ(heights[0], -1.0);
  EXPECT_TRUE(std::isnan(heights[1]));
}

TEST(GridMap3d, RejectsBadGeometry) {
  GridMap3dConfig config;
  config.ground_level = 9;
  EXPECT_THROW(GridMap3d{config}, std::invalid_argument);
  config = {};
  config.cell_size_m = 0.0;
  EXPECT_THROW(GridMap3d{config}, std::invalid_argument);
  config = {};
  config.levels = 0;
  EXPECT_THROW(GridMap3d{config}, std::invalid_argument);
}

}  // namespace
}  // namespace campo
