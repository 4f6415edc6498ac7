#pragma once
/// DIR/results.jsonl of a sweep: one JSON object per run, appended and
/// flushed line by line so a killed sweep keeps every finished run; read back
/// and aggregated per scene and axis values (seed 000's Table 5.1), or per
/// any fields and metrics (tables and plots).
#include <array>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "campo/json_reader.hpp"
#include "sweep/expansion.hpp"
#include "sweep/statistics.hpp"

namespace campo {

/// A run's directory inside the sweep directory: "runs/<name>".
std::string run_dir(const std::string& name);

/// How one sweep item (one run) ended, as its process reports it
/// (session/sweep_item.hpp): typed, and carried from the run's process to the
/// sweep's as JSON (to_json, sweep_item_result_from_json).
struct SweepItemResult {
  bool completed = false;  ///< the run produced its record; else it failed, for `reason`
  std::string reason;      ///< failed: why
  /// Failed only because its files (--keep-runs, --figures) could not be written: a resumed sweep runs it again.
  bool files_failed = false;
  /// What was asked for and not written: the run's files (files_failed), else the figures, videos and triage
  /// files that failed ("map: ...; video: ..."); empty when everything was written.
  std::string files_error;
  // A completed run's, from its run.json:
  nlohmann::json metrics;             ///< run.json's metrics (with several vehicles: the fleet's)
  /// With several vehicles, each one's {alias, metrics} from run.json's "vehicles", in scene order; null with one.
  nlohmann::json vehicles;
  nlohmann::json campo_version;       ///< its provenance's
  nlohmann::json git_rev;
  nlohmann::json scene_sha256;
  std::string trajectory_sha256;      ///< SHA-256 of its trajectory.csv text (what `campo table` compares)
  bool kept_run_dir = false;          ///< its files are in run_dir(name)

  /// Completed with outcome "reached".
  bool reached() const;
};

/// A completed run's result from its run.json and the SHA-256 of its trajectory.csv text; with several
/// vehicles, each vehicle's alias and metrics too.
SweepItemResult completed_item(const nlohmann::json& run_record, const std::string& trajectory_sha256);
/// A run that failed (threw, crashed, was killed) before writing its record.
SweepItemResult failed_item(const std::string& reason);

nlohmann::json to_json(const SweepItemResult& result);
/// The inverse of to_json (what the run's process sent).
SweepItemResult sweep_item_result_from_json(const nlohmann::json& json);

/// What the sweep's process adds to an item's line.
struct ResultLineContext {
  double wall_time_s = 0.0;  ///< the run's process, from fork to exit
  std::string spec_sha256;
  struct Triage {
    std::string dir;     ///< "triage/<name>", in the sweep directory
    std::string repro;   ///< the command that reruns it alone
  };
  std::optional<Triage> triage;  ///< for a run that failed or did not reach its goal, with --triage
};

/// The one place a results.jsonl line is assembled: {id, name, scene, planner,
/// params, seed, status ("completed" or "failed"), overrides, run_dir
/// (run_dir(name) when its files were kept, else null), metrics (null for a
/// failed run), campo_version, git_rev, scene_sha256, wall_time_s,
/// spec_sha256}; a completed run's trajectory_sha256, a failed one's
/// reason, files_error when something was not written, triage {dir, repro}.
/// A completed run of several vehicles also has "vehicles": [{alias,
/// metrics}] in scene order ("metrics" is then the fleet's); a run of one
/// vehicle has no such key, so its line is as before.
nlohmann::json result_line(const SweepRun& run, const SweepItemResult& result, const ResultLineContext& context);

/// results.jsonl opened for appending. A partial last line (a sweep killed
/// mid-write) is cut off first, so new lines start on a line of their own.
class ResultsLog {
 public:
  /// OutputError naming the file and the system's reason when it cannot be opened.
  explicit ResultsLog(const std::filesystem::path& path);
  ~ResultsLog();
  ResultsLog(const ResultsLog&) = delete;
  ResultsLog& operator=(const ResultsLog&) = delete;
  /// Writes one line. When it cannot be written whole (a full disk), the
  /// part written is cut off again and an OutputError names the file and the
  /// system's reason.
  void append(const nlohmann::json& line);
  /// Whether a partial last line was cut off on opening.
  bool cut_partial_line() const { return cut_partial_line_; }

