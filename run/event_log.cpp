#include "run/event_log.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <fstream>
#include <limits>
#include <optional>
#include <span>
#include <stdexcept>
#include <string_view>
#include <utility>

#include "campo/json_reader.hpp"

namespace campo {

namespace {

// Room a line needs around its decisions: {"time_s":-1.2345678901234567e-300,"decisions":}.
constexpr std::size_t kLineFrameBytes = 64;

// The names of the typed fields of Decisions in the record; nothing else names them.
constexpr std::string_view kReachedWaypoints = "reached_waypoints";
constexpr std::string_view kPlannedWaypoint = "planned_waypoint";
constexpr std::string_view kReachedIntermediate = "reached_intermediate";
constexpr std::string_view kDiscardedWaypoint = "discarded_waypoint";
constexpr std::string_view kPlannedPath = "planned_path";
constexpr std::string_view kAvoiding = "avoiding";
constexpr std::string_view kReplan = "replan";
constexpr std::string_view kLidarHits = "lidar_hits";
constexpr std::array<std::string_view, 8> kTypedKeys{kReachedWaypoints, kPlannedWaypoint, kReachedIntermediate,
                                                     kDiscardedWaypoint, kPlannedPath,     kAvoiding,
                                                     kReplan,           kLidarHits};
// And of ReplanDecision's.
constexpr std::string_view kIndex = "index";
constexpr std::string_view kSensor = "sensor";
constexpr std::string_view kTimeMs = "time_ms";
constexpr std::array<std::string_view, 3> kReplanKeys{kIndex, kSensor, kTimeMs};
// The notes bound_decisions leaves.
constexpr std::string_view kThinned = "thinned";
constexpr std::string_view kOmitted = "omitted";

nlohmann::json point_json(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }

nlohmann::json points_json(const std::vector<Eigen::Vector3d>& points) {
  nlohmann::json j = nlohmann::json::array();
  for (const Eigen::Vector3d& p : points) j.push_back(point_json(p));
  return j;
}

// Free-form JSON kept beside typed fields: an object (null for none) under none of the typed names.
nlohmann::json free_form(nlohmann::json j, std::span<const std::string_view> typed, const char* what) {
  if (j.is_null()) return nlohmann::json::object();
  if (!j.is_object()) throw std::invalid_argument(std::string("planner decisions: ") + what + " must be a JSON object");
  for (const std::string_view key : typed) {
    if (j.contains(key)) {
      throw std::invalid_argument(std::string("planner decisions: ") + what + " use the typed field's name \"" +
                                  std::string(key) + "\"");
    }
  }
  return j;
}

nlohmann::json replan_json(ReplanDecision replan) {
  nlohmann::json j = free_form(std::move(replan.details), kReplanKeys, "a replanning step's details");
  j[kIndex] = replan.index;
  if (replan.sensor) j[kSensor] = std::move(*replan.sensor);
  j[kTimeMs] = replan.time_ms;
  return j;
}

// Reads the typed fields of one decisions record, taking them out of it.
class DecisionsReader {
 public:
  DecisionsReader(nlohmann::json& record, const std::string& file, const std::string& pointer)
      : record_(record), file_(file), pointer_(pointer) {}

  // The value of `key`, taken out of the record, with its pointer; nullopt when absent.
  std::optional<std::pair<nlohmann::json, std::string>> take(std::string_view key) {
    const auto it = record_.find(key);
    if (it == record_.end()) return std::nullopt;
    std::pair<nlohmann::json, std::string> taken{std::move(*it), child_pointer(pointer_, key)};
    record_.erase(it);
    return taken;
  }

  [[noreturn]] void fail(const nlohmann::json& value, const std::string& pointer, const std::string& expected) const {
    JsonNode(value, file_, pointer).fail(expected);
  }

  // A point [x, y, z]; its pointer is made only for the message (a path has thousands).
  template <typename Pointer>
  Eigen::Vector3d point(const nlohmann::json& j, Pointer&& pointer) const {
    if (!j.is_array() || j.size() != 3 || !j[0].is_number() || !j[1].is_number() || !j[2].is_number()) {
      fail(j, pointer(), "a point [x, y, z] of numbers, m");
    }
    return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()};
  }

  std::optional<Eigen::Vector3d> optional_point(std::string_view key) {
    auto taken = take(key);
    if (!taken) return std::nullopt;
    return point(taken->first, [&] { return taken->second; });
  }

