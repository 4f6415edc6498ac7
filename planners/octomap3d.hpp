#pragma once
/// A 3D occupancy map for `dstar_lite_3d` built on an OctoMap octree: free,
/// occupied and unknown space from LIDAR rays, instead of seed 001's columns
/// (planners/grid_map3d.hpp), so an overhang such as a bridge deck keeps the
/// free space under it (lifting the limit 001 §6 names). Each scan's rays are
/// cast through the octree: the voxels a ray crosses are updated as free, a
/// hit's voxel as occupied, and a beam without a return is free up to its
/// range. A cell of the planning grid (GridMap3dConfig's columns x rows x
/// levels) is blocked while an occupied voxel lies within the cell's box grown
/// by the vehicle's radius; free and unknown cells are traversable (001's
/// optimistic assumption). Pure data, no Bullet; the octree is private.
#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "grid/grid_graph.hpp"
#include "planners/grid_map3d.hpp"

namespace campo {

/// Probabilities default to OctoMap's own defaults.
struct OctoMap3dConfig {
  double resolution_m = 0.75;       ///< octree leaf side, [0.05, 10] m; half of 001's 1.5 m cell, so faces align
  double probability_hit = 0.7;     ///< occupancy probability a return gives its voxel, (0.5, 1)
  double probability_miss = 0.4;    ///< occupancy probability a ray gives the voxels it crosses, (0, 0.5)
  double occupied_threshold = 0.5;  ///< a voxel is occupied above this probability, (0, 1)
  double clamping_min = 0.1192;     ///< occupancy probability clamped below here, (0, occupied_threshold)
  double clamping_max = 0.971;      ///< and above here, (occupied_threshold, 1)
  double vehicle_radius_m = 0.5;    ///< planning cells within this of an occupied voxel are blocked, [0, 100] m
};

/// One voxel's state in the octree.
enum class VoxelState : std::uint8_t { unknown, free, occupied };

/// An occupied octree voxel: its centre and side.
struct OccupiedVoxel {
  Eigen::Vector3d center_m = Eigen::Vector3d::Zero();
  double size_m = 0.0;
};

/// One leaf of the octree as OctoMap stores it, to tell whether two maps are
/// the same.
struct OctreeLeaf {
  std::array<std::uint16_t, 3> key{};  ///< OctoMap's key: voxel index + 2^15 on each axis, at depth 16
  int depth = 0;                       ///< 16 for a voxel of resolution_m, less for a pruned one
  float log_odds = 0.0f;               ///< occupancy log-odds
};

class OctoMap3d {
 public:
  /// Throws std::invalid_argument for a grid or octree configuration out of range.
  OctoMap3d(const GridMap3dConfig& grid, const OctoMap3dConfig& config);
  ~OctoMap3d();
  OctoMap3d(OctoMap3d&&) noexcept;
  OctoMap3d& operator=(OctoMap3d&&) noexcept;

  const GridMap3d& grid() const { return grid_; }
  const OctoMap3dConfig& config() const { return config_; }

  /// Casts one scan from `origin_m`: ray i ends at ends_m[i], a return when
  /// returns[i] is non-zero (its voxel occupied), else the end of a beam
  /// without a return (free all the way). Returns the planning cells whose
  /// blocked state changed (by level, then row, then column), for D* Lite.
  std::vector<grid::CellChange> insert_scan(const Eigen::Vector3d& origin_m, std::span<const Eigen::Vector3d> ends_m,
                                            std::span<const std::uint8_t> returns);

  /// The octree's state at a world point.
  VoxelState voxel_state(const Eigen::Vector3d& point_m) const;
  /// Planning cell: blocked, or unknown (traversable; nothing occupied near it).
  grid::CellState state(const grid::Cell& cell) const;
  /// Every occupied leaf of the octree, in the octree's order.
  std::vector<OccupiedVoxel> occupied_voxels() const;
  /// The keys (as OctreeLeaf::key) of the voxels a ray from `origin_m` to
  /// `end_m` crosses and insert_scan updates as free, in order from the
  /// origin's, the end's left out: what OctoMap's computeRayKeys lists.
  /// Empty when both lie in one voxel or either lies outside the octree.
  std::vector<std::array<std::uint16_t, 3>> ray_voxels(const Eigen::Vector3d& origin_m, const Eigen::Vector3d& end_m) const;
  /// Every leaf of the octree (free and occupied), in the octree's order.
  std::vector<OctreeLeaf> leaves() const;
  /// Occupied voxels counted at leaf size.
  std::int64_t occupied_leaf_count() const { return occupied_leaves_; }

 private:
  struct Tree;
  // Adds `delta` to the occupied-voxel count of every planning cell the voxel
  // centred at `center_m` (grown by the vehicle radius) touches.
  void count_voxel(const Eigen::Vector3d& center_m, int delta, std::vector<std::size_t>& touched);

  GridMap3d grid_;  ///< the planning grid's geometry (its own column heights stay empty)
  OctoMap3dConfig config_;
  std::unique_ptr<Tree> tree_;
  std::vector<std::int32_t> near_occupied_;  ///< per planning cell: occupied leaves within reach; blocked when > 0
  std::int64_t occupied_leaves_ = 0;
};

}  // namespace campo
