#pragma once
/// One item of a sweep (one run), from its SweepRun to its typed result: what
/// `campo sweep` (and so its Slurm array tasks, one shard each) runs in each
/// run's process, and what the sweep's process adds once it ended (a failed
/// job's reason, the triage script).
#include <filesystem>
#include <string>

#include "sweep/expansion.hpp"
#include "sweep/process_pool.hpp"
#include "sweep/results.hpp"

namespace campo {

/// What a sweep asks of each run besides its result (campo sweep's options).
struct SweepItemOptions {
  bool keep_runs = false;  ///< the run's files in DIR/runs/NAME/
  bool figures = false;    ///< also its figures there (implies keep_runs)
  /// A run that failed or did not reach its goal: DIR/triage/NAME/ with its files, figures and the
  /// depth map at its last step (write_triage_script adds repro.sh from the sweep's process).
  bool triage = false;
  bool videos = false;     ///< with figures or triage: video.mp4 of a run that did not reach its goal
};

/// Runs `run` in this process and writes what `options` ask for into the
/// sweep directory `dir`. Never throws for the run's own failure: bad input
/// or a failure of the run is a failed result with its reason; the run's
/// files that could not be written make it failed with files_failed (a
/// resumed sweep runs it again); figures, videos and triage files that could
/// not be written are its files_error, the run kept.
SweepItemResult run_sweep_item(const SweepRun& run, const std::filesystem::path& dir, const SweepItemOptions& options);

/// The result of an item whose process did not return one (crashed, killed
/// past its time limit, threw outside the run): the pool's reason, and the
/// last line the process wrote, which helps.
SweepItemResult failed_job_item(const JobOutcome& outcome);

/// The triage directory of a run inside the sweep directory: "triage/<name>".
std::string triage_dir(const SweepRun& run);

/// The one command that reruns `run` alone, as `campo run` would, into `triage_dir`/rerun.
std::string repro_command(const SweepRun& run, const std::string& triage_dir);

/// Writes DIR/triage/NAME/repro.sh (executable), the command that reruns the
/// run alone, and returns what its results line records of it. OutputError
/// when it cannot be written.
ResultLineContext::Triage write_triage_script(const SweepRun& run, const std::filesystem::path& dir);

}  // namespace campo