  // A list of points [[x, y, z], ...] under `key`; nullopt when absent.
  std::optional<std::vector<Eigen::Vector3d>> optional_points(std::string_view key) {
    const auto taken = take(key);
    if (!taken) return std::nullopt;
    const auto& [list, at] = *taken;
    if (!list.is_array()) fail(list, at, "a list of points [x, y, z], m");
    std::vector<Eigen::Vector3d> points;
    points.reserve(list.size());
    for (std::size_t i = 0; i < list.size(); ++i) {
      // A named copy: a lambda may not capture a structured binding (clang, C++20).
      const std::string& list_pointer = at;
      points.push_back(point(list[i], [&] { return child_pointer(list_pointer, i); }));
    }
    return points;
  }

  int index(const nlohmann::json& j, const std::string& pointer) const {
    return static_cast<int>(JsonNode(j, file_, pointer).as_int(0, std::numeric_limits<int>::max()));
  }

 private:
  nlohmann::json& record_;
  const std::string& file_;
  const std::string& pointer_;
};

ReplanDecision read_replan(nlohmann::json j, const std::string& file, const std::string& pointer) {
  if (!j.is_object()) JsonNode(j, file, pointer).fail("a replanning step {\"index\", \"time_ms\", ...}");
  if (!j.contains(kIndex)) JsonNode(j, file, pointer).fail("a replanning step with its \"index\"");
  if (!j.contains(kTimeMs)) JsonNode(j, file, pointer).fail("a replanning step with its \"time_ms\"");
  DecisionsReader r(j, file, pointer);
  ReplanDecision replan;
  const auto index = r.take(kIndex);
  replan.index = r.index(index->first, index->second);
  if (auto sensor = r.take(kSensor)) {
    if (!sensor->first.is_string()) r.fail(sensor->first, sensor->second, "a sensor's alias (a string)");
    replan.sensor = sensor->first.get<std::string>();
  }
  const auto time = r.take(kTimeMs);
  replan.time_ms = JsonNode(time->first, file, time->second).as_number();
  replan.details = std::move(j);
  return replan;
}

// Thins every over-long array under `j` (pointer `at`), noting original counts in `thinned`.
void thin_arrays(nlohmann::json& j, const std::string& at, nlohmann::json& thinned) {
  if (j.is_array() && j.size() > kEventArrayMaxEntries) {
    const std::size_t n = j.size(), k = kEventArrayMaxEntries;
    nlohmann::json kept = nlohmann::json::array();
    // Entry i of the k kept is entry round(i (n - 1) / (k - 1)): the first, the last, evenly between.
    for (std::size_t i = 0; i < k; ++i) kept.push_back(std::move(j[(i * (n - 1) + (k - 1) / 2) / (k - 1)]));
    j = std::move(kept);
    thinned[at] = n;
  }
  if (j.is_array()) {
    for (std::size_t i = 0; i < j.size(); ++i) thin_arrays(j[i], child_pointer(at, i), thinned);
  } else if (j.is_object()) {
    for (auto& [key, value] : j.items()) thin_arrays(value, child_pointer(at, key), thinned);
  }
}

}  // namespace

nlohmann::json decisions_to_json(Decisions decisions) {
  nlohmann::json j = free_form(std::move(decisions.own), kTypedKeys, "the planner's own decisions");
  if (!decisions.reached_waypoints.empty()) j[kReachedWaypoints] = decisions.reached_waypoints;
  if (decisions.planned_waypoint) j[kPlannedWaypoint] = point_json(*decisions.planned_waypoint);
  if (decisions.reached_intermediate) j[kReachedIntermediate] = point_json(*decisions.reached_intermediate);
  if (decisions.discarded_waypoint) j[kDiscardedWaypoint] = point_json(*decisions.discarded_waypoint);
  if (decisions.planned_path) j[kPlannedPath] = points_json(*decisions.planned_path);
  if (decisions.avoiding) j[kAvoiding] = *decisions.avoiding;
  if (decisions.replan) j[kReplan] = replan_json(std::move(*decisions.replan));
  if (!decisions.lidar_hits.empty()) j[kLidarHits] = points_json(decisions.lidar_hits);
  return j;
}

Decisions decisions_from_json(nlohmann::json record, const std::string& file, const std::string& pointer) {
  if (!record.is_object()) JsonNode(record, file, pointer).fail("an object of planner decisions");
  DecisionsReader r(record, file, pointer);
  Decisions d;
  if (const auto reached = r.take(kReachedWaypoints)) {
    const auto& [list, at] = *reached;
    if (!list.is_array()) r.fail(list, at, "a list of mission waypoint indices");
    for (std::size_t i = 0; i < list.size(); ++i) d.reached_waypoints.push_back(r.index(list[i], child_pointer(at, i)));
  }
  d.planned_waypoint = r.optional_point(kPlannedWaypoint);
  d.reached_intermediate = r.optional_point(kReachedIntermediate);
  d.discarded_waypoint = r.optional_point(kDiscardedWaypoint);
  d.planned_path = r.optional_points(kPlannedPath);
  if (const auto avoiding = r.take(kAvoiding)) {
    if (!avoiding->first.is_boolean()) r.fail(avoiding->first, avoiding->second, "true or false");
    d.avoiding = avoiding->first.get<bool>();
  }
  if (auto replan = r.take(kReplan)) d.replan = read_replan(std::move(replan->first), file, replan->second);
  d.lidar_hits = r.optional_points(kLidarHits).value_or(std::vector<Eigen::Vector3d>{});
  d.own = std::move(record);
  return d;
}

