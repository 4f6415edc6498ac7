#include "sweep/table.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <functional>

#include "sweep/sweep_spec.hpp"

namespace campo {

namespace {

// A "mean ± sd" statistic of the table.
struct SpreadColumn {
  std::string_view csv;     ///< CSV name stem: <csv>_mean, <csv>_sd
  std::string_view header;  ///< Markdown/LaTeX header
  int decimals;             ///< Markdown/LaTeX precision
  std::optional<MeanSd> TableRow::*member;
};
// Path length, ratio and time over all completed runs beside the same over the
// runs that reached their goal: an aborted run's short path lowers the first.
constexpr std::array kSpreadColumns{
    SpreadColumn{"waypoints_reached", "Waypoints reached", 1, &TableRow::waypoints_reached},
    SpreadColumn{"waypoints_discarded", "Discarded", 1, &TableRow::waypoints_discarded},
    SpreadColumn{"path_length_m", "Path length (m), all runs", 2, &TableRow::path_length_m},
    SpreadColumn{"path_length_m_reached", "Path length (m), reached runs", 2, &TableRow::path_length_m_reached},
    SpreadColumn{"path_ratio", "Normalized length, all runs", 3, &TableRow::path_ratio},
    SpreadColumn{"path_ratio_reached", "Normalized length, reached runs", 3, &TableRow::path_ratio_reached},
    SpreadColumn{"time_s", "Time (s), all runs", 1, &TableRow::time_s},
    SpreadColumn{"time_s_reached", "Time (s), reached runs", 1, &TableRow::time_s_reached},
};

constexpr auto kStatColumns = std::to_array<std::string_view>({
    "runs", "success_rate", "reached_runs",
    "waypoints_reached_mean", "waypoints_reached_sd", "waypoints_discarded_mean", "waypoints_discarded_sd",
    "path_length_m_mean", "path_length_m_sd", "path_length_m_reached_mean", "path_length_m_reached_sd",
    "path_ratio_mean", "path_ratio_sd", "path_ratio_reached_mean", "path_ratio_reached_sd",
    "time_s_mean", "time_s_sd", "time_s_reached_mean", "time_s_reached_sd",
    "collisions", "min_clearance_m_min", "replan_ms_median", "replan_ms_max", "failed", "identical"});

// What a cell or row of identical runs says instead of a spread.
constexpr std::string_view kIdenticalNote = "identical runs: seeds vary nothing";

constexpr std::array<std::pair<std::string_view, CellStat>, 4> kCellStatNames{{
    {"mean", CellStat::mean}, {"mean-sd", CellStat::mean_sd}, {"mean-ci", CellStat::mean_ci},
    {"mean-sd-ci", CellStat::mean_sd_ci}}};

bool shows_sd(CellStat stat) { return stat == CellStat::mean_sd || stat == CellStat::mean_sd_ci; }
bool shows_ci(CellStat stat) { return stat == CellStat::mean_ci || stat == CellStat::mean_sd_ci; }

// Shortest text that reads back as the same double.
std::string exact(double value) {
  char text[32];
  const auto [end, ec] = std::to_chars(text, text + sizeof text, value);
  return std::string(text, end);
}

std::string fixed(double value, int decimals) {
  char text[48];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::string csv(const SweepTable& table) {
  std::string out = "scene";
  for (const std::string& axis : table.axes) (out += ',') += csv_field(axis);
  for (std::string_view column : kStatColumns) (out += ',') += column;
  out += "\n";
  const auto optional = [](const std::optional<double>& v) { return v ? exact(*v) : std::string(); };
  for (const TableRow& row : table.rows) {
    std::vector<std::string> cells{csv_field(row.scene)};
    for (const auto& value : row.params) cells.push_back(csv_field(value.is_null() ? "" : value_label(value)));
    cells.push_back(std::to_string(row.runs));
    cells.push_back(exact(row.success_rate));
    cells.push_back(std::to_string(row.reached));
    for (const SpreadColumn& column : kSpreadColumns) {
      const std::optional<MeanSd>& s = row.*column.member;
      cells.push_back(s ? exact(s->mean) : "");
      cells.push_back(s && !row.identical ? exact(s->sd) : "");  // identical runs have no spread to speak of
    }
    cells.push_back(std::to_string(row.collisions));
    cells.push_back(optional(row.min_clearance_m));
    cells.push_back(optional(row.replan_ms_median));
    cells.push_back(optional(row.replan_ms_max));
    cells.push_back(std::to_string(row.failed));
    cells.push_back(row.identical ? "true" : "false");
    for (std::size_t i = 0; i < cells.size(); ++i) out += (i == 0 ? "" : ",") + cells[i];
    out += "\n";
  }
  return out;
}

// How the human-readable formats differ.
struct HumanStyle {
  std::function<std::string(const std::string&)> escape;
  std::string plus_minus;  ///< between mean and sd
  std::string percent;
  std::string missing;     ///< a statistic without runs
};

const HumanStyle kMarkdownStyle{[](const std::string& text) {
                                  std::string out;
                                  for (char c : text) out += c == '|' ? std::string("\\|") : std::string(1, c);
                                  return out;
                                },
                                " ± ", "%", "–"};

const HumanStyle kLatexStyle{[](const std::string& text) {
                               std::string out;
                               for (char c : text) {
                                 switch (c) {
                                   case '\\': out += "\\textbackslash{}"; break;
                                   case '~': out += "\\textasciitilde{}"; break;
                                   case '^': out += "\\textasciicircum{}"; break;
                                   case '&': case '%': case '$': case '#': case '_': case '{': case '}':
                                     out += '\\';
                                     out += c;
                                     break;
                                   default: out += c;
                                 }
                               }
                               return out;
                             },
                             " $\\pm$ ", "\\%", "--"};

// A mean with its sd and interval as the cell format asks (`ci` empty: one value); `decimals` for all three.
std::string spread_text(double mean, double sd, const std::optional<Interval>& ci, int decimals,
                        const CellFormat& format, const HumanStyle& style) {
  std::string text = fixed(mean, decimals);
  // One value has no sd to speak of (nor an interval): the mean alone.
  if (shows_sd(format.stat) && ci) text += style.plus_minus + fixed(sd, decimals);
  if (shows_ci(format.stat) && ci) text += " [" + fixed(ci->low, decimals) + ", " + fixed(ci->high, decimals) + "]";
  return text;
}

// Header and body cells of the summary table, shared by Markdown and LaTeX.
std::vector<std::vector<std::string>> human_cells(const SweepTable& table, const HumanStyle& style,
                                                  const CellFormat& format) {
  std::vector<std::string> header{"Scene"};
  for (const std::string& axis : table.axes) header.push_back(field_heading(axis));
  for (const char* h : {"Runs", "Success", "Reached runs"}) header.emplace_back(h);
  for (const SpreadColumn& column : kSpreadColumns) header.emplace_back(column.header);
  for (const char* h : {"Collisions", "Min clearance (m), closest run", "Replanning (ms, median)", "Failed"}) {
    header.emplace_back(h);
  }
  std::vector<std::vector<std::string>> cells{header};
  for (auto& h : cells.front()) h = style.escape(h);

  for (const TableRow& row : table.rows) {
    std::vector<std::string> line{style.escape(row.scene)};
    for (const auto& value : row.params) line.push_back(value.is_null() ? style.missing : style.escape(value_label(value)));
    line.push_back(std::to_string(row.runs) + (row.identical ? " " + std::string(kIdenticalNote) : ""));
    line.push_back(fixed(100.0 * row.success_rate, 0) + style.percent);
    line.push_back(std::to_string(row.reached));
    for (const SpreadColumn& column : kSpreadColumns) {
      const std::optional<MeanSd>& s = row.*column.member;
      if (!s) {
        line.push_back(style.missing);
      } else if (row.identical) {
        line.push_back(fixed(s->mean, column.decimals));  // one run repeated: no spread to speak of
      } else {
        line.push_back(spread_text(s->mean, s->sd, s->ci95, column.decimals, format, style));
      }
    }
    line.push_back(std::to_string(row.collisions));
    line.push_back(row.min_clearance_m ? fixed(*row.min_clearance_m, 3) : style.missing);
    line.push_back(row.replan_ms_median ? fixed(*row.replan_ms_median, 2) : style.missing);
    line.push_back(std::to_string(row.failed));
    cells.push_back(line);
  }
  return cells;
}

// A Markdown table: the first row is the header; the first column text (left), the others numbers (right).
std::string markdown_grid(const std::vector<std::vector<std::string>>& cells) {
  std::string out;
  for (std::size_t r = 0; r < cells.size(); ++r) {
    for (const std::string& cell : cells[r]) out += "| " + cell + " ";
    out += "|\n";
    if (r == 0) {
      out += "| --- ";
      for (std::size_t c = 1; c < cells[r].size(); ++c) out += "| ---: ";
      out += "|\n";
    }
  }
  return out;
}

// A booktabs tabular; `heading` (complete lines) goes above the first row, which is the header.
std::string latex_tabular(const std::vector<std::vector<std::string>>& cells, const std::string& heading = "") {
  std::string out = "% needs \\usepackage{booktabs}\n\\begin{tabular}{l" +
                    std::string(cells.front().size() - 1, 'r') + "}\n\\toprule\n" + heading;
  for (std::size_t r = 0; r < cells.size(); ++r) {
    for (std::size_t c = 0; c < cells[r].size(); ++c) out += (c == 0 ? "" : " & ") + cells[r][c];
    out += " \\\\\n";
    if (r == 0) out += "\\midrule\n";
  }
  return out + "\\bottomrule\n\\end{tabular}\n";
}

// LaTeX headings on two lines at their last ", " (the metric, then the runs it is over), in a nested
// tabular (no package needed), so the columns are not as wide as the headings.
std::vector<std::vector<std::string>> two_line_headings(std::vector<std::vector<std::string>> cells) {
  for (std::size_t c = 1; c < cells.front().size(); ++c) {
    std::string& h = cells.front()[c];
    // The last ", " outside parentheses ("Replanning (ms, median)" stays whole).
    std::size_t comma = std::string::npos;
    int depth = 0;
    for (std::size_t i = 0; i + 1 < h.size(); ++i) {
      depth += h[i] == '(' ? 1 : h[i] == ')' ? -1 : 0;
      if (depth == 0 && h[i] == ',' && h[i + 1] == ' ') comma = i;
    }
    if (comma != std::string::npos) {
      h = "\\begin{tabular}[b]{@{}c@{}}" + h.substr(0, comma + 1) + "\\\\" + h.substr(comma + 2) + "\\end{tabular}";
    }
  }
  return cells;
}

// Label of a row or column value; `missing` for null (a run without that axis or planner).
std::string value_text(const nlohmann::json& value, const std::string& missing) {
  return value.is_null() ? missing : value_label(value);
}

// Decimals showing three significant digits of a metric's largest |mean| (0 to 3).
int metric_decimals(const MetricTable& table, std::size_t metric) {
  double largest = 0.0;
  for (const auto& row : table.cells) {
    for (const MetricCell& cell : row) {
      if (cell.runs > 0 && cell.metrics[metric]) largest = std::max(largest, std::abs(cell.metrics[metric]->mean));
    }
  }
  return largest > 0.0 ? std::clamp(2 - static_cast<int>(std::floor(std::log10(largest))), 0, 3) : 0;
}

std::string human_cell(const MetricCell& cell, std::size_t metric, MetricKind kind, int decimals,
                       const HumanStyle& style, const CellFormat& format) {
  if (cell.runs == 0) return style.missing;
  const std::optional<Summary>& s = cell.metrics[metric];
  const int n = s ? s->n : 0;
  // The counts after the statistic: n when asked for, failed runs always.
  std::vector<std::string> notes;
  if (format.with_n) notes.push_back("n=" + std::to_string(n));
  if (cell.failed > 0) notes.push_back(std::to_string(cell.failed) + " failed");
  if (cell.identical) {
    // One run repeated: its value, and no spread or interval, which would pretend to a sample.
    notes.assign(1, format.with_n ? "n=" + (n == cell.runs ? "" : std::to_string(n) + " of ") +
                                        std::to_string(cell.runs) + " " + std::string(kIdenticalNote)
                                  : std::string("identical runs"));
  }
  std::string counts;
  for (std::size_t i = 0; i < notes.size(); ++i) counts += (i == 0 ? " (" : ", ") + notes[i];
  if (!notes.empty()) counts += ")";
  if (!s) return style.missing + counts;
  if (cell.identical) {
    return (kind == MetricKind::rate ? fixed(100.0 * s->mean, 0) + style.percent : fixed(s->mean, decimals)) + counts;
  }
  if (kind == MetricKind::rate) {
    // A rate has no sd worth printing: the rate, and its Wilson interval when intervals are asked for.
    std::string text = fixed(100.0 * s->mean, 0) + style.percent;
    if (shows_ci(format.stat) && s->ci95) {
      text += " [" + fixed(100.0 * s->ci95->low, 0) + ", " + fixed(100.0 * s->ci95->high, 0) + "]";
    }
    return text + counts;
  }
  return spread_text(s->mean, s->sd, s->ci95, decimals, format, style) + counts;
}

std::string capitalized(std::string text) {
  if (!text.empty()) text.front() = static_cast<char>(std::toupper(static_cast<unsigned char>(text.front())));
  return text;
}

// Header and body cells of a metric table; `grouped_header`: column values above (LaTeX), not in each header cell.
std::vector<std::vector<std::string>> metric_cells(const MetricTable& table, const HumanStyle& style,
                                                   bool grouped_header, const CellFormat& format) {
  const std::size_t metrics = table.request.metrics.size();
  std::vector<std::string> header{style.escape(field_heading(table.request.rows))};
  for (const nlohmann::json& col : table.cols) {
    for (const std::string& metric : table.request.metrics) {
      const std::string label = capitalized(metric_heading(metric));
      header.push_back(style.escape(table.request.cols.empty() || grouped_header
                                        ? label
                                        : field_value_heading(table.request.cols, col) + ": " + label));
    }
  }
  std::vector<int> decimals;
  for (std::size_t m = 0; m < metrics; ++m) decimals.push_back(metric_decimals(table, m));
  std::vector<std::vector<std::string>> cells{header};
  for (std::size_t r = 0; r < table.rows.size(); ++r) {
    std::vector<std::string> line{style.escape(value_text(table.rows[r], style.missing))};
    for (const MetricCell& cell : table.cells[r]) {
      for (std::size_t m = 0; m < metrics; ++m) {
        line.push_back(human_cell(cell, m, table.kinds[m], decimals[m], style, format));
      }
    }
    cells.push_back(line);
  }
  return cells;
}

std::string metric_csv(const MetricTable& table) {
  const bool has_cols = !table.request.cols.empty();
  std::string out = csv_field(table.request.rows) + (has_cols ? "," + csv_field(table.request.cols) : "") +
                    ",metric,over,kind,runs,failed,n,mean,sd,ci95_low,ci95_high,identical\n";
  for (std::size_t r = 0; r < table.rows.size(); ++r) {
    for (std::size_t c = 0; c < table.cols.size(); ++c) {
      const MetricCell& cell = table.cells[r][c];
      if (cell.runs == 0) continue;
      for (std::size_t m = 0; m < table.request.metrics.size(); ++m) {
        const std::optional<Summary>& s = cell.metrics[m];
        // Appended piece by piece: GCC 12 warns (-Wrestrict, wrongly) on "," + a temporary string.
        const auto field = [&out](const std::string& text) {
          out += ',';
          out += text;
        };
        out += csv_field(value_text(table.rows[r], ""));
        if (has_cols) field(csv_field(value_text(table.cols[c], "")));
        const MetricName name = split_metric(table.request.metrics[m]);
        field(csv_field(name.base));
        out += name.reached_only ? ",reached" : ",all";
        out += table.kinds[m] == MetricKind::rate ? ",rate," : ",mean,";
        out += std::to_string(cell.runs);
        field(std::to_string(cell.failed));
        field(std::to_string(s ? s->n : 0));
        field(s ? exact(s->mean) : "");
        field(s && !cell.identical ? exact(s->sd) : "");
        field(s && s->ci95 ? exact(s->ci95->low) : "");
        field(s && s->ci95 ? exact(s->ci95->high) : "");
        out += cell.identical ? ",true\n" : ",false\n";
      }
    }
  }
  return out;
}

std::string metric_latex(const MetricTable& table, const CellFormat& format) {
  std::string heading;
  if (!table.request.cols.empty()) {
    // One \multicolumn group per column value over its metrics, headed by the field and the
    // value, a rule under each group (trimmed, so neighbouring groups' rules stay apart).
    const std::size_t width = table.request.metrics.size();
    std::string rules;
    for (std::size_t c = 0; c < table.cols.size(); ++c) {
      heading += " & \\multicolumn{" + std::to_string(width) + "}{c}{" +
                 kLatexStyle.escape(field_value_heading(table.request.cols, table.cols[c])) + "}";
      const std::size_t first = 2 + c * width;
      rules += (c == 0 ? "" : " ") + std::string("\\cmidrule(lr){") + std::to_string(first) + "-" +
               std::to_string(first + width - 1) + "}";
    }
    heading += " \\\\\n" + rules + "\n";
  }
  return latex_tabular(two_line_headings(metric_cells(table, kLatexStyle, true, format)), heading);
}

}  // namespace

std::span<const std::string_view> table_stat_columns() { return kStatColumns; }

std::span<const std::pair<std::string_view, CellStat>> cell_stat_names() { return kCellStatNames; }

std::string format_table(const SweepTable& table, TableFormat format, const CellFormat& cell) {
  switch (format) {
    case TableFormat::markdown: return markdown_grid(human_cells(table, kMarkdownStyle, cell));
    case TableFormat::csv: return csv(table);
    case TableFormat::latex: return latex_tabular(two_line_headings(human_cells(table, kLatexStyle, cell)));
  }
  return {};
}

namespace {

// The request's form, and its fields against the axes when they are known.
std::vector<std::string> request_fields(const TableRequest& request, const TableLayout& layout, bool check_axes) {
  if (check_axes) check_field(request.rows, layout.axes, request.file, request.rows_at);
  std::vector<std::string> fields{request.rows};
  if (!request.cols.empty()) {
    if (check_axes) check_field(request.cols, layout.axes, request.file, request.cols_at);
    if (request.cols == request.rows) {
      throw InputError(request.file, request.cols_at, "a field other than the rows' (\"" + request.rows + "\")");
    }
    fields.push_back(request.cols);
  }
  if (request.metrics.empty()) throw InputError(request.file, request.metrics_at, "at least one metric");
  for (std::size_t m = 0; m < request.metrics.size(); ++m) {
    const std::string& metric = request.metrics[m];
    if (std::find(request.metrics.begin(), request.metrics.begin() + m, metric) != request.metrics.begin() + m) {
      throw InputError(request.file, request.metrics_at, "each metric once (\"" + metric + "\" appears twice)");
    }
  }
  return fields;
}

// The runs of one cell, a run at a time.
struct CellFold {
  int runs = 0, failed = 0;
  IdenticalRuns identical;
  std::vector<RunningStats> metrics;  // per requested metric: its values (rates: 1 and 0)
};

}  // namespace

struct MetricTableBuilder::Impl {
  const TableLayout& layout;
  TableRequest request;
  RunGroups groups;
  MetricCatalog catalog;
  std::vector<CellFold> cells;  // per group
};

MetricTableBuilder::MetricTableBuilder(const TableLayout& layout, TableRequest request)
    : impl_(new Impl{layout, request, RunGroups(layout, request_fields(request, layout, !layout.axes_from_runs)), {},
                     {}}) {
  MetricCatalog none;  // the metrics' names alone: whether they are metrics is known once runs are read
  for (const std::string& metric : impl_->request.metrics) none.check(metric, request.file, request.metrics_at);
}
MetricTableBuilder::~MetricTableBuilder() = default;
MetricTableBuilder::MetricTableBuilder(MetricTableBuilder&&) noexcept = default;
MetricTableBuilder& MetricTableBuilder::operator=(MetricTableBuilder&&) noexcept = default;

void MetricTableBuilder::add(const RunResult& run, std::size_t index) {
  Impl& d = *impl_;
  d.catalog.add(run);
  const std::size_t g = d.groups.add(run, index);
  if (g == d.cells.size()) d.cells.push_back({0, 0, {}, std::vector<RunningStats>(d.request.metrics.size())});
  CellFold& cell = d.cells[g];
  ++cell.runs;
  if (!run.completed) ++cell.failed;
  cell.identical.add(run);
  for (std::size_t m = 0; m < d.request.metrics.size(); ++m) {
    if (const auto v = metric_value(run, d.request.metrics[m])) cell.metrics[m].add(*v);
  }
}

MetricTable MetricTableBuilder::finish() const {
  const Impl& d = *impl_;
  const TableRequest& request = d.request;
  request_fields(request, d.layout, true);
  MetricTable table{d.layout.name, request, {}, {}, {}, {}};
  for (const std::string& metric : request.metrics) {
    table.kinds.push_back(d.catalog.check(metric, request.file, request.metrics_at));
  }
  const std::vector<std::size_t> order = d.groups.order();
  // Row and column values in the order of the groups: the sweep's expansion order.
  const auto col_of = [&](std::size_t g) {
    return d.groups.key(g).size() > 1 ? d.groups.key(g)[1] : nlohmann::json();
  };
  for (std::size_t g : order) {
    index_in_order(table.rows, d.groups.key(g)[0]);
    index_in_order(table.cols, col_of(g));
  }
  table.cells.assign(table.rows.size(), std::vector<MetricCell>(table.cols.size()));
  for (std::size_t g : order) {
    const CellFold& fold = d.cells[g];
    MetricCell& cell = table.cells[index_in_order(table.rows, d.groups.key(g)[0])][index_in_order(table.cols, col_of(g))];
    cell.runs = fold.runs;
    cell.failed = fold.failed;
    cell.identical = fold.identical.identical();
    for (std::size_t m = 0; m < request.metrics.size(); ++m) {
      const RunningStats& values = fold.metrics[m];
      std::optional<Summary> s;
      if (values.count() > 0) {
        s = table.kinds[m] == MetricKind::number ? values.values(metric_support(request.metrics[m])) : values.rate();
      }
      // Identical runs are one value, not a sample: no interval (a Wilson interval would still be wide).
      if (s && cell.identical) s->ci95.reset();
      cell.metrics.push_back(s);
    }
  }
  return table;
}

MetricTable tabulate(const std::vector<RunResult>& runs, const TableLayout& layout, const TableRequest& request) {
  MetricTableBuilder builder(layout, request);
  for (std::size_t i = 0; i < runs.size(); ++i) builder.add(runs[i], i);
  return builder.finish();
}

std::string format_metric_table(const MetricTable& table, TableFormat format, const CellFormat& cell) {
  switch (format) {
    case TableFormat::markdown: return markdown_grid(metric_cells(table, kMarkdownStyle, false, cell));
    case TableFormat::csv: return metric_csv(table);
    case TableFormat::latex: return metric_latex(table, cell);
  }
  return {};
}

QuantityName quantity_name(const std::string& name) {
  // Unit suffixes of run.json's metric and parameter names, wherever they stand after the first word.
  static constexpr std::array<std::pair<std::string_view, std::string_view>, 14> kUnits{{
      {"m", "m"}, {"s", "s"}, {"ms", "ms"}, {"mps", "m/s"}, {"mps2", "m/s^2"}, {"rad", "rad"},
      {"radps", "rad/s"}, {"deg", "deg"}, {"degps", "deg/s"}, {"hz", "Hz"}, {"px", "px"}, {"kg", "kg"},
      {"pct", "%"}, {"percent", "%"}}};
  QuantityName q;
  std::size_t start = 0;
  for (bool first = true; start <= name.size(); first = false) {
    const std::size_t end = std::min(name.find('_', start), name.size());
    const std::string_view word(name.data() + start, end - start);
    const auto u = std::find_if(kUnits.begin(), kUnits.end(), [&](const auto& entry) { return entry.first == word; });
    if (!first && q.unit.empty() && u != kUnits.end()) {
      q.unit = u->second;
    } else if (!word.empty()) {
      (q.words += q.words.empty() ? "" : " ") += word;
    }
    start = end + 1;
  }
  return q;
}

std::string quantity_label(const std::string& name) {
  const QuantityName q = quantity_name(name);
  const std::string words = capitalized(q.words);
  return q.unit.empty() ? words : words + " (" + q.unit + ")";
}

std::string metric_label(const std::string& metric_text) {
  // A vehicle's metric: the metric's label naming the vehicle, before the unit ("Path length of drone (m)").
  if (const VehicleMetricName v = split_vehicle_metric(metric_text); !v.vehicle.empty()) {
    const MetricName name = split_metric(v.metric);
    if (name.reached_only) return metric_label(v.vehicle + "." + name.base) + ", reached runs";
    std::string label = metric_label(name.base);
    const std::size_t unit = label.size() > 1 && label.back() == ')' ? label.rfind(" (") : std::string::npos;
    if (unit == std::string::npos) return label + " of " + v.vehicle;
    return label.substr(0, unit) + " of " + v.vehicle + label.substr(unit);
  }
  const MetricName name = split_metric(metric_text);
  if (name.reached_only) return metric_label(name.base) + ", reached runs";
  const std::string& metric = name.base;
  if (metric == "success" || metric == "outcome") return "Success rate (%)";
  if (metric == "path_ratio") return "Normalized path length";
  return quantity_label(metric);
}

std::string metric_heading(const std::string& metric) {
  const MetricName name = split_metric(split_vehicle_metric(metric).metric);
  if (name.reached_only || name.base == "success" || name.base == "outcome") return metric_label(metric);
  return metric_label(metric) + ", all runs";
}

std::string field_heading(const std::string& field) { return quantity_label(field); }

std::string field_value_heading(const std::string& field, const nlohmann::json& value) {
  const QuantityName q = quantity_name(field);
  if (value.is_null()) return capitalized(q.words) + " = -";
  return capitalized(q.words) + " = " + value_label(value) + (q.unit.empty() ? "" : " " + q.unit);
}

}  // namespace campo
