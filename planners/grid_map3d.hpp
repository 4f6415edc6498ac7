#pragma once
/// The 3D occupancy grid of seed 001 §4.2 (SPEC §7.2): columns of cells over
/// the map, levels a fixed spacing apart with one level at take-off ground
/// height. A LIDAR hit marks its cell and every cell below it blocked
/// (001 §4.2.4), so the map is a reconstructed height field: an overhang
/// looks like a hill (001 §6). Pure data, no Bullet.
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "grid/grid_graph.hpp"

namespace campo {

struct GridMap3dConfig {
  int columns = 100;                 ///< cells along x (east), 1..32000
  int rows = 100;                    ///< cells along y (north), 1..32000
  int levels = 9;                    ///< cells along z, 1..32000
  double cell_size_m = 1.5;          ///< horizontal cell side, > 0
  double level_spacing_m = 7.0;      ///< vertical distance between levels, > 0
  int ground_level = 2;              ///< index of the level at take-off ground height, 0..levels-1
  Eigen::Vector2d origin_m{0.0, 0.0};  ///< world x, y of the grid's south-west corner
  double ground_z_m = 0.0;           ///< world z of take-off ground (the centre of ground_level)
};

class GridMap3d {
 public:
  /// Throws std::invalid_argument for sizes or spacings out of range.
  explicit GridMap3d(const GridMap3dConfig& config);

  const GridMap3dConfig& config() const { return config_; }
  grid::GridSize size() const { return {config_.columns, config_.rows, config_.levels}; }
  bool contains(const grid::Cell& cell) const;

  /// The cell containing a world point: x -> column, y -> row (floor of the
  /// offset from the origin over the cell size), z -> level (nearest level
  /// centre, 001 §4.2.4). May lie outside the grid.
  grid::Cell cell_of(const Eigen::Vector3d& point_m) const;
  /// World position of a cell's centre (its level's height for z).
  Eigen::Vector3d center(const grid::Cell& cell) const;

  grid::CellState state(const grid::Cell& cell) const;
  /// Marks the hit's cell and every cell below it in its column blocked
  /// (levels below the grid are clamped; above it, the whole column).
  /// Returns the cells that were not blocked before, for D* Lite; nothing for
  /// a hit outside the grid's columns or below its lowest level.
  std::vector<grid::CellChange> mark_hit(const Eigen::Vector3d& point_m);

  /// Highest blocked level of a column, nullopt when none is blocked.
  std::optional<int> top_blocked_level(int column, int row) const;
  /// World height of the top of every column's reconstructed obstacle or
  /// terrain (the centre of its highest blocked level), NaN where nothing is
  /// blocked; rows x columns, row-major from the south-west corner.
  std::vector<double> height_map_m() const;

 private:
  GridMap3dConfig config_;
  std::vector<int> top_;  ///< per column: highest blocked level, -1 when none (blocked cells form a prefix)
};

}  // namespace campo
