#pragma once
/// Scene generators (SPEC §3): pure functions from a config and a seed to
/// shapes. Same config => same output, bit for bit. Every generator works in
/// its own local frame; the loader places the result with the generator's pose.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "campo/scene.hpp"

namespace campo {

/// Ground height at a world (x, y), used to stand generated objects on terrain.
using GroundFunction = std::function<double(double x_m, double y_m)>;

/// Smooth hills: a sum of `waves` plane waves of the given wavelength with
/// seeded directions and phases, scaled so the surface spans at most
/// +-amplitude_m.
struct RollingTerrainConfig {
  Eigen::Vector2d size_m{100.0, 100.0};  ///< extent along x and y, metres
  double spacing_m = 0.5;                ///< vertex spacing, metres
  double amplitude_m = 1.0;              ///< peak height above/below 0, metres
  double wavelength_m = 20.0;            ///< dominant hill wavelength, metres
  int waves = 4;                         ///< number of superposed waves, [1, 32]
  std::uint64_t seed = 1;
};
HeightGrid make_rolling_terrain(const RollingTerrainConfig& config);

enum class CrownShape { sphere, cone };

/// Trees scattered in a rectangle with a minimum trunk spacing, each trunk
/// standing on the ground (its base 0.2 m below the ground height at the trunk
/// centre so it never floats on a slope).
struct TreesConfig {
  Eigen::Vector2d area_min_m{-10.0, -10.0};  ///< rectangle in world x, y
  Eigen::Vector2d area_max_m{10.0, 10.0};
  int count = 20;                        ///< number of trees, [0, 10000]
  double min_spacing_m = 2.0;            ///< between trunk centres
  Eigen::Vector2d trunk_radius_m{0.15, 0.3};   ///< uniform in [min, max]
  Eigen::Vector2d trunk_height_m{2.0, 4.0};
  CrownShape crown = CrownShape::sphere;
  Eigen::Vector2d crown_radius_m{0.8, 1.6};
  double crown_height_ratio = 2.0;       ///< cone height / cone radius
  /// Circles (x, y, radius) kept free of trees (start and goal areas).
  std::vector<Eigen::Vector3d> keep_out;
  std::uint64_t seed = 1;
};
/// Shapes aliased "<alias>/tree<i>/trunk" and "<alias>/tree<i>/crown".
/// Throws std::runtime_error when `count` trees cannot be placed.
std::vector<Shape> make_trees(const TreesConfig& config, const std::string& alias,
                              const GroundFunction& ground);

/// A vineyard in its local frame: field centred on the origin, rows along
/// local y, equispaced across x, a fence around the field, headlands at both
/// row ends, and random obstacles in the spaces between rows.
struct VineyardConfig {
  Eigen::Vector2d field_size_m{100.0, 100.0};  ///< fenced area, x by y
  int row_count = 16;                   ///< vine rows, [1, 500]
  double row_spacing_m = 3.0;           ///< centre to centre, across x
  double headland_m = 8.0;              ///< free space between row ends and the fence
  double post_spacing_m = 5.0;          ///< along a row
  double post_radius_m = 0.05;
  double post_height_m = 2.0;
  double canopy_width_m = 0.6;          ///< across the row
  double canopy_bottom_m = 0.6;         ///< above ground
  double canopy_top_m = 1.8;            ///< above ground
  double fence_height_m = 1.5;
  double fence_thickness_m = 0.1;
  int obstacle_count = 6;               ///< random boxes between rows, [0, 10000]
  Eigen::Vector2d obstacle_size_m{0.3, 0.8};  ///< edge length range (x, y, z alike)
  /// Each obstacle leaves a free passage at least this wide between itself
  /// and one of its rows (0: anywhere between the rows), so a vehicle of
  /// that width can get past.
  double obstacle_passage_m = 0.0;
  std::uint64_t seed = 1;
};
/// Shapes in the vineyard's local frame (z = 0 ground), aliased
/// "<alias>/row<i>/post<j>", "<alias>/row<i>/canopy", "<alias>/fence/<side>",
/// "<alias>/obstacle<k>".
std::vector<Shape> make_vineyard(const VineyardConfig& config, const std::string& alias);

/// One block of cells: rows and columns are 1-based and inclusive.
struct GridBox {
  int row_first = 1;
  int row_last = 1;
  int col_first = 1;
  int col_last = 1;
  double height_m = 10.0;  ///< top above the highest ground under the block
};

/// Cell-indexed boxes (SPEC §8, 001 scenarios). Row 1 is the southernmost
/// row (y grows northward), column 1 the westernmost (x grows eastward).
/// Cell (r, c) spans x in [origin.x + (c-1) s, origin.x + c s],
/// y in [origin.y + (r-1) s, origin.y + r s].
struct GridObstaclesConfig {
  Eigen::Vector2d origin_m{0.0, 0.0};  ///< south-west corner of cell (1, 1), world
  double cell_size_m = 1.5;
  int rows = 100;
  int cols = 100;
  std::vector<GridBox> boxes;
};
/// World position of the centre of cell (row, col) at height 0.
Eigen::Vector2d grid_cell_center(const GridObstaclesConfig& config, int row, int col);

/// Most ground samples per side of one block (cell corners and centres, evenly
/// spaced when a block has more of them than this).
inline constexpr int kGridBoxGroundSamples = 256;
/// Most ground-shape visits of one grid_obstacles generator: the points
/// sampled under all its blocks x the ground shapes each point visits (about
/// 0.25 s on a heightfield).
inline constexpr double kGridBoxGroundVisits = 4194304.0;  // 2^22
/// The samples per side of make_grid_obstacles for `config`'s blocks over a
/// ground whose query visits `shapes_per_sample` ground shapes: the largest
/// n <= kGridBoxGroundSamples whose points, (min(2 cols, n) + 1) x (min(2
/// rows, n) + 1) a block, visit at most kGridBoxGroundVisits shapes in all,
/// but at least 1 (a block's corners). Blocks of few cells keep every corner
/// and centre; only many large blocks are sampled more coarsely. A flat
/// ground (0 shapes per sample) needs no more than the corners.
int grid_box_samples_per_side(const GridObstaclesConfig& config, std::size_t shapes_per_sample);

/// One cuboid per block, from 1 m below the lowest ground under it up to
/// height_m above the highest ground under it; aliased "<alias>/box<k>". The
/// ground is sampled at the cell corners and centres under a block, at most
/// `samples_per_side` + 1 points per side (in [1, kGridBoxGroundSamples]).
std::vector<Shape> make_grid_obstacles(const GridObstaclesConfig& config, const std::string& alias,
                                       const GroundFunction& ground, int samples_per_side = kGridBoxGroundSamples);

}  // namespace campo
