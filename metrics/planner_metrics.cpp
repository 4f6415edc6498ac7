// A planner's own metrics (metrics/planner_metrics.hpp): the clash check of
// their names and their merge into run.json's metrics.
#include "metrics/planner_metrics.hpp"

#include <string>
#include <vector>

#include "campo/episode_record.hpp"
#include "campo/json_reader.hpp"
#include "metrics/mission_metrics.hpp"

namespace campo {

namespace {

// run.json's generic metric keys: those to_json writes for any run (declared is null here).
const nlohmann::json& generic_metrics() {
  static const nlohmann::json keys = to_json(EpisodeMetrics{});
  return keys;
}

std::string planner_label(std::string_view planner) { return "planner \"" + std::string(planner) + "\""; }

std::string clash_message(std::string_view planner, const std::vector<std::string>& clashes) {
  std::string names;
  for (const std::string& c : clashes) names += (names.empty() ? "\"" : ", \"") + c + "\"";
  return planner_label(planner) + " declares metric " + names +
         ", expected names other than run.json's generic and mission metrics";
}

}  // namespace

void check_planner_metric_names(std::string_view planner, const PlannerRecord& record, const VehicleDef& def) {
  if (record.metrics.empty()) return;
  const RecordFields mission = mission_metric_fields(def);
  std::vector<std::string> clashes;
  for (const RecordFieldInfo& f : record.metrics.fields()) {
    if (generic_metrics().contains(f.name) || mission.find(f.name) != nullptr) clashes.push_back(f.name);
  }
  if (!clashes.empty()) throw InputError("", "/metrics", clash_message(planner, clashes));
}

void write_planner_metrics(std::string_view planner, const PlannerRecord& record, const PlannerRun& run,
                           nlohmann::json& declared) {
  if (record.metrics.empty() || !record.measure) return;
  nlohmann::json out = nlohmann::json::object();
  record.measure(run, out);
  try {
    record.metrics.check(out, "", "/metrics");
  } catch (const InputError& e) {
    throw InputError(e.file(), e.pointer(), planner_label(planner) + "'s measured metrics: " + e.message());
  }
  std::vector<std::string> clashes;
  for (const auto& [key, value] : out.items()) {
    if (generic_metrics().contains(key) || (declared.is_object() && declared.contains(key))) clashes.push_back(key);
  }
  if (!clashes.empty()) throw InputError("", "/metrics", clash_message(planner, clashes));
  if (declared.is_null()) declared = nlohmann::json::object();
  declared.update(out);
}

}  // namespace campo
