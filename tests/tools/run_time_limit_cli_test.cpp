// campo run --time-limit: a wall-clock limit for the whole run that ends it
// as failed with its files, and leaves a run within it unchanged.
#include <filesystem>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/cli_support.hpp"

namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

using campo::testing::Result;
using campo::testing::slurp;
using RunTimeLimit = campo::testing::CliTest;

TEST_F(RunTimeLimit, EndsARunPastItAsFailedWithItsFiles) {
  // two_barriers with its mapping planner takes about a second of computing: far past 0.05 s.
  const fs::path out = dir_ / "limited";
  const Result r = campo("run two_barriers --time-limit 0.05 --no-figures --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;  // a failed run is a run: recorded, exit 0
  const std::string reason = "exceeded the wall-clock limit of 0.05 s for the whole run (--time-limit) and was stopped";
  EXPECT_THAT(r.out, HasSubstr("two_barriers: failed (" + reason + ")"));
  const auto run = nlohmann::json::parse(slurp(out / "run.json"));
  EXPECT_EQ(run["metrics"]["outcome"], "failed");
  EXPECT_EQ(run["metrics"]["reason"], reason);
  EXPECT_LT(run["metrics"]["sim_time_s"].get<double>(), 23.0);  // the whole run reaches its goal at 23.9 s
  for (const char* file : {"events.jsonl", "trajectory.csv", "scene.json"}) EXPECT_TRUE(fs::exists(out / file)) << file;
}

TEST_F(RunTimeLimit, LeavesARunWithinItUnchanged) {
  const std::string scene = std::string(CAMPO_SOURCE_DIR) + "/tests/python/fixtures/open_field.json";
  const Result free = campo("run " + scene + " --planner straight --no-figures --out " + (dir_ / "free").string());
  ASSERT_EQ(free.exit_code, 0) << free.err;
  const Result limited = campo("run " + scene + " --planner straight --no-figures --time-limit 600 --out " +
                               (dir_ / "limited").string());
  ASSERT_EQ(limited.exit_code, 0) << limited.err;
  const auto a = nlohmann::json::parse(slurp(dir_ / "free" / "run.json"));
  const auto b = nlohmann::json::parse(slurp(dir_ / "limited" / "run.json"));
  EXPECT_EQ(a["metrics"]["outcome"], "reached");
  EXPECT_EQ(a["final_state_hash"], b["final_state_hash"]);
  EXPECT_EQ(slurp(dir_ / "free" / "trajectory.csv"), slurp(dir_ / "limited" / "trajectory.csv"));
  EXPECT_EQ(slurp(dir_ / "free" / "events.jsonl"), slurp(dir_ / "limited" / "events.jsonl"));
}

TEST_F(RunTimeLimit, AnythingButSecondsInItsRangeExitsTwoAndWritesNothing) {
  for (const char* bad : {"0", "-1", "nan", "inf", "1e10", "soon"}) {
    const fs::path out = dir_ / "bad";
    const Result r = campo(std::string("run two_barriers --time-limit ") + bad + " --out " + out.string());
    EXPECT_EQ(r.exit_code, 2) << bad << ": " << r.err;
    EXPECT_THAT(r.err, HasSubstr("--time-limit")) << bad;
    EXPECT_FALSE(fs::exists(out)) << bad;
  }
}

}  // namespace
