#pragma once
/// Files of a run: trajectory.csv and run.json (metrics, outcome, provenance
/// and every effective parameter); events.jsonl is run/event_log.hpp's.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "campo/episode.hpp"

namespace campo {

/// One row per planner call: time, pose (position and roll/pitch/yaw in
/// degrees), linear and angular velocity, the command (kind and fields),
/// clearance, then the vehicle's actuator values flattened into columns.
std::string trajectory_csv(const EpisodeResult& result);

/// run.json: {"metrics", "provenance", "parameters": {world, vehicle, planner,
/// sensors, mission}, "overrides", "final_state_hash", "final_body_poses",
/// "event_log": {"file": "events.jsonl", "count", "bounded"}}. Nothing in it
/// grows with the length of the run: the planner decisions go to
/// events.jsonl (events_jsonl in run/event_log.hpp).
nlohmann::json run_json(const Scene& scene, const EpisodeResult& result, const EpisodeOptions& options,
                        const std::vector<std::string>& overrides);

}  // namespace campo
