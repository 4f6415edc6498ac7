#include "planners/octomap3d.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <octomap/OcTree.h>

namespace campo {

namespace {

// The set of voxels one scan updates: open addressing with linear probing
// over keys packed in 48 bits, its slots reused from scan to scan (OctoMap's
// KeySet, a node-based unordered_set, allocates for every key it inserts).
// A slot's top 16 bits hold the scan it was filled in, so emptying the table
// is starting a new scan, not clearing its slots.
class KeyTable {
 public:
  // Empties the table.
  void clear() {
    if (++scan_ == 0) {  // the scan numbers wrapped: old slots could look current
      std::fill(slots_.begin(), slots_.end(), 0);
      scan_ = 1;
    }
    tag_ = static_cast<std::uint64_t>(scan_) << 48;
    size_ = 0;
  }
  // True when the key was not in the table.
  bool insert(const octomap::OcTreeKey& key) {
    if (size_ >= limit_) grow();
    return place(tag_ | static_cast<std::uint64_t>(key[0]) | static_cast<std::uint64_t>(key[1]) << 16 |
                 static_cast<std::uint64_t>(key[2]) << 32);
  }

 private:
  bool place(std::uint64_t tagged) {
    // Fibonacci hashing: the product's high bits mix all three coordinates.
    for (std::size_t i = (tagged * 0x9E3779B97F4A7C15ull) >> shift_;; i = (i + 1) & mask_) {
      const std::uint64_t slot = slots_[i];
      if (slot == tagged) return false;
      if ((slot ^ tag_) >> 48 != 0) {  // empty in this scan
        slots_[i] = tagged;
        ++size_;
        return true;
      }
    }
  }
  // Doubles the slots (at most half of them are full), keeping this scan's keys.
  void grow() {
    std::vector<std::uint64_t> old(slots_.empty() ? 4096 : 2 * slots_.size(), 0);
    old.swap(slots_);
    mask_ = slots_.size() - 1;
    shift_ = 64 - std::countr_zero(slots_.size());
    limit_ = slots_.size() / 2;
    size_ = 0;
    for (const std::uint64_t slot : old) {
      if ((slot ^ tag_) >> 48 == 0) place(slot);
    }
  }
  std::vector<std::uint64_t> slots_;
  std::size_t mask_ = 0;
  int shift_ = 64;
  std::size_t size_ = 0;
  std::size_t limit_ = 0;  ///< grow before holding more keys than this
  std::uint16_t scan_ = 0;
  std::uint64_t tag_ = 0;
};

// The keys OctoMap's computeRayKeys lists for the ray from `origin` to `end`
// (the voxels it crosses, the origin's first, the end's left out; none when
// both lie in one voxel), given to `visit` in that order, for a ray whose ends
// lie inside the octree with keys `origin_key` and `end_key`. The same
// traversal (Amanatides & Woo) in the same arithmetic, float and double as
// OctoMap has them, without its KeyRay buffer and with the origin's key found
// once per scan.
template <class Visit>
void ray_keys(const octomap::OcTree& t, const octomap::point3d& origin, const octomap::OcTreeKey& origin_key,
              const octomap::point3d& end, const octomap::OcTreeKey& end_key, Visit&& visit) {
  if (origin_key == end_key) return;
  visit(origin_key);
  octomap::point3d direction = end - origin;
  const float length = static_cast<float>(direction.norm());
  direction /= length;
  const double resolution = t.getResolution();
  int step[3];
  double t_max[3];
  double t_delta[3];
  octomap::OcTreeKey key = origin_key;
  for (int i = 0; i < 3; ++i) {
    step[i] = direction(i) > 0.0 ? 1 : direction(i) < 0.0 ? -1 : 0;
    if (step[i] != 0) {
      double border = t.keyToCoord(key[i]);
      border += static_cast<float>(step[i] * resolution * 0.5);
      t_max[i] = (border - origin(i)) / direction(i);
      t_delta[i] = resolution / std::fabs(direction(i));
    } else {
      t_max[i] = std::numeric_limits<double>::max();
      t_delta[i] = std::numeric_limits<double>::max();
    }
  }
  while (true) {
    const int dim = t_max[0] < t_max[1] ? (t_max[0] < t_max[2] ? 0 : 2) : (t_max[1] < t_max[2] ? 1 : 2);
    key[dim] = static_cast<octomap::key_type>(key[dim] + step[dim]);
    t_max[dim] += t_delta[dim];
    if (key == end_key) return;
    // Past the ray's length without reaching the end's voxel (rounding): stop.
    if (std::min(std::min(t_max[0], t_max[1]), t_max[2]) > length) return;
    visit(key);
  }
}

// An OcTree whose leaves are updated as OccupancyOcTreeBase::updateNode with
// lazy evaluation does (inner nodes keep their values, nothing is pruned),
// walking down from the deepest node the previous key shares with this one
// instead of twice from the root (updateNode's search, then its update).
class Octree : public octomap::OcTree {
 public:
  using OcTree::OcTree;

