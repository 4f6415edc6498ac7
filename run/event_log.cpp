#include "run/event_log.hpp"

#include <algorithm>
#include <fstream>
#include <utility>

#include "campo/json_reader.hpp"

namespace campo {

namespace {

// Room a line needs around its decisions: {"time_s":-1.2345678901234567e-300,"decisions":}.
constexpr std::size_t kLineFrameBytes = 64;

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

bool bound_decisions(nlohmann::json& decisions) {
  nlohmann::json thinned = nlohmann::json::object();
  thin_arrays(decisions, "", thinned);
  bool bounded = !thinned.empty();
  if (bounded) {
    if (!decisions.is_object()) decisions = {{"value", std::move(decisions)}};
    decisions["thinned"] = std::move(thinned);
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
    note["omitted"] = omitted;
    bytes = note.dump().size();
    if (bytes <= max_bytes) break;
  }
  decisions["omitted"] = std::move(omitted);
  if (decisions.dump().size() > max_bytes) {
    decisions = {{"omitted", {{"decisions", bytes}}}};  // hostile key names: keep only that something went
  }
  return true;
}

std::string event_line(const PlannerEvent& event) {
  return nlohmann::json{{"time_s", event.time_s}, {"decisions", event.decisions}}.dump();
}

std::string events_jsonl(const std::vector<PlannerEvent>& events) {
  std::string out;
  for (const PlannerEvent& e : events) out += event_line(e) + "\n";
  return out;
}

nlohmann::json read_events_jsonl(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), "", "cannot open the run's events file");
  std::streambuf* buffer = in.rdbuf();
  nlohmann::json events = nlohmann::json::array();
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
    nlohmann::json event = parse_json_text(line, source, {kEventLineMaxBytes, 64});
    if (!event.is_object() || !event.contains("time_s") || !event["time_s"].is_number() ||
        !event.contains("decisions")) {
      throw InputError(path.string(), "", "line " + std::to_string(number) +
                                              ": expected an event {\"time_s\": T, \"decisions\": {...}}");
    }
    events.push_back(std::move(event));
  }
  return events;
}

}  // namespace campo