 private:
  std::filesystem::path path_;
  int fd_ = -1;
  bool cut_partial_line_ = false;
};

/// What the table needs from a run's metrics (run.json, docs/running.md).
/// A run of several vehicles has the fleet's (fleet): outcome, time and
/// collisions; its path metrics are each vehicle's (RunResult::vehicles).
struct RunMetrics {
  std::string outcome;             ///< reached, collision, timeout or aborted
  bool fleet = false;              ///< the metrics of a run of several vehicles: no waypoint or path metrics
  double waypoints_reached = 0.0;
  double waypoints_discarded = 0.0;
  double path_length_m = 0.0;
  double path_ratio = 0.0;
  double time_s = 0.0;             ///< simulated
  int collisions = 0;
  std::optional<double> min_clearance_m;  ///< null without obstacles (and in results before it existed)
  int replans = 0;
  double replan_ms_median = 0.0;
  double replan_ms_max = 0.0;
};

/// One vehicle's metrics in a run of several (a results line's "vehicles").
struct VehicleMetrics {
  std::string alias;
  nlohmann::json metrics;  ///< as run.json records them
};

/// One line of results.jsonl, read back.
struct RunResult {
  std::string id;                      ///< unique per run (results before names were recorded: the name)
  std::string name;                    ///< readable, "two_barriers__resolution-256__seed-1"
  std::string scene;
  std::string planner;                 ///< empty in results written before planners were recorded
  nlohmann::json params;               ///< axis name -> value
  std::uint64_t seed = 0;
  bool completed = false;              ///< false: the run failed before producing its record
  std::string reason;                  ///< why it failed
  /// Failed only because its files (--keep-runs) could not be written: a resumed sweep runs it again.
  bool files_failed = false;
  std::vector<std::string> overrides;
  RunMetrics metrics;                  ///< completed runs only
  nlohmann::json metrics_json;         ///< the run's metrics object as recorded; null for a failed run
  /// A completed run of several vehicles: each one's metrics, in scene order
  /// (metrics are then the fleet's); empty for a run of one vehicle.
  std::vector<VehicleMetrics> vehicles;
  std::string trajectory_sha256;       ///< of its trajectory.csv; empty for failed runs and older results
};

struct ResultsFile {
  std::vector<RunResult> runs;        ///< the last line of each ID, in order of first appearance
  std::vector<std::string> warnings;  ///< e.g. a truncated last line that was ignored
};

/// One line of results.jsonl as JSON, and where it came from ("FILE line N").
struct ResultLine {
  nlohmann::json value;
  std::string source;
};

/// Limits of reading results.jsonl.
struct ResultsLimits {
  std::uintmax_t max_file_bytes = std::uintmax_t{1} << 32;  ///< the whole file: 4 GiB
  std::size_t max_line_bytes = 16u << 20;                   ///< one line, as every JSON file: 16 MiB
};

/// Calls `line(value, source)` for each line of a results.jsonl in file order,
/// parsed but not checked, reading one line at a time. A truncated last line
/// (a sweep killed mid-write) is skipped with a warning; any other line that
/// is not JSON, or longer than the limit, is an InputError naming the file
/// and line.
void for_each_result_line(const std::filesystem::path& path, std::vector<std::string>& warnings,
                          const std::function<void(nlohmann::json&& value, const std::string& source)>& line,
                          const ResultsLimits& limits = {});

/// The lines of a results.jsonl, in file order, parsed but not checked (for_each_result_line).
std::vector<ResultLine> read_result_lines(const std::filesystem::path& path, std::vector<std::string>& warnings);

/// Reads results.jsonl a line at a time, strictly (InputError naming the file,
/// line and JSON pointer; a truncated last line is ignored with a warning),
/// and calls `visit(run, index)` for the run of each ID, its last line (a
/// resumed sweep appends its reruns); `index` is the run's place among the
/// IDs in order of first appearance (read_results' order). A file in which
/// no ID has several lines is read once; otherwise `restart()` is called and
/// the file read again, visiting each ID's last line only (`restart()` is
/// also called before the first reading: it starts the caller's fold afresh).
/// Memory: one line, and 16 bytes per line to find repeated IDs.
void for_each_result(const std::filesystem::path& path, std::vector<std::string>& warnings,
                     const std::function<void()>& restart,
                     const std::function<void(const RunResult& run, std::size_t index)>& visit,
                     const ResultsLimits& limits = {});

/// Reads results.jsonl strictly into memory (for_each_result), every run in
/// order of first appearance.
ResultsFile read_results(const std::filesystem::path& path);

/// A table of chosen metrics (`campo table --rows`): one row per value of
/// the `rows` field, one column group per value of `cols`, the metrics' mean
/// and spread in each cell.
struct TableRequest {
  std::string rows;                  ///< a field: "scene", "planner", "seed" or an axis name
  std::string cols;                  ///< a field other than `rows`; empty: one column group
  std::vector<std::string> metrics;  ///< metric names (run.json metrics, or "success"), at least one
  // Where each part was given, for errors: a file, then a JSON pointer or an option.
  std::string file = "command line";
  std::string rows_at = "--rows", cols_at = "--cols", metrics_at = "--metrics";
};

/// Reads a spec's "table" object strictly: {"rows": FIELD, "cols": FIELD
/// (optional), "metrics": [METRIC, ...]}. Names are checked against the runs
/// at table time (check_field, check_metric).
TableRequest read_table_request(const JsonNode& node);

/// How to lay out the table: the axes and the expansion order of the runs.
struct TableLayout {
  std::string name;                    ///< the sweep's name (chart title)
  std::vector<std::string> axes;       ///< in spec order
  std::vector<std::string> run_order;  ///< run IDs in expansion order
  std::optional<TableRequest> table;   ///< the spec's default table, if it has one
  /// No sweep.json: the axes are the keys of the runs' params, in order of
  /// first appearance, gathered with add_axes as the runs are read.
  bool axes_from_runs = false;
};

/// From DIR/sweep.json when it exists; otherwise the axes are the params'
/// keys and the order is that of results.jsonl.
TableLayout table_layout(const std::filesystem::path& dir, const std::vector<RunResult>& runs);
/// The same before any run is read: without sweep.json, no axes yet
/// (axes_from_runs; add_axes adds them run by run).
TableLayout table_layout(const std::filesystem::path& dir);
/// Adds the keys of `run`'s params that are not axes yet, when layout.axes_from_runs.
void add_axes(TableLayout& layout, const RunResult& run);

/// Fields of every run that tables and plots group by, besides the axes.
inline constexpr std::array<std::string_view, 3> kRunFields{"scene", "planner", "seed"};

/// A run's value of `field` (kRunFields, else an axis: null when the run lacks it or its planner is unknown).
nlohmann::json field_value(const RunResult& run, const std::string& field);

/// Throws InputError(file, where, ...) listing the fields unless `field` is
/// one of kRunFields or `axes`.
void check_field(const std::string& field, const std::vector<std::string>& axes, const std::string& file,
                 const std::string& where);

/// How a metric is summarized: numbers as mean and spread; "success" and
/// boolean metrics as the rate of true.
enum class MetricKind { number, rate };

/// Suffix of a metric summarized over the runs that reached their goal only:
/// "path_ratio@reached". Without it, a metric is over every completed run
/// that has it (an aborted run's short path included).
inline constexpr std::string_view kReachedSuffix = "@reached";

/// A metric as tables and plots name it, split: "path_ratio@reached" ->
/// {"path_ratio", true}. Not checked (check_metric does that).
struct MetricName {
  std::string base;           ///< the run.json key, or "success"
  bool reached_only = false;  ///< over the runs with outcome "reached" only
};
MetricName split_metric(const std::string& metric);

/// A metric name as tables and plots take it, split into the vehicle it is
/// of and the metric: "ALIAS.METRIC" names vehicle ALIAS's metric in a run
/// of several vehicles ("drone.path_ratio", "rover.success",
/// "drone.path_ratio@reached": over the runs in which that vehicle reached
/// its goal); a name without a dot is the run's (the fleet's with several
/// vehicles). Split at the last dot before any "@": aliases may hold dots,
/// metric names do not. Not checked (check_metric does that).
struct VehicleMetricName {
  std::string vehicle;  ///< empty: the run's metric
  std::string metric;   ///< the metric, with its "@reached" if any
};
VehicleMetricName split_vehicle_metric(const std::string& metric);

/// `run` seen from one of its vehicles (`campo table --vehicle`, `campo plot
/// --vehicle`): that vehicle's metrics in place of the fleet's, so plain
/// metric names, "success" and the summary table mean that vehicle's;
/// "ALIAS.METRIC" still names any vehicle's. A failed run is unchanged. A
/// completed run without that vehicle is an InputError(file, where) naming
/// the run and listing its vehicles (or saying it has one).
RunResult vehicle_run(const RunResult& run, const std::string& alias, const std::string& file,
                      const std::string& where);

/// A metric name as `--vehicle ALIAS` reads it: a plain name becomes
/// "ALIAS.name"; a name with a vehicle stays as it is.
std::string vehicle_metric_name(const std::string& metric, const std::string& alias);

/// Whether a run.json metric is measured wall-clock time, which differs
/// between identical runs: wall_time_s, planner_time_ms_*, replan_time_ms_*.
bool measured_metric(std::string_view key);

/// Whether `runs` are the same run repeated: at least two, all completed,
/// with equal metrics but for the measured ones (measured_metric) and equal
/// trajectory digests (all present, or all absent in older results). Their
/// seeds then change nothing, and a spread or interval over them would be
/// spurious.
bool identical_runs(const std::vector<const RunResult*>& runs);

/// Whether runs added one at a time are the same run repeated
/// (identical_runs), keeping one run's metrics.
class IdenticalRuns {
 public:
  void add(const RunResult& run);
  /// identical_runs() of the runs added.
  bool identical() const { return runs_ >= 2 && same_; }

