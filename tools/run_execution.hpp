#pragma once
/// One run from a scene file to its run directory, shared by `campo run` and
/// `campo sweep`: overrides applied and validated, the episode run, the files
/// written all-or-nothing.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sim/episode.hpp"
#include "sim/output_dir.hpp"
#include "sim/scene.hpp"

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

/// A run simulated, its files not yet written.
struct SimulatedRun {
  Scene scene;                   ///< with the overrides
  nlohmann::json document;       ///< the effective scene document
  EpisodeResult result;
  std::size_t vehicle_index = 0;
  nlohmann::json record;         ///< run.json
};

/// Where a run's files go, asked for only once every input is valid (so bad
/// input creates nothing).
using OutputProvider = std::function<const StagedOutput&()>;

/// Validates every input (InputError naming the file and JSON path) and runs
/// the episode. Depth maps asked for by the request are written into
/// `output()`, which may be empty when the request asks for none.
SimulatedRun simulate_run(const RunRequest& request, const OutputProvider& output);

/// Writes run.json, trajectory.csv, scene.json and the requested figures into `out`.
void write_run_files(const SimulatedRun& run, const RunRequest& request, const StagedOutput& out);

/// simulate_run() and write_run_files() into `request.out`, all-or-nothing. Returns run.json.
nlohmann::json execute_run(const RunRequest& request);

/// The depth map the vehicle would see at the end of the run (the failure
/// step of a collision): its first image sensor, else the scanner3d depth
/// camera on its first sensor's mount, cast from the last recorded pose with
/// the movers where they were then. Written as a 16-bit PNG.
void write_final_depth(const SimulatedRun& run, const std::filesystem::path& png);

/// One line for the terminal: outcome, reason, times and path.
std::string run_summary_line(const nlohmann::json& record);

}  // namespace campo::cli
