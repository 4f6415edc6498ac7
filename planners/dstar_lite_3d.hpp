#pragma once
/// `dstar_lite_3d`: seed 001's LIDAR-mapped 3D grid navigation (001 §4.2,
/// SPEC §7.2). Each consecutive pair of mission waypoints, starting from the
/// vehicle's start, is a start/goal; D* Lite searches the 3D grid of
/// GridMap3d (unknown cells assumed free) from the goal to the vehicle's cell,
/// and the drone flies cell to cell along the path. Every fresh scan's hits
/// block their cells and the cells below them (mapping "columns"), or its rays
/// update an octree of free and occupied space that blocks the cells near
/// occupied voxels (mapping "octomap", OctoMap3d); only the cells that changed
/// go to D* Lite, which moves its start (k_m) and repairs the search.
#include <cstdint>
#include <memory>
#include <string>

#include "campo/config_fields.hpp"
#include "campo/planner.hpp"
#include "campo/planner_record.hpp"
#include "campo/record_fields.hpp"
#include "grid/grid_graph.hpp"
#include "planners/grid_map3d.hpp"
#include "planners/octomap3d.hpp"

namespace campo {

/// How LIDAR hits become the planning grid's occupancy.
enum class Mapping3d {
  columns,  ///< 001 §4.2.4: a hit blocks its cell and every cell below it (an overhang looks like a hill, 001 §6)
  octomap,  ///< free, occupied and unknown space from the rays in an octree (planners/octomap3d.hpp)
};

struct DStarLite3dConfig {
  std::string sensor;               ///< alias of the LIDAR; empty: the vehicle's first sensor
  int columns = 100;                ///< grid cells along x (east)
  int rows = 100;                   ///< grid cells along y (north)
  int levels = 9;                   ///< grid levels along z (001: 9, from -14 m to +42 m)
  double cell_size_m = 1.5;         ///< horizontal cell side (001: 1.5 m)
  double level_spacing_m = 7.0;     ///< vertical distance between levels (001: 7 m)
  int ground_level = 2;             ///< level at take-off ground height (001: 2)
  Eigen::Vector2d origin_m{0.0, 0.0};  ///< world x, y of the grid's south-west corner
  grid::Connectivity connectivity = grid::Connectivity::twenty_six;  ///< six or twenty_six
  /// Cost of a move of one level up or down, in horizontal cell moves, > 0;
  /// 0 = its length, level_spacing_m / cell_size_m (4.67). 001 gave every
  /// move the same cost: 1.
  double climb_cost_cells = 0.0;
  double speed_mps = 1.0;           ///< cruise speed (001 flew at 1 m/s)
  double tolerance_m = 0.5;         ///< a mission waypoint counts as reached within this distance
  int lookahead_cells = 3;          ///< fly up to this many cells ahead along a straight run of the path
  double cell_reached_m = 0.5;      ///< the search's start moves to the vehicle's cell within this distance of its centre
  Mapping3d mapping = Mapping3d::columns;  ///< "columns" (001, the default) or "octomap"
  OctoMap3dConfig octomap;                 ///< the octree's settings, for mapping "octomap" only
};

/// Limits of the planning grid (issue 16): its cells (about 40 bytes each
/// with the map and the search: 8 million take some 320 MB), and the cell
/// size and level spacing, so that positions convert to cells exactly
/// enough and a climb costs at most 1000 cell moves.
inline constexpr std::int64_t kMaxDStarLite3dCells = 8'000'000;
inline constexpr double kMinCellSizeM = 0.01;
inline constexpr double kMaxCellSizeM = 1000.0;

/// Throws InputError at `params` when the grid of `config` has more than
/// kMaxDStarLite3dCells cells or its derived climb cost exceeds 1000 cells.
/// parse_dstar_lite_3d_config runs it, so `campo run` and `campo validate` do.
void check_grid_size(const DStarLite3dConfig& config, const ParamsBlock& params);

std::unique_ptr<Planner> make_dstar_lite_3d_planner(const ParamsBlock& params, const PlannerContext& context);

/// The fields of `params` (keys as DStarLite3dConfig's members, "octomap" an
/// object of OctoMap3dConfig's); parameters() writes them back.
const ConfigFields<DStarLite3dConfig>& dstar_lite_3d_config_fields();

/// The configuration of `params` (keys as DStarLite3dConfig's fields;
/// connectivity "six" | "twenty_six"; mapping "columns" | "octomap", the
/// latter with an optional "octomap" object of OctoMap3dConfig's fields);
/// InputError naming the file and JSON pointer otherwise.
DStarLite3dConfig parse_dstar_lite_3d_config(const ParamsBlock& params);

/// The cost of a one-level climb the search uses, in horizontal cell moves.
double climb_cost_cells(const DStarLite3dConfig& config);

/// The map geometry of a configuration, with take-off ground at `ground_z_m`.
GridMap3dConfig grid_map_config(const DStarLite3dConfig& config, double ground_z_m);

/// The frame of the reconstructed height map (column mapping): a grid of
/// square cells in the horizontal plane.
struct HeightMapGrid {
  Eigen::Vector2d origin_m = Eigen::Vector2d::Zero();  ///< world x, y of the south-west corner of cell (0, 0), m
  double cell_size_m = 1.0;                             ///< side of a cell, m, > 0
  int columns = 1;                                      ///< cells along x (east), >= 1
  int rows = 1;                                         ///< cells along y (north), >= 1

  bool operator==(const HeightMapGrid&) const = default;
};

/// One column of the height map whose reconstructed top rose.
struct HeightMapColumn {
  int column = 0;      ///< cell index along x, from the grid's origin
  int row = 0;         ///< cell index along y
  double top_m = 0.0;  ///< world z of the centre of its highest blocked cell, m

  bool operator==(const HeightMapColumn&) const = default;
};

/// What dstar_lite_3d records beyond the generic decisions (docs/planners.md),
/// declared once: the description registered with it and its typed fields.
struct DStarLite3dRecord {
  PlannerRecord description;
  /// The height map's frame, recorded once, before its columns (column mapping only).
  RecordField<HeightMapGrid> height_map_grid;
  /// The height-map columns whose top rose this call, each listed once.
  RecordField<std::vector<HeightMapColumn>> height_map_columns;
  /// Planning cells an occupied voxel now blocks, [column, row, level] each (octomap mapping).
  RecordField<nlohmann::json> blocked_cells;
  /// Planning cells an occupied voxel no longer blocks (octomap mapping).
  RecordField<nlohmann::json> cleared_cells;
  /// Occupied leaves of the octree after the scan (octomap mapping).
  RecordField<std::int64_t> occupied_voxels;
  // The replanning step's details.
  RecordField<nlohmann::json> start_cell;
  RecordField<nlohmann::json> goal_cell;
  RecordField<std::int64_t> changed_cells;
  RecordField<std::int64_t> expansions;
  RecordField<double> mapping_ms;

  DStarLite3dRecord();
};
const DStarLite3dRecord& dstar_lite_3d_record();

}  // namespace campo
