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
#include "tools/commands.hpp"
#include "tools/path_options.hpp"

namespace campo::cli {

namespace {

namespace fs = std::filesystem;

struct PlotOptions {
  std::string dir;
  PlotRequest request;
  std::string vehicle;  ///< empty: the runs' own metrics (the fleet's with several vehicles)
  std::string out;
  std::vector<figure::FigureFormat> formats{figure::FigureFormat::png};
};

int run_plot(const PlotOptions& o) {
  // Every file to be written must be writable before any work.
  for (const fs::path& file : figure::figure_files(o.out, o.formats)) check_output_file(file, "--out");
  const fs::path dir = o.dir;
  TableLayout layout = table_layout(dir);
  // --vehicle: a plain metric name is that vehicle's, each run seen from it.
  PlotRequest request = o.request;
  if (!o.vehicle.empty()) request.y = vehicle_metric_name(request.y, o.vehicle);
  // The results a line at a time, each run folded into its point or box: memory grows with the plot.
  const bool axes_from_runs = layout.axes_from_runs;
  std::optional<PlotBuilder> plot;
  std::vector<std::string> warnings;
  for_each_result(
      dir / "results.jsonl", warnings,
      [&] {
        if (axes_from_runs) layout.axes.clear();
        plot.emplace(layout, request);
      },
      [&](const RunResult& run, std::size_t index) {
        add_axes(layout, run);
        if (o.vehicle.empty()) {
          plot->add(run, index);
        } else {
          plot->add(vehicle_run(run, o.vehicle, "command line", "--vehicle"), index);
        }
      });
  for (const std::string& warning : warnings) std::cerr << "warning: " << warning << "\n";
  for (const fs::path& file : plot->draw().write(o.out, o.formats)) {
    std::cerr << "wrote " << file.string() << "\n";
  }
  return kOk;
}

}  // namespace

Command add_plot(CLI::App& app) {
  auto o = std::make_shared<PlotOptions>();
  app.add_option("dir", o->dir, "Sweep output directory (holding results.jsonl, from campo sweep)")
      ->required()
      ->check(input_path());
  app.add_option("--x", o->request.x, "Field on the x axis: scene, planner, seed or an axis name")->required();
  app.add_option("--y", o->request.y,
                 "Metric on the y axis: success (rate of outcome reached) or a key of run.json's metrics; with "
                 "several vehicles a plain name is the run's (all_reached, makespan_s ...) and ALIAS.METRIC a "
                 "vehicle's (drone.path_ratio, rover.success)")
      ->required();
  app.add_option("--vehicle", o->vehicle,
                 "In runs of several vehicles, the vehicle whose metric a plain --y names (ALIAS.METRIC still "
                 "names any vehicle's); each completed run must have it")
      ->type_name("ALIAS");
  app.add_option("--group", o->request.group, "Field whose values are drawn as separate coloured series");
  app.add_option("--kind", o->request.kind,
                 "line (numeric x: mean and 95% interval), box (x as categories: quartiles, whiskers, outliers) "
                 "or auto (line when every x value is a number; default)")
      ->transform(named_choice<PlotKind>({{"line", PlotKind::line}, {"box", PlotKind::box},
                                          {"auto", PlotKind::automatic}}))  // by name, not a map "line->1"
      ->option_text("line|box|auto");
  app.add_option("--title", o->request.title, "Title (default: \"<sweep>: <metric> vs <x>\")");
  app.add_option("--xlabel", o->request.x_label,
                 "Label of the x axis (default: the field's name with its unit, e.g. \"Speed (m/s)\")");
  app.add_option("--ylabel", o->request.y_label,
                 "Label of the y axis (default: the metric's name with its unit and the runs it is over, e.g. "
                 "\"Sim time (s), all runs\")");
  app.add_option("--out", o->out,
                 "File to write, e.g. ratio.png; its extension (.png, .pdf or .svg) is replaced by each "
                 "--figure-format's, any other name gets the format's extension appended")
      ->required()
      ->type_name("FILE");
  add_figure_format_option(app, &o->formats);
  app.footer(
      "A 1600 x 1000 figure for a paper (PNG, and with --figure-format PDF or SVG: vectors, text as\n"
      "text): the metric against the field, one coloured series per --group value with a legend, axis\n"
      "labels with units (from the names' suffixes: _m, _s, _mps ...), and a note of the spread shown\n"
      "and the runs. --out ratio.png --figure-format png,pdf writes ratio.png and ratio.pdf.\n"
      "Line plots: the mean per x with its 95% confidence interval, named in the legend: for a metric\n"
      "that cannot be negative (lengths, times, counts, path_ratio) the t interval of log(mean), never\n"
      "below 0; for others the Student t interval; for rates the Wilson interval (docs/sweeps.md). An\n"
      "interval reaching far beyond the means (two runs) ends in an arrowhead at the frame. x on a\n"
      "log2 scale when every value is a power of two. Box plots: median, quartiles, whiskers at 1.5 IQR\n"
      "and outliers per category. The same results give the same bytes.\n"
      "Example: campo plot out/resolution --x resolution --y path_ratio --group scene --out ratio.png");
  return [o] { return run_plot(*o); };
}

}  // namespace campo::cli
