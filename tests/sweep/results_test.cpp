// results.jsonl: reading (a killed sweep's partial line), aggregation and the table formats.
#include "sweep/results.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "campo/json_reader.hpp"
#include "sweep/table.hpp"

namespace campo {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// One completed line with the metrics the table reads.
std::string completed(const std::string& id, int resolution, int seed, const std::string& outcome, double reached,
                      double discarded, double length, double ratio, double time, int collisions, int replans,
                      double replan_median, double replan_max, const nlohmann::json& min_clearance = nullptr) {
  const nlohmann::json line = {
      {"id", id}, {"scene", "two_barriers"}, {"params", {{"resolution", resolution}}}, {"seed", seed},
      {"status", "completed"}, {"overrides", {"/world/seed=" + std::to_string(seed)}}, {"run_dir", "runs/" + id},
      {"metrics", {{"outcome", outcome}, {"reason", "r"}, {"waypoints_reached", reached},
                   {"waypoints_discarded", discarded}, {"path_length_m", length}, {"path_ratio", ratio},
                   {"sim_time_s", time}, {"collisions", collisions}, {"replans", replans},
                   {"replan_time_ms_median", replan_median}, {"replan_time_ms_max", replan_max},
                   {"min_clearance_m", min_clearance}}},
      {"campo_version", "0.1.0"}, {"git_rev", "abc"}, {"scene_sha256", "00"}};
  return line.dump() + "\n";
}

std::string failed(const std::string& id, int resolution, int seed) {
  const nlohmann::json line = {
      {"id", id}, {"scene", "two_barriers"}, {"params", {{"resolution", resolution}}}, {"seed", seed},
      {"status", "failed"}, {"reason", "out of memory"}, {"overrides", nlohmann::json::array()},
      {"run_dir", "runs/" + id}, {"metrics", nullptr}, {"campo_version", "0.1.0"}, {"git_rev", "abc"},
      {"scene_sha256", "00"}};
  return line.dump() + "\n";
}

class ResultsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("campo_sweep_results_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    // Resolution 32 first in the file; its only run failed, then completed when resumed.
    std::ofstream(dir_ / "results.jsonl")
        << failed("b1", 32, 1)                                                      //
        << completed("a1", 16, 1, "reached", 2, 0, 10, 1.0, 50, 0, 4, 10, 30, 0.3)      //
        << completed("a2", 16, 2, "reached", 3, 0, 12, 1.2, 60, 0, 2, 20, 25, 0.12)     //
        << completed("a3", 16, 3, "collision", 4, 3, 14, 1.4, 100, 1, 0, 0, 0, -0.01)  //
        << failed("a4", 16, 4)                                                      //
        << completed("b1", 32, 1, "reached", 1, 1, 8, 1.1, 40, 0, 1, 7, 7)          //
        << R"({"id": "a5", "scene": "two_barr)";  // killed mid-write
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path dir_;
};

TEST_F(ResultsTest, ReadsLinesKeepingTheLastOfEachIdAndIgnoringAPartialLastLine) {
  const ResultsFile results = read_results(dir_ / "results.jsonl");
  ASSERT_EQ(results.runs.size(), 5u);
  EXPECT_EQ(results.runs[0].id, "b1");
  EXPECT_TRUE(results.runs[0].completed);  // the later line
  EXPECT_EQ(results.runs[4].id, "a4");
  EXPECT_FALSE(results.runs[4].completed);
  EXPECT_EQ(results.runs[4].reason, "out of memory");
  EXPECT_EQ(results.runs[1].metrics.path_ratio, 1.0);
  ASSERT_EQ(results.warnings.size(), 1u);
  EXPECT_THAT(results.warnings[0], HasSubstr("results.jsonl line 7 is incomplete"));
}

