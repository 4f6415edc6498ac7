#include "session/sweep_item.hpp"

#include <algorithm>
#include <optional>
#include <string>
#include <system_error>
#include <vector>

#include "campo/json_reader.hpp"
#include "campo/planner_registry.hpp"
#include "campo/run_record.hpp"
#include "campo/scene_loader.hpp"
#include "core/output_dir.hpp"
#include "render/run_files.hpp"
#include "render/run_video.hpp"
#include "session/run_session.hpp"

namespace campo {

namespace {

namespace fs = std::filesystem;

// One shell word: single-quoted unless plainly safe.
std::string shell_word(const std::string& word) {
  const bool safe = !word.empty() && word.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                                           "0123456789/._-+=,:") == std::string::npos;
  if (safe) return word;
  std::string quoted = "'";
  for (char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

// A video of a run that did not reach its goal, beside its files, for triage: at most about 30 s
// long, 1280 x 720 (encoding a sweep's worth of videos at full size would cost more than the runs).
void write_failure_video(const fs::path& run_dir) {
  const RecordedRun run = load_run_dir(run_dir);
  VideoOptions video;
  video.frame_px = {1280, 720};
  if (!run.view.track.empty()) video.speed = std::max(1.0, run.view.track.back().time_s / 30.0);
  write_video(run, video, run_dir / "video.mp4");
}

// Every vehicle's trajectory: the one file of a single vehicle, each of several headed by its file's name.
std::string trajectories_text(const EpisodeResult& result) {
  if (result.vehicles.size() == 1) return trajectory_csv(result.vehicles.front());
  std::string text;
  for (std::size_t v = 0; v < result.vehicles.size(); ++v) {
    text += "# " + trajectory_file(result, v) + "\n" + trajectory_csv(result.vehicles[v]);
  }
  return text;
}

// Appends one part to a "; "-separated list of what was not written.
void add_error(std::string& errors, const std::string& part) { errors += (errors.empty() ? "" : "; ") + part; }

}  // namespace

std::string triage_dir(const SweepRun& run) { return "triage/" + run.name; }

std::string repro_command(const SweepRun& run, const std::string& triage_dir) {
  std::string command = "campo run " + shell_word(fs::absolute(run.scene_file).lexically_normal().string());
  for (const LoadedPlugin& plugin : loaded_plugins()) command += " --plugin " + shell_word(plugin.path);
  for (const SceneOverride& o : run.overrides) command += " --set " + shell_word(o.text);
  return command + " --out " + shell_word(triage_dir + "/rerun");
}

SweepItemResult run_sweep_item(const SweepRun& run, const fs::path& dir, const SweepItemOptions& o) {
  RunRequest request;
  request.scene = run.scene_file;
  request.overrides = run.overrides;
  request.out = dir / run_dir(run.name);
  request.label = run.name;
  request.figures = o.figures;
  request.record_replans = false;
  std::optional<SimulatedRun> simulated;
  try {
    simulated = simulate_run(request, {});
  } catch (const std::exception& e) {
    return failed_item(e.what());
  }
  // The trajectory's digest tells `campo table` whether seeds changed anything.
  SweepItemResult result = completed_item(simulated->record, sha256_hex(trajectories_text(simulated->result)));
  // The run's own files, asked for and not written (a full disk), make it a failed run with the reason,
  // which a resumed sweep runs again; a figure that fails is reported, the run and its files kept.
  std::vector<FigureFailure> figure_failures;
  if (o.keep_runs || o.figures) {
    try {
      StagedOutput out(request.out);
      figure_failures = write_run_files(*simulated, request, out);
      out.commit();
      result.kept_run_dir = true;
    } catch (const std::exception& e) {
      SweepItemResult failed = failed_item(std::string("completed, but its files could not be written: ") + e.what());
      failed.files_failed = true;
      failed.files_error = e.what();
      return failed;
    }
  }
  for (const FigureFailure& f : figure_failures) add_error(result.files_error, f.figure + ": " + f.message);
  const bool reached = result.reached();
  if (o.videos && !reached && o.figures) {
    try {
      write_failure_video(request.out);
    } catch (const std::exception& e) {
      add_error(result.files_error, std::string("video: ") + e.what());
    }
  }
  try {
    if (o.triage && !reached) {
      // What a person needs to see why: the map, the depth map at the last step, the run's files.
      RunRequest figures = request;
      figures.out = dir / triage_dir(run);
      figures.figures = true;
      StagedOutput out(figures.out);
      for (const FigureFailure& f : write_run_files(*simulated, figures, out)) {
        add_error(result.files_error, "triage " + f.figure + ": " + f.message);
      }
      write_final_depth(*simulated, out.path("depth.png"));
      out.commit();
      if (o.videos) write_failure_video(figures.out);
    }
  } catch (const std::exception& e) {
    add_error(result.files_error, std::string("triage: ") + e.what());
  }
  return result;
}

SweepItemResult failed_job_item(const JobOutcome& outcome) {
  // Crashed, hung or threw outside the run: the last thing it said helps.
  std::string reason = outcome.reason;
  if (!outcome.stderr_tail.empty()) {
    const std::string last = outcome.stderr_tail.substr(outcome.stderr_tail.rfind('\n') + 1);
    reason += "; last output: " + last;
  }
  return failed_item(reason);
}

ResultLineContext::Triage write_triage_script(const SweepRun& run, const fs::path& dir) {
  const std::string where = triage_dir(run);
  const std::string command = repro_command(run, fs::absolute(dir / where).lexically_normal().string());
  const OutputDirectory triage(dir / where);
  const fs::path script = dir / where / "repro.sh";
  write_file_atomically(script, "#!/bin/sh\n# " + run.name + " (" + run.id + ")\n" + command + "\n");
  std::error_code ec;
  fs::permissions(script, fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec,
                  fs::perm_options::add, ec);
  if (ec) throw OutputError(script, system_reason("cannot make it executable", ec.value()));
  return {where, command};
}

}  // namespace campo
