#pragma once
/// Measures of a recorded trajectory that the theses' claims are about, as
/// pure functions of the samples (tested directly).
#include <span>
#include <vector>

#include <Eigen/Core>

namespace campo {

/// How a flight followed the terrain: its altitude range against the band
/// its height above the ground stayed in.
struct TerrainFollowing {
  int samples = 0;                       ///< samples measured (the cruise)
  double altitude_min_m = 0.0, altitude_max_m = 0.0;
  double height_above_ground_min_m = 0.0, height_above_ground_max_m = 0.0;
  double altitude_change_m() const { return altitude_max_m - altitude_min_m; }
  double band_m() const { return height_above_ground_max_m - height_above_ground_min_m; }
};

/// Over the samples whose horizontal distance to the first and to the last
/// sample is at least `end_margin_m` (take-off and arrival excluded). The
/// spans are the trajectory's x, y, z and height-above-ground columns, of
/// equal length. No sample measured: samples 0 and zero ranges.
TerrainFollowing measure_terrain_following(std::span<const double> x_m, std::span<const double> y_m,
                                           std::span<const double> z_m, std::span<const double> height_above_ground_m,
                                           double end_margin_m);

/// An interval of local obstacle avoidance, simulated seconds.
struct AvoidanceSpan {
  double start_s = 0.0;
  double end_s = 0.0;
};

/// Horizontal distance from `point` to the polyline `route` (a single point
/// when it has one vertex); infinity when it is empty.
double distance_to_polyline(const Eigen::Vector2d& point, const std::vector<Eigen::Vector2d>& route);

}  // namespace campo