 private:
  int runs_ = 0;
  bool same_ = true;
  nlohmann::json metrics_;  ///< the first run's metrics but the measured ones
  std::string trajectory_sha256_;
};

/// The metrics of the completed runs, gathered a run at a time: what
/// check_metric and available_metrics need (memory: one entry per metric
/// name and vehicle alias).
class MetricCatalog {
 public:
  void add(const RunResult& run);
  /// available_metrics() of the runs added.
  std::vector<std::string> available() const;
  /// The vehicles' aliases of the runs of several vehicles added, in order of first appearance.
  const std::vector<std::string>& vehicles() const { return aliases_; }
  /// check_metric() against the runs added.
  MetricKind check(const std::string& metric, const std::string& file, const std::string& where) const;

 private:
  bool completed_ = false;
  std::map<std::string, unsigned char> kinds_;  ///< metric -> 1: some number, 2: some boolean (bits)
  std::vector<std::string> aliases_;
  std::map<std::string, std::map<std::string, unsigned char>> vehicle_kinds_;  ///< alias -> its metrics' kinds
};

/// "success", then every metric with a number or boolean value in some
/// completed run, sorted; then, for runs of several vehicles, each vehicle's
/// as "ALIAS.success" and "ALIAS.METRIC" (vehicles in order of appearance).
std::vector<std::string> available_metrics(const std::vector<RunResult>& runs);

/// The kind of `metric`; throws InputError(file, where, ...) listing the
/// available metrics when no completed run has it as a number or boolean
/// (any name passes while no run has completed), and for a suffix other
/// than "@reached" or "success@reached" (always 100 %). "outcome" is "success".
/// "ALIAS.METRIC" (split_vehicle_metric) is checked against vehicle ALIAS's
/// metrics: an alias no run has is an error listing the vehicles, a metric
/// that vehicle lacks one listing its metrics.
MetricKind check_metric(const std::string& metric, const std::vector<RunResult>& runs, const std::string& file,
                        const std::string& where);

/// Whether a metric's values are >= 0 by its definition in run.json
/// (docs/running.md), which gives its mean a log-transformed interval
/// (mean_interval95): path_ratio; counts (collisions, replans,
/// planner_calls, waypoints_*); durations and lengths, named with a unit
/// of time or length ("_s", "_ms", "_m" as one of its words: sim_time_s,
/// replan_time_ms_max, path_length_m, cross_track_rms_m) except clearances,
/// which are signed (negative when the shapes overlapped). Any other metric
/// (a plugin's) is taken as signed: the Student t interval.
bool non_negative_metric(const std::string& metric);
/// non_negative_metric() as a Support.
Support metric_support(const std::string& metric);

/// A run's value of `metric`: for "success" (and "outcome"), 1 when the run
/// completed with outcome "reached", else 0 (failed runs included); otherwise
/// the completed run's number, or 1/0 for a boolean; empty when it has none,
/// and for "<metric>@reached" when the run did not reach its goal.
/// "ALIAS.METRIC" the same of vehicle ALIAS's metrics and outcome (empty
/// for a completed run without that vehicle; "ALIAS.success" is 0 for a failed run).
std::optional<double> metric_value(const RunResult& run, const std::string& metric);

/// The metric over `runs`, over those that have a value (the Summary's n);
/// empty when none has.
std::optional<Summary> summarize_metric(const std::vector<const RunResult*>& runs, const std::string& metric,
                                        MetricKind kind);

/// Runs sharing the values of some fields.
struct RunGroup {
  std::vector<nlohmann::json> key;     ///< the values of the fields, in their order
  std::vector<const RunResult*> runs;  ///< in the order of `runs`
};

/// The position of `value` in `values`, appended at the end when new: the
/// distinct values of a field in order of first appearance.
std::size_t index_in_order(std::vector<nlohmann::json>& values, const nlohmann::json& value);

/// Runs grouped by the values of some fields as they are read, keeping per
/// group its key and its rank only.
class RunGroups {
 public:
  /// `layout` must outlive this: its run_order ranks the groups.
  /// `all_params`: group by the whole params object after `fields` too (null
  /// values left out), the axes of a layout that gathers them from the runs.
  RunGroups(const TableLayout& layout, std::vector<std::string> fields, bool all_params = false);
  /// The group of `run` (a new group takes the next number); `index` is the
  /// run's place among the runs in order of first appearance.
  std::size_t add(const RunResult& run, std::size_t index);
  std::size_t size() const { return keys_.size(); }
  /// The values of the fields of a group, in their order (then the params with all_params).
  const std::vector<nlohmann::json>& key(std::size_t group) const { return keys_[group]; }
  /// The groups in the sweep's expansion order (their first run's place in
  /// layout.run_order), then in order of appearance.
  std::vector<std::size_t> order() const;

