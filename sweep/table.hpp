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
std::string format_table(const SweepTable& table, TableFormat format);

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
/// (headed by metric_heading), cells "mean ± sd [ci95 low, high] (n=N, F
/// failed)" or, for rates, "67% [21, 94] (n=3)", and for identical runs
/// "1.20 (n=3 identical runs: seeds vary nothing)"; three significant digits
/// of each metric's largest mean. LaTeX: the same as a tabular, column values
/// as \multicolumn groups. CSV (tidy, one line per row x column x metric with
/// runs): <rows>,[<cols>,]metric,over,kind,runs,failed,n,mean,sd,ci95_low,
/// ci95_high,identical with metric the name without "@reached", over "all" or
/// "reached", kind "mean" or "rate" (mean a fraction), numbers in full
/// precision, sd and interval empty for identical runs, identical true/false.
std::string format_metric_table(const MetricTable& table, TableFormat format);

/// A metric's name for people, with its unit from the name's suffix:
/// "path_length_m" -> "path length (m)", "replan_time_ms_median" -> "replan
/// time median (ms)", "path_ratio" -> "normalized path length", "success" ->
/// "success rate (%)", "path_ratio@reached" -> "normalized path length,
/// reached runs".
std::string metric_label(const std::string& metric);

/// metric_label() saying which runs a statistic is over, for table headings
/// and plot axes: ", all runs" after a metric without "@reached" (but
/// success, always over all runs): "normalized path length, all runs".
std::string metric_heading(const std::string& metric);

/// A field's name as a heading: "resolution" -> "Resolution", "start_gap" -> "Start gap".
std::string field_heading(const std::string& field);

}  // namespace campo
