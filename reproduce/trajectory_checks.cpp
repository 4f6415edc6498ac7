#include "reproduce/trajectory_checks.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace campo {

TerrainFollowing measure_terrain_following(std::span<const double> x_m, std::span<const double> y_m,
                                           std::span<const double> z_m, std::span<const double> height_above_ground_m,
                                           double end_margin_m) {
  TerrainFollowing out;
  const std::size_t n = std::min({x_m.size(), y_m.size(), z_m.size(), height_above_ground_m.size()});
  if (n == 0) return out;
  for (std::size_t i = 0; i < n; ++i) {
    const double from_start = std::hypot(x_m[i] - x_m[0], y_m[i] - y_m[0]);
    const double to_end = std::hypot(x_m[i] - x_m[n - 1], y_m[i] - y_m[n - 1]);
    if (from_start < end_margin_m || to_end < end_margin_m) continue;
    const double z = z_m[i], h = height_above_ground_m[i];
    if (out.samples++ == 0) {
      out.altitude_min_m = out.altitude_max_m = z;
      out.height_above_ground_min_m = out.height_above_ground_max_m = h;
      continue;
    }
    out.altitude_min_m = std::min(out.altitude_min_m, z);
    out.altitude_max_m = std::max(out.altitude_max_m, z);
    out.height_above_ground_min_m = std::min(out.height_above_ground_min_m, h);
    out.height_above_ground_max_m = std::max(out.height_above_ground_max_m, h);
  }
  return out;
}

double distance_to_polyline(const Eigen::Vector2d& point, const std::vector<Eigen::Vector2d>& route) {
  if (route.empty()) return std::numeric_limits<double>::infinity();
  double best = (point - route.front()).norm();
  for (std::size_t i = 1; i < route.size(); ++i) {
    const Eigen::Vector2d a = route[i - 1], ab = route[i] - a;
    const double length2 = ab.squaredNorm();
    const double t = length2 > 0.0 ? std::clamp((point - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
    best = std::min(best, (point - (a + t * ab)).norm());
  }
  return best;
}

}  // namespace campo