TEST_F(ResultsTest, AggregatesMeanSampleSdAndMedianPerGroup) {
  const ResultsFile results = read_results(dir_ / "results.jsonl");
  // The expansion order puts resolution 16 first.
  const TableLayout layout{"t", {"resolution"}, {"a1", "a2", "a3", "a4", "a5", "b1"}};
  const SweepTable table = aggregate(results.runs, layout);
  ASSERT_EQ(table.rows.size(), 2u);
  const TableRow& a = table.rows[0];
  EXPECT_EQ(a.scene, "two_barriers");
  EXPECT_EQ(a.params, std::vector<nlohmann::json>{16});
  EXPECT_EQ(a.runs, 4);
  EXPECT_EQ(a.failed, 1);
  EXPECT_DOUBLE_EQ(a.success_rate, 0.5);  // 2 reached of 4 runs, the failed one included
  EXPECT_DOUBLE_EQ(a.waypoints_reached->mean, 3.0);
  EXPECT_DOUBLE_EQ(a.waypoints_reached->sd, 1.0);
  EXPECT_DOUBLE_EQ(a.waypoints_discarded->mean, 1.0);
  EXPECT_DOUBLE_EQ(a.waypoints_discarded->sd, std::sqrt(3.0));
  EXPECT_DOUBLE_EQ(a.path_length_m->mean, 12.0);
  EXPECT_DOUBLE_EQ(a.path_length_m->sd, 2.0);
  EXPECT_DOUBLE_EQ(a.path_ratio->mean, 1.2);
  EXPECT_NEAR(a.path_ratio->sd, 0.2, 1e-12);
  EXPECT_DOUBLE_EQ(a.time_s->mean, 70.0);
  EXPECT_DOUBLE_EQ(a.time_s->sd, std::sqrt(700.0));
  // The same over the two runs that reached the goal (a1, a2), leaving the collision out.
  EXPECT_EQ(a.reached, 2);
  EXPECT_DOUBLE_EQ(a.path_length_m_reached->mean, 11.0);
  EXPECT_DOUBLE_EQ(a.path_length_m_reached->sd, std::sqrt(2.0));
  EXPECT_DOUBLE_EQ(a.path_ratio_reached->mean, 1.1);
  EXPECT_NEAR(a.path_ratio_reached->sd, std::sqrt(0.02), 1e-12);
  EXPECT_DOUBLE_EQ(a.time_s_reached->mean, 55.0);
  EXPECT_DOUBLE_EQ(a.time_s_reached->sd, std::sqrt(50.0));
  EXPECT_FALSE(a.identical);
  EXPECT_EQ(a.collisions, 1);
  EXPECT_DOUBLE_EQ(*a.min_clearance_m, -0.01);  // the closest call: the collision's overlap
  // Median over the runs that replanned (10 and 20 ms; the third never replanned).
  EXPECT_DOUBLE_EQ(*a.replan_ms_median, 15.0);
  EXPECT_DOUBLE_EQ(*a.replan_ms_max, 30.0);

  const TableRow& b = table.rows[1];
  EXPECT_EQ(b.params, std::vector<nlohmann::json>{32});
  EXPECT_EQ(b.runs, 1);
  EXPECT_EQ(b.failed, 0);
  EXPECT_DOUBLE_EQ(b.success_rate, 1.0);
  EXPECT_DOUBLE_EQ(b.path_ratio->sd, 0.0);  // one run
  EXPECT_DOUBLE_EQ(*b.replan_ms_median, 7.0);

  // Without a manifest: the order of appearance in results.jsonl, the axes from the params.
  const SweepTable unordered = aggregate(results.runs, table_layout(dir_, results.runs));
  EXPECT_EQ(unordered.axes, std::vector<std::string>{"resolution"});
  EXPECT_EQ(unordered.rows[0].params, std::vector<nlohmann::json>{32});
}

TEST_F(ResultsTest, GroupsWithoutCompletedRunsHaveEmptyStatistics) {
  std::ofstream(dir_ / "results.jsonl") << failed("x", 8, 1);
  const ResultsFile results = read_results(dir_ / "results.jsonl");
  const SweepTable table = aggregate(results.runs, table_layout(dir_, results.runs));
  ASSERT_EQ(table.rows.size(), 1u);
  EXPECT_FALSE(table.rows[0].path_ratio);
  EXPECT_FALSE(table.rows[0].path_ratio_reached);
  EXPECT_FALSE(table.rows[0].replan_ms_median);
  EXPECT_FALSE(table.rows[0].identical);  // one run, and failed
  EXPECT_EQ(format_table(table, TableFormat::csv).substr(format_table(table, TableFormat::csv).find('\n') + 1),
            "two_barriers,8,1,0,0," + std::string(16, ',') + "0,,,,1,false\n");
}

