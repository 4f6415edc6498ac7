// OctoMap3d against a reference: the straightforward scan insertion it
// replaced (OctoMap's computeUpdate: the free keys of computeRayKeys and the
// occupied end keys in OctoMap's KeySets, then updateNode for each key with
// lazy evaluation and change detection). After every one of many random scans
// the two maps must hold the same leaves (key, depth and log-odds, bit for
// bit), count the same occupied voxels and return the same planning cells.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <octomap/OcTree.h>

#include "campo/random.hpp"
#include "planners/octomap3d.hpp"

namespace campo {
namespace {

using grid::Cell;
using grid::CellChange;
using grid::CellState;

octomap::point3d to_point(const Eigen::Vector3d& v) {
  return {static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z())};
}

// The map as OctoMap3d built it before batching: an OcTree updated through its
// public API, and per planning cell the number of occupied voxels in reach.
class ReferenceMap {
 public:
  ReferenceMap(const GridMap3dConfig& grid, const OctoMap3dConfig& c) : grid_(grid), config_(c), tree_(c.resolution_m) {
    tree_.setProbHit(c.probability_hit);
    tree_.setProbMiss(c.probability_miss);
    tree_.setOccupancyThres(c.occupied_threshold);
    tree_.setClampingThresMin(c.clamping_min);
    tree_.setClampingThresMax(c.clamping_max);
    tree_.enableChangeDetection(true);
    near_.assign(static_cast<std::size_t>(grid.columns) * grid.rows * grid.levels, 0);
  }

  std::vector<CellChange> insert_scan(const Eigen::Vector3d& origin_m, const std::vector<Eigen::Vector3d>& ends_m,
                                      const std::vector<std::uint8_t>& returns) {
    octomap::KeySet free_keys, occupied_keys;
    octomap::KeyRay ray;
    const octomap::point3d origin = to_point(origin_m);
    for (std::size_t i = 0; i < ends_m.size(); ++i) {
      const octomap::point3d end = to_point(ends_m[i]);
      if (tree_.computeRayKeys(origin, end, ray)) free_keys.insert(ray.begin(), ray.end());
      octomap::OcTreeKey end_key;
      if (!tree_.coordToKeyChecked(end, end_key)) continue;
      (returns[i] ? occupied_keys : free_keys).insert(end_key);
    }
    for (const octomap::OcTreeKey& key : occupied_keys) free_keys.erase(key);
    tree_.resetChangeDetection();
    for (const octomap::OcTreeKey& key : free_keys) tree_.updateNode(key, false, true);
    for (const octomap::OcTreeKey& key : occupied_keys) tree_.updateNode(key, true, true);

    // Planning cells: every voxel whose occupancy flipped moves the count of
    // the cells its box grown by the vehicle radius overlaps (the same index
    // arithmetic as before); the cells whose count crossed zero changed.
    const GridMap3dConfig& g = grid_.config();
    const double reach = 0.5 * config_.resolution_m + config_.vehicle_radius_m;
    const auto overlapping = [](double after, double before, int count) {
      return std::pair<int, int>{std::max(0, static_cast<int>(std::floor(after)) + 1),
                                 std::min(count - 1, static_cast<int>(std::ceil(before)) - 1)};
    };
    const std::vector<std::int32_t> before = near_;
    for (auto it = tree_.changedKeysBegin(); it != tree_.changedKeysEnd(); ++it) {
      const octomap::OcTreeNode* node = tree_.search(it->first);
      const bool is = node && tree_.isNodeOccupied(node);
      const bool was = it->second ? false : !is;
      if (was == is) continue;
      occupied_ += is ? 1 : -1;
      // The centre as the GCC build of this code computed it: x and y in
      // double, z rounded to float (planners/octomap3d.cpp, voxel_center).
      const octomap::OcTreeKey& k = it->first;
      const Eigen::Vector3d c(tree_.keyToCoord(k[0]), tree_.keyToCoord(k[1]),
                              static_cast<double>(static_cast<float>(tree_.keyToCoord(k[2]))));
      const std::pair<int, int> xs = overlapping((c.x() - reach - g.origin_m.x()) / g.cell_size_m - 1.0,
                                                 (c.x() + reach - g.origin_m.x()) / g.cell_size_m, g.columns);
      const std::pair<int, int> ys = overlapping((c.y() - reach - g.origin_m.y()) / g.cell_size_m - 1.0,
                                                 (c.y() + reach - g.origin_m.y()) / g.cell_size_m, g.rows);
      const double level = (c.z() - g.ground_z_m) / g.level_spacing_m + g.ground_level;
      const double reach_levels = reach / g.level_spacing_m;
      const std::pair<int, int> zs = overlapping(level - reach_levels - 0.5, level + reach_levels + 0.5, g.levels);
      for (int z = zs.first; z <= zs.second; ++z) {
        for (int y = ys.first; y <= ys.second; ++y) {
          for (int x = xs.first; x <= xs.second; ++x) {
            near_[(static_cast<std::size_t>(z) * g.rows + y) * g.columns + x] += is ? 1 : -1;
          }
        }
      }
    }
    std::vector<CellChange> changes;
    for (std::size_t i = 0; i < near_.size(); ++i) {
      if ((before[i] > 0) == (near_[i] > 0)) continue;
      const Cell cell{static_cast<int>(i % g.columns), static_cast<int>(i / g.columns % g.rows),
                      static_cast<int>(i / (static_cast<std::size_t>(g.columns) * g.rows))};
      changes.push_back({cell, near_[i] > 0 ? CellState::blocked : CellState::unknown});
    }
    return changes;
  }

