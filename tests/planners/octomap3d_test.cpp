#include "planners/octomap3d.hpp"

#include <algorithm>
#include <stdexcept>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

namespace campo {
namespace {

using grid::Cell;
using grid::CellState;

// A planning grid of 1 m cubes: cell (x, y, z) spans [x, x+1] x [y, y+1] x [z, z+1] m
// (level 0's centre at z = 0.5 m, levels 1 m apart).
GridMap3dConfig unit_grid() {
  GridMap3dConfig g;
  g.columns = 20;
  g.rows = 20;
  g.levels = 6;
  g.cell_size_m = 1.0;
  g.level_spacing_m = 1.0;
  g.ground_level = 0;
  g.ground_z_m = 0.5;
  return g;
}

// 0.5 m voxels (voxel i spans [0.5 i, 0.5 (i + 1)) on each axis), vehicle radius 0.5 m.
OctoMap3dConfig half_metre_voxels() {
  OctoMap3dConfig c;
  c.resolution_m = 0.5;
  return c;
}

// Rays from the sensor at (2.2, 10.2, 2.2) to the west face (x = 10 m) of a
// box filling x in [10, 12]: ends on a 9 x 5 lattice of the face, y 6..14 m, z 0.5..4.5 m.
struct FaceScan {
  Eigen::Vector3d origin{2.2, 10.2, 2.2};
  std::vector<Eigen::Vector3d> ends;
  std::vector<std::uint8_t> returns;
  FaceScan() {
    for (int j = 0; j <= 8; ++j) {
      for (int k = 0; k <= 4; ++k) {
        ends.emplace_back(10.0, 6.1 + j, 0.6 + k);
        returns.push_back(1);
      }
    }
  }
};

bool contains(const std::vector<grid::CellChange>& changes, const Cell& cell, CellState state) {
  return std::any_of(changes.begin(), changes.end(),
                     [&](const grid::CellChange& c) { return c.cell == cell && c.state == state; });
}

TEST(OctoMap3d, RaysIntoABoxMarkItsFaceOccupiedTheRaysFreeAndBehindUnknown) {
  OctoMap3d map(unit_grid(), half_metre_voxels());
  const FaceScan scan;
  const std::vector<grid::CellChange> changes = map.insert_scan(scan.origin, scan.ends, scan.returns);

  for (const Eigen::Vector3d& end : scan.ends) {
    // The voxel at the face (x in [10, 10.5)) holds the return.
    EXPECT_EQ(map.voxel_state(end + Eigen::Vector3d(0.01, 0.0, 0.0)), VoxelState::occupied) << end.transpose();
    // Along the ray, well before the face: free.
    for (const double t : {0.2, 0.5, 0.9}) {
      EXPECT_EQ(map.voxel_state(scan.origin + t * (end - scan.origin)), VoxelState::free) << end.transpose() << t;
    }
    // Inside and behind the box nothing was seen.
    EXPECT_EQ(map.voxel_state(end + Eigen::Vector3d(1.0, 0.0, 0.0)), VoxelState::unknown);
    EXPECT_EQ(map.voxel_state(end + Eigen::Vector3d(4.0, 0.0, 0.0)), VoxelState::unknown);
  }
  // Beside the rays' fan (south of it) and behind the sensor: unknown.
  EXPECT_EQ(map.voxel_state({6.0, 2.0, 2.0}), VoxelState::unknown);
  EXPECT_EQ(map.voxel_state({0.5, 10.2, 2.2}), VoxelState::unknown);
  // 45 returns on distinct voxels of the face.
  EXPECT_EQ(map.occupied_leaf_count(), 45);
  EXPECT_EQ(map.occupied_voxels().size(), 45u);

  // Planning cells: an occupied voxel spans x in [10, 10.5]; grown by the
  // radius (0.5 m) it reaches x = 9.5, so columns 9 and 10 are blocked, 8 is
  // not. Returns at y = 10.1 m, z = 2.6 m block cell (10, 10, 2) and its neighbours.
  for (const Cell& c : {Cell{9, 10, 2}, Cell{10, 10, 2}, Cell{9, 6, 0}, Cell{10, 14, 4}}) {
    EXPECT_EQ(map.state(c), CellState::blocked) << c.x << " " << c.y << " " << c.z;
    EXPECT_TRUE(contains(changes, c, CellState::blocked));
  }
  for (const Cell& c : {Cell{8, 10, 2}, Cell{11, 10, 2}, Cell{5, 10, 2}, Cell{10, 3, 2}, Cell{10, 16, 2}}) {
    EXPECT_EQ(map.state(c), CellState::unknown) << c.x << " " << c.y << " " << c.z;
  }
  // Only changes, each cell once, in order (level, row, column).
  for (std::size_t i = 1; i < changes.size(); ++i) {
    const Cell& a = changes[i - 1].cell;
    const Cell& b = changes[i].cell;
    EXPECT_LT(std::tie(a.z, a.y, a.x), std::tie(b.z, b.y, b.x));
  }
  for (const grid::CellChange& c : changes) EXPECT_EQ(c.state, CellState::blocked);
}

TEST(OctoMap3d, ChangesAreIncrementalAndMissesClearWhatMoved) {
  OctoMap3d map(unit_grid(), half_metre_voxels());
  const FaceScan scan;
  EXPECT_FALSE(map.insert_scan(scan.origin, scan.ends, scan.returns).empty());
  // The same scan again: the voxels grow more certain, no planning cell changes.
  EXPECT_TRUE(map.insert_scan(scan.origin, scan.ends, scan.returns).empty());

  // The box is gone: beams without a return pass the face up to 15 m. One
  // hit (p 0.7) twice is log-odds 1.69; each miss (p 0.4) takes 0.41, so the
  // fifth miss makes the voxels free and their cells traversable again.
  std::vector<Eigen::Vector3d> far;
  for (const Eigen::Vector3d& end : scan.ends) far.push_back(scan.origin + 1.5 * (end - scan.origin));
  const std::vector<std::uint8_t> misses(far.size(), 0);
  for (int i = 0; i < 4; ++i) EXPECT_TRUE(map.insert_scan(scan.origin, far, misses).empty()) << i;
  EXPECT_EQ(map.voxel_state({10.01, 10.1, 2.6}), VoxelState::occupied);
  const std::vector<grid::CellChange> cleared = map.insert_scan(scan.origin, far, misses);
  EXPECT_EQ(map.voxel_state({10.01, 10.1, 2.6}), VoxelState::free);
  EXPECT_TRUE(contains(cleared, Cell{10, 10, 2}, CellState::unknown));
  EXPECT_EQ(map.state({10, 10, 2}), CellState::unknown);
  // A beam without a return is free to its end, and unknown beyond.
  EXPECT_EQ(map.voxel_state(far[22] - Eigen::Vector3d(0.3, 0.0, 0.0)), VoxelState::free);
  EXPECT_EQ(map.voxel_state(far[22] + Eigen::Vector3d(1.0, 0.0, 0.0)), VoxelState::unknown);
}

TEST(OctoMap3d, RejectsConfigurationsOutOfRange) {
  OctoMap3dConfig bad;
  bad.resolution_m = 0.0;
  EXPECT_THROW(OctoMap3d(unit_grid(), bad), std::invalid_argument);
  bad = {};
  bad.probability_miss = 0.6;
  EXPECT_THROW(OctoMap3d(unit_grid(), bad), std::invalid_argument);
  bad = {};
  bad.vehicle_radius_m = -1.0;
  EXPECT_THROW(OctoMap3d(unit_grid(), bad), std::invalid_argument);
  const std::vector<Eigen::Vector3d> ends{{1, 1, 1}};
  const std::vector<std::uint8_t> none;
  OctoMap3d map(unit_grid(), OctoMap3dConfig{});
  EXPECT_THROW(map.insert_scan({0, 0, 0}, ends, none), std::invalid_argument);
}

}  // namespace
}  // namespace campo
