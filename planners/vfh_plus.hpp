#pragma once
/// VFH+ (Ulrich & Borenstein 1998; seed 003 §2.4.3, SPEC §7.3): the rover's
/// alternative local planner, as pure functions on an OccupancyGrid. The four
/// stages (polar histogram with enlarged obstacle cells, binary histogram
/// with hysteresis, masking by the turning radius, candidate directions and
/// their cost) are separate functions; vfh_plus_step strings them together
/// and carries the state from one call to the next.
///
/// Angles are in the world frame, radians, counter-clockwise from +x. Sector
/// k of n points at k * alpha, alpha = 2 pi / n; an obstacle cell adds to
/// sector k when k * alpha lies within its enlarged angular span.
#include <cstdint>
#include <numbers>
#include <optional>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "scene/occupancy_grid.hpp"

namespace campo {

struct VfhPlusConfig {
  int sectors = 72;                 ///< n, [4, 3600]; alpha = 360 deg / n
  double window_radius_m = 3.5;     ///< cells whose centre lies within this distance form the active window, > 0
  /// Magnitude of an occupied cell at the robot's centre (a in m = a - b d^2);
  /// b follows from m = 1 at the window's edge, so a cell weighs 1..a. >= 1.
  double magnitude_a = 4.0;
  double robot_radius_m = 0.4;      ///< r_r, >= 0
  double safety_distance_m = 0.2;   ///< d_s; obstacle cells are enlarged by r_r + d_s, >= 0
  /// Hysteresis of the binary histogram, in units of one occupied cell's
  /// magnitude: above high a sector is blocked, below low free, in between as before.
  double threshold_low = 0.5;
  double threshold_high = 1.5;      ///< >= threshold_low
  double min_turning_radius_m = 0.5;  ///< left and right; 0 masks only the robot's own disc, >= 0
  int wide_opening_sectors = 16;    ///< s_max: openings with more free sectors are wide, >= 1
  double mu_target = 5.0;           ///< mu1, weight of the distance to the target direction
  double mu_heading = 2.0;          ///< mu2, of the distance to the current heading
  double mu_previous = 2.0;         ///< mu3, of the distance to the previous direction; mu1 > mu2 + mu3
};

/// Throws std::invalid_argument naming the first field out of range.
void validate(const VfhPlusConfig& config);

/// What VFH+ remembers between steps.
struct VfhPlusState {
  std::vector<std::uint8_t> binary;   ///< previous binary histogram (empty: none yet, all free)
  std::optional<double> direction_rad;  ///< previous chosen direction (none: use the heading)
};

/// Stage 1: the polar obstacle density H_k. Each occupied cell of the active
/// window (outside the grid counts as occupied), at distance d and bearing
/// beta from `position`, adds m = a - b d^2 to every sector within
/// beta +- gamma, gamma = asin((r_r + d_s) / d) (90 deg for cells nearer
/// than r_r + d_s). The window is the disc of window_radius_m rather than the
/// paper's square, whose corners would get negative magnitudes. The cell
/// under the robot (d = 0) has no bearing and is skipped.
std::vector<double> vfh_polar_histogram(const OccupancyGrid& grid, const Eigen::Vector2d& position_m,
                                        const VfhPlusConfig& config);

/// Stage 2: 1 above high, 0 below low, else the previous value (0 when
/// `previous` is empty).
std::vector<std::uint8_t> vfh_binary_histogram(std::span<const double> polar, std::span<const std::uint8_t> previous,
                                               double threshold_low, double threshold_high);

/// Stage 3 limits: the directions left and right of the heading that the
/// robot cannot reach because an obstacle cell, enlarged by r_r + d_s,
/// overlaps the turning circle on that side (centres min_turning_radius_m to
/// the left and right of the robot). Relative to the heading, in [-pi, 0]
/// and [0, pi]; -pi and pi when nothing blocks.
struct VfhTurnLimits {
  double right_rad = -std::numbers::pi;  ///< phi_r - theta
  double left_rad = std::numbers::pi;    ///< phi_l - theta
};
VfhTurnLimits vfh_turn_limits(const OccupancyGrid& grid, const Eigen::Vector2d& position_m, double heading_rad,
                              const VfhPlusConfig& config);

/// Stage 3: a sector stays free (0) only if it is free in `binary` and its
/// direction lies between the limits (going through the heading).
std::vector<std::uint8_t> vfh_masked_histogram(std::span<const std::uint8_t> binary, const VfhTurnLimits& limits,
                                               double heading_rad);

/// A run of consecutive free sectors, from its right (clockwise) end to its
/// left end; indices are modulo n, so left_sector < right_sector when it
/// wraps past sector 0.
struct VfhOpening {
  int right_sector = 0;  ///< k_r
  int left_sector = 0;   ///< k_l
  int sectors = 0;       ///< free sectors in the run (n when every sector is free)
  bool wide = false;     ///< more than s_max free sectors
};
std::vector<VfhOpening> vfh_openings(std::span<const std::uint8_t> masked, int wide_opening_sectors);

struct VfhCandidate {
  double direction_rad = 0.0;  ///< world frame, in (-pi, pi]
  double cost = 0.0;           ///< g(c), in sectors
};

/// Stage 4 candidates: a narrow opening's centre (k_r + k_l) / 2; a wide
/// opening's c_r = k_r + s_max / 2 and c_l = k_l - s_max / 2, and the target
/// direction when it lies between them; the target alone when every sector
/// is free. Cost g = mu1 D(c, target) + mu2 D(c, heading) + mu3 D(c, previous),
/// D the angular distance in sectors (the previous direction defaults to the heading).
std::vector<VfhCandidate> vfh_candidates(std::span<const VfhOpening> openings, int sectors, double target_rad,
                                         double heading_rad, std::optional<double> previous_rad,
                                         const VfhPlusConfig& config);

/// Everything one step computed, for the record.
struct VfhPlusResult {
  std::vector<double> polar;
  std::vector<std::uint8_t> binary;
  VfhTurnLimits limits;
  std::vector<std::uint8_t> masked;
  std::vector<VfhOpening> openings;
  std::vector<VfhCandidate> candidates;
  std::optional<double> direction_rad;  ///< the cheapest candidate (first on ties); none when every sector is blocked
};

/// One VFH+ step toward `target_m` from `position_m` with heading
/// `heading_rad`; updates `state` (binary histogram, chosen direction; a
/// blocked step keeps the previous direction). Throws std::invalid_argument
/// for a bad config.
VfhPlusResult vfh_plus_step(const OccupancyGrid& grid, const Eigen::Vector2d& position_m, double heading_rad,
                            const Eigen::Vector2d& target_m, const VfhPlusConfig& config, VfhPlusState& state);

}  // namespace campo
