#pragma once
/// 2D occupancy grid for ground vehicles (SPEC §7.3, seed 003 §2.1.1): the
/// scene's obstacles up to the vehicle's height projected onto the ground
/// plane, optionally inflated by the vehicle's radius. Plain data, so the
/// rover planners (A*, RRT*, VFH+, smoothing) take it without seeing Bullet.
#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace campo {

struct Scene;

/// Cell (col, row) covers x in [origin.x + col r, origin.x + (col + 1) r),
/// y in [origin.y + row r, origin.y + (row + 1) r), r = resolution_m:
/// row 0 is the south edge, columns grow east.
struct OccupancyGrid {
  int cols = 0;
  int rows = 0;
  double resolution_m = 0.1;
  Eigen::Vector2d origin_m = Eigen::Vector2d::Zero();  ///< south-west corner of cell (0, 0)
  std::vector<std::uint8_t> occupied;                  ///< row-major, cols * rows; 1 = obstacle

  bool contains(int col, int row) const { return col >= 0 && row >= 0 && col < cols && row < rows; }
  /// Outside the grid counts as occupied.
  bool is_occupied(int col, int row) const {
    return !contains(col, row) || occupied[static_cast<std::size_t>(row) * cols + col] != 0;
  }
  /// Cell holding a world point (may be outside the grid).
  Eigen::Vector2i cell_of(const Eigen::Vector2d& point_m) const;
  /// Centre of a cell in world coordinates.
  Eigen::Vector2d centre_of(int col, int row) const;
  /// Whether the point's cell is occupied (outside counts as occupied).
  bool is_occupied(const Eigen::Vector2d& point_m) const {
    const Eigen::Vector2i c = cell_of(point_m);
    return is_occupied(c.x(), c.y());
  }
  /// Whether the straight segment a-b crosses no occupied cell (every cell
  /// the segment touches is checked, not samples along it: an Amanatides-Woo
  /// walk; where it passes through a cell corner, within 1e-9 cells, both
  /// cells beside the corner count too). Non-finite points are never free.
  /// The walk stops at the first occupied or outside cell, so it looks up at
  /// most 2 (|a - b|_1 / resolution_m + 2) cells, however large the grid;
  /// `cells_checked`, when given, is increased by the look-ups made.
  bool segment_free(const Eigen::Vector2d& a_m, const Eigen::Vector2d& b_m,
                    std::int64_t* cells_checked = nullptr) const;
};

struct OccupancyConfig {
  double resolution_m = 0.1;      ///< cell size
  double vehicle_height_m = 1.0;  ///< obstacles from the ground up to this height count
  double ground_clearance_m = 0.05;  ///< surfaces lower than this above the ground are terrain
  double margin_m = 1.0;          ///< grid extends this far beyond the scene's obstacles
  std::int64_t max_cells = 100'000'000;  ///< larger grids are refused (hostile scenes)
};

/// The scene's static shapes (not planes or heightfields, not movers, not
/// dynamic bodies) between ground_clearance_m and vehicle_height_m above the
/// ground, projected down. Tested at the points of a half-cell lattice (cell
/// corners, edge midpoints, centres): a point is covered when the vertical
/// line through it passes strictly inside a shape somewhere strictly inside
/// the band, the ground taken under the point (Scene::ground_height, 0 where
/// there is none); a cell is occupied when any of its nine points is. So an
/// obstacle half a cell wide never vanishes, wherever it sits on the grid,
/// and a box whose sides lie on cell edges covers exactly the cells inside
/// it. Exact for any orientation of cuboids, cylinders, spheres and cones.
/// Bounds: the obstacles' bounding box, the vehicles' start and mission
/// points, plus margin_m, with the origin on a multiple of resolution_m; an
/// empty grid (0 x 0) when there is nothing. Throws std::invalid_argument for
/// a bad config or more than max_cells cells.
OccupancyGrid build_occupancy_grid(const Scene& scene, const OccupancyConfig& config = {});

/// The (x, y) box build_occupancy_grid covers before its margin: the static
/// obstacles' bounding box and the vehicles' start points, plus their
/// mission waypoints when `with_missions`. Empty when there is nothing.
Eigen::AlignedBox2d occupancy_bounds(const Scene& scene, bool with_missions = true);
/// Columns (x) and rows (y) of the grid build_occupancy_grid makes over
/// `bounds` (0 x 0 for an empty box); doubles, so that hostile extents are
/// measured without overflow before anything is allocated.
Eigen::Vector2d occupancy_grid_cells(const Eigen::AlignedBox2d& bounds, const OccupancyConfig& config);

/// Every cell whose centre lies within radius_m of an occupied cell's centre
/// becomes occupied (exact Euclidean distance via cv::distanceTransform;
/// radius 0 returns a copy). Cells outside the grid do not inflate.
/// Throws std::invalid_argument for a negative or non-finite radius.
OccupancyGrid inflate(const OccupancyGrid& grid, double radius_m);

}  // namespace campo
