#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "campo/json_reader.hpp"
#include "core/output_dir.hpp"
#include "sweep/merge.hpp"
#include "tools/commands.hpp"

namespace campo::cli {

namespace {

namespace fs = std::filesystem;

struct MergeOptions {
  std::vector<std::string> dirs;
  std::string out;
  bool allow_mismatch = false;
};

// The run's kept folders (runs/NAME, triage/NAME) from the directory its line came from.
void copy_folders(const nlohmann::json& line, const fs::path& from, const StagedOutput& out) {
  std::vector<std::string> folders;
  if (line.value("run_dir", nlohmann::json()).is_string()) folders.push_back(line["run_dir"]);
  if (line.contains("triage") && line["triage"].is_object()) folders.push_back(line["triage"].value("dir", ""));
  for (const std::string& folder : folders) {
    if (folder.empty() || !fs::exists(from / folder)) continue;
    copy_output_tree(from / folder, out.path(folder));
  }
}

int run_merge(const MergeOptions& o) {
  const fs::path out_dir = o.out;
  check_output_directory(out_dir, "--out");
  if (fs::exists(out_dir) && !(fs::is_directory(out_dir) && fs::is_empty(out_dir))) {
    throw InputError("command line", "--out", "expected a new or empty directory, got " + out_dir.string());
  }
  std::vector<std::string> warnings;
  std::vector<SweepDir> inputs;
  for (const std::string& dir : o.dirs) inputs.push_back(read_sweep_dir(dir, warnings));
  for (const std::string& w : warnings) std::cerr << "warning: " << w << "\n";
  const MergedSweep merged = merge_sweeps(inputs, o.allow_mismatch);

  StagedOutput out(out_dir);
  std::string results;
  for (std::size_t i = 0; i < merged.lines.size(); ++i) {
    results += merged.lines[i].dump() + "\n";
    copy_folders(merged.lines[i], inputs[merged.sources[i]].dir, out);
  }
  write_file_atomically(out.path("results.jsonl"), results);
  write_file_atomically(out.path("sweep.json"), merged.manifest.dump(2) + "\n");
  out.commit();
  std::cout << "merged " << merged.lines.size() << " runs from " << inputs.size() << " directories into "
            << out_dir.string() << " (" << merged.duplicates << " duplicate lines dropped";
  if (merged.missing > 0) std::cout << "; " << merged.missing << " runs of the manifest have no result yet";
  std::cout << ")\n";
  return kOk;
}

}  // namespace

Command add_merge(CLI::App& app) {
  auto o = std::make_shared<MergeOptions>();
  app.add_option("dirs", o->dirs, "Sweep directories (each with sweep.json and results.jsonl)")
      ->required()
      ->check(existing_directory());
  app.add_option("--out", o->out, "Output directory: new or empty")->required();
  app.add_flag("--allow-mismatch", o->allow_mismatch,
               "Merge directories of different specs or campo versions (refused by default)");
  app.footer(
      "Combines the results of several directories of one sweep, typically its shards (campo sweep\n"
      "--shard K/N), into DIR: results.jsonl with one line per run ID (a completed line is kept over a\n"
      "failed one), in the manifest's order, sweep.json (the manifest, without the shard), and the\n"
      "runs' kept folders (runs/, triage/). Refuses inputs of another spec or campo version unless\n"
      "--allow-mismatch. Says how many runs of the manifest have no result yet.\n"
      "Example: campo merge out/shard-1 out/shard-2 --out out/merged");
  return [o] { return run_merge(*o); };
}

}  // namespace campo::cli
