#pragma once
/// Combining the results of several directories of one sweep (its shards, or
/// reruns elsewhere) into one: `campo merge`.
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace campo {

/// One sweep directory: its sweep.json and results.jsonl lines.
struct SweepDir {
  std::filesystem::path dir;
  nlohmann::json manifest;            ///< sweep.json
  std::vector<nlohmann::json> lines;  ///< results.jsonl
};

/// Reads DIR/sweep.json and DIR/results.jsonl (InputError if either is missing
/// or bad, or a line has no string "id").
SweepDir read_sweep_dir(const std::filesystem::path& dir, std::vector<std::string>& warnings);

struct MergedSweep {
  nlohmann::json manifest;               ///< the first input's sweep.json, without "shard"
  std::vector<nlohmann::json> lines;     ///< one per run ID: in manifest order, then in order of appearance
  std::vector<std::size_t> sources;      ///< for each line, the input it came from (its folders are there)
  std::size_t duplicates = 0;            ///< lines dropped because another line of their run was kept
  std::size_t missing = 0;               ///< manifest runs no input has a line for
};

/// Merges the inputs. One line per run ID: a completed line before a failed
/// one, else the last one read (inputs in order, lines in file order).
/// Unless `allow_mismatch`, every input must have the first's spec_sha256 and
/// campo_version, and every line the campo_version of its sweep; otherwise an
/// InputError names the directory and what differs.
MergedSweep merge_sweeps(const std::vector<SweepDir>& inputs, bool allow_mismatch);

}  // namespace campo
