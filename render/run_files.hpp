#pragma once
/// Reading a recorded run directory (run.json, events.jsonl, trajectory.csv, scene.json)
/// back for figures, so every figure is reproducible from the files alone.
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "campo/episode.hpp"
#include "campo/scene.hpp"
#include "render/figures.hpp"

namespace campo {

struct RecordedRun {
  std::filesystem::path dir;
  nlohmann::json record;  ///< run.json
  /// The planner decisions in time order: events.jsonl (run.json's
  /// event_log), or the "events" array of run.json in runs recorded before it.
  std::vector<PlannerEvent> events;
  Scene scene;            ///< from scene.json, the effective scene of the run
  RunView view;           ///< track, mission and planner decisions
};

/// trajectory.csv read back as numbers, column by column (docs/running.md);
/// fields that are not numbers (the command's name) read as 0.
struct TrajectoryTable {
  std::string file;
  std::vector<std::string> header;
  std::vector<std::vector<double>> columns;  ///< [column][row]
  /// The column named `name`; InputError naming the file when there is none.
  const std::vector<double>& column(const std::string& name) const;
};

/// Reads a trajectory.csv; InputError naming the file and line when a line is short.
TrajectoryTable read_trajectory_table(const std::filesystem::path& path);

/// Loads a run directory written by `campo run`; InputError naming the file
/// when something is missing or malformed.
RecordedRun load_run_dir(const std::filesystem::path& dir);

/// File name, under the run's replans/ directory, of the depth map that
/// replanning `index` used (16-bit PNG, depth_image.hpp).
std::string replan_depth_file(int index);

}  // namespace campo
