// `campo table --rows ...` and `campo plot` run as a user would, on hand-written results.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "tests/cli_support.hpp"
#include "tests/sweep/results_fixture.hpp"

namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using campo::testing::Result;
using campo::testing::slurp;

class TableCli : public campo::testing::CliTest {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    write("results.jsonl", campo::testing::fixture_results());
    write("sweep.json", campo::testing::fixture_manifest());
  }
  std::string dir() const { return dir_.string(); }
};

TEST_F(TableCli, RowsColsAndMetricsAsTidyCsv) {
  const Result r = campo("table " + dir() + " --rows resolution --cols scene --metrics success,path_ratio --format csv --no-chart");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto lines = campo::testing::lines_of(r.out);
  ASSERT_EQ(lines.size(), 9u);
  EXPECT_EQ(lines[0], "resolution,scene,metric,over,kind,runs,failed,n,mean,sd,ci95_low,ci95_high,identical");
  // path_ratio is >= 0: its interval on the log scale, 2 / exp(t(0.975, 2) / sqrt(3) / 2) = 0.57757.
  EXPECT_THAT(lines[2], ::testing::StartsWith("32,two_barriers,path_ratio,all,mean,3,0,3,2,1,0.57757"));
  EXPECT_EQ(lines[6], "16,two_barriers,path_ratio,all,mean,3,2,1,1.5,0,,,false");
}

TEST_F(TableCli, TheSpecsTableIsTheDefaultAndMdIsMarkdown) {
  write("sweep.json", campo::testing::fixture_manifest(
                          {{"rows", "resolution"}, {"cols", "scene"}, {"metrics", {"success", "sim_time_s"}}}));
  const Result r = campo("table " + dir() + " --format md");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("| Resolution | Scene = two_barriers: Success rate (%) | "
                               "Scene = two_barriers: Sim time (s), all runs |"));
  EXPECT_THAT(r.out, HasSubstr("| 32 | 67% | 20 ± 10 |"));  // the default cell: mean ± sd
  // Times 10, 20 and 30 s: the t interval would start at -5 s; on the log scale 20 / f, 20 f with
  // f = exp(4.30265273 * 10 / sqrt(3) / 20) = 3.4628: [6, 69].
  const Result full = campo("table " + dir() + " --format md --cell mean-sd-ci --with-n --no-chart");
  ASSERT_EQ(full.exit_code, 0) << full.err;
  EXPECT_THAT(full.out, HasSubstr("| 32 | 67% [21, 94] (n=3) | 20 ± 10 [6, 69] (n=3) |"));
  const Result ci = campo("table " + dir() + " --cell MEAN-CI --no-chart");
  ASSERT_EQ(ci.exit_code, 0) << ci.err;
  EXPECT_THAT(ci.out, HasSubstr("| 32 | 67% [21, 94] | 20 [6, 69] |"));
  const Result bad_cell = campo("table " + dir() + " --cell median --no-chart");
  EXPECT_EQ(bad_cell.exit_code, 2);
  EXPECT_THAT(bad_cell.err, HasSubstr("--cell"));
  EXPECT_THAT(r.err, HasSubstr("wrote " + (dir_ / "chart.png").string()));  // the summary chart as before
  // --summary: the summary table instead.
  const Result summary = campo("table " + dir() + " --summary --no-chart");
  ASSERT_EQ(summary.exit_code, 0) << summary.err;
  EXPECT_THAT(summary.out, HasSubstr("| Scene | Resolution | Runs | Success |"));
}

TEST_F(TableCli, ReachedRunMetricsInTheSpecsTableAndThePlot) {
  write("sweep.json", campo::testing::fixture_manifest(
                          {{"rows", "resolution"}, {"cols", "scene"}, {"metrics", {"path_ratio@reached", "path_ratio"}}}));
  const Result r = campo("table " + dir() + " --no-chart");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("| Resolution | Scene = two_barriers: Normalized path length, reached runs | "
                               "Scene = two_barriers: Normalized path length, all runs |"));
  // Resolution 32 on two_barriers: ratios 1 and 2 reached the goal, 3 collided.
  EXPECT_THAT(r.out, HasSubstr("| 32 | 1.50 ± 0.71 | 2.00 ± 1.00 |"));

  const std::string png = (dir_ / "reached.png").string();
  const Result plot = campo("plot " + dir() + " --x resolution --y path_ratio@reached --group scene --out " + png);
  ASSERT_EQ(plot.exit_code, 0) << plot.err;
  EXPECT_TRUE(fs::exists(png));
  const Result bad = campo("plot " + dir() + " --x resolution --y success@reached --out " + png + ".2");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_THAT(bad.err, HasSubstr("command line: --y: expected \"success\" without \"@reached\""));
}

