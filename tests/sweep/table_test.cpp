// Tables of chosen metrics: the statistics against hand-computed values, the
// grouping and order of rows and columns, the three formats, and the errors.
#include "sweep/table.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "campo/json_reader.hpp"
#include "sweep/statistics.hpp"
#include "tests/sweep/results_fixture.hpp"

namespace campo {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

TEST(Statistics, StudentTQuantileMatchesPublishedTables) {
  // Two-sided 95 % critical values and a one-sided 95 % one.
  EXPECT_NEAR(student_t_quantile(0.975, 1), 12.7062047, 1e-6);
  EXPECT_NEAR(student_t_quantile(0.975, 2), 4.30265273, 1e-7);
  EXPECT_NEAR(student_t_quantile(0.975, 3), 3.18244631, 1e-7);
  EXPECT_NEAR(student_t_quantile(0.975, 4), 2.77644511, 1e-7);
  EXPECT_NEAR(student_t_quantile(0.975, 9), 2.26215716, 1e-7);
  EXPECT_NEAR(student_t_quantile(0.975, 29), 2.04522964, 1e-7);
  EXPECT_NEAR(student_t_quantile(0.975, 1000), 1.96233908, 1e-7);
  EXPECT_NEAR(student_t_quantile(0.95, 5), 2.01504837, 1e-7);
  EXPECT_NEAR(student_t_quantile(0.025, 2), -4.30265273, 1e-7);
  EXPECT_EQ(student_t_quantile(0.5, 7), 0.0);
}

TEST(Statistics, MeanSampleSdAndTInterval) {
  const Summary s = summarize_values({1.0, 2.0, 3.0});
  EXPECT_EQ(s.n, 3);
  EXPECT_DOUBLE_EQ(s.mean, 2.0);
  EXPECT_DOUBLE_EQ(s.sd, 1.0);
  ASSERT_TRUE(s.ci95);
  const double half = 4.30265273 / std::sqrt(3.0);  // t(0.975, 2) sd / sqrt(n)
  EXPECT_NEAR(s.ci95->low, 2.0 - half, 1e-7);
  EXPECT_NEAR(s.ci95->high, 2.0 + half, 1e-7);

  const Summary one = summarize_values({1.5});
  EXPECT_EQ(one.sd, 0.0);
  EXPECT_FALSE(one.ci95);  // no interval from one value
}

TEST(Statistics, WilsonIntervalOfARate) {
  const auto expect = [](int k, int n, double low, double high) {
    const Interval i = wilson_interval(k, n);
    EXPECT_NEAR(i.low, low, 1e-8) << k << "/" << n;
    EXPECT_NEAR(i.high, high, 1e-8) << k << "/" << n;
  };
  expect(2, 3, 0.20765960, 0.93850806);
  expect(7, 10, 0.39677815, 0.89220873);
  expect(0, 3, 0.0, 0.56149703);
  expect(3, 3, 0.43850297, 1.0);
  const Summary s = summarize_rate(2, 3);
  EXPECT_DOUBLE_EQ(s.mean, 2.0 / 3.0);
  EXPECT_NEAR(s.sd, std::sqrt(1.0 / 3.0), 1e-15);  // sample sd of {1, 1, 0}
  EXPECT_NEAR(s.ci95->low, 0.20765960, 1e-8);
}

TEST(Statistics, BoxStatsWithTukeyWhiskers) {
  const BoxStats b = box_stats({4.0, 100.0, 1.0, 3.0, 2.0});
  EXPECT_DOUBLE_EQ(b.q1, 2.0);
  EXPECT_DOUBLE_EQ(b.median, 3.0);
  EXPECT_DOUBLE_EQ(b.q3, 4.0);
  EXPECT_DOUBLE_EQ(b.whisker_low, 1.0);
  EXPECT_DOUBLE_EQ(b.whisker_high, 4.0);  // 100 lies beyond q3 + 1.5 IQR = 7
  EXPECT_EQ(b.outliers, std::vector<double>{100.0});
  const BoxStats even = box_stats({1.0, 2.0, 3.0, 4.0});  // R's quantile(type = 7)
  EXPECT_DOUBLE_EQ(even.q1, 1.75);
  EXPECT_DOUBLE_EQ(even.median, 2.5);
  EXPECT_DOUBLE_EQ(even.q3, 3.25);
  EXPECT_TRUE(even.outliers.empty());
}

TEST(MetricLabel, NamesWithUnitsFromTheSuffix) {
  EXPECT_EQ(metric_label("path_length_m"), "path length (m)");
  EXPECT_EQ(metric_label("sim_time_s"), "sim time (s)");
  EXPECT_EQ(metric_label("replan_time_ms_median"), "replan time median (ms)");
  EXPECT_EQ(metric_label("cross_track_rms_m"), "cross track rms (m)");
  EXPECT_EQ(metric_label("speed_mps"), "speed (m/s)");
  EXPECT_EQ(metric_label("path_ratio"), "normalized path length");
  EXPECT_EQ(metric_label("success"), "success rate (%)");
  EXPECT_EQ(metric_label("waypoints_reached"), "waypoints reached");
  EXPECT_EQ(field_heading("start_gap"), "Start gap");
}

class MetricTableTest : public testing::FixtureSweepTest {
 protected:
  MetricTable table(const std::string& rows, const std::string& cols, std::vector<std::string> metrics) const {
    return tabulate(runs_, layout_, TableRequest{.rows = rows, .cols = cols, .metrics = std::move(metrics)});
  }
};

TEST_F(MetricTableTest, ReadsTheCurrentResultsFormat) {
  ASSERT_EQ(runs_.size(), 12u);
  EXPECT_EQ(runs_[0].id, "id-trees__resolution-16__seed-1");
  EXPECT_EQ(runs_[0].name, "trees__resolution-16__seed-1");
  EXPECT_EQ(runs_[0].planner, "depth_reactive");
  EXPECT_EQ(runs_[0].metrics_json.at("path_ratio"), 2.0);
  EXPECT_TRUE(runs_[5].metrics_json.is_null());  // failed
  EXPECT_EQ(layout_.name, "res");
  EXPECT_EQ(layout_.axes, std::vector<std::string>{"resolution"});
  ASSERT_EQ(layout_.run_order.size(), 12u);
  EXPECT_EQ(layout_.run_order[0], "id-two_barriers__resolution-32__seed-1");
  EXPECT_FALSE(layout_.table);
}

TEST_F(MetricTableTest, CellsInExpansionOrderWithRatesMeansAndFailedRuns) {
  const MetricTable t = table("resolution", "scene", {"success", "path_ratio", "min_clearance_m", "hovered"});
  EXPECT_EQ(t.rows, (std::vector<nlohmann::json>{32, 16}));  // the spec's order, not the file's
  EXPECT_EQ(t.cols, (std::vector<nlohmann::json>{"two_barriers", "trees"}));
  EXPECT_EQ(t.kinds, (std::vector<MetricKind>{MetricKind::rate, MetricKind::number, MetricKind::number,
                                              MetricKind::rate}));
  const MetricCell& tb32 = t.cells[0][0];
  EXPECT_EQ(tb32.runs, 3);
  EXPECT_EQ(tb32.failed, 0);
  EXPECT_DOUBLE_EQ(tb32.metrics[0]->mean, 2.0 / 3.0);  // reached, reached, collision
  EXPECT_NEAR(tb32.metrics[0]->ci95->high, 0.93850806, 1e-8);
  EXPECT_DOUBLE_EQ(tb32.metrics[1]->mean, 2.0);
  EXPECT_DOUBLE_EQ(tb32.metrics[1]->sd, 1.0);
  EXPECT_EQ(tb32.metrics[2]->n, 2);  // one run has no clearance
  EXPECT_DOUBLE_EQ(tb32.metrics[2]->mean, 0.6);
  EXPECT_DOUBLE_EQ(tb32.metrics[3]->mean, 2.0 / 3.0);  // a boolean as a rate

  const MetricCell& tb16 = t.cells[1][0];
  EXPECT_EQ(tb16.runs, 3);
  EXPECT_EQ(tb16.failed, 2);
  EXPECT_EQ(tb16.metrics[0]->n, 3);  // failed runs count as not reaching the goal
  EXPECT_DOUBLE_EQ(tb16.metrics[0]->mean, 1.0 / 3.0);
  EXPECT_EQ(tb16.metrics[1]->n, 1);
  EXPECT_FALSE(tb16.metrics[1]->ci95);

  // Without a manifest, the order of appearance in results.jsonl.
  fs::remove(dir_ / "sweep.json");
  const MetricTable unordered = tabulate(runs_, table_layout(dir_, runs_), {.rows = "resolution", .cols = "scene",
                                                                            .metrics = {"success"}});
  EXPECT_EQ(unordered.rows, (std::vector<nlohmann::json>{16, 32}));
  EXPECT_EQ(unordered.cols, (std::vector<nlohmann::json>{"trees", "two_barriers"}));
}

TEST_F(MetricTableTest, OneColumnGroupWithoutCols) {
  const MetricTable t = table("seed", "", {"sim_time_s"});
  EXPECT_EQ(t.rows, (std::vector<nlohmann::json>{1, 2, 3}));
  ASSERT_EQ(t.cols.size(), 1u);
  EXPECT_EQ(t.cells[0][0].runs, 4);
  EXPECT_DOUBLE_EQ(t.cells[0][0].metrics[0]->mean, (10.0 + 40.0 + 50.0 + 100.0) / 4.0);
  const MetricTable by_planner = table("planner", "", {"success"});
  EXPECT_EQ(by_planner.rows, std::vector<nlohmann::json>{"depth_reactive"});
}

TEST_F(MetricTableTest, MarkdownCellsShowMeanSdIntervalAndCounts) {
  const std::string md = format_metric_table(table("resolution", "scene", {"success", "path_ratio"}),
                                             TableFormat::markdown);
  EXPECT_EQ(md,
            "| Resolution | two_barriers: Success rate (%) | two_barriers: Normalized path length, all runs | "
            "trees: Success rate (%) | trees: Normalized path length, all runs |\n"
            "| --- | ---: | ---: | ---: | ---: |\n"
            "| 32 | 67% [21, 94] (n=3) | 2.00 ± 1.00 [-0.48, 4.48] (n=3) | 100% [44, 100] (n=3) | "
            "1.20 ± 0.20 [0.70, 1.70] (n=3) |\n"
            "| 16 | 33% [6, 79] (n=3, 2 failed) | 1.50 (n=1, 2 failed) | 0% [0, 56] (n=3, 1 failed) | "
            "2.00 ± 0.00 [2.00, 2.00] (n=2, 1 failed) |\n");
}

TEST_F(MetricTableTest, TidyCsvOneLinePerCellAndMetric) {
  const std::string csv = format_metric_table(table("resolution", "scene", {"success", "path_ratio"}),
                                              TableFormat::csv);
  std::vector<std::vector<std::string>> lines;
  std::istringstream in(csv);
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> fields;
    std::istringstream f(line);
    for (std::string field; std::getline(f, field, ',');) fields.push_back(field);
    if (line.back() == ',') fields.emplace_back();
    lines.push_back(fields);
  }
  ASSERT_EQ(lines.size(), 1u + 2 * 2 * 2);
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "resolution,scene,metric,over,kind,runs,failed,n,mean,sd,ci95_low,ci95_high,identical");
  // Labels and counts exactly, numbers to rounding.
  const auto expect = [&](std::size_t i, const std::vector<std::string>& text, const std::vector<double>& numbers) {
    ASSERT_EQ(lines[i].size(), 13u) << i;
    for (std::size_t k = 0; k < text.size(); ++k) EXPECT_EQ(lines[i][k], text[k]) << i;
    for (std::size_t k = 0; k < numbers.size(); ++k) {
      if (std::isnan(numbers[k])) {
        EXPECT_EQ(lines[i][8 + k], "") << i;
      } else {
        EXPECT_NEAR(std::stod(lines[i][8 + k]), numbers[k], 1e-8) << i << " column " << 8 + k;
      }
    }
    EXPECT_EQ(lines[i][12], "false") << i;
  };
  const double none = std::nan("");
  const double half = 4.30265273 / std::sqrt(3.0);
  expect(1, {"32", "two_barriers", "success", "all", "rate", "3", "0", "3"}, {2.0 / 3.0, std::sqrt(1.0 / 3.0), 0.20765960, 0.93850806});
  expect(2, {"32", "two_barriers", "path_ratio", "all", "mean", "3", "0", "3"}, {2.0, 1.0, 2.0 - half, 2.0 + half});
  expect(3, {"32", "trees", "success", "all", "rate", "3", "0", "3"}, {1.0, 0.0, 0.43850297, 1.0});
  expect(4, {"32", "trees", "path_ratio", "all", "mean", "3", "0", "3"}, {1.2, 0.2, 1.2 - 0.2 * half, 1.2 + 0.2 * half});
  expect(5, {"16", "two_barriers", "success", "all", "rate", "3", "2", "3"}, {1.0 / 3.0, std::sqrt(1.0 / 3.0), 0.06149194, 0.79234040});
  expect(6, {"16", "two_barriers", "path_ratio", "all", "mean", "3", "2", "1"}, {1.5, 0.0, none, none});
  expect(8, {"16", "trees", "path_ratio", "all", "mean", "3", "1", "2"}, {2.0, 0.0, 2.0, 2.0});
}

