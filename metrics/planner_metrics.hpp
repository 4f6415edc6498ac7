#pragma once
/// A planner's own metrics (PlannerRecord::metrics, campo/planner_record.hpp):
/// their names checked against run.json's other metrics before a run, and
/// measured by the planner's code after it, into EpisodeMetrics::declared.
#include <string_view>

#include <nlohmann/json.hpp>

#include "campo/planner_record.hpp"
#include "campo/scene.hpp"

namespace campo {

/// Refuses metric names of `record` (the planner `planner`'s) that are run.json's
/// generic metrics' keys (to_json(EpisodeMetrics)) or mission metrics' keys of
/// `def` (mission_metric_fields): InputError naming the planner and every clash.
/// Checked before a run starts, so a clash costs no simulation.
void check_planner_metric_names(std::string_view planner, const PlannerRecord& record, const VehicleDef& def);

/// Measures the metrics of `record` (nothing when it declares none) on `run` and
/// merges them into `declared` (EpisodeMetrics::declared). InputError naming the
/// planner when its measure wrote a key it did not declare, a value not of its
/// declared type, or a key `declared` or the generic metrics hold already.
void write_planner_metrics(std::string_view planner, const PlannerRecord& record, const PlannerRun& run,
                           nlohmann::json& declared);

}  // namespace campo