TEST_F(TableCli, BadInputExitsWithCode2AndWritesNothing) {
  Result r = campo("table " + dir() + " --rows resolution --metrics success,path_ratios");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("error: command line: --metrics: expected a metric of the runs (success, "));
  EXPECT_THAT(r.err, HasSubstr("got \"path_ratios\""));
  EXPECT_EQ(r.out, "");
  EXPECT_FALSE(fs::exists(dir_ / "chart.png"));
  r = campo("table " + dir() + " --rows resolution");  // --rows needs --metrics
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--metrics"));
  r = campo("table " + dir() + " --rows resolution --metrics success --format tsv");
  EXPECT_EQ(r.exit_code, 2);
}

// A chart that cannot be written is an output error: exit 2 naming the file
// and the system's reason, and no table printed before it.
TEST_F(TableCli, AChartThatCannotBeWrittenIsExitTwoWithNothingPrinted) {
  const fs::path chart = dir_ / "no_such_dir" / "chart.png";
  const Result r = campo("table " + dir() + " --chart " + chart.string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(r.out, "");
  EXPECT_THAT(r.err, HasSubstr("error: " + chart.string() + ": cannot write: No such file or directory"));
  EXPECT_THAT(r.err, ::testing::Not(HasSubstr("libpng")));
  EXPECT_FALSE(fs::exists(chart));
}

TEST_F(TableCli, PlotWritesAPng) {
  const std::string png = (dir_ / "ratio.png").string();
  const Result r = campo("plot " + dir() + " --x resolution --y path_ratio --group scene --out " + png);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("wrote " + png));
  const cv::Mat image = cv::imread(png);
  EXPECT_EQ(image.cols, 1600);
  EXPECT_EQ(image.rows, 1000);
  const std::string first = slurp(png);
  ASSERT_EQ(campo("plot " + dir() + " --x resolution --y path_ratio --group scene --out " + png).exit_code, 0);
  EXPECT_EQ(slurp(png), first);  // same results, same bytes

  const Result bad = campo("plot " + dir() + " --x scene --y path_ratio --kind line --out " + png + ".2");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_THAT(bad.err, HasSubstr("--kind: line needs numeric values"));
  EXPECT_FALSE(fs::exists(png + ".2"));
}

// --figure-format: the plot and the table's chart in each format named, next to --out / --chart.
TEST_F(TableCli, FigureFormatsWriteEachFile) {
  const fs::path out = dir_ / "ratio.png";
  const Result r = campo("plot " + dir() + " --x resolution --y path_ratio --group scene --out " + out.string() +
                         " --figure-format png,pdf,svg");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* ext : {".png", ".pdf", ".svg"}) {
    const fs::path file = fs::path(out).replace_extension(ext);
    EXPECT_THAT(r.err, HasSubstr("wrote " + file.string())) << ext;
    EXPECT_TRUE(fs::exists(file)) << ext;
  }
  EXPECT_EQ(cv::imread(out.string()).size(), cv::Size(1600, 1000));
  EXPECT_EQ(slurp(dir_ / "ratio.pdf").rfind("%PDF-", 0), 0u);
  EXPECT_THAT(slurp(dir_ / "ratio.svg"), HasSubstr("<svg"));

  // --out's extension gives way to the format's; a name without one gets it appended.
  const Result pdf_only = campo("plot " + dir() + " --x resolution --y path_ratio --out " + dir() +
                                "/only.png --figure-format pdf");
  ASSERT_EQ(pdf_only.exit_code, 0) << pdf_only.err;
  EXPECT_TRUE(fs::exists(dir_ / "only.pdf"));
  EXPECT_FALSE(fs::exists(dir_ / "only.png"));
  ASSERT_EQ(campo("plot " + dir() + " --x resolution --y path_ratio --out " + dir() + "/bare --figure-format svg")
                .exit_code,
            0);
  EXPECT_TRUE(fs::exists(dir_ / "bare.svg"));

  // The table's chart: DIR/chart.png and DIR/chart.pdf.
  const Result table = campo("table " + dir() + " --figure-format png,pdf");
  ASSERT_EQ(table.exit_code, 0) << table.err;
  EXPECT_THAT(table.err, HasSubstr("wrote " + (dir_ / "chart.png").string()));
  EXPECT_THAT(table.err, HasSubstr("wrote " + (dir_ / "chart.pdf").string()));
  EXPECT_FALSE(fs::exists(dir_ / "chart.svg"));
  const Result named = campo("table " + dir() + " --chart " + dir() + "/summary.svg --figure-format svg");
  ASSERT_EQ(named.exit_code, 0) << named.err;
  EXPECT_TRUE(fs::exists(dir_ / "summary.svg"));
}

