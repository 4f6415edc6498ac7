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

/// The JSON record of a planner's decisions (docs/running.md, "Planner
/// decisions in the record"): each typed field that was decided under its
/// name, beside the planner's own (Decisions::own); a replanning step is one object of its
/// index, sensor and time_ms with the planner's details. The one writer of
/// decisions: events.jsonl and everything reading them back agree through
/// it and decisions_from_json. std::invalid_argument when its own decisions (or a
/// replanning step's details) are not a JSON object or use a typed field's
/// name, which would make the record ambiguous.
nlohmann::json decisions_to_json(Decisions decisions);

/// Decisions read back from their JSON record (an object): the typed fields
/// from their keys, every other key into `own` as it is. InputError naming
/// `file`, the JSON pointer of the offending value (under `pointer`, that of
/// the record) and what was expected when the record is not an object or a
/// typed field is malformed.
Decisions decisions_from_json(nlohmann::json record, const std::string& file, const std::string& pointer);

/// One recorded event {"time_s": T, "decisions": {...}} read back; InputError
/// as decisions_from_json, or naming `pointer` when it is not such an event.
PlannerEvent event_from_json(nlohmann::json record, const std::string& file, const std::string& pointer);

/// The decisions as they are recorded: bound_decisions applied to their JSON
/// record, read back. What the metrics read, so that they agree with the files.
Decisions bounded_decisions(Decisions decisions);

/// Whether bound_decisions thinned or cut these decisions (their `thinned` or `omitted` note).
bool was_bounded(const Decisions& decisions);

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

/// events.jsonl read back; an InputError naming the file and line for a line
/// that is too long or not an event (event_from_json).
std::vector<PlannerEvent> read_events_jsonl(const std::filesystem::path& path);

/// The `events` array of a run.json recorded before events.jsonl existed, read
/// back as event_from_json reads each; InputError naming `file` and the
/// offending JSON pointer under `pointer`.
std::vector<PlannerEvent> events_from_json(const nlohmann::json& events, const std::string& file,
                                           const std::string& pointer);

}  // namespace campo
