// Reading results.jsonl a line at a time and folding the runs into rows, cells and boxes in
// bounded memory (docs/limits.md, "Post-processing"): reruns, line limits, the running
// statistics against the two-pass ones, the quantile sketch against exact quantiles, and
// the peak memory of `campo table` and `campo plot` against the size of the file.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include "sweep/results.hpp"
#include "sweep/statistics.hpp"
#include "sweep/table.hpp"
#include "tests/cli_support.hpp"
#include "tests/sweep/results_fixture.hpp"
#include "tests/sanitizers.hpp"

namespace campo {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using testing::fixture_line;
using testing::fixture_run;

class ResultsStream : public testing::CliTest {};

TEST_F(ResultsStream, EachIdsLastLineIsVisitedInThePlaceOfItsFirst) {
  // A resumed sweep: a failed, then a rerun that completed, appended after another run.
  const std::string file = write("results.jsonl", fixture_line("trees", 32, 1, "failed", 0, 0) +
                                                      fixture_line("trees", 32, 2, "reached", 1.4, 70, 1.0) +
                                                      fixture_line("trees", 32, 1, "reached", 1.2, 50, 1.0) +
                                                      fixture_line("trees", 16, 3, "timeout", 2.0, 100));
  int restarts = 0;
  std::vector<std::pair<std::size_t, std::string>> visited;
  std::vector<std::string> warnings;
  for_each_result(
      file, warnings,
      [&] {
        ++restarts;
        visited.clear();
      },
      [&](const RunResult& run, std::size_t index) {
        visited.emplace_back(index, run.name + (run.completed ? "" : " failed"));
      });
  EXPECT_EQ(restarts, 2);  // an ID with two lines: read again
  EXPECT_TRUE(warnings.empty());
  const std::vector<std::pair<std::size_t, std::string>> expected{{1, "trees__resolution-32__seed-2"},
                                                                  {0, "trees__resolution-32__seed-1"},
                                                                  {2, "trees__resolution-16__seed-3"}};
  EXPECT_EQ(visited, expected);
  // read_results: the same runs in order of first appearance; and the table counts the rerun once.
  const ResultsFile results = read_results(file);
  ASSERT_EQ(results.runs.size(), 3u);
  EXPECT_TRUE(results.runs[0].completed);
  EXPECT_EQ(results.runs[0].name, "trees__resolution-32__seed-1");
  const SweepTable table = aggregate(results.runs, table_layout(dir_, results.runs));
  ASSERT_EQ(table.rows.size(), 2u);
  EXPECT_EQ(table.rows[0].runs, 2);
  EXPECT_EQ(table.rows[0].failed, 0);
}

TEST_F(ResultsStream, ReadOnceWithoutRepeatedIdsAndLongLinesAreRefused) {
  const std::string file = write("results.jsonl", fixture_line("trees", 32, 1, "reached", 1.2, 50) +
                                                      fixture_line("trees", 32, 2, "reached", 1.4, 70));
  int restarts = 0, visits = 0;
  std::vector<std::string> warnings;
  for_each_result(file, warnings, [&] { ++restarts; }, [&](const RunResult&, std::size_t) { ++visits; });
  EXPECT_EQ(restarts, 1);
  EXPECT_EQ(visits, 2);
  // A line longer than the limit is refused naming it, before it is held whole.
  try {
    for_each_result(file, warnings, [] {}, [](const RunResult&, std::size_t) {}, {.max_line_bytes = 100});
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("results.jsonl line 1: line too long: expected at most 100 bytes"));
  }
}

TEST(RunningStats, AgreesWithTheTwoPassSummary) {
  std::mt19937 random(7);
  std::normal_distribution<double> normal(1e3, 0.01);  // a large mean and a small spread: cancellation's worst case
  for (const std::size_t n : {1u, 2u, 3u, 10u, 1000u}) {
    std::vector<double> values;
    RunningStats running;
    for (std::size_t i = 0; i < n; ++i) {
      values.push_back(normal(random));
      running.add(values.back());
    }
    const Summary want = summarize_values(values), got = running.values();
    EXPECT_EQ(got.n, want.n);
    EXPECT_EQ(got.mean, want.mean) << n;  // the same sum in the same order
    EXPECT_NEAR(got.sd, want.sd, 1e-9 * want.sd + 1e-15) << n;
    ASSERT_EQ(got.ci95.has_value(), want.ci95.has_value());
    if (want.ci95) EXPECT_NEAR(got.ci95->high, want.ci95->high, 1e-9);
  }
  RunningStats same;
  for (int i = 0; i < 5; ++i) same.add(1.2);
  EXPECT_EQ(same.values().sd, 0.0);  // equal values: no spread, exactly
  RunningStats rate;
  for (double v : {1.0, 0.0, 1.0}) rate.add(v);
  EXPECT_EQ(rate.rate().mean, summarize_rate(2, 3).mean);
  EXPECT_EQ(rate.rate().ci95->low, summarize_rate(2, 3).ci95->low);
}

TEST(QuantileSketch, ExactUpToItsLimit) {
  std::mt19937 random(3);
  std::lognormal_distribution<double> skewed(0.0, 1.5);  // outliers on the high side
  QuantileSketch sketch;
  std::vector<double> values;
  for (std::size_t i = 0; i < QuantileSketch::kExactValues; ++i) {
    values.push_back(skewed(random));
    sketch.add(values.back());
  }
  const BoxStats want = box_stats(values), got = sketch.box();
  EXPECT_EQ(got.q1, want.q1);
  EXPECT_EQ(got.median, want.median);
  EXPECT_EQ(got.q3, want.q3);
  EXPECT_EQ(got.whisker_high, want.whisker_high);
  EXPECT_EQ(got.outliers, want.outliers);
  EXPECT_EQ(sketch.median(), want.median);
}

