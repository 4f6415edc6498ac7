#pragma once
/// The metrics of one run (EpisodeMetrics, campo/episode_record.hpp) as functions of
/// what the closed loop records: its planner events, its trajectory samples,
/// its mission and the clearances it measured. The loop (run/episode.cpp)
/// keeps its state and calls these. What campo/episode_record.hpp declares
/// (cross_track_error, avoiding_time, to_json, to_string(Outcome)) is in
/// metrics/episode_record.cpp; the mission's per-leg and per-gate fields in
/// metrics/mission_metrics.hpp.
#include <algorithm>
#include <limits>
#include <optional>
#include <span>
#include <string>

#include <Eigen/Core>

#include "campo/episode_record.hpp"
#include "campo/scene.hpp"
#include "campo/world.hpp"

namespace campo {

/// Sets the metrics of the planner's decisions in `m`: waypoints_planned,
/// _reached and _discarded, replans, and the median and maximum of the
/// replans' times (zero without replans).
void count_decisions(std::span<const PlannerEvent> events, EpisodeMetrics& m);

/// Length of the nominal route: straight legs from `start` through each
/// mission waypoint, taken at reached_at[k] when it was reached there, as
/// given otherwise; horizontal (x, y) lengths for a rover, 3D for a
/// quadrotor. reached_at holds one entry per mission waypoint.
double nominal_route_m(VehicleType type, const Eigen::Vector3d& start, std::span<const Waypoint> mission,
                       std::span<const std::optional<Eigen::Vector3d>> reached_at);

/// Path length over the nominal route (EpisodeMetrics::path_ratio); 0 for a
/// nominal route of (almost) no length.
double path_ratio(double path_length_m, double nominal_route_m);

/// The name of a body as Clearance::obstacle and Touch::body number it: the
/// alias of Scene::shapes[id], or of mover -(1 + id).
std::string body_name(const Scene& scene, int id);

/// The running minima of the clearance metrics over a run.
struct ClearanceMinima {
  double obstacle_m = std::numeric_limits<double>::infinity();
  int obstacle = -1;  ///< as Clearance::obstacle; valid when obstacle_m is finite
  double obstacle_time_s = 0.0;
  double ground_m = std::numeric_limits<double>::infinity();

  /// Takes clearance `c`, measured at simulated time `t_s`.
  void update(const Clearance& c, double t_s);
  // Cutoffs for a query that only needs to find a new minimum or a touch:
  // anything farther than the minima so far cannot change them.
  double obstacle_cutoff() const { return std::max(obstacle_m, kTouchSearch_m); }
  double ground_cutoff() const { return std::max(ground_m, kTouchSearch_m); }
  static constexpr double kTouchSearch_m = 1e-6;  ///< finds every overlap

  /// Writes min_clearance_m, min_ground_clearance_m and, when an obstacle was
  /// measured, nearest_obstacle and min_clearance_time_s into `m`.
  void write(const Scene& scene, EpisodeMetrics& m) const;
};

}  // namespace campo
