#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <iostream>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include <sched.h>
#include <unistd.h>

#include "campo/json_reader.hpp"
#include "campo/planner_registry.hpp"
#include "campo/scene_loader.hpp"
#include "core/output_dir.hpp"
#include "session/scene_checks.hpp"
#include "session/sweep_item.hpp"
#include "sweep/expansion.hpp"
#include "sweep/process_pool.hpp"
#include "sweep/progress.hpp"
#include "sweep/results.hpp"
#include "sweep/sweep_spec.hpp"
#include "tools/bundled.hpp"
#include "tools/commands.hpp"
#include "tools/plugin_options.hpp"

namespace campo::cli {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

struct SweepOptions {
  std::string spec;
  std::string out;
  bool list = false;
  int jobs = 0;               ///< 0: every core this process may use
  std::string shard;          ///< "K/N"
  double time_limit_s = 0.0;  ///< 0: the spec's
  SweepItemOptions item;      ///< --keep-runs, --figures, --triage, --videos
  bool retry_failed = false;
  double progress_every_s = 10.0;
  std::vector<std::string> plugins;
};

struct Shard {
  int index = 1;
  int count = 1;
};

Shard parse_shard(const std::string& text) {
  Shard shard;
  char rest = 0;
  if (text.empty()) return shard;
  if (std::sscanf(text.c_str(), "%d/%d%c", &shard.index, &shard.count, &rest) != 2 || shard.count < 1 ||
      shard.index < 1 || shard.index > shard.count) {
    throw InputError("command line", "--shard", "expected K/N with 1 <= K <= N (e.g. 2/8), got \"" + text + "\"");
  }
  return shard;
}

int available_cores() {
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof set, &set) == 0) return std::max(1, CPU_COUNT(&set));
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

// A directory holds one sweep (one shard of it): it may be resumed, not mixed with another.
void check_same_sweep(const fs::path& manifest_file, const nlohmann::json& manifest) {
  if (!fs::exists(manifest_file)) return;
  const nlohmann::json existing = read_json_file(manifest_file);
  if (existing.contains("runs") && existing["runs"].size() == manifest["runs"].size()) {
    for (std::size_t i = 0; i < manifest["runs"].size(); ++i) {
      if (existing["runs"][i].value("id", "") != manifest["runs"][i]["id"]) {
        throw InputError(manifest_file.string(), "/runs/" + std::to_string(i) + "/id",
                         "expected the runs this directory holds (to resume them), but run " +
                             manifest["runs"][i]["name"].get<std::string>() +
                             " now has another ID: a scene file changed; use a new --out directory");
      }
    }
  }
  for (const char* key : {"spec_sha256", "campo_version", "shard", "plugins"}) {
    if (existing.value(key, nlohmann::json()) != manifest.value(key, nlohmann::json())) {
      throw InputError(manifest_file.string(), std::string("/") + key,
                       "expected the sweep this directory holds (to resume it), but its " + std::string(key) +
                           " was " + existing.value(key, nlohmann::json()).dump() +
                           "; use a new --out directory for another spec, campo version, shard or plugin");
    }
  }
}

// Terminal: one bar line redrawn in place. Otherwise: a plain line now and then.
class ProgressReport {
 public:
  ProgressReport(std::size_t total, int jobs, double every_s)
      : tty_(::isatty(STDERR_FILENO) == 1), jobs_(static_cast<std::size_t>(jobs)), every_s_(every_s) {
    p_.total = total;
  }
  SweepProgress& counts() { return p_; }
  void start() { start_ = last_ = Clock::now(); }
  void tick(bool force = false) {
    p_.elapsed_s = std::chrono::duration<double>(Clock::now() - start_).count();
    p_.running = std::min(jobs_, p_.total - p_.done);  // the pool keeps every slot busy while runs remain
    if (tty_) {
      std::cerr << "\r" << progress_bar(p_) << "\033[K" << std::flush;
    } else if (force || std::chrono::duration<double>(Clock::now() - last_).count() >= every_s_) {
      last_ = Clock::now();
      std::cerr << progress_line(p_) << "\n";
    }
  }
  /// A line of its own, above the bar.
  void say(const std::string& text) {
    if (tty_) std::cerr << "\r\033[K";
    std::cerr << text << "\n";
    if (tty_) tick();
  }
  void finish() {
    tick(true);
    if (tty_) std::cerr << "\n";
  }

 private:
  bool tty_;
  std::size_t jobs_;
  double every_s_;
  SweepProgress p_;
  Clock::time_point start_, last_;
};

// Runs `expand`; the errors it finds in the spec (a run's scene that does not
// load, named at the spec's scene entry) get their line and column in it.
template <class Expand>
void located_in_spec(const SweepSpec& spec, Expand expand) {
  try {
    expand();
  } catch (const InputError& e) {
    throw with_locations(e, spec.file.string(), read_text_file(spec.file));
  }
}

