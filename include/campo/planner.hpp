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
#include "campo/rgb_image.hpp"
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

/// Latest sample of one IMU: what it measured at time_s, in its own frame.
struct ImuReading {
  std::string_view alias;
  const ImuConfig* config = nullptr;
  double time_s = 0.0;
  Eigen::Vector3d specific_force_mps2 = Eigen::Vector3d::Zero();  ///< accelerometer: a - g (+g up at rest)
  Eigen::Vector3d angular_rate_radps = Eigen::Vector3d::Zero();    ///< gyroscope
  bool valid = false;  ///< false before the first sample
  bool fresh = false;  ///< taken since the previous observation
};

/// Latest image of one colour camera.
struct ImageReading {
  std::string_view alias;
  const RgbCameraConfig* config = nullptr;
  /// Null before the first image; shared like SensorReading::scan.
  std::shared_ptr<const RgbImage> image;
  bool fresh = false;
};

struct Observation {
  double time_s = 0.0;
  VehicleType vehicle = VehicleType::quadrotor;
  VehicleState state;
  bool stable = false;                   ///< speeds below the vehicle's thresholds
  std::span<const SensorReading> sensors;
  std::span<const Waypoint> mission;
  std::span<const ImuReading> imus;      ///< the vehicle's IMUs, in scene order
  std::span<const ImageReading> images;  ///< its colour cameras, in scene order

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
  /// The planner's own decisions (a JSON object), recorded beside the typed
  /// fields under keys other than theirs: the fields its PlannerRecord::decisions
  /// declares (campo/planner_record.hpp), written and read through them.
  nlohmann::json own = nlohmann::json::object();

  /// Whether there is nothing to record.
  bool empty() const {
    return reached_waypoints.empty() && !planned_waypoint && !reached_intermediate && !discarded_waypoint &&
           !planned_path && !avoiding && !replan && lidar_hits.empty() && own.empty();
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
/// Registered with its name in planners/planner_registry.cpp, or by a plugin with
/// CAMPO_REGISTER_PLANNERS (campo/plugin.hpp).
using PlannerFactory = std::unique_ptr<Planner> (*)(const ParamsBlock& params, const PlannerContext& context);

/// Builds the planner a vehicle's spec names (planners/ provides
/// create_planner; the Python module wraps Python objects).
using PlannerMaker = std::function<std::unique_ptr<Planner>(const PlannerSpec& spec, const PlannerContext& context)>;

}  // namespace campo