  // A leaf's occupancy before and after an update (unknown counts as not occupied).
  struct Change {
    bool was_occupied = false;
    bool is_occupied = false;
  };

  // Forgets the previous key: the next walk starts at the root.
  void begin_walk() { walked_ = false; }

  // Adds `log_odds` to the leaf of `key` (creating it and its ancestors as
  // updateNodeRecurs does), clamped to the clamping thresholds.
  Change update_leaf(const octomap::OcTreeKey& key, float log_odds) {
    constexpr int kDepth = 16;  // OcTree's tree_depth
    int depth = 0;              // depth of the deepest node known on the key's path
    bool created = false;       // that node was created by this update
    if (!root) {
      root = new octomap::OcTreeNode();
      ++tree_size;
      walked_ = false;
      created = true;
    }
    if (walked_) {
      // Keys share the nodes above their highest differing bit.
      const unsigned diff = static_cast<unsigned>((key[0] ^ last_[0]) | (key[1] ^ last_[1]) | (key[2] ^ last_[2]));
      depth = kDepth - static_cast<int>(std::bit_width(diff));
    }
    path_[0] = root;
    octomap::OcTreeNode* node = path_[depth];
    for (; depth < kDepth; ++depth) {
      const unsigned pos = octomap::computeChildIdx(key, kDepth - 1 - depth);
      if (!nodeChildExists(node, pos)) {
        if (!nodeHasChildren(node) && !created) {
          expandNode(node);  // a pruned node, as updateNodeRecurs expands it (this map never prunes)
        } else {
          createNodeChild(node, pos);
          created = true;
        }
      } else {
        created = false;
      }
      node = getNodeChild(node, pos);
      path_[depth + 1] = node;
    }
    last_ = key;
    walked_ = true;

    // updateNode's early exit (a leaf at the clamping bound in the update's
    // direction stays as it is) and updateNodeLogOdds.
    const float before = node->getLogOdds();
    const bool was_occupied = !created && isNodeOccupied(node);
    if (!created && ((log_odds >= 0.0f && before >= clamping_thres_max) ||
                     (log_odds <= 0.0f && before <= clamping_thres_min))) {
      return {was_occupied, was_occupied};
    }
    float after = before + log_odds;
    if (after < clamping_thres_min) {
      after = clamping_thres_min;
    } else if (after > clamping_thres_max) {
      after = clamping_thres_max;
    }
    node->setLogOdds(after);
    return {was_occupied, isNodeOccupied(node)};
  }