  std::vector<OctreeLeaf> leaves() const {
    std::vector<OctreeLeaf> out;
    for (auto it = tree_.begin_leafs(), end = tree_.end_leafs(); it != end; ++it) {
      out.push_back({{it.getKey()[0], it.getKey()[1], it.getKey()[2]}, static_cast<int>(it.getDepth()),
                     it->getLogOdds()});
    }
    return out;
  }
  std::int64_t occupied() const { return occupied_; }
  const octomap::OcTree& tree() const { return tree_; }

 private:
  GridMap3d grid_;
  OctoMap3dConfig config_;
  octomap::OcTree tree_;
  std::vector<std::int32_t> near_;
  std::int64_t occupied_ = 0;
};

struct Scan {
  Eigen::Vector3d origin;
  std::vector<Eigen::Vector3d> ends;
  std::vector<std::uint8_t> returns;
};

// A random scan from near `origin`: beams of 0-25 m in every direction, some
// along an axis or in an axis plane, some ending on voxel faces or in the
// origin's own voxel; about a fifth without a return.
Scan random_scan(Rng& rng, const Eigen::Vector3d& origin, double resolution, int beams) {
  Scan s;
  s.origin = origin;
  if (rng.bernoulli(0.3)) {  // on a voxel face
    s.origin.x() = std::round(origin.x() / resolution) * resolution;
  }
  for (int i = 0; i < beams; ++i) {
    Eigen::Vector3d d(rng.normal(0.0, 1.0), rng.normal(0.0, 1.0), rng.normal(0.0, 0.4));
    const int kind = static_cast<int>(rng.uniform_int(0, 9));
    if (kind == 0) d = Eigen::Vector3d::Unit(static_cast<int>(rng.uniform_int(0, 2))) * (rng.bernoulli(0.5) ? 1 : -1);
    if (kind == 1) d.z() = 0.0;
    if (d.norm() < 1e-9) d = Eigen::Vector3d::UnitX();
    const double range = kind == 2 ? rng.uniform(0.0, resolution) : rng.uniform(0.5, 25.0);
    Eigen::Vector3d end = s.origin + d.normalized() * range;
    if (kind == 3) end = (end / resolution).array().round().matrix() * resolution;
    s.ends.push_back(end);
    s.returns.push_back(rng.bernoulli(0.8) ? 1 : 0);
  }
  return s;
}

void expect_same_leaves(const std::vector<OctreeLeaf>& got, const std::vector<OctreeLeaf>& want, const std::string& at) {
  ASSERT_EQ(got.size(), want.size()) << at;
  for (std::size_t i = 0; i < got.size(); ++i) {
    ASSERT_EQ(got[i].key, want[i].key) << at << " leaf " << i;
    ASSERT_EQ(got[i].depth, want[i].depth) << at << " leaf " << i;
    // Bit for bit: the same float additions in the same order per voxel.
    ASSERT_EQ(got[i].log_odds, want[i].log_odds) << at << " leaf " << i;
  }
}

void expect_same_changes(const std::vector<CellChange>& got, const std::vector<CellChange>& want, const std::string& at) {
  ASSERT_EQ(got.size(), want.size()) << at;
  for (std::size_t i = 0; i < got.size(); ++i) {
    EXPECT_EQ(got[i].cell, want[i].cell) << at << " change " << i;
    EXPECT_EQ(got[i].state, want[i].state) << at << " change " << i;
  }
}

// Flies `scans` random scans through both maps, checking them after each.
void map_random_scans(const GridMap3dConfig& grid, const OctoMap3dConfig& config, std::uint64_t seed, int scans, int beams) {
  OctoMap3d map(grid, config);
  ReferenceMap reference(grid, config);
  Rng rng(seed);
  Eigen::Vector3d origin(grid.origin_m.x() + 0.5 * grid.columns * grid.cell_size_m,
                         grid.origin_m.y() + 0.5 * grid.rows * grid.cell_size_m, grid.ground_z_m + 3.0);
  std::int64_t changed = 0, flips = 0;
  for (int n = 0; n < scans; ++n) {
    const std::string at = "seed " + std::to_string(seed) + " scan " + std::to_string(n);
    // Revisit the same places so voxels are seen many times, to the clamping bounds and back.
    origin += Eigen::Vector3d(rng.normal(0.0, 1.0), rng.normal(0.0, 1.0), rng.normal(0.0, 0.3));
    const Scan s = random_scan(rng, origin, config.resolution_m, beams);
    const std::int64_t occupied_before = map.occupied_leaf_count();
    const std::vector<CellChange> got = map.insert_scan(s.origin, s.ends, s.returns);
    const std::vector<CellChange> want = reference.insert_scan(s.origin, s.ends, s.returns);
    ASSERT_NO_FATAL_FAILURE(expect_same_leaves(map.leaves(), reference.leaves(), at));
    ASSERT_EQ(map.occupied_leaf_count(), reference.occupied()) << at;
    ASSERT_NO_FATAL_FAILURE(expect_same_changes(got, want, at));
    changed += static_cast<std::int64_t>(got.size());
    flips += std::abs(map.occupied_leaf_count() - occupied_before);
  }
  // The run exercised what it checks: cells blocked and freed, voxels flipping.
  EXPECT_GT(changed, 0);
  EXPECT_GT(flips, 0);
  // Every cell's state agrees with the reference's counts through the public queries too.
  const std::vector<OccupiedVoxel> voxels = map.occupied_voxels();
  EXPECT_EQ(static_cast<std::int64_t>(voxels.size()), map.occupied_leaf_count());
  for (const OccupiedVoxel& v : voxels) {
    const octomap::OcTreeNode* node = reference.tree().search(to_point(v.center_m));
    ASSERT_NE(node, nullptr);
    EXPECT_TRUE(reference.tree().isNodeOccupied(node));
    EXPECT_EQ(map.voxel_state(v.center_m), VoxelState::occupied);
  }
}

// A planning grid of 1 m cubes, 30 x 30 x 8, ground level 2 at z = 0.5 m.
GridMap3dConfig metre_grid() {
  GridMap3dConfig g;
  g.columns = 30;
  g.rows = 30;
  g.levels = 8;
  g.cell_size_m = 1.0;
  g.level_spacing_m = 1.0;
  g.ground_level = 2;
  g.ground_z_m = 0.5;
  g.origin_m = {-3.0, 2.0};
  return g;
}

TEST(OctoMap3dReference, DefaultSettingsGiveTheSameMapScanAfterScan) {
  for (const std::uint64_t seed : {1u, 2u, 3u}) map_random_scans(metre_grid(), OctoMap3dConfig{}, seed, 60, 64);
}

TEST(OctoMap3dReference, FineVoxelsAndWideScansGiveTheSameMap) {
  OctoMap3dConfig c;
  c.resolution_m = 0.3;
  c.vehicle_radius_m = 0.2;
  map_random_scans(metre_grid(), c, 7, 25, 512);
}

TEST(OctoMap3dReference, StrongUpdatesReachTheClampingBoundsAndGiveTheSameMap) {
  // Few scans reach the bounds; unusual thresholds move voxels back and forth.
  OctoMap3dConfig c;
  c.resolution_m = 1.0;
  c.probability_hit = 0.9;
  c.probability_miss = 0.2;
  c.occupied_threshold = 0.6;
  c.clamping_min = 0.3;
  c.clamping_max = 0.8;
  c.vehicle_radius_m = 0.0;
  map_random_scans(metre_grid(), c, 11, 80, 96);
}

TEST(OctoMap3dReference, PlannerGridOverTheBridgeGivesTheSameMap) {
  GridMap3dConfig g;  // dstar_lite_3d's default: 100 x 100 cells of 1.5 m, 9 levels 7 m apart
  g.ground_z_m = 0.3;
  map_random_scans(g, OctoMap3dConfig{}, 5, 30, 64);
}

TEST(OctoMap3dReference, MoreScansThanTheKeyTableCountsGiveTheSameMap) {
  // The set of a scan's voxels tells scans apart by a 16-bit count, which
  // wraps after 65,535 scans; voxels seen long ago must not look seen.
  OctoMap3dConfig c;
  c.resolution_m = 0.5;
  OctoMap3d map(metre_grid(), c);
  ReferenceMap reference(metre_grid(), c);
  Rng rng(13);
  for (int n = 0; n < 70000; ++n) {
    const Eigen::Vector3d origin(4.0 + rng.uniform(-1.0, 1.0), 10.0 + rng.uniform(-1.0, 1.0), 1.0);
    const std::vector<Eigen::Vector3d> ends{origin + Eigen::Vector3d(rng.uniform(-3.0, 3.0), rng.uniform(-3.0, 3.0), 0.2)};
    const std::vector<std::uint8_t> returns{static_cast<std::uint8_t>(rng.bernoulli(0.5))};
    const std::vector<CellChange> got = map.insert_scan(origin, ends, returns);
    const std::vector<CellChange> want = reference.insert_scan(origin, ends, returns);
    if (n % 5000 == 0 || n > 65530) {
      const std::string at = "scan " + std::to_string(n);
      ASSERT_NO_FATAL_FAILURE(expect_same_changes(got, want, at));
      ASSERT_NO_FATAL_FAILURE(expect_same_leaves(map.leaves(), reference.leaves(), at));
    }
  }
  ASSERT_NO_FATAL_FAILURE(expect_same_leaves(map.leaves(), reference.leaves(), "end"));
  EXPECT_EQ(map.occupied_leaf_count(), reference.occupied());
}

// Rays for the traversal test: from anywhere near the origin, often on voxel
// faces, edges and corners, along axes and diagonals, long and short.
std::pair<Eigen::Vector3d, Eigen::Vector3d> random_ray(Rng& rng, double resolution) {
  const auto point = [&](double spread) {
    Eigen::Vector3d p(rng.uniform(-spread, spread), rng.uniform(-spread, spread), rng.uniform(-spread, spread));
    for (int i = 0; i < 3; ++i) {
      if (rng.bernoulli(0.3)) p[i] = std::round(p[i] / resolution) * resolution;  // on a face
    }
    return p;
  };
  const Eigen::Vector3d a = point(30.0);
  Eigen::Vector3d b = a + point(rng.bernoulli(0.2) ? 2.0 * resolution : 60.0);
  const int kind = static_cast<int>(rng.uniform_int(0, 5));
  if (kind == 0) b[rng.uniform_int(0, 2)] = a[rng.uniform_int(0, 2)];  // in an axis plane, or nearly
  if (kind == 1) {                                                     // along an axis
    const int axis = static_cast<int>(rng.uniform_int(0, 2));
    b = a;
    b[axis] += rng.uniform(-40.0, 40.0);
  }
  if (kind == 2) b = a + Eigen::Vector3d::Constant(rng.uniform(-20.0, 20.0));  // a diagonal through corners
  return {a, b};
}

TEST(OctoMap3dReference, RayTraversalListsComputeRayKeysKeys) {
  for (const double resolution : {0.75, 0.1, 0.3, 1.0}) {
    OctoMap3dConfig c;
    c.resolution_m = resolution;
    const OctoMap3d map(metre_grid(), c);
    octomap::OcTree tree(resolution);
    octomap::KeyRay ray;
    Rng rng(static_cast<std::uint64_t>(resolution * 1000));
    std::size_t keys = 0;
    for (int n = 0; n < 20000; ++n) {
      const auto [a, b] = random_ray(rng, resolution);
      ASSERT_TRUE(tree.computeRayKeys(to_point(a), to_point(b), ray));
      std::vector<std::array<std::uint16_t, 3>> want;
      for (const octomap::OcTreeKey& k : ray) want.push_back({k[0], k[1], k[2]});
      ASSERT_EQ(map.ray_voxels(a, b), want) << resolution << " ray " << n;
      keys += want.size();
    }
    EXPECT_GT(keys, 20000u * 5);
  }
}

TEST(OctoMap3dReference, EndsOutsideTheOctreeAreSkippedAsBefore) {
  // 0.05 m voxels: the octree spans +-1638.4 m; a beam ending beyond it has no
  // ray keys and no end key; one starting beyond it likewise.
  OctoMap3dConfig c;
  c.resolution_m = 0.05;
  OctoMap3d map(metre_grid(), c);
  ReferenceMap reference(metre_grid(), c);
  const std::vector<Eigen::Vector3d> ends{{5.0, 5.0, 1.0}, {3000.0, 5.0, 1.0}, {4.0, 7.0, 2.0}};
  const std::vector<std::uint8_t> returns{1, 1, 0};
  for (const Eigen::Vector3d& origin : {Eigen::Vector3d(1.0, 5.0, 1.0), Eigen::Vector3d(-2000.0, 5.0, 1.0)}) {
    expect_same_changes(map.insert_scan(origin, ends, returns), reference.insert_scan(origin, ends, returns), "far");
    expect_same_leaves(map.leaves(), reference.leaves(), "far");
  }
  EXPECT_EQ(map.voxel_state({5.01, 5.01, 1.01}), VoxelState::occupied);
  EXPECT_EQ(map.voxel_state({3.0, 5.0, 1.0}), VoxelState::free);
}

}  // namespace
}  // namespace campo