TEST_F(TableCli, FigureFormatErrorsExitTwoAndWriteNothing) {
  const std::string plot = "plot " + dir() + " --x resolution --y path_ratio --out " + dir() + "/f.png";
  const Result gif = campo(plot + " --figure-format png,gif");
  EXPECT_EQ(gif.exit_code, 2);
  EXPECT_THAT(gif.err, HasSubstr("error: command line: "));
  EXPECT_THAT(gif.err, HasSubstr("--figure-format"));
  EXPECT_THAT(gif.err, HasSubstr("'gif' is not one of png, pdf, svg"));
  const Result twice = campo(plot + " --figure-format pdf,png,pdf");
  EXPECT_EQ(twice.exit_code, 2);
  EXPECT_THAT(twice.err, HasSubstr("names pdf twice"));
  const Result empty = campo(plot + " --figure-format ''");
  EXPECT_EQ(empty.exit_code, 2);
  const Result table = campo("table " + dir() + " --figure-format svg,jpeg");
  EXPECT_EQ(table.exit_code, 2);
  EXPECT_THAT(table.err, HasSubstr("'jpeg' is not one of png, pdf, svg"));
  EXPECT_EQ(table.out, "");
  for (const char* file : {"f.png", "f.pdf", "f.svg", "chart.png", "chart.svg"}) {
    EXPECT_FALSE(fs::exists(dir_ / file)) << file;
  }
  // No chart, no chart formats.
  EXPECT_EQ(campo("table " + dir() + " --no-chart --figure-format pdf").exit_code, 2);
  // Every file is checked before any work: a PDF that cannot be written leaves no PNG behind.
  fs::create_directories(dir_ / "taken.pdf");
  const Result taken = campo("plot " + dir() + " --x resolution --y path_ratio --out " + dir() +
                             "/taken.png --figure-format png,pdf");
  EXPECT_EQ(taken.exit_code, 2);
  EXPECT_THAT(taken.err, HasSubstr("taken.pdf"));
  EXPECT_FALSE(fs::exists(dir_ / "taken.png"));
}

