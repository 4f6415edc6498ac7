#pragma once
/// DIR/results.jsonl of a sweep: one JSON object per run, appended and
/// flushed line by line so a killed sweep keeps every finished run; read back
/// and aggregated per scene and axis values (seed 000's Table 5.1).
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sweep/expansion.hpp"

namespace campo {

/// A run's directory inside the sweep directory: "runs/<id>".
std::string run_dir(const std::string& id);

/// The results.jsonl line of a run that completed, from its run.json:
/// {id, scene, params, seed, status: "completed", overrides, run_dir,
/// metrics, campo_version, git_rev, scene_sha256}.
nlohmann::json completed_result(const SweepRun& run, const nlohmann::json& run_record);
/// The line of a run that failed (threw) before writing its record: status
/// "failed", its `reason`, metrics null.
nlohmann::json failed_result(const SweepRun& run, const std::string& reason);

/// results.jsonl opened for appending. A partial last line (a sweep killed
/// mid-write) is cut off first, so new lines start on a line of their own.
class ResultsLog {
 public:
  explicit ResultsLog(const std::filesystem::path& path);
  /// Writes one line and flushes it.
  void append(const nlohmann::json& line);
  /// Whether a partial last line was cut off on opening.
  bool cut_partial_line() const { return cut_partial_line_; }

 private:
  std::ofstream out_;
  bool cut_partial_line_ = false;
};

/// What the table needs from a run's metrics (run.json, docs/running.md).
struct RunMetrics {
  std::string outcome;             ///< reached, collision, timeout or aborted
  double waypoints_reached = 0.0;
  double waypoints_discarded = 0.0;
  double path_length_m = 0.0;
  double path_ratio = 0.0;
  double time_s = 0.0;             ///< simulated
  int collisions = 0;
  int replans = 0;
  double replan_ms_median = 0.0;
  double replan_ms_max = 0.0;
};

/// One line of results.jsonl, read back.
struct RunResult {
  std::string id;
  std::string scene;
  nlohmann::json params;               ///< axis name -> value
  std::uint64_t seed = 0;
  bool completed = false;              ///< false: the run failed before producing its record
  std::string reason;                  ///< why it failed
  std::vector<std::string> overrides;
  RunMetrics metrics;                  ///< completed runs only
};

struct ResultsFile {
  std::vector<RunResult> runs;        ///< the last line of each ID, in order of first appearance
  std::vector<std::string> warnings;  ///< e.g. a truncated last line that was ignored
};

/// Reads results.jsonl strictly (InputError naming the file, line and JSON
/// pointer), except a truncated last line, which is ignored with a warning.
ResultsFile read_results(const std::filesystem::path& path);

/// How to lay out the table: the axes and the expansion order of the runs.
struct TableLayout {
  std::string name;                    ///< the sweep's name (chart title)
  std::vector<std::string> axes;       ///< in spec order
  std::vector<std::string> run_order;  ///< run IDs in expansion order
};

/// From DIR/sweep.json when it exists; otherwise the axes are the params'
/// keys and the order is that of results.jsonl.
TableLayout table_layout(const std::filesystem::path& dir, const std::vector<RunResult>& runs);

/// Mean and sample standard deviation (n - 1; 0 for one value).
struct MeanSd {
  double mean = 0.0;
  double sd = 0.0;
};

/// One row of the table: the runs of one scene with the same axis values.
struct TableRow {
  std::string scene;
  std::vector<nlohmann::json> params;  ///< one value per axis, in layout order (null if a run lacks it)
  int runs = 0;                        ///< all runs, failed ones included
  int failed = 0;                      ///< runs that failed rather than completed
  double success_rate = 0.0;           ///< runs with outcome "reached" / runs
  // Over the completed runs (whatever their outcome); empty when there are none.
  std::optional<MeanSd> waypoints_reached, waypoints_discarded, path_length_m, path_ratio, time_s;
  int collisions = 0;                  ///< total
  /// Median of the runs' replan_time_ms_median and max of their maxima, over
  /// the completed runs that replanned; empty when none did.
  std::optional<double> replan_ms_median, replan_ms_max;
};

struct SweepTable {
  std::string name;
  std::vector<std::string> axes;
  std::vector<TableRow> rows;  ///< in expansion order (then in order of appearance)
};

/// Groups the runs by scene and axis values and computes each group's row.
SweepTable aggregate(const std::vector<RunResult>& runs, const TableLayout& layout);

}  // namespace campo
