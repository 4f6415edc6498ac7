#pragma once
/// The planner contract (SPEC §7): a planner receives observations at the
/// control rate and returns a command with a typed status, plus the decisions
/// it took for the record. Planners see plain data only, never Bullet.
/// Implementations and the registry live in planners/; planners built outside
/// campo register with campo/plugin.hpp (docs/extending.md).
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "campo/range_scan.hpp"
#include "campo/scene.hpp"
#include "campo/vehicle.hpp"

namespace campo {

/// Latest reading of one sensor.
struct SensorReading {
  std::string_view alias;
  const RangeSensorConfig* config = nullptr;
  /// Null before the first scan. Shared, so a reader may keep the buffer
  /// alive (the Python module's zero-copy arrays); the sensor's next scan
  /// overwrites it in place.
  std::shared_ptr<const RangeScan> scan;
  bool fresh = false;               ///< taken since the previous observation
};

struct Observation {
  double time_s = 0.0;
  VehicleType vehicle = VehicleType::quadrotor;
  VehicleState state;
  bool stable = false;                   ///< speeds below the vehicle's thresholds
  std::span<const SensorReading> sensors;
  std::span<const Waypoint> mission;

  /// The reading of the sensor named `alias`, or the first one when `alias`
  /// is empty; null when there is none.
  const SensorReading* sensor(std::string_view alias) const;
};

enum class PlanStatus {
  running,        ///< keep going with the returned command
  reached,        ///< the mission is complete
  no_path,        ///< the goal cannot be reached
  invalid_start,  ///< the planner cannot start from here
  aborted,        ///< the planner gave up (reason says why)
};
std::string_view to_string(PlanStatus status);

/// One replanning step of a planner. The metrics count the steps and take
/// the median and maximum of their times; `campo render --kind depth --step K`
/// finds a step by its index.
struct ReplanDecision {
  int index = 0;                        ///< the planner's count of its steps, 0 for the first
  std::optional<std::string> sensor{};  ///< alias of the sensor whose reading the step used, if it read one
  double time_ms = 0.0;                 ///< measured wall-clock time of the step, ms
  /// The planner's own inputs and outputs of the step (a JSON object under
  /// keys other than "index", "sensor" and "time_ms"), recorded beside them.
  nlohmann::json details = nlohmann::json::object();

  bool operator==(const ReplanDecision&) const = default;
};

/// The frame of a mapping planner's reconstructed height map (dstar_lite_3d
/// with column mapping): a grid of square cells in the horizontal plane.
struct HeightMapGrid {
  Eigen::Vector2d origin_m = Eigen::Vector2d::Zero();  ///< world x, y of the south-west corner of cell (0, 0), m
  double cell_size_m = 1.0;                             ///< side of a cell, m, > 0
  int columns = 1;                                      ///< cells along x (east), >= 1
  int rows = 1;                                         ///< cells along y (north), >= 1

  bool operator==(const HeightMapGrid&) const = default;
};

/// One column of the height map whose reconstructed top rose.
struct HeightMapColumn {
  int column = 0;      ///< cell index along x, from the grid's origin
  int row = 0;         ///< cell index along y
  double top_m = 0.0;  ///< world z of the centre of its highest blocked cell, m

  bool operator==(const HeightMapColumn&) const = default;
};

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

/// What a planner decided in one call, for the record (events.jsonl,
/// docs/running.md). The typed fields are the decisions the metrics and
/// figures read; run/event_log.hpp writes them to JSON and reads them back.
/// Positions are world coordinates, m. A field left empty was not decided.
/// Every field has an initializer, so designated initializers may name only
/// the fields decided.
struct Decisions {
  /// Indices into the mission of the waypoints reached this call, in the order reached.
  std::vector<int> reached_waypoints{};
  std::optional<Eigen::Vector3d> planned_waypoint{};      ///< an intermediate waypoint set
  std::optional<Eigen::Vector3d> reached_intermediate{};  ///< an intermediate waypoint reached
  std::optional<Eigen::Vector3d> discarded_waypoint{};    ///< an intermediate waypoint dropped
  /// The global route (a polyline) when it is set or changes: the cross-track
  /// metrics measure against the latest one; an empty route leaves none.
  std::optional<std::vector<Eigen::Vector3d>> planned_path{};
  /// Local obstacle avoidance took over from route following (true) or handed
  /// back (false), recorded at each switch: the avoiding time, the map's amber band.
  std::optional<bool> avoiding{};
  std::optional<ReplanDecision> replan{};  ///< the replanning step taken this call
  /// The range-sensor hits a mapping planner used this call, drawn on the map.
  std::vector<Eigen::Vector3d> lidar_hits{};
  /// The frame of a mapping planner's height map, recorded once, before its columns.
  std::optional<HeightMapGrid> height_map_grid{};
  /// The height-map columns whose top rose this call, each listed once.
  std::vector<HeightMapColumn> height_map_columns{};
  /// Follow-the-gap's choice on the scan read this call (rover_route while avoiding).
  std::optional<GapDecision> gap{};
  /// The planner's other decisions (a JSON object), free-form, under keys other
  /// than the typed fields' names: recorded beside them, for its own figures.
  nlohmann::json extras = nlohmann::json::object();

  /// Whether there is nothing to record.
  bool empty() const {
    return reached_waypoints.empty() && !planned_waypoint && !reached_intermediate && !discarded_waypoint &&
           !planned_path && !avoiding && !replan && lidar_hits.empty() && !height_map_grid &&
           height_map_columns.empty() && !gap && extras.empty();
  }
  bool operator==(const Decisions&) const = default;
};

struct PlanResult {
  PlanStatus status = PlanStatus::running;
  Command command;
  std::string reason;        ///< why, for any status but running
  Decisions decisions;       ///< what it decided this call, empty when nothing to record
};

/// What a planner may know when it is created.
struct PlannerContext {
  VehicleType vehicle = VehicleType::quadrotor;
  const Scene* scene = nullptr;  ///< static map knowledge for global planners
  /// The vehicle the planner drives (its start and mission), when known: a
  /// planner checks at creation that the work its mission implies stays
  /// within its limits, so `campo validate` refuses what `campo run` would.
  const VehicleDef* vehicle_def = nullptr;
};

class Planner {
 public:
  virtual ~Planner() = default;
  virtual PlanResult plan(const Observation& observation) = 0;
  /// The effective parameters, for provenance.
  virtual nlohmann::json parameters() const = 0;
};

/// Builds a planner from its parameters (the scene's planner "params" block:
/// `params.values`, at `params.file` and `params.pointer`); throws InputError
/// (naming that file and a pointer under that block) for bad parameters.
/// Registered with its name in planners/registry.cpp, or by a plugin with
/// CAMPO_REGISTER_PLANNERS (campo/plugin.hpp).
using PlannerFactory = std::unique_ptr<Planner> (*)(const ParamsBlock& params, const PlannerContext& context);

/// Builds the planner a vehicle's spec names (planners/ provides
/// create_planner; the Python module wraps Python objects).
using PlannerMaker = std::function<std::unique_ptr<Planner>(const PlannerSpec& spec, const PlannerContext& context)>;

}  // namespace campo
