#pragma once
/// `rover_route`: seed 003's rover navigation (003 §3, SPEC §7.3). A global
/// route through the mission waypoints — Dubins paths through their headings
/// (straight along the rows, arcs to switch rows), or A* / RRT* on the
/// scene's occupancy grid smoothed to a drivable path — followed by pure
/// pursuit, with a local planner (follow-the-gap or VFH+) taking over while
/// an obstacle stands in the rover's way within the activation range; pure
/// pursuit resumes from the route point nearest the rover afterwards.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "campo/config_fields.hpp"
#include "campo/planner.hpp"
#include "campo/planner_record.hpp"
#include "campo/record_fields.hpp"
#include "planners/follow_the_gap.hpp"
#include "planners/path_smoothing.hpp"
#include "planners/pure_pursuit.hpp"
#include "planners/rrt_star.hpp"
#include "planners/vfh_plus.hpp"
#include "scene/occupancy_grid.hpp"

namespace campo {

enum class GlobalRoute { dubins, astar, rrt_star };
enum class LocalAvoidance { follow_the_gap, vfh_plus, none };

struct RoverRouteConfig {
  std::string sensor;            ///< alias of the planar LIDAR; empty: the vehicle's first sensor
  GlobalRoute global = GlobalRoute::dubins;
  LocalAvoidance local = LocalAvoidance::follow_the_gap;
  /// Dubins radius and the smallest fillet of A*/RRT* routes, which also
  /// leave and reach each waypoint straight along its heading for this long
  double turning_radius_m = 2.0;
  double route_step_m = 0.1;         ///< spacing of the route polyline pure pursuit follows
  double waypoint_tolerance_m = 1.0; ///< a mission waypoint counts as passed within this distance
  double clearance_m = 0.8;          ///< A*/RRT*: obstacles inflated by this (half the rover's width + margin)
  double occupancy_resolution_m = 0.1;  ///< A*/RRT* occupancy grid cell
  /// An obstacle is "in the way" when a scan point lies within this distance
  /// of the route ahead, from the rover's nearest route point on for the
  /// activation range: vine rows alongside the route, and row ends beside a
  /// headland turn, are not in the way. Also the width of the stop check
  /// straight ahead of the sensor (stop_distance_m).
  double corridor_half_width_m = 0.65;
  /// Avoidance ends only once the corridor widened by this is clear too, so
  /// the rover does not turn back to the route while the obstacle is beside it.
  double release_margin_m = 0.4;
  double avoid_speed_mps = 0.4;      ///< forward speed while avoiding, before slowing in turns
  double avoid_turn_gain = 1.5;      ///< yaw rate per radian of heading error while avoiding, 1/s
  double stop_distance_m = 0.3;      ///< nearer than this ahead (from the sensor): stop and turn in place
  /// Safety guard: every command is checked by driving it for guard_horizon_s
  /// against the latest scan's points with the rover's footprint (a
  /// rectangle about the body centre); a command that would touch one is
  /// slowed, then driven straight on, then reduced to turning in place, to
  /// backing off, then to stopping.
  double footprint_half_length_m = 0.85;  ///< 003's chassis is 1.5 m long, plus a margin
  double footprint_half_width_m = 0.6;    ///< and 1.0 m wide, plus a margin
  double guard_horizon_s = 1.0;
  double guard_step_s = 0.1;              ///< time step of the guard's drive over the horizon, s
  double guard_reverse_speed_mps = 0.2;   ///< the guard's last resort before stopping: back off at this speed
  /// While avoiding, the rover stops (and only turns) above this heading error.
  double avoid_stop_heading_deg = 60.0;
  /// Stopped close ahead by an obstacle at one side with the heading straight
  /// on, the rover turns away from that side as if its heading error were this (20 deg).
  double blocked_turn_rad = 0.35;
  /// Scan hits are remembered within the guard's reach (footprint, horizon at
  /// full speed) plus this margin: the sensor looks ahead, so an obstacle being passed is only in earlier scans.
  double memory_margin_m = 1.0;
  double memory_cell_m = 0.05;            ///< one remembered hit per square cell of this side
  double see_through_margin_m = 0.2;      ///< a remembered hit is forgotten once its beam reads this much farther
  double vfh_grid_resolution_m = 0.1;     ///< VFH+: cell of the grid of one scan's hits around the rover
  double vfh_grid_margin_m = 1.0;         ///< VFH+: that grid reaches this far beyond the active window
  double rejoin_behind_m = 5.0;           ///< the nearest route point is looked for this far behind the one pursued
  double rejoin_ahead_m = 30.0;           ///< and this far ahead of it (also when rejoining after avoidance)
  double record_path_step_m = 0.25;       ///< spacing of the planned path in the record (a chord error under 4 mm on 2 m arcs)
  PurePursuitConfig pure_pursuit;
  FollowTheGapConfig follow_the_gap;
  VfhPlusConfig vfh_plus;
  RrtStarConfig rrt_star;
};

/// Limits of the work a mission may ask of rover_route (issue 16): the
/// route polyline pure pursuit follows has at most kMaxRoutePoints points
/// (the Dubins route's length over route_step_m: 100 km at 0.1 m), and the
/// occupancy grid of the A* and RRT* routes at most kMaxRouteGridCells cells
/// (400 m x 400 m at 0.1 m; about 30 bytes a cell with inflation and A*).
inline constexpr std::size_t kMaxRoutePoints = 1'000'000;
inline constexpr std::int64_t kMaxRouteGridCells = 16'000'000;

/// Checks that the vehicle's mission stays within those limits, from the
/// scene's start pose; throws InputError naming the scene file and the JSON
/// pointer of the first waypoint past a limit (or the planner's params when
/// the obstacles alone make the grid too large). Run by
/// make_rover_route_planner whenever the context names the vehicle, so by
/// `campo run` and `campo validate` alike.
void check_rover_route_extent(const RoverRouteConfig& config, const VehicleDef& vehicle, const Scene& scene);

std::unique_ptr<Planner> make_rover_route_planner(const ParamsBlock& params, const PlannerContext& context);

/// The gap follow-the-gap chose on one scan. Angles in degrees relative to
/// the route's direction (GapDecision::route_heading_deg), positive left.
struct ChosenGap {
  double center_deg = 0.0;   ///< phi_center: the middle of the gap, which side of the route the opening is
  double heading_deg = 0.0;  ///< phi_gap: the heading steered for
  double width_m = 0.0;      ///< L_gap: distance between the gap's end readings, m

