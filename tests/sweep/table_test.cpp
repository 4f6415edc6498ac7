// Tables of chosen metrics: the statistics against hand-computed values, the
// grouping and order of rows and columns, the three formats, and the errors.
#include "sweep/table.hpp"

#include <cmath>
#include <cstdio>
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

TEST(Statistics, IntervalOfANonNegativeMetricNeverGoesBelowZero) {
  // Two runs' times, 20 s and 30 s: mean 25, sd sqrt(50), standard error 5, t(0.975, 1) = 12.7062047.
  // The Student t interval is 25 ± 63.53: from -38.5 s, a time no run can take.
  const Summary t = summarize_values({20.0, 30.0});
  EXPECT_NEAR(t.ci95->low, 25.0 - 12.7062047 * 5.0, 1e-6);
  // On the log scale: log(25) ± 12.7062047 * 5 / 25 (the delta method's standard error of log(mean)),
  // taken back: 25 / f and 25 f with f = exp(2.54124094) = 12.6954155.
  const Summary s = summarize_values({20.0, 30.0}, Support::non_negative);
  ASSERT_TRUE(s.ci95);
  EXPECT_DOUBLE_EQ(s.mean, 25.0);
  EXPECT_NEAR(s.ci95->low, 25.0 / 12.6954155, 1e-6);  // 1.969 s
  EXPECT_NEAR(s.ci95->high, 25.0 * 12.6954155, 1e-5);  // 317.4 s
  EXPECT_GT(s.ci95->low, 0.0);
  // The same from the running statistics tables and plots keep.
  RunningStats running;
  running.add(20.0);
  running.add(30.0);
  EXPECT_NEAR(running.values(Support::non_negative).ci95->low, 25.0 / 12.6954155, 1e-6);
  // All zeros (no collisions in any run): [0, 0]; one value: none.
  const Summary zeros = summarize_values({0.0, 0.0, 0.0}, Support::non_negative);
  EXPECT_EQ(zeros.ci95->low, 0.0);
  EXPECT_EQ(zeros.ci95->high, 0.0);
  EXPECT_FALSE(mean_interval95(3.0, 0.0, 1, Support::non_negative));
  // A negative value says the metric is signed after all: the t interval.
  EXPECT_NEAR(summarize_values({-1.0, 1.0}, Support::non_negative).ci95->low, -12.7062047, 1e-6);
  // Which metrics are >= 0 by definition.
  EXPECT_TRUE(non_negative_metric("sim_time_s"));
  EXPECT_TRUE(non_negative_metric("sim_time_s@reached"));
  EXPECT_TRUE(non_negative_metric("path_length_m"));
  EXPECT_TRUE(non_negative_metric("path_ratio"));
  EXPECT_TRUE(non_negative_metric("replan_time_ms_median"));
  EXPECT_TRUE(non_negative_metric("collisions"));
  EXPECT_TRUE(non_negative_metric("cross_track_rms_m"));
  EXPECT_FALSE(non_negative_metric("min_clearance_m"));  // negative when the shapes overlapped
  EXPECT_FALSE(non_negative_metric("min_ground_clearance_m"));
  EXPECT_FALSE(non_negative_metric("heading_error"));  // unknown: signed
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
  EXPECT_EQ(metric_label("path_length_m"), "Path length (m)");
  EXPECT_EQ(metric_label("sim_time_s"), "Sim time (s)");
  EXPECT_EQ(metric_label("replan_time_ms_median"), "Replan time median (ms)");
  EXPECT_EQ(metric_label("cross_track_rms_m"), "Cross track rms (m)");
  EXPECT_EQ(metric_label("speed_mps"), "Speed (m/s)");
  EXPECT_EQ(metric_label("path_ratio"), "Normalized path length");
  EXPECT_EQ(metric_label("success"), "Success rate (%)");
  EXPECT_EQ(metric_label("waypoints_reached"), "Waypoints reached");
  // Parameters (axes) get their units from the same function.
  EXPECT_EQ(field_heading("start_gap"), "Start gap");
  EXPECT_EQ(field_heading("speed_mps"), "Speed (m/s)");
  EXPECT_EQ(field_heading("time_s"), "Time (s)");
  EXPECT_EQ(field_heading("yaw_deg"), "Yaw (deg)");
  EXPECT_EQ(field_heading("image_width_px"), "Image width (px)");
  EXPECT_EQ(field_heading("rate_hz"), "Rate (Hz)");
  EXPECT_EQ(field_heading("resolution"), "Resolution");
  EXPECT_EQ(field_heading("scene"), "Scene");
  EXPECT_EQ(quantity_label("accel_max_mps2"), "Accel max (m/s^2)");
  // A column group: the field, the value and its unit.
  EXPECT_EQ(field_value_heading("resolution", 64), "Resolution = 64");
  EXPECT_EQ(field_value_heading("speed_mps", 2.5), "Speed = 2.5 m/s");
  EXPECT_EQ(field_value_heading("scene", "two_barriers"), "Scene = two_barriers");
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
  // Everything: mean ± sd [95 % interval] (n, failed). path_ratio is >= 0: its interval is on the log
  // scale, mean / f to mean * f with f = exp(t(0.975, 2) * sd / sqrt(3) / mean): 2 ± 1 -> f = 3.4628,
  // [0.58, 6.93]; 1.2 ± 0.2 -> f = 1.5129, [0.79, 1.82].
  const CellFormat everything{.stat = CellStat::mean_sd_ci, .with_n = true};
  const std::string md = format_metric_table(table("resolution", "scene", {"success", "path_ratio"}),
                                             TableFormat::markdown, everything);
  EXPECT_EQ(md,
            "| Resolution | Scene = two_barriers: Success rate (%) | Scene = two_barriers: Normalized path length, "
            "all runs | Scene = trees: Success rate (%) | Scene = trees: Normalized path length, all runs |\n"
            "| --- | ---: | ---: | ---: | ---: |\n"
            "| 32 | 67% [21, 94] (n=3) | 2.00 ± 1.00 [0.58, 6.93] (n=3) | 100% [44, 100] (n=3) | "
            "1.20 ± 0.20 [0.79, 1.82] (n=3) |\n"
            "| 16 | 33% [6, 79] (n=3, 2 failed) | 1.50 (n=1, 2 failed) | 0% [0, 56] (n=3, 1 failed) | "
            "2.00 ± 0.00 [2.00, 2.00] (n=2, 1 failed) |\n");
  // The default: mean ± sd, the failed runs, no n; a rate alone.
  const std::string plain = format_metric_table(table("resolution", "scene", {"success", "path_ratio"}),
                                                TableFormat::markdown);
  EXPECT_THAT(plain, HasSubstr("| 32 | 67% | 2.00 ± 1.00 | 100% | 1.20 ± 0.20 |\n"));
  EXPECT_THAT(plain, HasSubstr("| 16 | 33% (2 failed) | 1.50 (2 failed) | 0% (1 failed) | 2.00 ± 0.00 (1 failed) |\n"));
  // The mean alone, the mean with its interval, with n.
  const auto row32 = [&](CellFormat format) {
    const std::string text = format_metric_table(table("resolution", "", {"path_ratio"}), TableFormat::markdown, format);
    return text.substr(text.find("| 32 |"), text.find('\n', text.find("| 32 |")) - text.find("| 32 |"));
  };
  // Resolution 32 over both scenes: 1, 2, 3, 1.2, 1.4, 1.0: mean 1.6, sd sqrt(3.04 / 5) = 0.780;
  // f = exp(t(0.975, 5) sd / sqrt(6) / 1.6).
  const double f = std::exp(2.57058184 * std::sqrt(3.04 / 5.0) / std::sqrt(6.0) / 1.6);
  char interval[64];
  std::snprintf(interval, sizeof interval, "[%.2f, %.2f]", 1.6 / f, 1.6 * f);
  EXPECT_EQ(row32({.stat = CellStat::mean}), "| 32 | 1.60 |");
  EXPECT_EQ(row32({.stat = CellStat::mean_ci}), "| 32 | 1.60 " + std::string(interval) + " |");
  EXPECT_EQ(row32({.stat = CellStat::mean_sd, .with_n = true}), "| 32 | 1.60 ± 0.78 (n=6) |");
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
  // path_ratio is >= 0: mean / f, mean * f with f = exp(t sd / sqrt(n) / mean).
  const double f2 = std::exp(half / 2.0), f12 = std::exp(0.2 * half / 1.2);
  expect(2, {"32", "two_barriers", "path_ratio", "all", "mean", "3", "0", "3"}, {2.0, 1.0, 2.0 / f2, 2.0 * f2});
  expect(3, {"32", "trees", "success", "all", "rate", "3", "0", "3"}, {1.0, 0.0, 0.43850297, 1.0});
  expect(4, {"32", "trees", "path_ratio", "all", "mean", "3", "0", "3"}, {1.2, 0.2, 1.2 / f12, 1.2 * f12});
  expect(5, {"16", "two_barriers", "success", "all", "rate", "3", "2", "3"}, {1.0 / 3.0, std::sqrt(1.0 / 3.0), 0.06149194, 0.79234040});
  expect(6, {"16", "two_barriers", "path_ratio", "all", "mean", "3", "2", "1"}, {1.5, 0.0, none, none});
  expect(8, {"16", "trees", "path_ratio", "all", "mean", "3", "1", "2"}, {2.0, 0.0, 2.0, 2.0});
}

