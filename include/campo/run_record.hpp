#pragma once
/// Files of a run: trajectory.csv and run.json (metrics, outcome, provenance
/// and every effective parameter); events.jsonl is run/event_log.hpp's.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "campo/episode.hpp"

namespace campo {

/// One row per planner call of one vehicle: time, pose (position and
/// roll/pitch/yaw in degrees), linear and angular velocity, the command (kind
/// and fields), clearance, then the vehicle's actuator values flattened into columns.
std::string trajectory_csv(const VehicleResult& result);

/// The names of vehicle `vehicle`'s files in the run directory: with one
/// vehicle trajectory.csv and events.jsonl, with several
/// trajectory_<alias>.csv and events_<alias>.jsonl.
std::string trajectory_file(const EpisodeResult& result, std::size_t vehicle);
std::string events_file(const EpisodeResult& result, std::size_t vehicle);

/// run.json. With one vehicle: {"metrics", "provenance", "parameters":
/// {world, vehicle, planner, sensors, mission, stop_on_collision},
/// "overrides", "final_state_hash", "final_body_poses", "event_log": {"file":
/// "events.jsonl", "count", "bounded"}}. With several: "metrics" is the
/// run's (FleetMetrics), "parameters" {world, end, stop_on_collision}, and
/// "vehicles" one object per vehicle {alias, metrics, parameters: {vehicle,
/// planner, sensors, mission}, planner_provenance, trajectory_file,
/// event_log}. Nothing in it grows with the length of the run: the planner
/// decisions go to the events files (events_jsonl in run/event_log.hpp).
nlohmann::json run_json(const Scene& scene, const EpisodeResult& result, const EpisodeOptions& options,
                        const std::vector<std::string>& overrides);

}  // namespace campo
