#include "planners/path_smoothing.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace campo {
namespace {

void smoothing_requires(bool ok, const std::string& message) {
  if (!ok) throw std::invalid_argument("path smoothing: " + message);
}

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

/// Appends the points after `from` up to and including `to`, no two farther apart than step.
void append_straight(std::vector<Eigen::Vector2d>& points, const Eigen::Vector2d& from, const Eigen::Vector2d& to,
                     double step) {
  if ((to - from).norm() <= 1e-12) return;  // a fillet's exit that is the next one's entry
  const int pieces = std::max(1, static_cast<int>(std::ceil((to - from).norm() / step)));
  for (int k = 1; k < pieces; ++k) points.push_back(from + (to - from) * (static_cast<double>(k) / pieces));
  points.push_back(to);
}

/// Points of a fillet's arc after its entry, up to and including its exit,
/// with chords no longer than max_chord.
std::vector<Eigen::Vector2d> arc_points(const Fillet& f, double max_chord) {
  const Eigen::Vector2d r0 = f.entry_m - f.centre_m;
  const double a0 = std::atan2(r0.y(), r0.x());
  const int pieces = std::max(1, static_cast<int>(std::ceil(f.radius_m * std::abs(f.turn_rad) / max_chord)));
  std::vector<Eigen::Vector2d> points;
  for (int k = 1; k < pieces; ++k) {
    const double a = a0 + f.turn_rad * (static_cast<double>(k) / pieces);
    points.push_back(f.centre_m + f.radius_m * Eigen::Vector2d(std::cos(a), std::sin(a)));
  }
  points.push_back(f.exit_m);
  return points;
}

bool arc_free(const OccupancyGrid& grid, const Fillet& f, double max_chord) {
  Eigen::Vector2d previous = f.entry_m;
  for (const Eigen::Vector2d& p : arc_points(f, max_chord)) {
    if (!grid.segment_free(previous, p)) return false;
    previous = p;
  }
  return true;
}

/// The path without consecutive repeated points, which have no direction.
std::vector<Eigen::Vector2d> without_repeats(std::span<const Eigen::Vector2d> path) {
  std::vector<Eigen::Vector2d> out;
  for (const Eigen::Vector2d& p : path) {
    if (out.empty() || (p - out.back()).norm() > 1e-12) out.push_back(p);
  }
  return out;
}

}  // namespace

void validate(const PathSmoothingConfig& c) {
  smoothing_requires(std::isfinite(c.min_turning_radius_m) && c.min_turning_radius_m > 0.0,
          "min_turning_radius must be finite and > 0");
  smoothing_requires(std::isfinite(c.max_turning_radius_m) && c.max_turning_radius_m >= c.min_turning_radius_m,
          "max_turning_radius must be finite and >= min_turning_radius");
  smoothing_requires(c.radius_ratio > 0.0 && c.radius_ratio < 1.0, "radius_ratio must be in (0, 1)");
  smoothing_requires(std::isfinite(c.step_m) && c.step_m > 0.0, "step must be finite and > 0");
}

std::vector<Eigen::Vector2d> shortcut_path(const OccupancyGrid& grid, std::span<const Eigen::Vector2d> path_m) {
  const std::vector<Eigen::Vector2d> path = without_repeats(path_m);
  if (path.size() <= 2) return path;
  std::vector<Eigen::Vector2d> out{path.front()};
  std::size_t i = 0;
  while (i + 1 < path.size()) {
    // Extend the sight line while it stays free: one check per input point.
    std::size_t j = i + 1;
    while (j + 1 < path.size() && grid.segment_free(path[i], path[j + 1])) ++j;
    out.push_back(path[j]);
    i = j;
  }
  return out;
}

SmoothedPath fillet_corners(const OccupancyGrid& grid, std::span<const Eigen::Vector2d> waypoints_m,
                            const PathSmoothingConfig& config) {
  validate(config);
  SmoothedPath result;
  result.waypoints_m = without_repeats(waypoints_m);
  const std::vector<Eigen::Vector2d>& w = result.waypoints_m;
  if (w.empty()) return result;
  const double fine_chord = std::min(config.step_m, 0.5 * grid.resolution_m);

  std::vector<Eigen::Vector2d>& points = result.points_m;
  points.push_back(w.front());
  Eigen::Vector2d cursor = w.front();  // where the straight run being built starts
  double used = 0.0;                   // tangent length the previous fillet took off the incoming segment
  for (std::size_t c = 1; c + 1 < w.size(); ++c) {
    const double in_length = (w[c] - w[c - 1]).norm();
    const double out_length = (w[c + 1] - w[c]).norm();
    const Eigen::Vector2d u = (w[c] - w[c - 1]) / in_length;
    const Eigen::Vector2d v = (w[c + 1] - w[c]) / out_length;
    const double turn = std::atan2(cross(u, v), u.dot(v));
    if (std::abs(turn) < 1e-9) {
      used = 0.0;
      continue;
    }
    // Tangent length t = R tan(|turn| / 2) must fit on both segments.
    const double tan_half = std::tan(0.5 * std::abs(turn));
    const double room = std::min(in_length - used, c + 2 == w.size() ? out_length : 0.5 * out_length);
    const double largest = std::abs(turn) < std::numbers::pi - 1e-9 ? room / tan_half : 0.0;
    bool filleted = false;
    if (largest >= config.min_turning_radius_m) {
      const Eigen::Vector2d inward = turn > 0.0 ? Eigen::Vector2d(-u.y(), u.x()) : Eigen::Vector2d(u.y(), -u.x());
      for (double radius = std::min(largest, config.max_turning_radius_m);;
           radius = std::max(radius * config.radius_ratio, config.min_turning_radius_m)) {
        const double tangent = radius * tan_half;
        Fillet f;
        f.corner = c;
        f.radius_m = radius;
        f.turn_rad = turn;
        f.entry_m = w[c] - u * tangent;
        f.exit_m = w[c] + v * tangent;
        f.centre_m = f.entry_m + inward * radius;
        if (arc_free(grid, f, config.step_m) && (fine_chord >= config.step_m || arc_free(grid, f, fine_chord))) {
          append_straight(points, cursor, f.entry_m, config.step_m);
          const std::vector<Eigen::Vector2d> arc = arc_points(f, config.step_m);
          points.insert(points.end(), arc.begin(), arc.end());
          cursor = f.exit_m;
          used = tangent;
          result.fillets.push_back(f);
          filleted = true;
          break;
        }
        if (radius <= config.min_turning_radius_m) break;
      }
    }
    if (!filleted) {
      ++result.sharp_corners;
      append_straight(points, cursor, w[c], config.step_m);
      cursor = w[c];
      used = 0.0;
    }
  }
  if (w.size() > 1) append_straight(points, cursor, w.back(), config.step_m);
  for (std::size_t i = 1; i < points.size(); ++i) result.length_m += (points[i] - points[i - 1]).norm();
  return result;
}

SmoothedPath smooth_path(const OccupancyGrid& grid, std::span<const Eigen::Vector2d> path_m,
                         const PathSmoothingConfig& config) {
  return fillet_corners(grid, shortcut_path(grid, path_m), config);
}

}  // namespace campo
