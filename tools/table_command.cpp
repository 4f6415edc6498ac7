#include <filesystem>
#include <iostream>
#include <map>
#include <string>

#include "sweep/chart.hpp"
#include "sweep/results.hpp"
#include "sweep/table.hpp"
#include "tools/commands.hpp"

namespace campo::cli {

namespace {

namespace fs = std::filesystem;

struct TableOptions {
  std::string dir;
  TableFormat format = TableFormat::markdown;
  std::string chart;  ///< empty: DIR/chart.png
  bool no_chart = false;
};

int run_table(const TableOptions& o) {
  const fs::path dir = o.dir;
  const ResultsFile results = read_results(dir / "results.jsonl");
  for (const std::string& warning : results.warnings) std::cerr << "warning: " << warning << "\n";
  const SweepTable table = aggregate(results.runs, table_layout(dir, results.runs));
  std::cout << format_table(table, o.format);
  if (o.no_chart) return kOk;
  if (!chartable(table)) {
    std::cerr << "no chart: it needs exactly one axis with numeric values\n";
    return kOk;
  }
  const fs::path chart = o.chart.empty() ? dir / "chart.png" : fs::path(o.chart);
  write_sweep_chart(table, chart);
  std::cerr << "wrote " << chart.string() << "\n";
  return kOk;
}

}  // namespace

Command add_table(CLI::App& app) {
  auto o = std::make_shared<TableOptions>();
  app.add_option("dir", o->dir, "Sweep output directory (holding results.jsonl, from campo sweep)")->required();
  app.add_option("--format", o->format, "Table format: markdown, csv or latex (default: markdown)")
      ->transform(CLI::CheckedTransformer(
          std::map<std::string, TableFormat>{
              {"markdown", TableFormat::markdown}, {"csv", TableFormat::csv}, {"latex", TableFormat::latex}},
          CLI::ignore_case));
  auto* chart = app.add_option("--chart", o->chart, "Where to write the chart PNG (default: DIR/chart.png)");
  app.add_flag("--no-chart", o->no_chart, "Do not draw the chart")->excludes(chart);
  app.footer(
      "One row per scene and axis values, over the seeds: runs, success rate (outcome reached), waypoints\n"
      "reached and discarded, path length, normalized path length (over the nominal route) and\n"
      "simulated time as mean and sample standard deviation over the completed runs, total collisions,\n"
      "the median of the runs' median replanning times, and the runs that failed. Rows follow the\n"
      "sweep's expansion order. CSV has one header line of snake_case column names.\n"
      "With exactly one numeric axis, also draws DIR/chart.png: normalized path length (mean +/- sd)\n"
      "and success rate against the axis, one series per scene.\n"
      "Example: campo table out/resolution --format csv > resolution.csv");
  return [o] { return run_table(*o); };
}

}  // namespace campo::cli
