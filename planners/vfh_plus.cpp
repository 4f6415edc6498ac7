#include "planners/vfh_plus.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace campo {
namespace {


/// Angle in (-pi, pi].
double wrap(double angle) {
  double a = std::remainder(angle, 2.0 * std::numbers::pi);
  if (a <= -std::numbers::pi) a += 2.0 * std::numbers::pi;
  return a;
}

double sector_width(int sectors) { return 2.0 * std::numbers::pi / sectors; }

void vfh_requires(bool ok, const std::string& message) {
  if (!ok) throw std::invalid_argument("VFH+: " + message);
}

/// Calls visit(centre, distance, bearing) for every occupied cell of the
/// active window; cells outside the grid count as occupied.
template <typename Visit>
void for_each_window_obstacle(const OccupancyGrid& grid, const Eigen::Vector2d& position_m, double radius_m,
                              Visit&& visit) {
  const Eigen::Vector2i lo = grid.cell_of(position_m - Eigen::Vector2d::Constant(radius_m));
  const Eigen::Vector2i hi = grid.cell_of(position_m + Eigen::Vector2d::Constant(radius_m));
  for (int row = lo.y(); row <= hi.y(); ++row) {
    for (int col = lo.x(); col <= hi.x(); ++col) {
      if (!grid.is_occupied(col, row)) continue;
      const Eigen::Vector2d centre = grid.centre_of(col, row);
      const Eigen::Vector2d offset = centre - position_m;
      const double distance = offset.norm();
      if (distance > radius_m || distance < 1e-12) continue;
      visit(centre, distance, std::atan2(offset.y(), offset.x()));
    }
  }
}

}  // namespace

void validate(const VfhPlusConfig& c) {
  vfh_requires(c.sectors >= 4 && c.sectors <= 3600, "sectors must be in [4, 3600], got " + std::to_string(c.sectors));
  vfh_requires(std::isfinite(c.window_radius_m) && c.window_radius_m > 0.0, "window_radius must be finite and > 0");
  vfh_requires(std::isfinite(c.magnitude_a) && c.magnitude_a >= 1.0, "magnitude_a must be finite and >= 1");
  vfh_requires(std::isfinite(c.robot_radius_m) && c.robot_radius_m >= 0.0, "robot_radius must be finite and >= 0");
  vfh_requires(std::isfinite(c.safety_distance_m) && c.safety_distance_m >= 0.0,
          "safety_distance must be finite and >= 0");
  vfh_requires(std::isfinite(c.threshold_low) && std::isfinite(c.threshold_high) && c.threshold_low >= 0.0 &&
              c.threshold_low <= c.threshold_high,
          "thresholds need 0 <= threshold_low <= threshold_high");
  vfh_requires(std::isfinite(c.min_turning_radius_m) && c.min_turning_radius_m >= 0.0,
          "min_turning_radius must be finite and >= 0");
  vfh_requires(c.wide_opening_sectors >= 1, "wide_opening_sectors must be >= 1");
  vfh_requires(c.mu_target >= 0.0 && c.mu_heading >= 0.0 && c.mu_previous >= 0.0, "the mu weights must be >= 0");
  // Otherwise heading and previous direction together could outweigh the target.
  vfh_requires(c.mu_target > c.mu_heading + c.mu_previous, "mu_target must exceed mu_heading + mu_previous");
}

std::vector<double> vfh_polar_histogram(const OccupancyGrid& grid, const Eigen::Vector2d& position_m,
                                        const VfhPlusConfig& config) {
  const int n = config.sectors;
  const double alpha = sector_width(n);
  const double enlargement = config.robot_radius_m + config.safety_distance_m;
  const double b = (config.magnitude_a - 1.0) / (config.window_radius_m * config.window_radius_m);
  std::vector<double> polar(static_cast<std::size_t>(n), 0.0);
  for_each_window_obstacle(grid, position_m, config.window_radius_m,
                           [&](const Eigen::Vector2d&, double distance, double bearing) {
                             const double magnitude = config.magnitude_a - b * distance * distance;
                             const double gamma = distance > enlargement ? std::asin(enlargement / distance) : std::numbers::pi / 2;
                             const int first = static_cast<int>(std::ceil((bearing - gamma) / alpha));
                             const int last = static_cast<int>(std::floor((bearing + gamma) / alpha));
                             for (int k = first; k <= last; ++k) polar[static_cast<std::size_t>(((k % n) + n) % n)] += magnitude;
                           });
  return polar;
}

std::vector<std::uint8_t> vfh_binary_histogram(std::span<const double> polar, std::span<const std::uint8_t> previous,
                                               double threshold_low, double threshold_high) {
  std::vector<std::uint8_t> binary(polar.size(), 0);
  for (std::size_t k = 0; k < polar.size(); ++k) {
    if (polar[k] > threshold_high) {
      binary[k] = 1;
    } else if (polar[k] >= threshold_low && previous.size() == polar.size()) {
      binary[k] = previous[k];
    }
  }
  return binary;
}

