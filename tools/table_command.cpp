#include <cctype>
#include <filesystem>
#include <iostream>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/output_dir.hpp"
#include "sweep/chart.hpp"
#include "sweep/results.hpp"
#include "sweep/table.hpp"
#include "tools/commands.hpp"
#include "tools/path_options.hpp"

namespace campo::cli {

namespace {

namespace fs = std::filesystem;

struct TableOptions {
  std::string dir;
  TableFormat format = TableFormat::markdown;
  CellFormat cell;
  std::string rows, cols;            ///< fields; empty: the spec's table, else the summary
  std::vector<std::string> metrics;
  std::string vehicle;               ///< empty: the runs' own metrics (the fleet's with several vehicles)
  bool summary = false;              ///< the summary table even when the spec has a table
  std::string chart;                 ///< empty: DIR/chart.png
  bool no_chart = false;
  std::vector<figure::FigureFormat> formats{figure::FigureFormat::png};  ///< of the chart
};

// The default table of runs of several vehicles: the fleet's success (every vehicle reached), makespan,
// collisions and least distance between vehicles, and each vehicle's path ratio: a row per value of the
// sweep's one axis (a column group per scene when there are several), else a row per scene.
TableRequest fleet_request(const TableLayout& layout, const std::vector<std::string>& vehicles, bool scenes) {
  const bool one_axis = layout.axes.size() == 1;
  TableRequest request{.rows = one_axis ? layout.axes.front() : std::string("scene"),
                       .cols = one_axis && scenes ? std::string("scene") : std::string(),
                       .metrics = {"success", "makespan_s", "collisions", "min_vehicle_distance_m"}};
  for (const std::string& alias : vehicles) request.metrics.push_back(alias + ".path_ratio");
  request.file = "the default table of several vehicles";
  return request;
}

int run_table(const TableOptions& o) {
  const fs::path dir = o.dir;
  // A chart asked for must be writable before any work; the default one only when the sweep has a chart.
  if (!o.no_chart && !o.chart.empty()) {
    for (const fs::path& file : figure::figure_files(o.chart, o.formats)) check_output_file(file, "--chart");
  }
  TableLayout layout = table_layout(dir);
  // Which table: the options', else the spec's, else the summary. Checked before anything is written.
  std::optional<TableRequest> request;
  if (!o.rows.empty()) {
    request = TableRequest{.rows = o.rows, .cols = o.cols, .metrics = o.metrics};
  } else if (!o.summary) {
    request = layout.table;
  }
  // --vehicle: plain metric names are that vehicle's (each run is seen from it: vehicle_run).
  if (request && !o.vehicle.empty()) {
    for (std::string& metric : request->metrics) metric = vehicle_metric_name(metric, o.vehicle);
  }
  MetricCatalog catalog;  // which vehicles the runs have
  // The results a line at a time, each run folded into its row and cell: memory grows with the table.
  const bool axes_from_runs = layout.axes_from_runs;
  std::optional<SummaryBuilder> summary_rows;
  std::optional<MetricTableBuilder> metric_cells;
  std::vector<std::string> warnings;
  for_each_result(
      dir / "results.jsonl", warnings,
      [&] {
        if (axes_from_runs) layout.axes.clear();
        summary_rows.emplace(layout);
        if (request) metric_cells.emplace(layout, *request);
        catalog = {};
      },
      [&](const RunResult& run, std::size_t index) {
        add_axes(layout, run);
        // --vehicle: each run seen from that vehicle (plain names are its metrics).
        std::optional<RunResult> seen;
        if (!o.vehicle.empty()) seen = vehicle_run(run, o.vehicle, "command line", "--vehicle");
        const RunResult& r = seen ? *seen : run;
        summary_rows->add(r, index);
        if (metric_cells) metric_cells->add(r, index);
        catalog.add(run);
      });
  for (const std::string& warning : warnings) std::cerr << "warning: " << warning << "\n";
  const SweepTable summary = summary_rows->finish();
  // Runs of several vehicles and no table asked for: the fleet's table, from a second reading.
  const bool fleet = !catalog.vehicles().empty() && o.vehicle.empty();
  if (fleet && !request && !o.summary) {
    bool scenes = false;  // several scenes
    for (const TableRow& row : summary.rows) scenes = scenes || row.scene != summary.rows.front().scene;
    request = fleet_request(layout, catalog.vehicles(), scenes);
    std::vector<std::string> ignored;  // the first reading reported them
    for_each_result(
        dir / "results.jsonl", ignored, [&] { metric_cells.emplace(layout, *request); },
        [&](const RunResult& run, std::size_t index) { metric_cells->add(run, index); });
    if (layout.axes.size() > 1) {
      std::cerr << "note: each scene's runs over every value of the axes; choose rows and columns with --rows and "
                   "--cols\n";
    }
  }
  const std::string table = request ? format_metric_table(metric_cells->finish(), o.format, o.cell)
                                    : format_table(summary, o.format, o.cell);
  // The chart first: a chart that cannot be written is an error (exit 2) with nothing printed before it.
  std::vector<fs::path> charts;
  // The summary chart is of one vehicle's path ratio: with several vehicles, of --vehicle's only.
  if (!o.no_chart && chartable(summary) && !fleet) {
    charts = draw_sweep_chart(summary).write(o.chart.empty() ? dir / "chart.png" : fs::path(o.chart),
                          o.formats);
  }
  std::cout << table << std::flush;
  for (const fs::path& chart : charts) std::cerr << "wrote " << chart.string() << "\n";
  if (charts.empty() && !o.no_chart) {
    std::cerr << (fleet ? "no chart: the runs have several vehicles; chart one with --vehicle ALIAS (campo plot draws "
                          "any metric, e.g. --y ALIAS.path_ratio)\n"
                        : "no chart: it needs exactly one axis with numeric values (campo plot draws any)\n");
  }
  return kOk;
}

}  // namespace

Command add_table(CLI::App& app) {
  auto o = std::make_shared<TableOptions>();
  app.add_option("dir", o->dir, "Sweep output directory (holding results.jsonl, from campo sweep)")
      ->required()
      ->check(input_path());
  // The choices, in the help and in errors, by name (not a transformer's map "csv->1").
  app.add_option("--format", o->format,
                 "Table format: markdown (or md), csv or latex (a booktabs tabular; default: markdown)")
      ->transform(named_choice<TableFormat>({{"markdown", TableFormat::markdown},
                                             {"md", TableFormat::markdown},
                                             {"csv", TableFormat::csv},
                                             {"latex", TableFormat::latex}}))
      ->option_text("markdown|csv|latex");
  std::vector<std::pair<std::string, CellStat>> cell_stats;
  for (const auto& [name, stat] : cell_stat_names()) cell_stats.emplace_back(name, stat);
  app.add_option("--cell", o->cell.stat,
                 "What a Markdown or LaTeX cell shows: mean, mean-sd (mean ± sd; default), mean-ci (mean and "
                 "95% confidence interval) or mean-sd-ci; a rate shows its Wilson interval with -ci only. CSV "
                 "always has every statistic in its own column")
      ->transform(named_choice(cell_stats))
      ->option_text("mean|mean-sd|mean-ci|mean-sd-ci");
  app.add_flag("--with-n", o->cell.with_n, "Also print each cell's number of runs: \"(n=5)\"");
  auto* rows = app.add_option("--rows", o->rows, "Field giving the rows: scene, planner, seed or an axis name");
  auto* cols = app.add_option("--cols", o->cols, "Field giving the column groups (default: one group)")->needs(rows);
  auto* metrics = app.add_option("--metrics", o->metrics,
                                 "Metrics, comma-separated: success (rate of outcome reached) or keys of run.json's "
                                 "metrics (path_ratio, sim_time_s ...), over all completed runs, or with @reached "
                                 "over the runs that reached their goal (path_ratio@reached); with several vehicles "
                                 "the plain names are the run's (all_reached, makespan_s, collisions ...) and "
                                 "ALIAS.METRIC a vehicle's (drone.path_ratio, rover.success, drone.path_ratio@reached)")
                      ->delimiter(',')
                      ->needs(rows);
  rows->needs(metrics);
  app.add_option("--vehicle", o->vehicle,
                 "In runs of several vehicles, the vehicle whose metrics the plain metric names, success and the "
                 "summary table mean (ALIAS.METRIC still names any vehicle's); each completed run must have it")
      ->type_name("ALIAS");
  app.add_flag("--summary", o->summary, "The summary table, even when the sweep's spec has a \"table\"")
      ->excludes(rows)
      ->excludes(cols);
  auto* chart = app.add_option("--chart", o->chart,
                               "Where to write the chart (default: DIR/chart.png); its extension (.png, .pdf or "
                               ".svg) is replaced by each --figure-format's, any other name gets the format's "
                               "extension appended")
                    ->check(input_path());  // an empty path is refused, not taken for the default
  auto* formats = add_figure_format_option(app, &o->formats);
  app.add_flag("--no-chart", o->no_chart, "Do not draw the chart")->excludes(chart)->excludes(formats);
  app.footer(
      "With --rows FIELD [--cols FIELD] --metrics M1,M2 (or the spec's \"table\"): one row per value of\n"
      "the rows field, one column group per value of the cols field (headed \"Resolution = 64\"), and in\n"
      "each cell every metric over the cell's runs, as --cell says: the mean, sample sd and 95%\n"
      "confidence interval of the mean of numbers, over every completed run or, for METRIC@reached,\n"
      "over the runs that reached their goal; the rate with its 95% Wilson interval for success and\n"
      "boolean metrics; the failed runs, and n with --with-n. The interval of a metric that cannot be\n"
      "negative (lengths, times, counts, path_ratio) is the t interval of log(mean) (delta method),\n"
      "never below 0; of any other, the Student t interval (docs/sweeps.md). A cell whose runs are\n"
      "identical (same metrics but wall-clock times, same trajectory) shows the value and \"identical\n"
      "runs\" instead of a spread and interval.\n"
      "LaTeX is a booktabs tabular (\\toprule, \\midrule, \\cmidrule, \\bottomrule: \\usepackage{booktabs}).\n"
      "CSV is tidy: one line per row, column and metric (metric, over: all|reached, runs, failed, n,\n"
      "mean, sd, ci95_low, ci95_high, identical).\n"
      "Otherwise the summary table: one row per scene and axis values, over the seeds: runs, success\n"
      "rate, reached runs, waypoints reached and discarded, path length, normalized path length and\n"
      "simulated time (mean and sd over the completed runs, and the last three over the reached runs),\n"
      "total collisions, the median of the runs' median replanning times, the runs that failed, and\n"
      "whether the runs are identical.\n"
      "Runs of several vehicles (docs/sweeps.md): without --rows, a spec table or --vehicle, the table\n"
      "is the fleet's, a row per value of the sweep's one axis (else per scene): success (every vehicle\n"
      "reached), makespan_s, collisions, min_vehicle_distance_m and each vehicle's ALIAS.path_ratio.\n"
      "Rows follow the sweep's expansion order. With exactly one numeric axis, also draws\n"
      "DIR/chart.png: normalized path length of the reached runs (mean and 95% confidence interval,\n"
      "as campo plot draws it) and success rate (with its Wilson interval) against the axis; with\n"
      "--figure-format png,pdf also DIR/chart.pdf (PDF and SVG: vectors, text as text).\n"
      "Example: campo table out/resolution --rows scene --cols resolution --metrics success,path_ratio --format latex");
  return [o] { return run_table(*o); };
}

}  // namespace campo::cli
