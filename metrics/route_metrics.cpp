#include "metrics/route_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace campo {

double polyline_length_m(std::span<const Eigen::Vector3d> points) {
  double length = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i) length += (points[i] - points[i - 1]).norm();
  return length;
}

double lateral_offset_m(const Eigen::Vector3d& p, const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
  const Eigen::Vector2d d = (to - from).head<2>();
  const Eigen::Vector2d v = (p - from).head<2>();
  const double n = d.norm();
  if (n < 1e-9) return v.norm();
  // |d x v| / |d|: the distance from the line.
  return std::abs(d.x() * v.y() - d.y() * v.x()) / n;
}

std::optional<double> lateral_before_climb_m(std::span<const Eigen::Vector3d> points, const Eigen::Vector3d& from,
                                             const Eigen::Vector3d& to, double climb_m) {
  double peak = -std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& p : points) peak = std::max(peak, p.z());
  if (!(peak > std::max(from.z(), to.z()) + climb_m)) return std::nullopt;
  double lateral = 0.0;
  for (const Eigen::Vector3d& p : points) {
    if (p.z() >= peak - climb_m) break;
    lateral = std::max(lateral, lateral_offset_m(p, from, to));
  }
  return lateral;
}

std::optional<std::size_t> first_inside(std::span<const Eigen::Vector3d> points, std::span<const double> agl_m,
                                        const Eigen::AlignedBox2d& area, std::optional<double> max_agl_m) {
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!area.contains(points[i].head<2>())) continue;
    if (max_agl_m && !(i < agl_m.size() && agl_m[i] <= *max_agl_m)) continue;
    return i;
  }
  return std::nullopt;
}

}  // namespace campo