 private:
  std::array<octomap::OcTreeNode*, 17> path_{};  ///< path_[d]: the node at depth d on the previous key's path
  octomap::OcTreeKey last_;
  bool walked_ = false;
};

}  // namespace

struct OctoMap3d::Tree {
  explicit Tree(double resolution_m) : octree(resolution_m) {}
  Octree octree;
  // Buffers reused from scan to scan.
  octomap::KeyRay ray;
  KeyTable seen;
  std::vector<octomap::OcTreeKey> occupied_keys;
  std::vector<octomap::OcTreeKey> free_keys;
  std::vector<octomap::OcTreeKey> end_keys;  ///< per ray: its end's key
  std::vector<std::uint8_t> end_inside;      ///< per ray: its end lies inside the octree
};

namespace {

void check(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("OctoMap3d: " + what);
}

octomap::point3d to_point(const Eigen::Vector3d& v) {
  return {static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z())};
}

// The centre a voxel's planning cells are counted from: OctoMap's centre of
// the key in double on x and y, rounded to float on z. The first version took
// OctoMap's float centre (keyToCoord of the whole key), but GCC 12 at -O2 and
// -O3 kept x and y in double there (it dropped their float rounding, and not
// z's), which decides which cell a voxel whose grown box ends within the
// rounding of a cell face reaches; kept, so cells change as they did.
Eigen::Vector3d voxel_center(const octomap::OcTree& t, const octomap::OcTreeKey& key) {
  return {t.keyToCoord(key[0]), t.keyToCoord(key[1]), static_cast<double>(static_cast<float>(t.keyToCoord(key[2])))};
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
  Octree& t = tree_->octree;
  t.setProbHit(c.probability_hit);
  t.setProbMiss(c.probability_miss);
  t.setOccupancyThres(c.occupied_threshold);
  t.setClampingThresMin(c.clamping_min);
  t.setClampingThresMax(c.clamping_max);
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
  Octree& t = tree_->octree;
  // As OctoMap's own scan insertion (computeUpdate): every voxel is updated
  // once per scan, and a voxel some ray ended in is occupied even if another
  // ray crossed it. The returns' voxels go into the set first, so a crossed
  // voxel already there is skipped; the order of first sight is kept, in
  // which a ray's voxels are neighbours in the tree.
  KeyTable& seen = tree_->seen;
  std::vector<octomap::OcTreeKey>& occupied_keys = tree_->occupied_keys;
  std::vector<octomap::OcTreeKey>& free_keys = tree_->free_keys;
  std::vector<octomap::OcTreeKey>& end_keys = tree_->end_keys;
  std::vector<std::uint8_t>& end_inside = tree_->end_inside;
  seen.clear();
  occupied_keys.clear();
  free_keys.clear();
  end_keys.resize(ends_m.size());
  end_inside.resize(ends_m.size());
  for (std::size_t i = 0; i < ends_m.size(); ++i) {
    end_inside[i] = t.coordToKeyChecked(to_point(ends_m[i]), end_keys[i]);
    if (returns[i] && end_inside[i] && seen.insert(end_keys[i])) occupied_keys.push_back(end_keys[i]);
  }
  const octomap::point3d origin = to_point(origin_m);
  octomap::OcTreeKey origin_key;
  const bool origin_inside = t.coordToKeyChecked(origin, origin_key);
  const auto add_free = [&](const octomap::OcTreeKey& key) {
    if (seen.insert(key)) free_keys.push_back(key);
  };
  for (std::size_t i = 0; i < ends_m.size(); ++i) {
    const octomap::point3d end = to_point(ends_m[i]);
    if (origin_inside && end_inside[i]) {
      ray_keys(t, origin, origin_key, end, end_keys[i], add_free);
    } else if (t.computeRayKeys(origin, end, tree_->ray)) {  // fails, with OctoMap's warning
      for (const octomap::OcTreeKey& key : tree_->ray) add_free(key);
    }
    if (!returns[i] && end_inside[i]) add_free(end_keys[i]);
  }

  // Every voxel that turned occupied, or stopped being occupied, moves the
  // counts of the planning cells near it.
  std::vector<std::size_t> touched;
  const auto update = [&](const std::vector<octomap::OcTreeKey>& keys, float log_odds) {
    t.begin_walk();
    for (const octomap::OcTreeKey& key : keys) {
      const Octree::Change change = t.update_leaf(key, log_odds);
      if (change.was_occupied == change.is_occupied) continue;
      occupied_leaves_ += change.is_occupied ? 1 : -1;
      count_voxel(voxel_center(t, key), change.is_occupied ? 1 : -1, touched);
    }
  };
  update(free_keys, t.getProbMissLog());
  update(occupied_keys, t.getProbHitLog());

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

std::vector<std::array<std::uint16_t, 3>> OctoMap3d::ray_voxels(const Eigen::Vector3d& origin_m,
                                                                 const Eigen::Vector3d& end_m) const {
  std::vector<std::array<std::uint16_t, 3>> keys;
  const octomap::OcTree& t = tree_->octree;
  const octomap::point3d origin = to_point(origin_m), end = to_point(end_m);
  octomap::OcTreeKey origin_key, end_key;
  if (!t.coordToKeyChecked(origin, origin_key) || !t.coordToKeyChecked(end, end_key)) return keys;
  ray_keys(t, origin, origin_key, end, end_key, [&](const octomap::OcTreeKey& k) { keys.push_back({k[0], k[1], k[2]}); });
  return keys;
}

std::vector<OctreeLeaf> OctoMap3d::leaves() const {
  std::vector<OctreeLeaf> leaves;
  const octomap::OcTree& t = tree_->octree;
  for (auto it = t.begin_leafs(), end = t.end_leafs(); it != end; ++it) {
    const octomap::OcTreeKey& key = it.getKey();
    leaves.push_back({{key[0], key[1], key[2]}, static_cast<int>(it.getDepth()), it->getLogOdds()});
  }
  return leaves;
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
