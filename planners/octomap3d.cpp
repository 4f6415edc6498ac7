#include "planners/octomap3d.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <octomap/OcTree.h>

namespace campo {

struct OctoMap3d::Tree {
  explicit Tree(double resolution_m) : octree(resolution_m) {}
  octomap::OcTree octree;
  octomap::KeyRay ray;  ///< buffers reused from scan to scan
  octomap::KeySet free_keys;
  octomap::KeySet occupied_keys;
};

namespace {

void check(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("OctoMap3d: " + what);
}

octomap::point3d to_point(const Eigen::Vector3d& v) {
  return {static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z())};
}

// The indices i in [0, count) with after < i < before (empty when first > last).
std::pair<int, int> overlapping(double after, double before, int count) {
  const int first = std::max(0, static_cast<int>(std::floor(after)) + 1);
  const int last = std::min(count - 1, static_cast<int>(std::ceil(before)) - 1);
  return {first, last};
}

}  // namespace

OctoMap3d::OctoMap3d(const GridMap3dConfig& grid, const OctoMap3dConfig& config) : grid_(grid), config_(config) {
  const OctoMap3dConfig& c = config;
  check(c.resolution_m >= 0.05 && c.resolution_m <= 10.0, "resolution must be in [0.05, 10] m");
  check(c.probability_hit > 0.5 && c.probability_hit < 1.0, "hit probability must be in (0.5, 1)");
  check(c.probability_miss > 0.0 && c.probability_miss < 0.5, "miss probability must be in (0, 0.5)");
  check(c.occupied_threshold > 0.0 && c.occupied_threshold < 1.0, "occupied threshold must be in (0, 1)");
  check(c.clamping_min > 0.0 && c.clamping_min < c.occupied_threshold, "clamping minimum must be in (0, threshold)");
  check(c.clamping_max > c.occupied_threshold && c.clamping_max < 1.0, "clamping maximum must be in (threshold, 1)");
  check(c.vehicle_radius_m >= 0.0 && c.vehicle_radius_m <= 100.0, "vehicle radius must be in [0, 100] m");
  tree_ = std::make_unique<Tree>(c.resolution_m);
  octomap::OcTree& t = tree_->octree;
  t.setProbHit(c.probability_hit);
  t.setProbMiss(c.probability_miss);
  t.setOccupancyThres(c.occupied_threshold);
  t.setClampingThresMin(c.clamping_min);
  t.setClampingThresMax(c.clamping_max);
  t.enableChangeDetection(true);
  near_occupied_.assign(static_cast<std::size_t>(grid.columns) * grid.rows * grid.levels, 0);
}

OctoMap3d::~OctoMap3d() = default;
OctoMap3d::OctoMap3d(OctoMap3d&&) noexcept = default;
OctoMap3d& OctoMap3d::operator=(OctoMap3d&&) noexcept = default;

void OctoMap3d::count_voxel(const Eigen::Vector3d& c, int delta, std::vector<std::size_t>& touched) {
  const GridMap3dConfig& g = grid_.config();
  const double reach = 0.5 * config_.resolution_m + config_.vehicle_radius_m;
  // Column i spans [i, i + 1] cells from the origin; grown by the reach it
  // overlaps the voxel when (c - reach) / s - 1 < i < (c + reach) / s.
  const auto [x0, x1] = overlapping((c.x() - reach - g.origin_m.x()) / g.cell_size_m - 1.0,
                                    (c.x() + reach - g.origin_m.x()) / g.cell_size_m, g.columns);
  const auto [y0, y1] = overlapping((c.y() - reach - g.origin_m.y()) / g.cell_size_m - 1.0,
                                    (c.y() + reach - g.origin_m.y()) / g.cell_size_m, g.rows);
  // Level k spans [k - 0.5, k + 0.5] level spacings about ground level.
  const double level = (c.z() - g.ground_z_m) / g.level_spacing_m + g.ground_level;
  const double reach_levels = reach / g.level_spacing_m;
  const auto [z0, z1] = overlapping(level - reach_levels - 0.5, level + reach_levels + 0.5, g.levels);
  for (int z = z0; z <= z1; ++z) {
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        const std::size_t i = (static_cast<std::size_t>(z) * g.rows + y) * g.columns + x;
        const std::int32_t before = near_occupied_[i];
        near_occupied_[i] += delta;
        if ((before > 0) != (near_occupied_[i] > 0)) touched.push_back(i);
      }
    }
  }
}

