#include "sweep/table.hpp"

#include <array>
#include <cctype>
#include <charconv>
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
constexpr std::array kSpreadColumns{
    SpreadColumn{"waypoints_reached", "Waypoints reached", 1, &TableRow::waypoints_reached},
    SpreadColumn{"waypoints_discarded", "Discarded", 1, &TableRow::waypoints_discarded},
    SpreadColumn{"path_length_m", "Path length (m)", 2, &TableRow::path_length_m},
    SpreadColumn{"path_ratio", "Normalized length", 3, &TableRow::path_ratio},
    SpreadColumn{"time_s", "Time (s)", 1, &TableRow::time_s},
};

constexpr auto kStatColumns = std::to_array<std::string_view>({
    "runs", "success_rate",
    "waypoints_reached_mean", "waypoints_reached_sd", "waypoints_discarded_mean", "waypoints_discarded_sd",
    "path_length_m_mean", "path_length_m_sd", "path_ratio_mean", "path_ratio_sd", "time_s_mean", "time_s_sd",
    "collisions", "replan_ms_median", "replan_ms_max", "failed"});

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
    for (const SpreadColumn& column : kSpreadColumns) {
      const std::optional<MeanSd>& s = row.*column.member;
      cells.push_back(s ? exact(s->mean) : "");
      cells.push_back(s ? exact(s->sd) : "");
    }
    cells.push_back(std::to_string(row.collisions));
    cells.push_back(optional(row.replan_ms_median));
    cells.push_back(optional(row.replan_ms_max));
    cells.push_back(std::to_string(row.failed));
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

// Header and body cells shared by Markdown and LaTeX.
std::vector<std::vector<std::string>> human_cells(const SweepTable& table, const HumanStyle& style) {
  std::vector<std::string> header{"Scene"};
  for (std::string axis : table.axes) {
    for (char& c : axis) c = c == '_' ? ' ' : c;
    axis.front() = static_cast<char>(std::toupper(static_cast<unsigned char>(axis.front())));
    header.push_back(axis);
  }
  for (const char* h : {"Runs", "Success"}) header.emplace_back(h);
  for (const SpreadColumn& column : kSpreadColumns) header.emplace_back(column.header);
  for (const char* h : {"Collisions", "Replanning (ms, median)", "Failed"}) header.emplace_back(h);
  std::vector<std::vector<std::string>> cells{header};
  for (auto& h : cells.front()) h = style.escape(h);

  for (const TableRow& row : table.rows) {
    std::vector<std::string> line{style.escape(row.scene)};
    for (const auto& value : row.params) line.push_back(value.is_null() ? style.missing : style.escape(value_label(value)));
    line.push_back(std::to_string(row.runs));
    line.push_back(fixed(100.0 * row.success_rate, 0) + style.percent);
    for (const SpreadColumn& column : kSpreadColumns) {
      const std::optional<MeanSd>& s = row.*column.member;
      line.push_back(s ? fixed(s->mean, column.decimals) + style.plus_minus + fixed(s->sd, column.decimals)
                       : style.missing);
    }
    line.push_back(std::to_string(row.collisions));
    line.push_back(row.replan_ms_median ? fixed(*row.replan_ms_median, 2) : style.missing);
    line.push_back(std::to_string(row.failed));
    cells.push_back(line);
  }
  return cells;
}

std::string markdown(const SweepTable& table) {
  const HumanStyle style{[](const std::string& text) {
                           std::string out;
                           for (char c : text) out += c == '|' ? std::string("\\|") : std::string(1, c);
                           return out;
                         },
                         " ± ", "%", "–"};
  const auto cells = human_cells(table, style);
  std::string out;
  for (std::size_t r = 0; r < cells.size(); ++r) {
    for (const std::string& cell : cells[r]) out += "| " + cell + " ";
    out += "|\n";
    if (r == 0) {
      // Text columns left, numbers right.
      out += "| --- ";
      for (std::size_t c = 1; c < cells[r].size(); ++c) out += "| ---: ";
      out += "|\n";
    }
  }
  return out;
}

std::string latex(const SweepTable& table) {
  const HumanStyle style{[](const std::string& text) {
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
  const auto cells = human_cells(table, style);
  std::string out = "\\begin{tabular}{l" + std::string(cells.front().size() - 1, 'r') + "}\n\\hline\n";
  for (std::size_t r = 0; r < cells.size(); ++r) {
    for (std::size_t c = 0; c < cells[r].size(); ++c) out += (c == 0 ? "" : " & ") + cells[r][c];
    out += " \\\\\n";
    if (r == 0) out += "\\hline\n";
  }
  return out + "\\hline\n\\end{tabular}\n";
}

}  // namespace

std::span<const std::string_view> table_stat_columns() { return kStatColumns; }

std::string format_table(const SweepTable& table, TableFormat format) {
  switch (format) {
    case TableFormat::markdown: return markdown(table);
    case TableFormat::csv: return csv(table);
    case TableFormat::latex: return latex(table);
  }
  return {};
}

}  // namespace campo