TEST_F(MetricTableTest, LatexGroupsColumnsUnderTheirValue) {
  const std::string tex = format_metric_table(table("resolution", "scene", {"success", "path_ratio"}),
                                              TableFormat::latex);
  EXPECT_THAT(tex, HasSubstr("\\begin{tabular}{lrrrr}\n\\hline\n"
                             " & \\multicolumn{2}{c}{two\\_barriers} & \\multicolumn{2}{c}{trees} \\\\\n"
                             "Resolution & Success rate (\\%) & Normalized path length, all runs & "
                             "Success rate (\\%) & Normalized path length, all runs \\\\\n\\hline\n"));
  EXPECT_THAT(tex, HasSubstr("32 & 67\\% [21, 94] (n=3) & 2.00 $\\pm$ 1.00 [-0.48, 4.48] (n=3) &"));
  EXPECT_THAT(tex, HasSubstr("\\end{tabular}\n"));
}

TEST_F(MetricTableTest, ErrorsNameTheOptionAndListWhatExists) {
  const auto message = [&](const TableRequest& request) {
    try {
      tabulate(runs_, layout_, request);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_THAT(message({.rows = "resolution", .metrics = {"path_ratios"}}),
              HasSubstr("command line: --metrics: expected a metric of the runs (success, collisions, hovered, "
                        "min_clearance_m, path_length_m, path_ratio, sim_time_s), got \"path_ratios\""));
  EXPECT_THAT(message({.rows = "resolutions", .metrics = {"success"}}),
              HasSubstr("command line: --rows: expected a field of the runs (scene, planner, seed, resolution), "
                        "got \"resolutions\""));
  EXPECT_THAT(message({.rows = "scene", .cols = "scene", .metrics = {"success"}}),
              HasSubstr("--cols: a field other than the rows' (\"scene\")"));
  EXPECT_THAT(message({.rows = "scene", .metrics = {"success", "success"}}), HasSubstr("each metric once"));
  EXPECT_THAT(message({.rows = "scene", .metrics = {"reason"}}), HasSubstr("got \"reason\""));  // text, not a metric
}

TEST_F(MetricTableTest, TheSpecsTableIsReadFromTheManifestAndCheckedAtTableTime) {
  std::ofstream(dir_ / "sweep.json") << testing::fixture_manifest(
      {{"rows", "resolution"}, {"cols", "scene"}, {"metrics", {"success", "path_ratios"}}});
  const TableLayout layout = table_layout(dir_, runs_);
  ASSERT_TRUE(layout.table);
  EXPECT_EQ(layout.table->rows, "resolution");
  EXPECT_EQ(layout.table->cols, "scene");
  EXPECT_EQ(layout.table->metrics, (std::vector<std::string>{"success", "path_ratios"}));
  try {
    tabulate(runs_, layout, *layout.table);
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("sweep.json: /spec/table/metrics: expected a metric of the runs"));
  }
  std::ofstream(dir_ / "sweep.json") << testing::fixture_manifest({{"rows", "resolution"}, {"metric", {"success"}}});
  EXPECT_THROW(table_layout(dir_, runs_), InputError);
}

// Results written line by line for one test, read without a manifest (rows in order of appearance).
class OwnResultsTest : public testing::FixtureSweepTest {
 protected:
  void use(const std::vector<nlohmann::json>& lines) {
    {
      std::ofstream out(dir_ / "results.jsonl");
      for (const nlohmann::json& line : lines) out << line.dump() << "\n";
    }
    fs::remove(dir_ / "sweep.json");
    runs_ = read_results(dir_ / "results.jsonl").runs;
    layout_ = table_layout(dir_, runs_);
  }
  MetricTable table(std::vector<std::string> metrics) const {
    return tabulate(runs_, layout_, TableRequest{.rows = "resolution", .metrics = std::move(metrics)});
  }
  std::string text(std::vector<std::string> metrics, TableFormat format) const {
    return format_metric_table(table(std::move(metrics)), format);
  }

  // Three seeds of one run: the same metrics and trajectory, different wall-clock measurements.
  static std::vector<nlohmann::json> repeated_run(const std::string& outcome = "reached") {
    std::vector<nlohmann::json> lines;
    for (int seed = 1; seed <= 3; ++seed) {
      nlohmann::json line = testing::fixture_run("trees", 16, seed, outcome, 1.2, 50, 0.5);
      line["metrics"]["hovered"] = true;
      line["metrics"]["wall_time_s"] = 0.5 * seed;
      line["metrics"]["planner_time_ms_max"] = 3.0 * seed;
      line["metrics"]["replan_time_ms_median"] = 2.0 * seed;
      line["wall_time_s"] = 1.0 + seed;
      line["trajectory_sha256"] = "one-trajectory";
      lines.push_back(line);
    }
    return lines;
  }
};

TEST_F(OwnResultsTest, ReachedRunMeansBesideAllRunMeans) {
  // Two runs reach the goal, one aborts after a short path, one fails.
  use({testing::fixture_run("two_barriers", 32, 1, "reached", 1.1, 20),
       testing::fixture_run("two_barriers", 32, 2, "reached", 1.3, 30),
       testing::fixture_run("two_barriers", 32, 3, "aborted", 0.3, 5),
       testing::fixture_run("two_barriers", 32, 4, "failed", 0, 0)});
  const MetricTable t =
      table({"success", "path_ratio@reached", "path_ratio", "sim_time_s@reached", "sim_time_s", "path_length_m@reached"});
  EXPECT_EQ(t.kinds, (std::vector<MetricKind>{MetricKind::rate, MetricKind::number, MetricKind::number,
                                              MetricKind::number, MetricKind::number, MetricKind::number}));
  const MetricCell& c = t.cells[0][0];
  EXPECT_EQ(c.runs, 4);
  EXPECT_EQ(c.failed, 1);
  EXPECT_FALSE(c.identical);
  EXPECT_EQ(c.metrics[0]->n, 4);
  EXPECT_DOUBLE_EQ(c.metrics[0]->mean, 0.5);
  // Reached: 1.1 and 1.3. All completed: 1.1, 1.3 and the aborted run's 0.3.
  EXPECT_EQ(c.metrics[1]->n, 2);
  EXPECT_DOUBLE_EQ(c.metrics[1]->mean, 1.2);
  EXPECT_NEAR(c.metrics[1]->sd, std::sqrt(0.02), 1e-12);
  EXPECT_NEAR(c.metrics[1]->ci95->low, 1.2 - 12.7062047 * 0.1, 1e-6);  // t(0.975, 1) sd / sqrt(2)
  EXPECT_EQ(c.metrics[2]->n, 3);
  EXPECT_DOUBLE_EQ(c.metrics[2]->mean, 0.9);
  EXPECT_NEAR(c.metrics[2]->sd, std::sqrt(0.28), 1e-12);  // (0.04 + 0.16 + 0.36) / 2
  EXPECT_DOUBLE_EQ(c.metrics[3]->mean, 25.0);
  EXPECT_NEAR(c.metrics[3]->sd, std::sqrt(50.0), 1e-12);
  EXPECT_DOUBLE_EQ(c.metrics[4]->mean, 55.0 / 3.0);
  EXPECT_DOUBLE_EQ(c.metrics[5]->mean, 12.0);  // 11 and 13 m

  const std::string md = text({"success", "path_ratio@reached", "path_ratio"}, TableFormat::markdown);
  EXPECT_EQ(md,
            "| Resolution | Success rate (%) | Normalized path length, reached runs | "
            "Normalized path length, all runs |\n"
            "| --- | ---: | ---: | ---: |\n"
            "| 32 | 50% [15, 85] (n=4, 1 failed) | 1.20 ± 0.14 [-0.07, 2.47] (n=2, 1 failed) | "
            "0.900 ± 0.529 [-0.414, 2.214] (n=3, 1 failed) |\n");
  const std::string tex = text({"path_ratio@reached", "path_ratio"}, TableFormat::latex);
  EXPECT_THAT(tex, HasSubstr("Resolution & Normalized path length, reached runs & Normalized path length, all runs"));

  // Tidy CSV: the metric's name, then which runs.
  const std::string csv = text({"path_ratio@reached", "path_ratio"}, TableFormat::csv);
  EXPECT_THAT(csv, HasSubstr("resolution,metric,over,kind,runs,failed,n,mean,sd,ci95_low,ci95_high,identical\n"
                             "32,path_ratio,reached,mean,4,1,2,1.2"));
  EXPECT_THAT(csv, HasSubstr("\n32,path_ratio,all,mean,4,1,3,0.9"));

  // The summary table has both too.
  const SweepTable summary = aggregate(runs_, layout_);
  ASSERT_EQ(summary.rows.size(), 1u);
  EXPECT_EQ(summary.rows[0].reached, 2);
  EXPECT_DOUBLE_EQ(summary.rows[0].path_ratio_reached->mean, 1.2);
  EXPECT_DOUBLE_EQ(summary.rows[0].path_ratio->mean, 0.9);
  EXPECT_DOUBLE_EQ(summary.rows[0].time_s_reached->mean, 25.0);
  EXPECT_DOUBLE_EQ(summary.rows[0].path_length_m_reached->mean, 12.0);
  EXPECT_DOUBLE_EQ(summary.rows[0].path_length_m->mean, 9.0);  // 11, 13 and 3 m
}

TEST_F(OwnResultsTest, IdenticalRunsOverSeedsSaySoWithoutAnInterval) {
  use(repeated_run());
  const MetricTable t = table({"success", "path_ratio@reached", "path_ratio", "hovered"});
  const MetricCell& c = t.cells[0][0];
  EXPECT_TRUE(c.identical);
  for (const auto& s : c.metrics) {
    ASSERT_TRUE(s);
    EXPECT_EQ(s->n, 3);
    EXPECT_FALSE(s->ci95);  // neither Student t nor Wilson
  }
  EXPECT_DOUBLE_EQ(c.metrics[1]->mean, 1.2);

  const std::string md = text({"success", "path_ratio@reached", "hovered"}, TableFormat::markdown);
  EXPECT_THAT(md, HasSubstr("| 16 | 100% (n=3 identical runs: seeds vary nothing) | "
                            "1.20 (n=3 identical runs: seeds vary nothing) | "
                            "100% (n=3 identical runs: seeds vary nothing) |\n"));
  EXPECT_THAT(md, Not(HasSubstr("±")));
  EXPECT_THAT(md, Not(HasSubstr("[")));
  EXPECT_THAT(text({"path_ratio"}, TableFormat::latex), HasSubstr("16 & 1.20 (n=3 identical runs: seeds vary nothing) \\\\"));
  const std::string csv = text({"success", "path_ratio@reached"}, TableFormat::csv);
  EXPECT_THAT(csv, HasSubstr("\n16,success,all,rate,3,0,3,1,,,,true\n"));
  EXPECT_THAT(csv, HasSubstr("\n16,path_ratio,reached,mean,3,0,3,1.2,,,,true\n"));

  // The summary table: the runs counted as identical, means without a spread.
  const SweepTable summary = aggregate(runs_, layout_);
  ASSERT_EQ(summary.rows.size(), 1u);
  EXPECT_TRUE(summary.rows[0].identical);
  const std::string summary_md = format_table(summary, TableFormat::markdown);
  EXPECT_THAT(summary_md, HasSubstr("| trees | 16 | 3 identical runs: seeds vary nothing | 100% | 3 | "));
  EXPECT_THAT(summary_md, HasSubstr("| 12.00 | 12.00 | 1.200 | 1.200 | 50.0 | 50.0 |"));
  const std::string summary_csv = format_table(summary, TableFormat::csv);
  EXPECT_THAT(summary_csv, HasSubstr(",12,,12,,1.2,,1.2,,50,,50,,"));
  EXPECT_THAT(summary_csv, ::testing::EndsWith(",true\n"));

  // Repeated runs that never reach the goal have no reached-run value, and say why.
  use(repeated_run("timeout"));
  EXPECT_THAT(text({"path_ratio@reached"}, TableFormat::markdown),
              HasSubstr("| 16 | – (n=0 of 3 identical runs: seeds vary nothing) |"));
}

TEST_F(OwnResultsTest, DistinctRunsStillPrintTheirInterval) {
  // The same metrics but another trajectory in seed 2.
  std::vector<nlohmann::json> lines = repeated_run();
  lines[1]["trajectory_sha256"] = "another-trajectory";
  use(lines);
  EXPECT_FALSE(table({"success"}).cells[0][0].identical);
  EXPECT_THAT(text({"success", "path_ratio"}, TableFormat::markdown),
              HasSubstr("| 16 | 100% [44, 100] (n=3) | 1.20 ± 0.00 [1.20, 1.20] (n=3) |"));
  EXPECT_THAT(text({"success"}, TableFormat::csv), HasSubstr("\n16,success,all,rate,3,0,3,1,0,0.43850"));
  EXPECT_FALSE(aggregate(runs_, layout_).rows[0].identical);

  // A deterministic metric that differs.
  lines = repeated_run();
  lines[2]["metrics"]["min_clearance_m"] = 0.25;
  use(lines);
  const MetricTable t = table({"path_ratio"});
  EXPECT_FALSE(t.cells[0][0].identical);
  EXPECT_TRUE(t.cells[0][0].metrics[0]->ci95);

  // A run that failed.
  lines = repeated_run();
  lines.push_back(testing::fixture_run("trees", 16, 4, "failed", 0, 0));
  use(lines);
  EXPECT_FALSE(table({"path_ratio"}).cells[0][0].identical);

  // One run alone is a sample of one, not a repetition.
  use({repeated_run().front()});
  EXPECT_FALSE(table({"path_ratio"}).cells[0][0].identical);
}

TEST(IdenticalRuns, OlderResultsWithoutADigestCompareTheirMetrics) {
  RunResult a;
  a.completed = true;
  a.metrics_json = {{"outcome", "reached"}, {"path_ratio", 1.2}, {"wall_time_s", 3.0}, {"replan_time_ms_max", 4.0}};
  RunResult b = a;
  b.metrics_json["wall_time_s"] = 5.0;  // measured: not compared
  b.metrics_json["replan_time_ms_max"] = 9.0;
  EXPECT_TRUE(identical_runs({&a, &b}));
  b.trajectory_sha256 = "digest";  // one with a digest, one without
  EXPECT_FALSE(identical_runs({&a, &b}));
  a.trajectory_sha256 = "digest";
  EXPECT_TRUE(identical_runs({&a, &b}));
  b.metrics_json["path_ratio"] = 1.25;
  EXPECT_FALSE(identical_runs({&a, &b}));
  EXPECT_TRUE(measured_metric("planner_time_ms_mean"));
  EXPECT_FALSE(measured_metric("sim_time_s"));
}

TEST_F(MetricTableTest, MetricsOverReachedRunsAreNamedAndChecked) {
  EXPECT_EQ(metric_label("path_ratio@reached"), "normalized path length, reached runs");
  EXPECT_EQ(metric_heading("path_ratio@reached"), "normalized path length, reached runs");
  EXPECT_EQ(metric_heading("sim_time_s"), "sim time (s), all runs");
  EXPECT_EQ(metric_heading("success"), "success rate (%)");
  EXPECT_EQ(split_metric("sim_time_s@reached").base, "sim_time_s");
  EXPECT_TRUE(split_metric("sim_time_s@reached").reached_only);
  const auto message = [&](const std::string& metric) {
    try {
      table("resolution", "", {metric});
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message("path_ratio@reached"), "no error");
  EXPECT_THAT(message("path_ratio@all"),
              HasSubstr("command line: --metrics: expected a metric, or a metric over the runs that reached their goal "
                        "as \"path_ratio@reached\", got \"path_ratio@all\""));
  EXPECT_THAT(message("success@reached"),
              HasSubstr("command line: --metrics: expected \"success\" without \"@reached\""));
  EXPECT_THAT(message("path_ratios@reached"),
              HasSubstr("--metrics: expected a metric of the runs (success, collisions"));
}

}  // namespace
}  // namespace campo
