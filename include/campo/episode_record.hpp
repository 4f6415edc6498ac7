#pragma once
/// What the closed loop records of a run and measures on it: how it ended,
/// its metrics (run.json), its trajectory samples and its planner's events,
/// with the functions that measure them. Implemented in metrics/ (episode_record.cpp),
/// one floor below the loop itself (episode.hpp, run/), which fills an
/// EpisodeResult of them.
#include <cstddef>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "campo/planner.hpp"
#include "campo/planner_record.hpp"  // PlannerEvent
#include "campo/vehicle.hpp"

namespace campo {

/// How a run ended: the planner reported the mission complete (reached) or
/// gave up (aborted), the vehicle collided, the time limit passed, or the
/// planner failed (threw: a bug, or a Python planner's exception). In a run
/// of several vehicles ended by the first failure (EndRule::first_failure),
/// the vehicles still on their missions then were stopped.
enum class Outcome { reached, collision, timeout, aborted, failed, stopped };
std::string_view to_string(Outcome outcome);

/// A collision: when the vehicle began to touch something, what, and where.
struct CollisionEvent {
  double time_s = 0.0;  ///< at the end of the physics step that found it
  std::string body;     ///< the alias path of the body touched (a ground shape's when `ground`)
  bool ground = false;  ///< a plane or heightfield
  Eigen::Vector3d point_m = Eigen::Vector3d::Zero();  ///< on the touched body's surface (Touch::point_m), world frame
};

/// How near one vehicle came to another during its run.
struct VehicleSeparation {
  std::string other;  ///< the other vehicle's alias
  /// Signed distance between their collision shapes (negative: overlapping),
  /// the least over every physics step while this vehicle was on its mission.
  double min_distance_m = std::numeric_limits<double>::infinity();
  double min_distance_time_s = 0.0;  ///< when it was measured
};

/// Metrics of one vehicle's run, named as in run.json.
struct EpisodeMetrics {
  Outcome outcome = Outcome::aborted;
  std::string reason;
  double sim_time_s = 0.0;
  double wall_time_s = 0.0;        ///< measured, so it differs between identical runs
  double path_length_m = 0.0;      ///< distance travelled (flown/driven), integrated every physics step
  /// Path length / nominal route: straight legs from the start through each
  /// waypoint where the vehicle was when it reached it (the waypoint as
  /// given when it was not reached). At least 1 for a run that reached its goal.
  double path_ratio = 0.0;
  /// Minimum signed distance between the vehicle's collision shapes and any
  /// obstacle's (every shape but ground: static, dynamic, movers), over every
  /// physics step; negative when they overlapped. Infinite without obstacles.
  double min_clearance_m = 0.0;
  std::string nearest_obstacle;       ///< alias of the obstacle at min_clearance_m
  double min_clearance_time_s = 0.0;  ///< when min_clearance_m was measured
  /// The same between the bodies that may not touch the ground (a quadrotor,
  /// a rover's chassis, not its wheels) and the ground (planes, heightfields).
  double min_ground_clearance_m = 0.0;
  int collisions = 0;  ///< times the collision shapes began to touch (Clearance::touching)
  /// The first kMaxCollisionEvents of them, in order, as "collision_events".
  /// Bounded because a vehicle scraping along a wall or a rover bumping over
  /// a kerb can begin a new contact every few steps for a whole run, and a
  /// sweep copies every run's metrics into its results: 100 keeps a record
  /// within about 10 kB while a run that stops at its first collision, or
  /// any run a person would read event by event, is complete; `collisions` counts them all.
  std::vector<CollisionEvent> collision_events;
  static constexpr std::size_t kMaxCollisionEvents = 100;
  int planner_calls = 0;
  double planner_time_ms_mean = 0.0;  ///< measured
  double planner_time_ms_max = 0.0;   ///< measured
  // From the planner's decisions (planner.hpp, Decisions); zero for planners that do not set them.
  int waypoints_planned = 0;    ///< intermediate waypoints set (Decisions::planned_waypoint)
  int waypoints_reached = 0;    ///< intermediate waypoints reached (Decisions::reached_intermediate)
  int waypoints_discarded = 0;  ///< intermediate waypoints dropped (Decisions::discarded_waypoint)
  int replans = 0;              ///< replanning steps (Decisions::replan)
  double replan_time_ms_median = 0.0;  ///< measured (ReplanDecision::time_ms)
  double replan_time_ms_max = 0.0;     ///< measured
  /// Horizontal (x, y) distance of the vehicle, at every trajectory sample,
  /// to the route in force then: the latest planned path recorded at or
  /// before the sample, as a polyline. Root mean square, mean and maximum
  /// over the samples that have a route (cross_track_error); zero when the
  /// planner records no planned path.
  double cross_track_rms_m = 0.0;
  double cross_track_mean_m = 0.0;
  double cross_track_max_m = 0.0;
  /// Simulated time spent in local obstacle avoidance: from each decision
  /// avoiding true to the next avoiding false, or to the end of the run (avoiding_time).
  double avoiding_time_s = 0.0;
  /// Metrics that the room measuring them declares as record fields
  /// (campo/record_fields.hpp), written through their declarations, e.g. the
  /// mission's per-leg and per-gate measures (metrics/mission_metrics.hpp)
  /// and the planner's own (PlannerRecord::metrics, metrics/planner_metrics.hpp):
  /// an object (null: none), written into run.json's metrics beside the
  /// fields above. Read them back through the same declarations.
  nlohmann::json declared;
  /// In a run of several vehicles, one per other vehicle in scene order,
  /// written as min_distance_to_<alias>_m and min_distance_to_<alias>_time_s.
  std::vector<VehicleSeparation> separations;
};
nlohmann::json to_json(const EpisodeMetrics& metrics);

/// The metrics of a run of several vehicles as a whole (run.json's
/// "metrics" then; each vehicle's are under "vehicles").
struct FleetMetrics {
  /// reached when every vehicle reached its goal; else the outcome of the
  /// vehicle whose end decided it: the first (in time, then scene order)
  /// that did not reach.
  Outcome outcome = Outcome::aborted;
  std::string reason;              ///< "<alias>: <its reason>", or that all reached
  int vehicles = 0;
  int vehicles_reached = 0;
  bool all_reached = false;
  bool any_collision = false;      ///< some vehicle collided (collisions > 0)
  int collisions = 0;              ///< the vehicles' collisions summed (one between two vehicles counts for both)
  /// When the last vehicle reached its goal; only when all reached (else null in run.json).
  double makespan_s = std::numeric_limits<double>::quiet_NaN();
  /// The least distance between any two vehicles over the run, which pair and when.
  double min_vehicle_distance_m = std::numeric_limits<double>::infinity();
  std::string min_vehicle_distance_pair;  ///< "<alias>|<alias>"
  double min_vehicle_distance_time_s = 0.0;
  double sim_time_s = 0.0;
  double wall_time_s = 0.0;        ///< measured
};
nlohmann::json to_json(const FleetMetrics& metrics);


/// One row of trajectory.csv, taken at every planner call.
struct TrajectorySample {
  double time_s = 0.0;
  VehicleState state;  ///< the truth
  Eigen::Vector3d estimated_position_m = Eigen::Vector3d::Zero();  ///< what the planner was told
  Command command;
  double clearance_m = 0.0;  ///< signed distance to the nearest obstacle then (as min_clearance_m)
  /// Height of the vehicle's origin above the ground straight below it
  /// (the highest plane or heightfield there); NaN where there is none.
  double height_above_ground_m = 0.0;
  nlohmann::json actuators;
};

/// Cross-track error of a trajectory against the routes its planner recorded.
struct CrossTrack {
  double rms_m = 0.0;
  double mean_m = 0.0;
  double max_m = 0.0;
  std::size_t samples = 0;  ///< samples measured: those with a route in force
};

/// The cross-track metrics of EpisodeMetrics from the samples and the events,
/// both in time order. A planned path decision (z is ignored) becomes the
/// route for the samples at or after its time until the next one; an empty
/// one leaves no route (samples skipped until the next),
/// a single point is a route of one point. Samples before the first planned
/// path are skipped; with none measured, everything is zero. Exact (the
/// distance to the nearest segment), in about log(route segments) per sample.
CrossTrack cross_track_error(std::span<const TrajectorySample> trajectory, std::span<const PlannerEvent> events);

/// Total time between each decision avoiding true and the next avoiding
/// false (repeated values change nothing); an avoidance still on at the end
/// counts up to `end_time_s`. Events in time order.
double avoiding_time(std::span<const PlannerEvent> events, double end_time_s);

}  // namespace campo