int run_sweep(const SweepOptions& o) {
  // Everything is validated before anything is written.
  const Shard shard = parse_shard(o.shard);
  const SweepSpec spec = read_sweep_spec(file_or_bundled(o.spec, &bundled_sweep_spec));
  // Loaded here, so the runs' processes (forked from this one) have their planners.
  for (const SweepPlugin& plugin : spec.plugins) load_planner_plugin(plugin.file, spec.file.string(), plugin.origin);
  load_plugins(o.plugins);
  // What `campo validate` and `campo run` check, in their order.
  const SceneCheck check = [](const Scene& scene) {
    check_runnable(scene);
    check_vehicles_and_planners(scene);
  };
  if (o.list) {
    // Streamed: each run printed as soon as it is validated, none kept (100,000 runs: about a second).
    std::size_t index = 0, listed = 0;
    located_in_spec(spec, [&] {
      for_each_sweep_run(spec, check, [&](const SweepRun& run) {
        if (index++ % static_cast<std::size_t>(shard.count) != static_cast<std::size_t>(shard.index - 1)) return;
        std::cout << manifest_entry(run).dump() << '\n';
        ++listed;
      });
    });
    std::cerr << spec.name << ": " << listed << " runs" << (o.shard.empty() ? "" : " in shard " + o.shard)
              << ", all valid; nothing was run\n";
    return kOk;
  }
  std::vector<SweepRun> all_runs;
  located_in_spec(spec, [&] { all_runs = expand_sweep(spec, check); });
  const std::vector<SweepRun> runs = shard_of(all_runs, shard.index, shard.count);
  if (o.out.empty()) throw InputError("command line", "--out", "expected an output directory (or --list)");
  if (o.item.videos && !o.item.figures && !o.item.triage) {
    throw InputError("command line", "--videos", "draws videos of the runs --figures or --triage keep; add one of them");
  }
  nlohmann::json manifest = sweep_manifest(spec, all_runs);
  if (!o.shard.empty()) manifest["shard"] = {{"index", shard.index}, {"count", shard.count}};
  // Which plugin files the planners came from: resuming with a rebuilt plugin is another sweep.
  for (const LoadedPlugin& plugin : loaded_plugins()) {
    manifest["plugins"].push_back({{"path", plugin.path}, {"sha256", plugin.sha256}, {"planners", plugin.planners}});
  }
  const fs::path dir = o.out;
  check_output_directory(dir, "--out");
  // Files of a sweep begun before are written through, and must be files (a FIFO would block).
  for (const char* file : {"sweep.json", "results.jsonl"}) output_file_target(dir / file);
  check_same_sweep(dir / "sweep.json", manifest);
  const OutputDirectory sweep_dir(dir);
  write_file_atomically(dir / "sweep.json", manifest.dump(2) + "\n");

  const fs::path results_file = dir / "results.jsonl";
  ResultsLog log(results_file);
  if (log.cut_partial_line()) std::cerr << "warning: cut off the incomplete last line of " << results_file << "\n";
  // Resuming: runs already recorded are not redone (failed ones only with --retry-failed).
  std::set<std::string> recorded;
  for (const RunResult& r : read_results(results_file).runs) {
    // A run that failed only for want of its files' room is done again without being asked.
    if (r.completed || (!o.retry_failed && !r.files_failed)) recorded.insert(r.id);
  }
  std::vector<const SweepRun*> pending;
  for (const SweepRun& run : runs) {
    if (!recorded.contains(run.id)) pending.push_back(&run);
  }
  const std::size_t skipped = runs.size() - pending.size();

  ProcessPoolConfig pool;
  pool.jobs = o.jobs > 0 ? o.jobs : available_cores();
  pool.time_limit_s = o.time_limit_s > 0.0 ? o.time_limit_s : spec.time_limit_s;
  const std::string spec_hash = spec_sha256(spec);
  std::cerr << spec.name << ": " << pending.size() << " runs to do" << (o.shard.empty() ? "" : " in shard " + o.shard)
            << " (" << skipped << " already recorded), " << pool.jobs << " at a time\n";

  ProgressReport progress(pending.size(), pool.jobs, o.progress_every_s);
  double overhead_s = 0.0;
  std::size_t returned = 0;
  std::size_t files_errors = 0;
  progress.start();
  run_isolated(
      pending.size(), [&](std::size_t i) { return to_json(run_sweep_item(*pending[i], dir, o.item)).dump(); },
      [&](std::size_t i, const JobOutcome& outcome) {
        const SweepRun& run = *pending[i];
        SweepItemResult result;
        if (outcome.ok) {
          result = sweep_item_result_from_json(nlohmann::json::parse(outcome.output));
          overhead_s += outcome.wall_time_s - outcome.work_time_s;
          ++returned;
        } else {
          result = failed_job_item(outcome);
        }
        ResultLineContext context{outcome.wall_time_s, spec_hash, std::nullopt};
        if (o.item.triage && !result.reached()) context.triage = write_triage_script(run, dir);
        log.append(result_line(run, result, context));
        SweepProgress& counts = progress.counts();
        ++counts.done;
        if (!result.completed) {
          ++counts.failed;
          progress.say("failed: " + run.name + " (" + run.id + "): " + result.reason);
        }
        if (!result.files_error.empty() && result.completed) {
          ++files_errors;
          progress.say("completed, but some of its figures could not be written: " + run.name + " (" + run.id +
                       "): " + result.files_error);
        }
        progress.tick();
      },
      pool, [&] { progress.tick(); });
  progress.finish();

  // The sweep's state on disk, this invocation's runs and earlier ones alike.
  std::set<std::string> ids;
  for (const SweepRun& run : runs) ids.insert(run.id);
  std::size_t completed = 0, failed = 0, files_failed = 0;
  for (const RunResult& r : read_results(results_file).runs) {
    if (!ids.contains(r.id)) continue;
    ++(r.completed ? completed : failed);
    files_failed += !r.completed && r.files_failed;
  }
  if (returned > 0) {
    std::cerr << "sweep overhead: " << 1000.0 * overhead_s / static_cast<double>(returned)
              << " ms per run (process start, result transport)\n";
  }
  std::cout << spec.name << ": " << completed << " of " << runs.size() << " runs completed, " << failed
            << " failed (" << pending.size() << " run now, " << skipped << " already recorded); results in "
            << results_file.string() << " (campo table " << dir.string() << ")\n";
  if (failed == 0 && files_errors == 0) return kOk;
  // Runs whose only failure was the place to write them (a full disk) are the output's fault, not
  // campo's: exit 2, as for any output that cannot be written; a resumed sweep redoes them.
  if (failed == files_failed) {
    std::cerr << "error: " << dir.string() << ": the files of " << files_failed + files_errors
              << " runs could not be written (see the lines above and results.jsonl); campo sweep "
              << "redoes those runs when resumed\n";
    return kBadInput;
  }
  return kInternalError;
}

}  // namespace

