#pragma once
/// Drivable paths from grid or tree paths (SPEC §7.3): A* and RRT* give
/// polylines with needless zig-zags and corners no rover can turn. Shortcut
/// them by line of sight on the occupancy grid, then round each corner with
/// a circular fillet no tighter than the minimum turning radius where one
/// fits collision-free, and sample the result densely for the path follower.
#include <span>
#include <vector>

#include <Eigen/Core>

#include "scene/occupancy_grid.hpp"

namespace campo {

struct PathSmoothingConfig {
  double min_turning_radius_m = 1.0;  ///< tightest fillet, > 0
  double max_turning_radius_m = 5.0;  ///< widest fillet tried, >= min_turning_radius_m
  double radius_ratio = 0.8;          ///< radii tried shrink by this factor, (0, 1)
  double step_m = 0.1;                ///< spacing of the output points, > 0
};

/// Throws std::invalid_argument naming the first field out of range.
void validate(const PathSmoothingConfig& config);

/// Greedy line of sight: from each kept point, jump to the farthest later
/// point reachable by a free segment (OccupancyGrid::segment_free); where
/// not even the next point is, keep the input's segment. Never longer than
/// the input (triangle inequality); endpoints kept.
std::vector<Eigen::Vector2d> shortcut_path(const OccupancyGrid& grid, std::span<const Eigen::Vector2d> path_m);

/// A circular arc replacing a corner between two straight segments.
struct Fillet {
  std::size_t corner = 0;             ///< index of the corner in the shortcut path
  Eigen::Vector2d centre_m = Eigen::Vector2d::Zero();
  double radius_m = 0.0;
  Eigen::Vector2d entry_m = Eigen::Vector2d::Zero();  ///< tangent point on the incoming segment
  Eigen::Vector2d exit_m = Eigen::Vector2d::Zero();   ///< tangent point on the outgoing segment
  double turn_rad = 0.0;              ///< signed heading change, + counter-clockwise
};

struct SmoothedPath {
  std::vector<Eigen::Vector2d> waypoints_m;  ///< after shortcutting
  std::vector<Fillet> fillets;
  int sharp_corners = 0;  ///< corners left unrounded: no fillet of radius >= the minimum fits free
  std::vector<Eigen::Vector2d> points_m;     ///< the drivable path, no two points farther apart than step_m
  double length_m = 0.0;                     ///< of points_m
};

/// Rounds the corners of `waypoints_m`. Each corner may use what its
/// predecessor left of the incoming segment and half of the outgoing one
/// (all of it for the last corner). Radii are tried from the largest that
/// fits (at most max_turning_radius_m) down by radius_ratio to the minimum;
/// the first whose arc is free is kept. An arc counts as free when the
/// chords between its samples, both at the output spacing and at half a
/// grid cell, are (the arc bulges at most step^2 / 8 R beyond them).
/// Straight corners (under 1e-9 rad) need no fillet. Throws
/// std::invalid_argument for a bad config.
SmoothedPath fillet_corners(const OccupancyGrid& grid, std::span<const Eigen::Vector2d> waypoints_m,
                            const PathSmoothingConfig& config = {});

/// shortcut_path, then fillet_corners.
SmoothedPath smooth_path(const OccupancyGrid& grid, std::span<const Eigen::Vector2d> path_m,
                         const PathSmoothingConfig& config = {});

}  // namespace campo
