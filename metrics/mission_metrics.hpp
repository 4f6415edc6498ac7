#pragma once
/// The measures of a flown mission, per leg and per gate, as declared metric
/// fields (campo/record_fields.hpp) of a run's metrics (EpisodeMetrics::declared,
/// run.json): each field is declared here once, with its name, type, unit and
/// meaning, written through its declaration and read back through the same
/// declaration; no reader spells a key.
///
///   leg<k>_path_length_m           number, m: the path flown along leg k; null when it was not flown
///   leg<k>_lateral_before_climb_m  number, m: how far it moved sideways before it climbed; null: no climb
///   gate_<name>_passed             flag: whether the vehicle passed through the gate
///   gate_<name>_time_s             number, s: when it first was inside it; null: never
///
/// Leg k runs from the start (leg 0) or mission waypoint k - 1 to mission
/// waypoint k; the measures are metrics/route_metrics.hpp's.
#include <cstddef>
#include <optional>
#include <span>
#include <string>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "campo/episode_record.hpp"
#include "campo/record_fields.hpp"
#include "campo/scene.hpp"

namespace campo {

/// The declared metric fields of mission leg k.
struct LegMetricFields {
  explicit LegMetricFields(std::size_t k);

  RecordFields fields;
  RecordField<double> path_length_m;           ///< null: waypoint k (or k - 1) was not reached
  RecordField<double> lateral_before_climb_m;  ///< null: the leg does not climb, or was not flown
};

/// The declared metric fields of the mission gate named `name` (MissionGate::name).
struct GateMetricFields {
  explicit GateMetricFields(const std::string& name);

  RecordFields fields;
  RecordField<bool> passed;
  RecordField<double> time_s;  ///< null: never inside
};

/// Every mission metric field of a vehicle's mission (its legs, then its
/// gates), for the docs and for checking a record.
RecordFields mission_metric_fields(const VehicleDef& def);

/// Writes `value` through `field`, or null when there is none (a measure that
/// could not be taken: run.json keeps the key, so every run of a mission has the same keys).
void set_or_null(nlohmann::json& record, const RecordField<double>& field, std::optional<double> value);
/// What set_or_null wrote: nullopt when the record has no value there or null.
/// InputError when the value is of another type.
std::optional<double> get_unless_null(const nlohmann::json& record, const RecordField<double>& field);

/// Writes the mission metrics of a run into `record` (EpisodeMetrics::declared):
/// the fields of every leg (one per mission waypoint of `def`) and of every
/// gate, measured on the trajectory. Leg k runs from sample reached_sample[k - 1]
/// (sample 0 for leg 0, flown from `start`) to sample reached_sample[k], the
/// samples of the planner calls that reported the two waypoints reached
/// (nullopt: not reached; the leg's fields are null). reached_sample holds one
/// entry per mission waypoint.
void write_mission_metrics(const VehicleDef& def, const Eigen::Vector3d& start,
                           std::span<const TrajectorySample> trajectory,
                           std::span<const std::optional<std::size_t>> reached_sample, nlohmann::json& record);

}  // namespace campo
