#include <filesystem>
#include <iostream>
#include <map>
#include <vector>
#include <string>

#include "sim/json_reader.hpp"
#include "sim/output_dir.hpp"
#include "sweep/expansion.hpp"
#include "sweep/results.hpp"
#include "sweep/sweep_spec.hpp"
#include "tools/commands.hpp"
#include "tools/run_execution.hpp"
#include "tools/scene_checks.hpp"

namespace campo::cli {

namespace {

namespace fs = std::filesystem;

struct SweepOptions {
  std::string spec;
  std::string out;
  bool figures = false;
  bool dry_run = false;
};

// What makes two manifests the same sweep: run IDs and their overrides (scene
// paths may differ with the working directory).
nlohmann::json sweep_identity(const nlohmann::json& manifest) {
  nlohmann::json identity = nlohmann::json::array();
  for (const auto& run : manifest.value("runs", nlohmann::json::array())) {
    identity.push_back({run.value("id", ""), run.value("overrides", nlohmann::json())});
  }
  return identity;
}

// A directory holds one sweep: it may be resumed, not mixed with another.
void check_same_sweep(const fs::path& manifest_file, const nlohmann::json& manifest) {
  if (!fs::exists(manifest_file)) return;
  if (sweep_identity(read_json_file(manifest_file)) != sweep_identity(manifest)) {
    throw InputError(manifest_file.string(), "/runs",
                     "the directory holds a different sweep (other runs or overrides); expected the same "
                     "spec to resume it, or use a new --out directory");
  }
}

// run_summary_line() without its leading scene name, which the run ID already gives.
std::string outcome_summary(const nlohmann::json& record) {
  const std::string line = run_summary_line(record);
  const std::string scene = record.at("provenance").at("scene").value("name", "") + ": ";
  return line.starts_with(scene) ? line.substr(scene.size()) : line;
}

int run_sweep(const SweepOptions& o) {
  // Everything is validated before anything is written.
  const SweepSpec spec = read_sweep_spec(o.spec);
  const std::vector<SweepRun> runs = expand_sweep(spec, [](const Scene& scene) {
    check_vehicles_and_planners(scene);
    check_runnable(scene);
  });
  const nlohmann::json manifest = sweep_manifest(spec, runs);
  if (o.dry_run) {
    std::cout << manifest.dump(2) << "\n";
    std::cerr << spec.name << ": " << runs.size() << " runs, all valid; nothing was run\n";
    return kOk;
  }
  if (o.out.empty()) throw InputError("command line", "--out", "expected an output directory (or --dry-run)");
  const fs::path dir = o.out;
  check_same_sweep(dir / "sweep.json", manifest);
  fs::create_directories(dir);
  write_file_atomically(dir / "sweep.json", manifest.dump(2) + "\n");

  const fs::path results_file = dir / "results.jsonl";
  ResultsLog log(results_file);
  if (log.cut_partial_line()) std::cerr << "warning: cut off the incomplete last line of " << results_file << "\n";
  // Resuming: runs already completed with the same overrides are not redone.
  std::map<std::string, std::vector<std::string>> done;  // id -> overrides
  for (const RunResult& r : read_results(results_file).runs) {
    if (r.completed) done.emplace(r.id, r.overrides);
  }

  int completed = 0, failed = 0, skipped = 0;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const SweepRun& run = runs[i];
    std::cerr << "[" << i + 1 << "/" << runs.size() << "] " << run.id << ": ";
    if (const auto it = done.find(run.id); it != done.end() && it->second == run.overrides) {
      std::cerr << "already completed, skipped\n";
      ++skipped;
      continue;
    }
    RunRequest request;
    request.scene = run.scene_file;
    request.overrides = run.overrides;
    request.out = dir / run_dir(run.id);
    request.label = run.id;
    request.figures = o.figures;
    request.record_replans = false;
    nlohmann::json line;
    // A run that throws is recorded as failed and the sweep goes on.
    try {
      const nlohmann::json record = execute_run(request);
      line = completed_result(run, record);
      ++completed;
      std::cerr << outcome_summary(record) << "\n";
    } catch (const std::exception& e) {
      line = failed_result(run, e.what());
      ++failed;
      std::cerr << "failed: " << e.what() << "\n";
    }
    log.append(line);
  }
  std::cout << spec.name << ": " << completed << " runs completed, " << failed << " failed, "
            << skipped << " already done; results in " << results_file.string() << " (campo table "
            << dir.string() << ")\n";
  return failed == 0 ? kOk : kInternalError;
}

}  // namespace

Command add_sweep(CLI::App& app) {
  auto o = std::make_shared<SweepOptions>();
  app.add_option("spec", o->spec, "Sweep spec file (JSON, see docs/sweeps.md)")->required();
  app.add_option("--out", o->out, "Output directory (created if missing; an interrupted sweep resumes there)");
  app.add_flag("--figures", o->figures, "Draw map.png and side.png for every run (slower)");
  app.add_flag("--dry-run", o->dry_run, "Validate every run and print the manifest (as sweep.json) without running");
  app.footer(
      "Expands the spec into runs (scenes x axis values x seeds), validates every run's scene with\n"
      "its overrides, then runs them one after the other. Writes DIR/sweep.json (the spec and the\n"
      "manifest of runs), DIR/runs/<id>/ (each run's files, as campo run) and DIR/results.jsonl (one\n"
      "line per run, appended as it finishes: params, seed, status, metrics, provenance). A run that\n"
      "fails is recorded with its reason and the sweep goes on; run again with the same --out to\n"
      "resume (completed runs are skipped). Summarize with campo table DIR.\n"
      "Example: campo sweep scenes/sweeps/resolution_000.json --out out/resolution\n"
      "Exit 0 when every run completed (whatever its outcome), 1 if any failed, 2 on bad input\n"
      "(nothing is written).");
  return [o] { return run_sweep(*o); };
}

}  // namespace campo::cli
