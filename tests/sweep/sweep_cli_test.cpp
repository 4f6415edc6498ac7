// `campo sweep` and `campo table` run as a user would: a tiny sweep end to end.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include "tests/cli_support.hpp"

namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::StartsWith;

using campo::testing::Result;
using campo::testing::lines_of;
using campo::testing::slurp;

// Two barriers with the straight planner, the scanner at 16 and 32 columns, one seed, 5 s.
constexpr const char* kTinySpec = R"({
  "campo_sweep": 1,
  "name": "tiny",
  "scenes": ["two_barriers"],
  "set": { "/objects/drone/planner/name": "straight", "/world/time_limit_s": 5,
           "/objects/drone/sensors/scanner/resolution": [16, 16] },
  "axes": [ { "name": "resolution", "values": [16, 32],
              "set": ["/objects/drone/sensors/scanner/resolution/0"] } ],
  "seeds": { "first": 1, "count": 1 },
  "start_jitter": { "vehicle": "drone", "radius_m": 0.25 }
})";

class SweepCli : public campo::testing::CliTest {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    write("tiny.json", kTinySpec);
  }
};

TEST_F(SweepCli, RunsEveryRunThenTabulatesAndCharts) {
  const fs::path out = dir_ / "out";
  const Result sweep = campo("sweep " + (dir_ / "tiny.json").string() + " --out " + out.string());
  ASSERT_EQ(sweep.exit_code, 0) << sweep.err;
  EXPECT_THAT(sweep.err, HasSubstr("[1/2] two_barriers__resolution-16__seed-1: timeout"));
  EXPECT_THAT(sweep.err, HasSubstr("[2/2] two_barriers__resolution-32__seed-1: timeout"));

  const auto results = lines_of(slurp(out / "results.jsonl"));
  ASSERT_EQ(results.size(), 2u);
  const nlohmann::json first = nlohmann::json::parse(results[0]);
  EXPECT_EQ(first["id"], "two_barriers__resolution-16__seed-1");
  EXPECT_EQ(first["status"], "completed");
  EXPECT_EQ(first["params"], nlohmann::json({{"resolution", 16}}));
  EXPECT_EQ(first["seed"], 1);
  EXPECT_EQ(first["run_dir"], "runs/two_barriers__resolution-16__seed-1");
  EXPECT_EQ(first["metrics"]["outcome"], "timeout");
  EXPECT_EQ(first["scene_sha256"].get<std::string>().size(), 64u);
  EXPECT_TRUE(first.contains("campo_version") && first.contains("git_rev"));
  EXPECT_EQ(first["overrides"].back().get<std::string>().rfind("/objects/drone/pose/position_m=", 0), 0u);
  // Each run's record, with the resolution the axis set.
  const nlohmann::json record = nlohmann::json::parse(slurp(out / first["run_dir"].get<std::string>() / "run.json"));
  EXPECT_EQ(record["overrides"], first["overrides"]);
  EXPECT_FALSE(fs::exists(out / first["run_dir"].get<std::string>() / "map.png"));  // no --figures
  EXPECT_EQ(nlohmann::json::parse(slurp(out / "sweep.json"))["runs"].size(), 2u);

  // Run again: everything is already done.
  const Result again = campo("sweep " + (dir_ / "tiny.json").string() + " --out " + out.string());
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_THAT(again.err, HasSubstr("[2/2] two_barriers__resolution-32__seed-1: already completed, skipped"));
  EXPECT_EQ(lines_of(slurp(out / "results.jsonl")).size(), 2u);

  const Result table = campo("table " + out.string() + " --format csv");
  ASSERT_EQ(table.exit_code, 0) << table.err;
  const auto rows = lines_of(table.out);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_THAT(rows[0], StartsWith("scene,resolution,runs,success_rate,"));
  EXPECT_THAT(rows[1], StartsWith("two_barriers,16,1,0,0,0,0,0,"));
  EXPECT_THAT(rows[2], StartsWith("two_barriers,32,1,0,"));
  EXPECT_THAT(table.err, HasSubstr("chart.png"));
  const cv::Mat chart = cv::imread((out / "chart.png").string());
  ASSERT_FALSE(chart.empty());
  EXPECT_EQ(chart.type(), CV_8UC3);

  const Result markdown = campo("table " + out.string() + " --no-chart");
  ASSERT_EQ(markdown.exit_code, 0) << markdown.err;
  EXPECT_THAT(markdown.out, HasSubstr("| two_barriers | 32 | 1 | 0% |"));
}

TEST_F(SweepCli, ARunThatFailsIsRecordedAndTheSweepGoesOn) {
  // A file where the first run's directory should be: that run cannot write its outputs.
  const fs::path out = dir_ / "out";
  fs::create_directories(out / "runs");
  std::ofstream(out / "runs" / "two_barriers__resolution-16__seed-1") << "in the way";
  const Result sweep = campo("sweep " + (dir_ / "tiny.json").string() + " --out " + out.string());
  EXPECT_EQ(sweep.exit_code, 1);
  EXPECT_THAT(sweep.err, HasSubstr("[1/2] two_barriers__resolution-16__seed-1: failed: "));
  const auto results = lines_of(slurp(out / "results.jsonl"));
  ASSERT_EQ(results.size(), 2u);
  const nlohmann::json failed = nlohmann::json::parse(results[0]);
  EXPECT_EQ(failed["status"], "failed");
  EXPECT_FALSE(failed["reason"].get<std::string>().empty());
  EXPECT_TRUE(failed["metrics"].is_null());
  EXPECT_EQ(nlohmann::json::parse(results[1])["status"], "completed");

  const Result table = campo("table " + out.string() + " --format csv --no-chart");
  ASSERT_EQ(table.exit_code, 0) << table.err;
  EXPECT_THAT(table.out, HasSubstr("\ntwo_barriers,16,1,0,,,,,,,,,,,0,,,1\n"));
}

TEST_F(SweepCli, BadSpecWritesNothing) {
  std::string spec = kTinySpec;
  spec.replace(spec.find("/resolution/0"), 13, "/resolutoin/0");
  std::ofstream(dir_ / "bad.json") << spec;
  const Result r = campo("sweep " + (dir_ / "bad.json").string() + " --out " + (dir_ / "out").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("bad.json: /scenes/0: run two_barriers__resolution-16__seed-1: "));
  EXPECT_THAT(r.err, HasSubstr("resolutoin"));
  EXPECT_FALSE(fs::exists(dir_ / "out"));
}

TEST_F(SweepCli, DryRunPrintsTheManifest) {
  const Result r = campo("sweep " + (dir_ / "tiny.json").string() + " --dry-run");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json manifest = nlohmann::json::parse(r.out);
  ASSERT_EQ(manifest["runs"].size(), 2u);
  EXPECT_EQ(manifest["runs"][1]["id"], "two_barriers__resolution-32__seed-1");
  EXPECT_THAT(r.err, HasSubstr("2 runs"));
}

TEST_F(SweepCli, HelpHasExamples) {
  for (const char* sub : {"sweep", "table"}) {
    const Result help = campo(std::string(sub) + " --help");
    EXPECT_EQ(help.exit_code, 0) << sub;
    EXPECT_THAT(help.out, HasSubstr("Usage")) << sub;
    EXPECT_THAT(help.out, HasSubstr("Example: campo " + std::string(sub))) << sub;
  }
}

}  // namespace