VfhTurnLimits vfh_turn_limits(const OccupancyGrid& grid, const Eigen::Vector2d& position_m, double heading_rad,
                              const VfhPlusConfig& config) {
  const double radius = config.min_turning_radius_m;
  const Eigen::Vector2d left_of_heading(-std::sin(heading_rad), std::cos(heading_rad));
  const Eigen::Vector2d right_centre = position_m - radius * left_of_heading;
  const Eigen::Vector2d left_centre = position_m + radius * left_of_heading;
  // An enlarged cell overlapping a turning circle's disc blocks that turn.
  const double reach = radius + config.robot_radius_m + config.safety_distance_m;
  VfhTurnLimits limits;
  for_each_window_obstacle(grid, position_m, config.window_radius_m,
                           [&](const Eigen::Vector2d& centre, double, double bearing) {
                             const double relative = wrap(bearing - heading_rad);
                             if (relative <= 0.0 && (centre - right_centre).norm() < reach) {
                               limits.right_rad = std::max(limits.right_rad, relative);
                             }
                             if (relative >= 0.0 && (centre - left_centre).norm() < reach) {
                               limits.left_rad = std::min(limits.left_rad, relative);
                             }
                           });
  return limits;
}

std::vector<std::uint8_t> vfh_masked_histogram(std::span<const std::uint8_t> binary, const VfhTurnLimits& limits,
                                               double heading_rad) {
  const int n = static_cast<int>(binary.size());
  const double alpha = sector_width(n);
  std::vector<std::uint8_t> masked(binary.size(), 1);
  for (int k = 0; k < n; ++k) {
    const double relative = wrap(k * alpha - heading_rad);
    if (binary[static_cast<std::size_t>(k)] == 0 && relative >= limits.right_rad && relative <= limits.left_rad) {
      masked[static_cast<std::size_t>(k)] = 0;
    }
  }
  return masked;
}

std::vector<VfhOpening> vfh_openings(std::span<const std::uint8_t> masked, int wide_opening_sectors) {
  const int n = static_cast<int>(masked.size());
  std::vector<VfhOpening> openings;
  const auto blocked = std::find(masked.begin(), masked.end(), 1);
  if (blocked == masked.end()) {
    if (n > 0) openings.push_back({0, n - 1, n, true});
    return openings;
  }
  // Walk once round the circle starting just after a blocked sector, so no run is split.
  const int start = static_cast<int>(blocked - masked.begin());
  int run = 0;
  for (int i = 1; i <= n; ++i) {
    const int k = (start + i) % n;
    if (masked[static_cast<std::size_t>(k)] == 0) {
      ++run;
      continue;
    }
    if (run > 0) {
      const int right = ((k - run) % n + n) % n;
      openings.push_back({right, (k - 1 + n) % n, run, run > wide_opening_sectors});
    }
    run = 0;
  }
  return openings;
}

std::vector<VfhCandidate> vfh_candidates(std::span<const VfhOpening> openings, int sectors, double target_rad,
                                         double heading_rad, std::optional<double> previous_rad,
                                         const VfhPlusConfig& config) {
  const double alpha = sector_width(sectors);
  const double previous = previous_rad.value_or(heading_rad);
  const auto in_sectors = [&](double a, double b) { return std::abs(wrap(a - b)) / alpha; };
  std::vector<VfhCandidate> candidates;
  const auto add = [&](double direction) {
    const double d = wrap(direction);
    candidates.push_back({d, config.mu_target * in_sectors(d, target_rad) + config.mu_heading * in_sectors(d, heading_rad) +
                                 config.mu_previous * in_sectors(d, previous)});
  };
  const double half_wide = 0.5 * config.wide_opening_sectors;
  for (const VfhOpening& opening : openings) {
    if (opening.sectors == sectors) {
      add(target_rad);
      continue;
    }
    // Sector positions counted from k_r counter-clockwise, so wrapped openings need no special case.
    const double right = opening.right_sector;
    const double left = right + opening.sectors - 1;
    if (!opening.wide) {
      add(0.5 * (right + left) * alpha);
      continue;
    }
    add((right + half_wide) * alpha);
    add((left - half_wide) * alpha);
    const double target_from_right = wrap(target_rad - right * alpha);
    const double target_offset = (target_from_right < 0.0 ? target_from_right + 2.0 * std::numbers::pi : target_from_right) / alpha;
    if (target_offset >= half_wide && target_offset <= left - right - half_wide) add(target_rad);
  }
  return candidates;
}

VfhPlusResult vfh_plus_step(const OccupancyGrid& grid, const Eigen::Vector2d& position_m, double heading_rad,
                            const Eigen::Vector2d& target_m, const VfhPlusConfig& config, VfhPlusState& state) {
  validate(config);
  VfhPlusResult result;
  result.polar = vfh_polar_histogram(grid, position_m, config);
  result.binary = vfh_binary_histogram(result.polar, state.binary, config.threshold_low, config.threshold_high);
  result.limits = vfh_turn_limits(grid, position_m, heading_rad, config);
  result.masked = vfh_masked_histogram(result.binary, result.limits, heading_rad);
  result.openings = vfh_openings(result.masked, config.wide_opening_sectors);
  const Eigen::Vector2d to_target = target_m - position_m;
  const double target_rad = std::atan2(to_target.y(), to_target.x());
  result.candidates =
      vfh_candidates(result.openings, config.sectors, target_rad, heading_rad, state.direction_rad, config);
  const auto best = std::min_element(result.candidates.begin(), result.candidates.end(),
                                     [](const VfhCandidate& a, const VfhCandidate& b) { return a.cost < b.cost; });
  if (best != result.candidates.end()) {
    result.direction_rad = best->direction_rad;
    state.direction_rad = best->direction_rad;
  }
  state.binary = result.binary;
  return result;
}

}  // namespace campo
