// Every override recorded is an override applied (issue 31): `campo run
// --planner` with planner `--set`s, and sweeps whose `planners` choose the
// planner, either apply them to the planner that runs or refuse them (exit 2).
#include <filesystem>
#include <fstream>
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
using Overrides = campo::testing::CliTest;

const std::string kSpeed = "/objects/drone/planner/params/speed_mps";

nlohmann::json planner_of(const fs::path& run_dir) {
  return nlohmann::json::parse(slurp(run_dir / "run.json")).at("parameters").at("planner");
}

TEST_F(Overrides, PlannerSetsGoToThePlannerChosenOnTheCommandLine) {
  // two_barriers' own planner is depth_reactive: --planner straight replaces it, and the --set is for straight.
  const Result base = campo("run two_barriers --planner straight --no-figures --out " + (dir_ / "base").string());
  ASSERT_EQ(base.exit_code, 0) << base.err;
  const Result fast = campo("run two_barriers --planner straight --no-figures --set " + kSpeed + "=2.0 --out " +
                            (dir_ / "fast").string());
  ASSERT_EQ(fast.exit_code, 0) << fast.err;
  const nlohmann::json planner = planner_of(dir_ / "fast");
  EXPECT_EQ(planner.at("name"), "straight");
  EXPECT_EQ(planner.at("parameters").at("speed_mps"), 2.0);
  // The effective scene is the one that ran: running it again is the same run.
  const auto scene_json = nlohmann::json::parse(slurp(dir_ / "fast" / "scene.json"));
  EXPECT_EQ(scene_json.at("objects").at(4).at("planner"),
            nlohmann::json::parse(R"({"name": "straight", "params": {"speed_mps": 2.0}})"));
  const Result again = campo("run " + (dir_ / "fast" / "scene.json").string() + " --no-figures --out " +
                             (dir_ / "again").string());
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_EQ(nlohmann::json::parse(slurp(dir_ / "again" / "run.json")).at("final_state_hash"),
            nlohmann::json::parse(slurp(dir_ / "fast" / "run.json")).at("final_state_hash"));
  // And flown: the mean speed over the run exceeds the default speed and stays within the one set.
  const double default_speed = planner_of(dir_ / "base").at("parameters").at("speed_mps").get<double>();
  ASSERT_LT(default_speed, 2.0);
  const auto metrics = nlohmann::json::parse(slurp(dir_ / "fast" / "run.json")).at("metrics");
  const double mean_speed = metrics.at("path_length_m").get<double>() / metrics.at("sim_time_s").get<double>();
  EXPECT_GT(mean_speed, default_speed);
  EXPECT_LE(mean_speed, 2.0 * 1.05);
}

TEST_F(Overrides, PlannerSetsAreCheckedByThePlannerChosen) {
  struct Case {
    std::string set;
    std::string message;
  };
  const Case cases[] = {
      {kSpeed + "=99", "command line (--planner straight with --set): /objects/4/planner/params/speed_mps: expected a "
                       "number in [0.01, 20], got 99"},
      // depth_reactive's parameter, which straight does not take.
      {"/objects/drone/planner/params/fov_deg=60", "/objects/4/planner/params/fov_deg: unknown key \"fov_deg\""},
      // The planner chosen twice, two ways.
      {"/objects/drone/planner/name=depth_reactive",
       "--set /objects/drone/planner/name=depth_reactive: chooses the planner of vehicle drone (\"depth_reactive\") "
       "while --planner straight chooses another"},
      {"/objects/drone/planner={\"name\":\"depth_reactive\"}", "while --planner straight chooses another"},
  };
  for (const Case& c : cases) {
    const fs::path out = dir_ / "refused";
    const Result r = campo("run two_barriers --planner straight --set '" + c.set + "' --out " + out.string());
    EXPECT_EQ(r.exit_code, 2) << c.set << ": " << r.err;
    EXPECT_THAT(r.err, HasSubstr(c.message)) << c.set;
    EXPECT_FALSE(fs::exists(out)) << c.set;
  }
}

TEST_F(Overrides, ASceneWithoutAPlannerTakesPlannerSetsForThePlannerChosen) {
  const std::string scene = std::string(CAMPO_SOURCE_DIR) + "/tests/python/fixtures/open_field.json";
  const Result r = campo("run " + scene + " --planner straight --no-figures --set " + kSpeed + "=1.5 --out " +
                         (dir_ / "run").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(planner_of(dir_ / "run").at("parameters").at("speed_mps"), 1.5);
  // The effective scene names the planner that ran.
  const auto scene_json = nlohmann::json::parse(slurp(dir_ / "run" / "scene.json"));
  EXPECT_EQ(scene_json.at("objects").at(2).at("planner").at("name"), "straight");
}

TEST_F(Overrides, TheScenesOwnPlannerKeepsItsSets) {
  const Result r = campo("run two_barriers --planner depth_reactive --no-figures --set /world/time_limit_s=1 --set " +
                         kSpeed + "=0.5 --out " + (dir_ / "run").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(planner_of(dir_ / "run").at("parameters").at("speed_mps"), 0.5);
}

// Checked by the sweep spec itself (sweep/sweep_spec.cpp); here as one of the paths an override takes.
TEST_F(Overrides, ASweepRefusesASetThatWouldReplaceThePlannerItChooses) {
  const fs::path spec = dir_ / "spec.json";
  std::ofstream(spec) << R"({"campo_sweep": 1, "scenes": ["two_barriers"], "planners": ["straight"],
    "set": {"/objects/drone/planner/name": "depth_reactive"}})";
  const Result r = campo("sweep " + spec.string() + " --list");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_THAT(r.err, HasSubstr("expected no planner choice when \"planners\" is given"));

  // Its parameters are the planner's: applied to it, recorded as applied.
  std::ofstream(spec) << R"({"campo_sweep": 1, "scenes": ["two_barriers"], "planners": ["straight"],
    "set": {"/objects/drone/planner/params/speed_mps": 2.0, "/world/time_limit_s": 1}})";
  const fs::path out = dir_ / "sweep";
  const Result ok = campo("sweep " + spec.string() + " --jobs 1 --keep-runs --out " + out.string());
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  bool found = false;
  for (const auto& entry : fs::recursive_directory_iterator(out)) {
    if (entry.path().filename() != "run.json") continue;
    found = true;
    EXPECT_EQ(planner_of(entry.path().parent_path()).at("name"), "straight");
    EXPECT_EQ(planner_of(entry.path().parent_path()).at("parameters").at("speed_mps"), 2.0);
  }
  EXPECT_TRUE(found);
}

}  // namespace