PlannerEvent event_from_json(nlohmann::json record, const std::string& file, const std::string& pointer) {
  if (!record.is_object() || !record.contains("time_s") || !record["time_s"].is_number() ||
      !record.contains("decisions")) {
    JsonNode(record, file, pointer).fail("an event {\"time_s\": T, \"decisions\": {...}}");
  }
  return {record["time_s"].get<double>(),
          decisions_from_json(std::move(record["decisions"]), file, child_pointer(pointer, "decisions"))};
}

Decisions bounded_decisions(Decisions decisions) {
  nlohmann::json record = decisions_to_json(std::move(decisions));
  bound_decisions(record);
  return decisions_from_json(std::move(record), "planner decisions", "");
}

bool was_bounded(const Decisions& decisions) {
  return decisions.own.contains(kThinned) || decisions.own.contains(kOmitted);
}

bool bound_decisions(nlohmann::json& decisions) {
  nlohmann::json thinned = nlohmann::json::object();
  thin_arrays(decisions, "", thinned);
  bool bounded = !thinned.empty();
  if (bounded) {
    if (!decisions.is_object()) decisions = {{"value", std::move(decisions)}};
    decisions[kThinned] = std::move(thinned);
  }
  const std::size_t max_bytes = kEventLineMaxBytes - kLineFrameBytes;
  std::size_t bytes = decisions.dump().size();
  if (bytes <= max_bytes) return bounded;
  if (!decisions.is_object()) decisions = {{"value", std::move(decisions)}};
  // The largest keys go first, until the rest fits with the note of what went.
  std::vector<std::pair<std::size_t, std::string>> sizes;
  for (const auto& [key, value] : decisions.items()) sizes.emplace_back(value.dump().size(), key);
  std::sort(sizes.begin(), sizes.end(), [](const auto& a, const auto& b) {
    return a.first != b.first ? a.first > b.first : a.second < b.second;
  });
  nlohmann::json omitted = nlohmann::json::object();
  for (const auto& [size, key] : sizes) {
    decisions.erase(key);
    omitted[key] = size;
    // The note is bounded too: keys are names of a planner's decisions, each dropped at most once.
    nlohmann::json note = decisions;
    note[kOmitted] = omitted;
    bytes = note.dump().size();
    if (bytes <= max_bytes) break;
  }
  decisions[kOmitted] = std::move(omitted);
  if (decisions.dump().size() > max_bytes) {
    decisions = {{kOmitted, {{"decisions", bytes}}}};  // hostile key names: keep only that something went
  }
  return true;
}

std::string event_line(const PlannerEvent& event) {
  return nlohmann::json{{"time_s", event.time_s}, {"decisions", decisions_to_json(event.decisions)}}.dump();
}

std::string events_jsonl(const std::vector<PlannerEvent>& events) {
  std::string out;
  for (const PlannerEvent& e : events) out += event_line(e) + "\n";
  return out;
}

std::vector<PlannerEvent> read_events_jsonl(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), "", "cannot open the run's events file");
  std::streambuf* buffer = in.rdbuf();
  std::vector<PlannerEvent> events;
  std::string line;
  for (std::size_t number = 1;; ++number) {
    line.clear();
    int c = buffer->sbumpc();
    if (c == std::char_traits<char>::eof()) break;
    for (; c != std::char_traits<char>::eof() && c != '\n'; c = buffer->sbumpc()) {
      if (line.size() >= kEventLineMaxBytes) {
        throw InputError(path.string(), "", "line " + std::to_string(number) + ": expected at most " +
                                                std::to_string(kEventLineMaxBytes) + " bytes a line");
      }
      line.push_back(static_cast<char>(c));
    }
    const std::string source = path.string() + " line " + std::to_string(number);
    events.push_back(event_from_json(parse_json_text(line, source, {kEventLineMaxBytes, 64}), source, ""));
  }
  return events;
}

std::vector<PlannerEvent> events_from_json(const nlohmann::json& events, const std::string& file,
                                           const std::string& pointer) {
  if (!events.is_array()) JsonNode(events, file, pointer).fail("a list of events");
  std::vector<PlannerEvent> read;
  read.reserve(events.size());
  for (std::size_t i = 0; i < events.size(); ++i) read.push_back(event_from_json(events[i], file, child_pointer(pointer, i)));
  return read;
}

}  // namespace campo