 private:
  std::vector<std::string> fields_;
  bool all_params_;
  std::map<std::string_view, std::size_t> rank_of_;  ///< run ID (in layout.run_order) -> place
  std::size_t order_size_;
  std::map<std::string, std::size_t> index_of_;      ///< key as JSON text -> group
  std::vector<std::vector<nlohmann::json>> keys_;
  std::vector<std::size_t> ranks_;                   ///< per group: its first run's rank
};

/// Groups `runs` (which must outlive the result) by the values of `fields`;
/// groups in the sweep's expansion order (their first run's place in
/// layout.run_order), then in order of appearance.
std::vector<RunGroup> group_runs(const std::vector<RunResult>& runs, const TableLayout& layout,
                                 const std::vector<std::string>& fields);

/// Mean and sample standard deviation (n - 1; 0 for one value), and the
/// 95 % interval of the mean (mean_interval95; empty for one value).
struct MeanSd {
  double mean = 0.0;
  double sd = 0.0;
  std::optional<Interval> ci95 = std::nullopt;
};

/// One row of the table: the runs of one scene with the same axis values.
struct TableRow {
  std::string scene;
  std::vector<nlohmann::json> params;  ///< one value per axis, in layout order (null if a run lacks it)
  int runs = 0;                        ///< all runs, failed ones included
  int failed = 0;                      ///< runs that failed rather than completed
  double success_rate = 0.0;           ///< runs with outcome "reached" / runs
  int reached = 0;                     ///< runs with outcome "reached"
  // Over the completed runs (whatever their outcome); empty when there are none.
  std::optional<MeanSd> waypoints_reached, waypoints_discarded, path_length_m, path_ratio, time_s;
  // Over the runs that reached their goal only; empty when none did.
  std::optional<MeanSd> path_length_m_reached, path_ratio_reached, time_s_reached;
  bool identical = false;              ///< the runs are one run repeated (identical_runs): no spread to show
  int collisions = 0;                  ///< total
  /// The lowest min_clearance_m of the completed runs (the closest call);
  /// empty when none measured one.
  std::optional<double> min_clearance_m;
  /// Median of the runs' replan_time_ms_median and max of their maxima, over
  /// the completed runs that replanned; empty when none did.
  std::optional<double> replan_ms_median, replan_ms_max;
};

struct SweepTable {
  std::string name;
  std::vector<std::string> axes;
  std::vector<TableRow> rows;  ///< in expansion order (then in order of appearance)
};

/// The summary table built a run at a time: memory per row, not per run
/// (RunningStats, QuantileSketch for the median of the replanning times).
class SummaryBuilder {
 public:
  /// `layout` must outlive this; with axes_from_runs its axes may grow until finish().
  explicit SummaryBuilder(const TableLayout& layout);
  ~SummaryBuilder();
  SummaryBuilder(SummaryBuilder&&) noexcept;
  SummaryBuilder& operator=(SummaryBuilder&&) noexcept;
  /// `index`: the run's place in order of first appearance (for_each_result).
  void add(const RunResult& run, std::size_t index);
  SweepTable finish() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Groups the runs by scene and axis values and computes each group's row (SummaryBuilder).
SweepTable aggregate(const std::vector<RunResult>& runs, const TableLayout& layout);

}  // namespace campo