std::vector<grid::CellChange> OctoMap3d::insert_scan(const Eigen::Vector3d& origin_m,
                                                     std::span<const Eigen::Vector3d> ends_m,
                                                     std::span<const std::uint8_t> returns) {
  if (ends_m.size() != returns.size()) throw std::invalid_argument("OctoMap3d: one return flag per ray");
  octomap::OcTree& t = tree_->octree;
  // As OctoMap's own scan insertion (computeUpdate): every voxel is updated
  // once per scan, and a voxel some ray ended in is occupied even if another
  // ray crossed it. Updates of distinct voxels commute, so the map does not
  // depend on the sets' order.
  octomap::KeySet& free_keys = tree_->free_keys;
  octomap::KeySet& occupied_keys = tree_->occupied_keys;
  free_keys.clear();
  occupied_keys.clear();
  const octomap::point3d origin = to_point(origin_m);
  for (std::size_t i = 0; i < ends_m.size(); ++i) {
    const octomap::point3d end = to_point(ends_m[i]);
    if (t.computeRayKeys(origin, end, tree_->ray)) free_keys.insert(tree_->ray.begin(), tree_->ray.end());
    octomap::OcTreeKey end_key;
    if (!t.coordToKeyChecked(end, end_key)) continue;
    (returns[i] ? occupied_keys : free_keys).insert(end_key);
  }
  for (const octomap::OcTreeKey& key : occupied_keys) free_keys.erase(key);

  // Lazy updates: only leaves are read, so inner nodes are never brought up
  // to date (nor pruned). OctoMap's change detection lists the leaves created
  // or whose occupancy flipped.
  t.resetChangeDetection();
  for (const octomap::OcTreeKey& key : free_keys) t.updateNode(key, false, true);
  for (const octomap::OcTreeKey& key : occupied_keys) t.updateNode(key, true, true);

  // Every voxel that turned occupied, or stopped being occupied, moves the
  // counts of the planning cells near it.
  std::vector<std::size_t> touched;
  for (auto it = t.changedKeysBegin(); it != t.changedKeysEnd(); ++it) {
    const octomap::OcTreeNode* node = t.search(it->first);
    const bool is = node && t.isNodeOccupied(node);
    const bool was = it->second ? false : !is;  // true: created in this scan (unknown before)
    if (was == is) continue;
    const octomap::point3d c = t.keyToCoord(it->first);
    occupied_leaves_ += is ? 1 : -1;
    count_voxel({c.x(), c.y(), c.z()}, is ? 1 : -1, touched);
  }

  // A cell's count crossed zero once per entry: an even number of crossings
  // leaves it as it was before the scan.
  std::sort(touched.begin(), touched.end());
  const GridMap3dConfig& g = grid_.config();
  std::vector<grid::CellChange> changes;
  for (std::size_t a = 0; a < touched.size();) {
    std::size_t b = a;
    while (b < touched.size() && touched[b] == touched[a]) ++b;
    if ((b - a) % 2 == 1) {
      const std::size_t i = touched[a];
      const int x = static_cast<int>(i % g.columns);
      const int y = static_cast<int>(i / g.columns % g.rows);
      const int z = static_cast<int>(i / (static_cast<std::size_t>(g.columns) * g.rows));
      changes.push_back({{x, y, z}, near_occupied_[i] > 0 ? grid::CellState::blocked : grid::CellState::unknown});
    }
    a = b;
  }
  return changes;
}

VoxelState OctoMap3d::voxel_state(const Eigen::Vector3d& point_m) const {
  const octomap::OcTreeNode* node = tree_->octree.search(to_point(point_m));
  if (!node) return VoxelState::unknown;
  return tree_->octree.isNodeOccupied(node) ? VoxelState::occupied : VoxelState::free;
}

grid::CellState OctoMap3d::state(const grid::Cell& c) const {
  if (!grid_.contains(c)) throw std::out_of_range("OctoMap3d: cell outside the grid");
  const GridMap3dConfig& g = grid_.config();
  const std::size_t i = (static_cast<std::size_t>(c.z) * g.rows + c.y) * g.columns + c.x;
  return near_occupied_[i] > 0 ? grid::CellState::blocked : grid::CellState::unknown;
}

std::vector<OccupiedVoxel> OctoMap3d::occupied_voxels() const {
  std::vector<OccupiedVoxel> voxels;
  const octomap::OcTree& t = tree_->octree;
  for (auto it = t.begin_leafs(), end = t.end_leafs(); it != end; ++it) {
    if (t.isNodeOccupied(*it)) voxels.push_back({{it.getX(), it.getY(), it.getZ()}, it.getSize()});
  }
  return voxels;
}

}  // namespace campo
