#pragma once
/// The planner contract (SPEC §7): a planner receives observations at the
/// control rate and returns a command with a typed status, plus the decisions
/// it took for the record. Planners see plain data only, never Bullet.
/// Implementations and the registry live in planners/; planners built outside
/// campo register with campo/plugin.hpp (docs/extending.md).
#include <memory>
#include <span>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "campo/lidar_scan.hpp"
#include "campo/scene.hpp"
#include "campo/vehicle.hpp"

namespace campo {

/// Latest reading of one sensor.
struct SensorReading {
  std::string_view alias;
  const LidarConfig* config = nullptr;
  const LidarScan* scan = nullptr;  ///< null before the first scan
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

struct PlanResult {
  PlanStatus status = PlanStatus::running;
  Command command;
  std::string reason;        ///< why, for any status but running
  /// What it decided this call, null when nothing to record. Keys the
  /// metrics and figures understand: "reached_waypoints" (indices of mission
  /// waypoints reached), "planned_waypoint" / "reached_intermediate" /
  /// "discarded_waypoint" ([x, y, z] of an intermediate waypoint set, reached,
  /// dropped), "planned_path" (list of [x, y, z]: the global route, recorded
  /// when it is set or changes; the cross-track metrics measure against it),
  /// "avoiding" (bool, recorded when local obstacle avoidance switches on
  /// (true) or off (false): the avoiding time, highlighted on the map),
  /// "replan" (object with "index", "sensor" and "time_ms" for each
  /// replanning step).
  nlohmann::json decisions;
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
/// CAMPO_REGISTER_PLANNER (campo/plugin.hpp).
using PlannerFactory = std::unique_ptr<Planner> (*)(const ParamsBlock& params, const PlannerContext& context);

}  // namespace campo