  bool operator==(const ChosenGap&) const = default;
};

/// Follow-the-gap's view of one scan while rover_route avoids with it.
struct GapDecision {
  int gaps = 0;                    ///< how many gaps the scan had
  double nearest_range_m = 0.0;    ///< d_min: the nearest reading, m
  /// The route's direction at the rover's nearest route point, degrees
  /// counter-clockwise from x (east), world frame: what the other angles are relative to.
  double route_heading_deg = 0.0;
  double goal_deg = 0.0;           ///< the pure-pursuit goal point, degrees relative to the route, positive left
  std::optional<ChosenGap> chosen{};  ///< the gap steered for, when one was left

  bool operator==(const GapDecision&) const = default;
};

/// What rover_route records beyond the generic decisions (docs/planners.md),
/// declared once: the description registered with it and its typed fields.
struct RoverRouteRecord {
  PlannerRecord description;
  /// Follow-the-gap's choice on the scan read this call.
  RecordField<GapDecision> gap;
  // The route's replanning step's details.
  RecordField<std::string> global;
  RecordField<std::int64_t> route_points;

  RoverRouteRecord();
};
const RoverRouteRecord& rover_route_record();

/// The fields of `params` (keys as RoverRouteConfig's members; nested objects
/// "pure_pursuit", "follow_the_gap", "vfh_plus", "rrt_star"); parameters()
/// writes them back, the fields from guard_step_s to record_path_step_m only
/// when they differ from their defaults.
const ConfigFields<RoverRouteConfig>& rover_route_config_fields();

/// The configuration of `params` (keys as RoverRouteConfig's fields; global
/// "dubins" | "astar" | "rrt_star"; local "follow_the_gap" | "vfh_plus" |
/// "none"; nested objects "pure_pursuit", "follow_the_gap", "vfh_plus",
/// "rrt_star" with their configs' fields); InputError naming the file and
/// JSON pointer otherwise.
RoverRouteConfig parse_rover_route_config(const ParamsBlock& params);

}  // namespace campo
