#pragma once
/// One run from a scene file to its run directory, shared by `campo run` and
/// `campo sweep`: overrides applied and validated, the episode run, the files
/// written all-or-nothing.
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace campo::cli {

struct RunRequest {
  std::filesystem::path scene;          ///< scene file
  std::vector<std::string> overrides;   ///< "/json/pointer=VALUE", applied in order (scene_overrides.hpp)
  std::string planner;                  ///< empty: the scene's, else the default planner
  std::string vehicle;                  ///< empty: the first vehicle
  std::filesystem::path out;            ///< run directory (created)
  std::string label;                    ///< figure legend; empty: the directory name
  bool continue_after_collision = false;
  bool figures = true;                  ///< map.png and side.png
  int record_depth_every = 0;           ///< depth map of every N-th scan under out/depth/ (0 = none)
  bool record_replans = true;           ///< the depth map of every replanning under out/replans/
};

/// Validates every input (InputError naming the file and JSON path), runs the
/// episode and writes run.json, trajectory.csv, scene.json and the requested
/// figures and depth maps into `request.out` all-or-nothing. Returns run.json.
nlohmann::json execute_run(const RunRequest& request);

/// One line for the terminal: outcome, reason, times and path.
std::string run_summary_line(const nlohmann::json& record);

}  // namespace campo::cli
