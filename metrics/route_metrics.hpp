#pragma once
/// Measures of a flown route against its mission, as pure functions of the
/// recorded positions (the run record's per-leg and gate metrics): how long
/// each leg was, how far the vehicle moved sideways before it first climbed,
/// and whether it passed through a named area.
#include <optional>
#include <span>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace campo {

/// Height above a leg's endpoints that counts as climbing (well above the
/// altitude controller's tracking error of a few decimetres).
inline constexpr double kClimbThresholdM = 2.0;

/// Length of the polyline through `points`, in metres (0 for fewer than two).
double polyline_length_m(std::span<const Eigen::Vector3d> points);

/// Horizontal distance of `p` from the infinite line through `from` and `to`
/// (x, y only); the distance to `from` when they coincide horizontally.
double lateral_offset_m(const Eigen::Vector3d& p, const Eigen::Vector3d& from, const Eigen::Vector3d& to);

/// For a leg flown from `from` to `to` through `points` (in time order) that
/// climbs (its highest point is more than `climb_m` above max(from.z, to.z)):
/// the largest lateral_offset_m of the points before the first one within
/// `climb_m` of the leg's highest point, i.e. how far the vehicle moved
/// sideways before it topped its climb ("flew along the wall before climbing
/// over it"); nullopt for a leg that does not climb.
std::optional<double> lateral_before_climb_m(std::span<const Eigen::Vector3d> points, const Eigen::Vector3d& from,
                                             const Eigen::Vector3d& to, double climb_m = kClimbThresholdM);

/// Index of the first point whose (x, y) lies in `area` (edges included) and,
/// when `max_agl_m` is set, whose height above ground (`agl_m`, one per point)
/// is at most max_agl_m; nullopt when none does.
std::optional<std::size_t> first_inside(std::span<const Eigen::Vector3d> points, std::span<const double> agl_m,
                                        const Eigen::AlignedBox2d& area, std::optional<double> max_agl_m);

}  // namespace campo
