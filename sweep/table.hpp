#pragma once
/// Sweep tables as text: Markdown, CSV or LaTeX. The summary table (one row
/// per scene and axis values, fixed statistics) and tables of chosen metrics
/// (rows and column groups by any fields, mean, spread and 95 % intervals).
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "sweep/results.hpp"

namespace campo {

enum class TableFormat { markdown, csv, latex };

/// What a cell of a table people read shows of its runs (Markdown and
/// LaTeX; CSV always has every statistic in a column of its own).
enum class CellStat {
  mean,        ///< "1.23"
  mean_sd,     ///< "1.23 ± 0.04": the default
  mean_ci,     ///< "1.23 [1.10, 1.41]": the 95 % interval of the mean
  mean_sd_ci,  ///< "1.23 ± 0.04 [1.10, 1.41]"
};

/// A cell's format: the statistic, and whether the number of runs follows.
/// A rate has no sd: "67%" (mean, mean_sd) or "67% [21, 94]" (Wilson).
/// Failed runs are always counted ("(1 failed)"); identical runs print their
/// value alone, marked "(identical runs)".
struct CellFormat {
  CellStat stat = CellStat::mean_sd;
  bool with_n = false;  ///< "(n=3)" after the statistic
};

/// The names of the cell statistics on the command line, in both directions:
/// "mean", "mean-sd", "mean-ci", "mean-sd-ci".
std::span<const std::pair<std::string_view, CellStat>> cell_stat_names();

/// CSV columns of the summary table after "scene" and the axes: runs,
/// success_rate, reached_runs, waypoints_reached_mean ... replan_ms_max,
/// failed, identical.
std::span<const std::string_view> table_stat_columns();

/// The summary table. Markdown: "mean ± sd" cells under human headers (path
/// length, ratio and time over all completed runs and over the reached ones;
/// means alone, and "N identical runs: seeds vary nothing" under Runs, when
/// the row's runs are identical). CSV: one header line of snake_case names,
/// then one line per row, numbers in full precision, empty cells where a
/// statistic has no runs (and sd of identical runs). LaTeX: a tabular.
/// LaTeX: a booktabs tabular (\toprule, \midrule, \bottomrule; needs
/// \usepackage{booktabs}). Spread cells follow `cell` (mean ± sd by default).
std::string format_table(const SweepTable& table, TableFormat format, const CellFormat& cell = {});

/// The runs of one row value and one column value.
struct MetricCell {
  int runs = 0;                                 ///< all of them, failed ones included; 0: no such runs
  int failed = 0;                               ///< runs that failed rather than completed
  /// The runs are one run repeated (identical_runs): the summaries have no
  /// interval, and the formats print the value alone, saying so.
  bool identical = false;
  std::vector<std::optional<Summary>> metrics;  ///< per requested metric; empty when no run has a value
};

/// A table of chosen metrics.
struct MetricTable {
  std::string name;                          ///< the sweep's name
  TableRequest request;
  std::vector<MetricKind> kinds;             ///< per metric
  std::vector<nlohmann::json> rows;          ///< values of the rows field, in expansion order
  std::vector<nlohmann::json> cols;          ///< values of the cols field; one null without cols
  std::vector<std::vector<MetricCell>> cells;  ///< [row][col]
};

/// A table of chosen metrics built a run at a time: memory per cell and
/// metric (RunningStats, IdenticalRuns), not per run.
class MetricTableBuilder {
 public:
  /// `layout` must outlive this (with axes_from_runs its axes may grow until
  /// finish()). Checks what it can before any run: the request's form, and
  /// its fields when the layout's axes are known (InputError).
  MetricTableBuilder(const TableLayout& layout, TableRequest request);
  ~MetricTableBuilder();
  MetricTableBuilder(MetricTableBuilder&&) noexcept;
  MetricTableBuilder& operator=(MetricTableBuilder&&) noexcept;
  /// `index`: the run's place in order of first appearance (for_each_result).
  void add(const RunResult& run, std::size_t index);
  /// Checks the request's fields and metrics against the runs added
  /// (InputError naming where they were given) and summarizes each metric per cell.
  MetricTable finish() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Groups the runs by the request's fields and summarizes each metric per
/// cell (MetricTableBuilder). Checks the request's fields and metrics
/// (InputError naming where they were given).
MetricTable tabulate(const std::vector<RunResult>& runs, const TableLayout& layout, const TableRequest& request);

/// Markdown: one row per row value, one column per column value and metric
/// (headed "Resolution = 64: <metric_heading>"), cells as `cell` says
/// ("mean ± sd" by default; "mean ± sd [ci95 low, high] (n=N, F failed)" with
/// everything; rates "67% [21, 94]"; identical runs "1.20 (identical runs)",
/// with n "1.20 (n=3 identical runs: seeds vary nothing)"); three significant
/// digits of each metric's largest mean. LaTeX: a booktabs tabular, each
/// column value a \multicolumn group headed by the field and the value
/// ("Resolution = 64", "Speed = 2 m/s") with a \cmidrule under it. CSV (tidy, one line per row x column x metric with
/// runs): <rows>,[<cols>,]metric,over,kind,runs,failed,n,mean,sd,ci95_low,
/// ci95_high,identical with metric the name without "@reached", over "all" or
/// "reached", kind "mean" or "rate" (mean a fraction), numbers in full
/// precision, sd and interval empty for identical runs, identical true/false.
std::string format_metric_table(const MetricTable& table, TableFormat format, const CellFormat& cell = {});

/// A name with a unit suffix split into words and unit: the first word
/// after the first that is a unit (m, s, ms, mps, mps2, rad, radps, deg,
/// degps, hz, px, kg, pct) gives the unit, "m/s" for mps and so on, and the
/// others the words: "replan_time_ms_median" -> {"replan time median", "ms"},
/// "speed_mps" -> {"speed", "m/s"}, "resolution" -> {"resolution", ""}.
struct QuantityName {
  std::string words;
  std::string unit;  ///< empty: none
};
QuantityName quantity_name(const std::string& name);

/// The one label of a metric or parameter name with its unit, for table
/// headers, plot and chart axes: "speed_mps" -> "Speed (m/s)", "time_s" ->
/// "Time (s)", "replan_time_ms_median" -> "Replan time median (ms)".
std::string quantity_label(const std::string& name);

/// A metric's label (quantity_label), with the names run.json gives
/// meaning: "path_ratio" -> "Normalized path length", "success" -> "Success
/// rate (%)", "path_ratio@reached" -> "Normalized path length, reached runs".
std::string metric_label(const std::string& metric);

/// metric_label() saying which runs a statistic is over, for table headings
/// and plot axes: ", all runs" after a metric without "@reached" (but
/// success, always over all runs): "Normalized path length, all runs".
std::string metric_heading(const std::string& metric);

/// A field's name as a heading with its unit (quantity_label):
/// "resolution" -> "Resolution", "start_gap" -> "Start gap", "speed_mps" -> "Speed (m/s)".
std::string field_heading(const std::string& field);

/// A field's value as a group heading: "Resolution = 64", "Speed = 2 m/s".
std::string field_value_heading(const std::string& field, const nlohmann::json& value);

}  // namespace campo
