#pragma once
/// One run from a scene file to its run directory, shared by `campo run` and
/// `campo sweep`: overrides applied and validated, the episode run, the files
/// written all-or-nothing.
#include <filesystem>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "campo/episode.hpp"
#include "campo/scene.hpp"
#include "core/output_dir.hpp"
#include "render/figure_canvas.hpp"
#include "render/run_figures.hpp"
#include "scene/scene_overrides.hpp"
#include "session/imu_record.hpp"

namespace campo {

/// Draws one figure of a recorded run into a directory, in the formats given
/// (render's write_figure; a test injects one that fails).
using FigureWriter = std::function<void(const RecordedRun& run, FigureKind kind, const std::filesystem::path& dir,
                                        const FigureFormats& formats)>;

struct RunRequest {
  std::filesystem::path scene;          ///< scene file
  std::vector<SceneOverride> overrides; ///< applied in order; run.json records their texts
  /// The world's seed (/world/seed), applied after the overrides; recorded
  /// among them as "/world/seed=N". Empty: the scene's.
  std::optional<std::uint64_t> seed;
  std::string planner;                  ///< empty: the scene's, else the default planner
  std::string vehicle;                  ///< empty: the first vehicle
  std::filesystem::path out;            ///< run directory (created)
  std::string label;                    ///< figure legend; empty: the directory name
  bool continue_after_collision = false;
  bool figures = true;                  ///< map.png and side.png
  /// The formats of those figures (PNG alone unless asked).
  std::vector<figure::FigureFormat> figure_formats{figure::FigureFormat::png};
  int record_depth_every = 0;           ///< depth map of every N-th scan under out/depth/ (0 = none)
  bool record_replans = true;           ///< the depth map of every replanning under out/replans/
  int record_images_every = 0;          ///< every N-th image of each colour camera under out/images/ (0 = none)
  /// Wall clock the whole run may take, s (0: no limit). Checked at every
  /// planner call, and a Python planner's call in progress is interrupted:
  /// past it the run ends as failed (its files written) with a reason naming
  /// the limit. Host time, not simulated time: a run within it is unchanged.
  double time_limit_s = 0.0;
  std::string time_limit_name = "--time-limit";  ///< how the caller set it, for the reason
  /// Makes the planner; empty: create_planner (the registry). The Python
  /// module passes one that wraps a Python object.
  PlannerMaker make_planner;
  /// Draws each figure write_run_files writes; empty: write_figure (render/run_figures.hpp).
  FigureWriter write_figure;
};

/// A run's inputs, read and validated: the scene with the overrides, its
/// effective document, which vehicle runs, and the episode's options.
struct PreparedRun {
  Scene scene;
  nlohmann::json document;
  std::size_t vehicle_index = 0;
  EpisodeOptions options;
  /// Where each of the request's overrides assigned, aliases resolved to
  /// indices (apply_override): "/objects/4/planner/params/speed_mps".
  std::vector<std::string> override_pointers;
};

/// Reads the scene, applies the overrides, picks the vehicle and planner
/// (`request.planner` other than the scene's takes the overrides of the
/// vehicle's planner parameters; one that names another planner is refused) and
/// validates every input (InputError naming the file and JSON path), the
/// planner's parameters too unless `validate_planner` is false (an episode
/// driven from outside has no planner).
PreparedRun prepare_run(const RunRequest& request, bool validate_planner = true);

/// A run simulated, its files not yet written.
struct SimulatedRun {
  Scene scene;                   ///< with the overrides
  nlohmann::json document;       ///< the effective scene document
  EpisodeResult result;
  std::size_t vehicle_index = 0;
  nlohmann::json record;         ///< run.json
  /// Every vehicle's IMU samples (imu.csv), in scene order; empty lists for vehicles without IMUs.
  std::vector<std::vector<RecordedImuSample>> imu_samples;
};

/// Where a run's files go, asked for only once every input is valid (so bad
/// input creates nothing).
using OutputProvider = std::function<const StagedOutput&()>;

/// Validates every input (InputError naming the file and JSON path) and runs
/// the episode. Depth maps asked for by the request are written into
/// `output()`, which may be empty when the request asks for none.
SimulatedRun simulate_run(const RunRequest& request, const OutputProvider& output);

/// A figure that could not be drawn or written after the run's files were.
struct FigureFailure {
  std::string figure;        ///< "map", "side", "heightmap"
  std::string message;       ///< what went wrong, naming the file where there is one
  bool bad_input = false;    ///< an InputError (the record, the scene, the place to write), else a bug
};

/// Writes run.json, events.jsonl, trajectory.csv, imu.csv (vehicles with IMUs) and scene.json into `out`
/// (an OutputError naming the file when one cannot be written), then the
/// requested figures. A figure that fails does not take the run with it: the
/// figures that failed are returned and the run's files stay staged.
std::vector<FigureFailure> write_run_files(const SimulatedRun& run, const RunRequest& request,
                                           const StagedOutput& out);

/// What `campo run` prints when figures failed after the run's files were
/// written: one line per figure ("error: map figure: ..." for bad input,
/// "internal error: ..." else), then that the run is kept in `out`.
struct FigureFailureReport {
  std::string text;        ///< the lines, each ending in '\n'
  bool bad_input = true;   ///< every failure was bad input (exit 2), else a bug (exit 1)
};
FigureFailureReport figure_failure_report(const std::vector<FigureFailure>& failures, const std::string& out);

/// The run completed but its own files could not be written: the OutputError
/// of the file, its message naming the run's outcome (run_summary_line) and
/// that none of its files were kept; the run's record travels with it.
class RunNotKeptError : public OutputError {
 public:
  RunNotKeptError(const OutputError& cause, nlohmann::json record);
  const nlohmann::json& record() const { return record_; }

 private:
  nlohmann::json record_;
};

/// A run executed into its directory.
struct ExecutedRun {
  nlohmann::json record;                        ///< run.json
  std::vector<FigureFailure> figure_failures;   ///< figures missing from the directory
};

/// simulate_run() and write_run_files() into `request.out`. Bad input writes
/// nothing; a completed run is kept even when a figure fails (reported in
/// the result). When the run's own files cannot be written: RunNotKeptError,
/// so its outcome is not lost.
ExecutedRun execute_run(const RunRequest& request);

/// The depth map the vehicle would see at the end of the run (the failure
/// step of a collision): its first image sensor, else the scanner3d depth
/// camera on its first sensor's mount, cast from the last recorded pose with
/// the movers where they were then. Written as a 16-bit PNG.
void write_final_depth(const SimulatedRun& run, const std::filesystem::path& png);

/// The signal a run past its wall-clock limit sends its thread (the main
/// thread only) to interrupt a Python planner's call in progress there
/// (python/bindings/planner_limits.hpp); ignored by other code.
int planner_interrupt_signal();

/// One line for the terminal: outcome, reason, times and path.
std::string run_summary_line(const nlohmann::json& record);

}  // namespace campo
