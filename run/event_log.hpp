#pragma once
/// The planner decisions of a run, bounded by design. Each decision is kept
/// within a fixed size when it is recorded (so the recorder's memory and
/// every line of events.jsonl are bounded whatever the planner emits), and
/// the decisions are written one per line to events.jsonl beside run.json,
/// which itself holds no per-step data (docs/running.md, "Size of the record").
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "campo/episode.hpp"

namespace campo {

/// Entries kept of any one array of a decision (the LIDAR hits of a scan, a planned path).
inline constexpr std::size_t kEventArrayMaxEntries = 2048;
/// Bytes of one events.jsonl line, its newline excluded.
inline constexpr std::size_t kEventLineMaxBytes = 256u << 10;
/// The events file next to run.json.
inline constexpr const char* kEventsFile = "events.jsonl";

/// Bounds one event's decisions in place. An array of more than
/// kEventArrayMaxEntries entries, at any depth, keeps that many, evenly spaced
/// and including its first and last (a thinned path still starts and ends
/// where it did; a thinned scan covers the same obstacles), and
/// `decisions.thinned` maps its JSON pointer to the original count. If the
/// event's line would still exceed kEventLineMaxBytes, its largest keys are
/// dropped, largest first, and `decisions.omitted` maps each to its size in
/// bytes. Returns whether anything was thinned or dropped.
bool bound_decisions(nlohmann::json& decisions);

/// One line of events.jsonl: {"time_s": T, "decisions": {...}} without its newline.
std::string event_line(const PlannerEvent& event);

/// The events, one line each, in time order.
std::string events_jsonl(const std::vector<PlannerEvent>& events);

/// events.jsonl read back as a JSON array of {"time_s", "decisions"}; an
/// InputError naming the file and line for a line that is too long or not an
/// event.
nlohmann::json read_events_jsonl(const std::filesystem::path& path);

}  // namespace campo