TEST(QuantileSketch, WithinItsStatedRankErrorForAMillionValues) {
  // 0 .. n-1 in a shuffled order: the value at rank r is r, so a quantile's rank error is its error.
  constexpr std::size_t n = 1000000;
  std::vector<double> values(n);
  std::iota(values.begin(), values.end(), 0.0);
  std::shuffle(values.begin(), values.end(), std::mt19937(11));
  QuantileSketch sketch;
  for (double v : values) sketch.add(v);
  const double k = QuantileSketch::kExactValues;
  const double bound = (1.0 + std::log2(n / k)) * n / k;  // documented: 0.22 % of the values
  const BoxStats b = sketch.box();
  EXPECT_NEAR(b.q1, 0.25 * (n - 1), bound);
  EXPECT_NEAR(b.median, 0.5 * (n - 1), bound);
  EXPECT_NEAR(b.q3, 0.75 * (n - 1), bound);
  EXPECT_NEAR(sketch.median(), 0.5 * (n - 1), bound);
  // Uniform values have no outliers; the whiskers reach the exact extremes.
  EXPECT_TRUE(b.outliers.empty());
  EXPECT_EQ(b.whisker_low, 0.0);
  EXPECT_EQ(b.whisker_high, n - 1.0);
  // The same values in the same order give the same box.
  QuantileSketch again;
  for (double v : values) again.add(v);
  EXPECT_EQ(again.box().median, b.median);
}

// Peak resident memory of `campo ARGS` in KiB (wait4's ru_maxrss), -1 when it did not exit 0.
long campo_peak_kib(const std::string& args, const fs::path& err) {
  const std::string command = "exec " + std::string(CAMPO_BINARY) + " " + args + " >/dev/null 2>" + err.string();
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  int status = 0;
  rusage usage{};
  if (pid < 0 || ::wait4(pid, &status, 0, &usage) != pid) return -1;
  return WIFEXITED(status) && WEXITSTATUS(status) == 0 ? usage.ru_maxrss : -1;
}

// A sweep directory of `runs` results lines of about 1.4 KB each (as campo sweep writes: a
// run.json's forty metrics), two resolutions, a few scenes; no sweep.json.
void write_results(const fs::path& dir, int runs) {
  fs::create_directories(dir);
  std::ofstream out(dir / "results.jsonl", std::ios::binary);
  for (int i = 0; i < runs; ++i) {
    const char* outcome = i % 5 == 0 ? "timeout" : i % 17 == 0 ? "failed" : "reached";
    nlohmann::json line = fixture_run(i % 3 == 0 ? "trees" : "two_barriers", i % 2 == 0 ? 16 : 32, i, outcome,
                                      1.0 + (i % 97) * 0.01, 10.0 + i % 13, 0.5);
    if (line["status"] == "completed") {
      for (int m = 0; m < 32; ++m) line["metrics"]["extra_metric_" + std::to_string(m) + "_m"] = 0.001 * ((i * 31 + m) % 1000);
    }
    out << line.dump() << "\n";
  }
}

TEST_F(ResultsStream, PeakMemoryOfTableAndPlotDoesNotGrowWithTheFile) {
#if defined(CAMPO_TEST_UNDER_ASAN)
  GTEST_SKIP() << "AddressSanitizer keeps freed memory in quarantine: the plain build measures this";
#endif
  // 1,000 and 10,000 runs: about 1.5 and 15 MB. Holding the runs (5.7 times the file before
  // streaming) would add some 75 MB; the bound leaves 12 MB for noise.
  const fs::path small = dir_ / "small", big = dir_ / "big";
  write_results(small, 1000);
  write_results(big, 10000);
  ASSERT_GT(fs::file_size(big / "results.jsonl"), 13u << 20);
  const fs::path err = dir_ / "err";
  for (const std::string& args :
       {std::string("table DIR --rows resolution --cols scene --metrics success,path_ratio,extra_metric_3_m --no-chart"),
        std::string("plot DIR --x scene --y path_ratio --kind box --out DIR/box.png")}) {
    const auto with = [&](const fs::path& dir) {
      std::string a = args;
      for (std::size_t at; (at = a.find("DIR")) != std::string::npos;) a.replace(at, 3, dir.string());
      return a;
    };
    const long small_kib = campo_peak_kib(with(small), err);
    ASSERT_GT(small_kib, 0) << testing::slurp(err);
    const long big_kib = campo_peak_kib(with(big), err);
    ASSERT_GT(big_kib, 0) << testing::slurp(err);
    EXPECT_LT(big_kib, small_kib + 12 * 1024) << args << ": " << small_kib << " KiB for 1.5 MB, " << big_kib
                                              << " KiB for 15 MB";
  }
  // And the big table counts every run.
  const testing::Result r = campo("table " + big.string() + " --rows resolution --metrics success --format csv --no-chart");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("\n16,success,all,rate,5000,"));
  EXPECT_THAT(r.out, HasSubstr("\n32,success,all,rate,5000,"));
}

}  // namespace
}  // namespace campo