// LaTeX for a paper: booktabs rules, column groups headed by the field and its value, cells as asked.
TEST_F(TableCli, LatexIsBooktabsAndCompilesWhereATeXEngineIs) {
  const Result r = campo("table " + dir() + " --rows scene --cols resolution --metrics success,sim_time_s --format latex "
                         "--no-chart");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("\\toprule\n"));
  EXPECT_THAT(r.out, HasSubstr(" & \\multicolumn{2}{c}{Resolution = 32} & \\multicolumn{2}{c}{Resolution = 16} \\\\\n"
                               "\\cmidrule(lr){2-3} \\cmidrule(lr){4-5}\n"));
  EXPECT_THAT(r.out, HasSubstr("\\midrule\n"));
  EXPECT_THAT(r.out, HasSubstr("two\\_barriers & 67\\% & 20 $\\pm$ 10 & "));
  EXPECT_THAT(r.out, HasSubstr("\\bottomrule\n\\end{tabular}\n"));
  EXPECT_THAT(r.out, ::testing::Not(HasSubstr("\\hline")));
  // Every row has as many cells as the tabular has columns: l and 4 r.
  EXPECT_THAT(r.out, HasSubstr("\\begin{tabular}{lrrrr}"));
  for (const std::string& line : campo::testing::lines_of(r.out)) {
    if (line.starts_with("two") || line.starts_with("trees") || line.starts_with("Scene")) {
      EXPECT_EQ(std::count(line.begin(), line.end(), '&'), 4) << line;
    }
  }
  const Result summary = campo("table " + dir() + " --summary --format latex --no-chart");
  ASSERT_EQ(summary.exit_code, 0) << summary.err;

  if (std::system("command -v pdflatex > /dev/null 2>&1") != 0) {
    GTEST_SKIP() << "pdflatex is not installed: the LaTeX was checked structurally only";
  }
  for (const auto& [name, table] : {std::pair{"metrics", r.out}, std::pair{"summary", summary.out}}) {
    const std::string tex = write(std::string(name) + ".tex",
                                  "\\documentclass{article}\n\\usepackage[utf8]{inputenc}\n\\usepackage{booktabs}\n"
                                  "\\usepackage[landscape,margin=1cm]{geometry}\n\\begin{document}\n" + table +
                                  "\\end{document}\n");
    const std::string command = "cd " + dir() + " && pdflatex -interaction=nonstopmode -halt-on-error " + tex +
                                " > " + dir() + "/" + name + ".out 2>&1";
    EXPECT_EQ(std::system(command.c_str()), 0) << slurp(dir_ / (std::string(name) + ".out"));
    EXPECT_TRUE(fs::exists(dir_ / (std::string(name) + ".pdf")));
  }
}

// Axis labels with units by default, the user's words when given.
TEST_F(TableCli, PlotLabelsOverride) {
  const std::string png = (dir_ / "time.png").string();
  const Result r = campo("plot " + dir() + " --x resolution --y sim_time_s --xlabel 'Grid resolution' --ylabel "
                         "'Flight time (s)' --title 'Time' --out " + png);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const cv::Mat labelled = cv::imread(png);
  ASSERT_EQ(campo("plot " + dir() + " --x resolution --y sim_time_s --out " + png).exit_code, 0);
  const cv::Mat plain = cv::imread(png);
  ASSERT_EQ(labelled.size(), plain.size());
  EXPECT_GT(cv::norm(labelled, plain, cv::NORM_L1), 0.0);  // the labels drew other text
}

// Help texts name the choices, never the argument parser's internals (a transformer's map "csv->1").
TEST_F(TableCli, HelpTextsShowNoParserInternals) {
  for (const char* command : {"table", "plot", "sweep", "merge", "run", "validate", "plan", "render", "scan", "bench",
                              "reproduce"}) {
    const Result r = campo(std::string(command) + " --help");
    EXPECT_EQ(r.exit_code, 0) << command;
    EXPECT_THAT(r.out, ::testing::Not(::testing::ContainsRegex("[a-z]->[0-9]"))) << command;
    EXPECT_THAT(r.out, ::testing::Not(HasSubstr("} OR {"))) << command;
  }
  const Result table = campo("table --help");
  EXPECT_THAT(table.out, HasSubstr("--format markdown|csv|latex"));
  EXPECT_THAT(table.out, HasSubstr("--cell mean|mean-sd|mean-ci|mean-sd-ci"));
  EXPECT_THAT(campo("plot --help").out, HasSubstr("--kind line|box|auto"));
  for (const char* command : {"table", "plot"}) {
    EXPECT_THAT(campo(std::string(command) + " --help").out, HasSubstr("--figure-format")) << command;
  }
  // A wrong choice: the names, not the parser's map.
  const Result format = campo("table " + dir() + " --format tex");
  EXPECT_EQ(format.exit_code, 2);
  EXPECT_THAT(format.err, HasSubstr("error: command line: --format: expected markdown, md, csv or latex, got \"tex\""));
  const Result cell = campo("table " + dir() + " --cell median");
  EXPECT_THAT(cell.err, HasSubstr("--cell: expected mean, mean-sd, mean-ci or mean-sd-ci, got \"median\""));
  const Result kind = campo("plot " + dir() + " --x resolution --y success --kind bar --out " + dir() + "/k.png");
  EXPECT_THAT(kind.err, HasSubstr("--kind: expected line, box or auto, got \"bar\""));
  for (const Result& r : {format, cell, kind}) EXPECT_THAT(r.err, ::testing::Not(::testing::ContainsRegex("[a-z]->[0-9]")));
}

}  // namespace