TEST_F(MetricTableTest, LatexIsBooktabsWithGroupsHeadedByFieldAndValue) {
  const std::string tex = format_metric_table(table("scene", "resolution", {"success", "path_ratio"}),
                                              TableFormat::latex);
  EXPECT_EQ(tex,
            "% needs \\usepackage{booktabs}\n"
            "\\begin{tabular}{lrrrr}\n"
            "\\toprule\n"
            " & \\multicolumn{2}{c}{Resolution = 32} & \\multicolumn{2}{c}{Resolution = 16} \\\\\n"
            "\\cmidrule(lr){2-3} \\cmidrule(lr){4-5}\n"
            "Scene & Success rate (\\%) & \\begin{tabular}[b]{@{}c@{}}Normalized path length,\\\\all runs\\end{tabular} & "
            "Success rate (\\%) & \\begin{tabular}[b]{@{}c@{}}Normalized path length,\\\\all runs\\end{tabular} \\\\\n"
            "\\midrule\n"
            "two\\_barriers & 67\\% & 2.00 $\\pm$ 1.00 & 33\\% (2 failed) & 1.50 (2 failed) \\\\\n"
            "trees & 100\\% & 1.20 $\\pm$ 0.20 & 0\\% (1 failed) & 2.00 $\\pm$ 0.00 (1 failed) \\\\\n"
            "\\bottomrule\n"
            "\\end{tabular}\n");
  EXPECT_THAT(tex, Not(HasSubstr("\\hline")));
  // Cell formats apply to LaTeX too.
  const std::string full = format_metric_table(table("scene", "resolution", {"success", "path_ratio"}),
                                               TableFormat::latex, {.stat = CellStat::mean_sd_ci, .with_n = true});
  EXPECT_THAT(full, HasSubstr("two\\_barriers & 67\\% [21, 94] (n=3) & 2.00 $\\pm$ 1.00 [0.58, 6.93] (n=3) &"));
  // Units in the group heading; the summary table is booktabs as well.
  EXPECT_EQ(field_value_heading("speed_mps", 2), "Speed = 2 m/s");
  const std::string summary = format_table(aggregate(runs_, layout_), TableFormat::latex);
  EXPECT_THAT(summary, HasSubstr("\\toprule\nScene & Resolution & Runs"));
  EXPECT_THAT(summary, HasSubstr(" & \\begin{tabular}[b]{@{}c@{}}Time (s),\\\\reached runs\\end{tabular} & "));
  EXPECT_THAT(summary, HasSubstr(" & Replanning (ms, median) & "));
  EXPECT_THAT(summary, HasSubstr("\\bottomrule\n\\end{tabular}\n"));
  EXPECT_THAT(summary, Not(HasSubstr("\\hline")));
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
  std::string text(std::vector<std::string> metrics, TableFormat format, const CellFormat& cell = {}) const {
    return format_metric_table(table(std::move(metrics)), format, cell);
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
  // t(0.975, 1) sd / sqrt(2) / mean on the log scale: 1.2 / exp(12.7062047 * 0.1 / 1.2).
  EXPECT_NEAR(c.metrics[1]->ci95->low, 1.2 / std::exp(12.7062047 * 0.1 / 1.2), 1e-6);
  EXPECT_EQ(c.metrics[2]->n, 3);
  EXPECT_DOUBLE_EQ(c.metrics[2]->mean, 0.9);
  EXPECT_NEAR(c.metrics[2]->sd, std::sqrt(0.28), 1e-12);  // (0.04 + 0.16 + 0.36) / 2
  EXPECT_DOUBLE_EQ(c.metrics[3]->mean, 25.0);
  EXPECT_NEAR(c.metrics[3]->sd, std::sqrt(50.0), 1e-12);
  EXPECT_DOUBLE_EQ(c.metrics[4]->mean, 55.0 / 3.0);
  EXPECT_DOUBLE_EQ(c.metrics[5]->mean, 12.0);  // 11 and 13 m

  // Two reached runs: f = exp(12.7062047 * 0.1 / 1.2) = 2.88305, [0.42, 3.46] (the t interval: [-0.07, 2.47]);
  // three completed: f = exp(4.30265273 * sqrt(0.28 / 3) / 0.9) = 4.30827, [0.209, 3.877].
  const std::string md = text({"success", "path_ratio@reached", "path_ratio"}, TableFormat::markdown,
                              {.stat = CellStat::mean_sd_ci, .with_n = true});
  EXPECT_EQ(md,
            "| Resolution | Success rate (%) | Normalized path length, reached runs | "
            "Normalized path length, all runs |\n"
            "| --- | ---: | ---: | ---: |\n"
            "| 32 | 50% [15, 85] (n=4, 1 failed) | 1.20 ± 0.14 [0.42, 3.46] (n=2, 1 failed) | "
            "0.900 ± 0.529 [0.209, 3.877] (n=3, 1 failed) |\n");
  // The times of the two reached runs, 20 s and 30 s: never below 0 s (the t interval's low end is -38.5 s).
  EXPECT_NEAR(c.metrics[3]->ci95->low, 25.0 / 12.6954155, 1e-6);
  const std::string tex = text({"path_ratio@reached", "path_ratio"}, TableFormat::latex);
  EXPECT_THAT(tex, HasSubstr("Resolution & \\begin{tabular}[b]{@{}c@{}}Normalized path length,\\\\reached runs\\end{tabular} & "
                             "\\begin{tabular}[b]{@{}c@{}}Normalized path length,\\\\all runs\\end{tabular} \\\\\n"));

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

  const CellFormat everything{.stat = CellStat::mean_sd_ci, .with_n = true};
  const std::string md = text({"success", "path_ratio@reached", "hovered"}, TableFormat::markdown, everything);
  EXPECT_THAT(md, HasSubstr("| 16 | 100% (n=3 identical runs: seeds vary nothing) | "
                            "1.20 (n=3 identical runs: seeds vary nothing) | "
                            "100% (n=3 identical runs: seeds vary nothing) |\n"));
  EXPECT_THAT(md, Not(HasSubstr("±")));
  EXPECT_THAT(md, Not(HasSubstr("[")));
  EXPECT_THAT(text({"path_ratio"}, TableFormat::latex), HasSubstr("16 & 1.20 (identical runs) \\\\"));
  EXPECT_THAT(text({"path_ratio"}, TableFormat::latex, everything),
              HasSubstr("16 & 1.20 (n=3 identical runs: seeds vary nothing) \\\\"));
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
  EXPECT_THAT(text({"path_ratio@reached"}, TableFormat::markdown, {.with_n = true}),
              HasSubstr("| 16 | – (n=0 of 3 identical runs: seeds vary nothing) |"));
}

TEST_F(OwnResultsTest, DistinctRunsStillPrintTheirInterval) {
  // The same metrics but another trajectory in seed 2.
  std::vector<nlohmann::json> lines = repeated_run();
  lines[1]["trajectory_sha256"] = "another-trajectory";
  use(lines);
  EXPECT_FALSE(table({"success"}).cells[0][0].identical);
  EXPECT_THAT(text({"success", "path_ratio"}, TableFormat::markdown, {.stat = CellStat::mean_sd_ci, .with_n = true}),
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
  EXPECT_EQ(metric_label("path_ratio@reached"), "Normalized path length, reached runs");
  EXPECT_EQ(metric_heading("path_ratio@reached"), "Normalized path length, reached runs");
  EXPECT_EQ(metric_heading("sim_time_s"), "Sim time (s), all runs");
  EXPECT_EQ(metric_heading("success"), "Success rate (%)");
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