TEST_F(ResultsTest, CsvHasExactlyTheDocumentedColumns) {
  const ResultsFile results = read_results(dir_ / "results.jsonl");
  const SweepTable table = aggregate(results.runs, {"t", {"resolution"}, {"a1", "b1"}});
  const std::string csv = format_table(table, TableFormat::csv);
  std::istringstream lines(csv);
  std::string header, first, second, extra;
  std::getline(lines, header);
  std::getline(lines, first);
  std::getline(lines, second);
  EXPECT_FALSE(std::getline(lines, extra));
  EXPECT_EQ(header,
            "scene,resolution,runs,success_rate,reached_runs,waypoints_reached_mean,waypoints_reached_sd,"
            "waypoints_discarded_mean,waypoints_discarded_sd,path_length_m_mean,path_length_m_sd,"
            "path_length_m_reached_mean,path_length_m_reached_sd,path_ratio_mean,path_ratio_sd,"
            "path_ratio_reached_mean,path_ratio_reached_sd,time_s_mean,time_s_sd,time_s_reached_mean,time_s_reached_sd,"
            "collisions,min_clearance_m_min,replan_ms_median,replan_ms_max,failed,identical");
  EXPECT_THAT(first, ::testing::StartsWith("two_barriers,16,4,0.5,2,3,1,1,"));
  EXPECT_THAT(first, HasSubstr(",12,2,11,1.414"));  // path length: all completed runs, then the reached ones
  EXPECT_THAT(first, ::testing::EndsWith(",1,-0.01,15,30,1,false"));
  EXPECT_EQ(second, "two_barriers,32,1,1,1,1,0,1,0,8,0,8,0,1.1,0,1.1,0,40,0,40,0,0,,7,7,0,false");  // no clearance
}

TEST_F(ResultsTest, MarkdownAndLatexShowMeanAndSpread) {
  const ResultsFile results = read_results(dir_ / "results.jsonl");
  const SweepTable table = aggregate(results.runs, {"t", {"resolution"}, {"a1", "b1"}});
  const std::string markdown = format_table(table, TableFormat::markdown);
  EXPECT_THAT(markdown, HasSubstr("| Scene | Resolution | Runs | Success | Reached runs | Waypoints reached | "
                                  "Discarded | Path length (m), all runs | Path length (m), reached runs | "
                                  "Normalized length, all runs | Normalized length, reached runs | Time (s), all runs | "
                                  "Time (s), reached runs | Collisions | Min clearance (m), closest run | Replanning (ms, median) | "
                                  "Failed |"));
  EXPECT_THAT(markdown, HasSubstr("| two_barriers | 16 | 4 | 50% | 2 | 3.0 ± 1.0 | 1.0 ± 1.7 | 12.00 ± 2.00 | "
                                  "11.00 ± 1.41 | 1.200 ± 0.200 | 1.100 ± 0.141 | 70.0 ± 26.5 | 55.0 ± 7.1 | 1 | "
                                  "-0.010 | 15.00 | 1 |"));
  const std::string latex = format_table(table, TableFormat::latex);
  EXPECT_THAT(latex, HasSubstr("\\begin{tabular}{lrrrrrrrrrrrrrrrr}"));
  EXPECT_THAT(latex, HasSubstr("two\\_barriers & 16 & 4 & 50\\% & 2 & 3.0 $\\pm$ 1.0"));
  EXPECT_THAT(latex, HasSubstr("\\end{tabular}"));
}

TEST_F(ResultsTest, AMalformedLineBeforeTheLastIsAnError) {
  std::ofstream(dir_ / "results.jsonl") << "{not json\n" << failed("x", 8, 1);
  try {
    read_results(dir_ / "results.jsonl");
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("results.jsonl line 1: invalid JSON"));
  }
  std::ofstream(dir_ / "results.jsonl") << R"({"id": "x", "status": "done"})" << "\n";
  try {
    read_results(dir_ / "results.jsonl");
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("results.jsonl line 1: missing required key \"scene\""));
  }
}

TEST_F(ResultsTest, LogCutsAPartialLastLineBeforeAppending) {
  const fs::path file = dir_ / "results.jsonl";
  std::ofstream(file) << failed("x", 8, 1) << R"({"id": "y", "sce)";
  {
    ResultsLog log(file);
    EXPECT_TRUE(log.cut_partial_line());
    log.append({{"k", 1}});
  }
  EXPECT_EQ(slurp(file), failed("x", 8, 1) + "{\"k\":1}\n");
  ResultsLog again(file);
  EXPECT_FALSE(again.cut_partial_line());
}

}  // namespace
}  // namespace campo

namespace campo {
namespace {

// A full disk: the line is refused with the file and the system's reason.
TEST(ResultsLogFullDisk, AppendNamesTheFileAndTheSystemsReason) {
  if (!std::filesystem::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  ResultsLog log("/dev/full");
  try {
    log.append(nlohmann::json{{"id", "a"}});
    ADD_FAILURE() << "expected an OutputError";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "/dev/full: cannot append: No space left on device");
  }
}

}  // namespace
}  // namespace campo
