// `campo table --rows ...` and `campo plot` run as a user would, on hand-written results.
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
  EXPECT_THAT(lines[2], ::testing::StartsWith("32,two_barriers,path_ratio,all,mean,3,0,3,2,1,-0.48413"));
  EXPECT_EQ(lines[6], "16,two_barriers,path_ratio,all,mean,3,2,1,1.5,0,,,false");
}

TEST_F(TableCli, TheSpecsTableIsTheDefaultAndMdIsMarkdown) {
  write("sweep.json", campo::testing::fixture_manifest(
                          {{"rows", "resolution"}, {"cols", "scene"}, {"metrics", {"success", "sim_time_s"}}}));
  const Result r = campo("table " + dir() + " --format md");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("| Resolution | two_barriers: Success rate (%) | two_barriers: Sim time (s), all runs |"));
  EXPECT_THAT(r.out, HasSubstr("| 32 | 67% [21, 94] (n=3) | 20 ± 10 [-5, 45] (n=3) |"));
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
  EXPECT_THAT(r.out, HasSubstr("| Resolution | two_barriers: Normalized path length, reached runs | "
                               "two_barriers: Normalized path length, all runs |"));
  // Resolution 32 on two_barriers: ratios 1 and 2 reached the goal, 3 collided.
  EXPECT_THAT(r.out, HasSubstr("| 32 | 1.50 ± 0.71 [-4.85, 7.85] (n=2) | 2.00 ± 1.00 [-0.48, 4.48] (n=3) |"));

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

}  // namespace
