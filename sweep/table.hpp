#pragma once
/// The sweep table as text: Markdown, CSV or LaTeX.
#include <span>
#include <string>
#include <string_view>

#include "sweep/results.hpp"

namespace campo {

enum class TableFormat { markdown, csv, latex };

/// CSV columns after "scene" and the axes: runs, success_rate,
/// waypoints_reached_mean ... replan_ms_max, failed.
std::span<const std::string_view> table_stat_columns();

/// Markdown: "mean ± sd" cells under human headers. CSV: one header line of
/// snake_case names, then one line per row, numbers in full precision, empty
/// cells where a statistic has no runs. LaTeX: a tabular.
std::string format_table(const SweepTable& table, TableFormat format);

}  // namespace campo