Command add_sweep(CLI::App& app) {
  auto o = std::make_shared<SweepOptions>();
  app.add_option("spec", o->spec,
                 "Sweep spec file (JSON, see docs/sweeps.md), or the name of a bundled spec (e.g. resolution_000)")
      ->required()
      ->check(input_path());
  add_plugin_option(app, o->plugins);
  app.add_option("--out", o->out, "Output directory (created if missing; an interrupted sweep resumes there)");
  app.add_flag("--list", o->list,
               "Validate every run and print the manifest, one JSON line per run (id, name, scene, planner, "
               "params, seed, overrides, scene_file), without running anything; each line is printed as soon as "
               "its run is validated, so a run that is refused ends the listing with exit 2");
  app.add_option("--jobs,-j", o->jobs, "Runs at a time, each in its own process (default: every available core)")
      ->check(CLI::Range(1, 1024));
  app.add_option("--shard", o->shard, "Run only part K of N of the manifest (runs K, K+N, K+2N, ...; K from 1)");
  app.add_option("--time-limit", o->time_limit_s,
                 "Wall-clock seconds a run may take before it is killed and recorded as failed (default: the "
                 "spec's time_limit_s, else 3600)")
      ->check(positive_number());
  app.add_flag("--keep-runs", o->item.keep_runs,
               "Keep each run's files (run.json, trajectory.csv, scene.json) in DIR/runs/NAME/");
  app.add_flag("--figures", o->item.figures, "Also draw map.png and side.png for every run (implies --keep-runs; slower)");
  app.add_flag("--triage", o->item.triage,
               "For every run that failed or did not reach its goal: DIR/triage/NAME/ with map.png, side.png, "
               "depth.png (what the vehicle saw at the last step), the run's files and repro.sh, the command "
               "that reruns it alone");
  app.add_flag("--videos", o->item.videos,
               "With --figures or --triage: also video.mp4 (campo render --kind video, sped up to at most about "
               "30 s) of each run that did not reach its goal, in its run and triage directories");
  app.add_flag("--retry-failed", o->retry_failed, "Rerun the runs recorded as failed (completed runs are kept)");
  app.add_option("--progress-every", o->progress_every_s,
                 "Seconds between progress lines when stderr is not a terminal (default: 10)")
      ->check(positive_number());
  app.footer(
      "Expands the spec into runs (scenes x planners x axis values or samples x seeds), validates every\n"
      "run's scene with its overrides, then runs them in parallel, each in its own process: a run that\n"
      "crashes, hangs past the time limit or throws is recorded as failed with its reason, and the\n"
      "others go on. Writes DIR/sweep.json (the spec and the manifest) and appends one line per finished\n"
      "run to DIR/results.jsonl (id, params, seed, status, metrics, provenance; with several vehicles\n"
      "the run's metrics and each vehicle's, tabled as ALIAS.METRIC), so a killed sweep loses\n"
      "no finished run: run the same command again and it does only the rest. Run IDs are content\n"
      "hashes (campo version, run name, effective scene): the same run has the same ID in any spec, order\n"
      "or shard, and its results do not depend on --jobs or --shard. On a terminal, a progress bar with\n"
      "ETA; otherwise a progress line every 10 s. Shards of one spec combine with campo merge.\n"
      "Example: campo sweep scenes/sweeps/resolution_000.json --out out/resolution --jobs 2\n"
      "Exit 0 when every run completed (whatever its outcome), 1 if any failed, 2 on bad input\n"
      "(nothing is written).");
  return [o] { return run_sweep(*o); };
}

}  // namespace campo::cli
