// `campo validate`, `campo run` and `campo sweep` report every error of a
// scene or sweep spec at once (issue 31, point 3): one "error: " line each,
// FILE:LINE:COLUMN: /pointer (aliases): what was expected; exit 2, nothing written.
#include <filesystem>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "../cli_support.hpp"

namespace campo::testing {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

using AllErrorsCli = CliTest;

// Three independent errors; lines and columns counted by hand (the text starts with "{" on line 1).
const char* kScene = R"({
  "objects": [
    {"alias": "box", "type": "cuboid", "size_m": [1, -2, 1]},
    {"alias": "forest", "type": "dummy", "children": [
      {"alias": "tree4", "type": "cylinder", "radius_m": 0.2, "height_m": 3, "colour": [1, 0, 0]}]},
    {"alias": "drone", "type": "quadrotor", "pose": {"position_m": [0, 0, 1]},
     "mission": {"waypoints": [{"position_m": [5, 0, "high"]}]}}
  ]
})";

TEST_F(AllErrorsCli, ValidateAndRunReportEveryErrorOfAScene) {
  const std::string file = write("several.json", kScene);
  const std::vector<std::string> expected = {
      "error: " + file + ":3:54: /objects/0/size_m/1 (box): expected a number in (0, 1e+06], got -2",
      "error: " + file + ":5:78: /objects/1/children/0/colour (forest/tree4): unknown key \"colour\"; expected one of: "
                         "alias, children, color, friction, height_m, mass_kg, pose, radius_m, static, type",
      "error: " + file + ":7:54: /objects/2/mission/waypoints/0/position_m/2 (drone): expected a number in "
                         "[-1e+06, 1e+06], got \"high\"",
  };
  const Result validate = campo("validate " + file);
  EXPECT_EQ(validate.exit_code, 2);
  EXPECT_EQ(lines_of(validate.err), expected) << validate.err;
  EXPECT_EQ(validate.out, "");

  const Result run = campo("run " + file + " --out " + (dir_ / "run").string());
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(lines_of(run.err), expected) << run.err;
  EXPECT_FALSE(fs::exists(dir_ / "run"));
}

// The planner's and the vehicle's parameter blocks are checked with the rest of the scene: their errors,
// every one of each block, come in the same list, in the order of the file, placed as the others are.
TEST_F(AllErrorsCli, ParameterBlocksReportEveryErrorWithTheScenes) {
  const std::string file = write("params.json", R"({
  "objects": [
    {"alias": "box", "type": "cuboid", "size_m": [1, -2, 1]},
    {"alias": "drone", "type": "quadrotor", "pose": {"position_m": [0, 0, 1]},
     "planner": {"name": "straight", "params": {"speed_mps": -1, "colour": 2}},
     "params": {"mass_kg": -3, "arm_length_m": 0},
     "mission": {"waypoints": [{"position_m": [5, 0, 1]}]}}
  ]
})");
  const std::vector<std::string> expected = {
      "error: " + file + ":3:54: /objects/0/size_m/1 (box): expected a number in (0, 1e+06], got -2",
      "error: " + file + ":5:49: /objects/1/planner/params/speed_mps (drone): expected a number in [0.01, 20], got -1",
      "error: " + file + ":5:66: /objects/1/planner/params/colour (drone): unknown key \"colour\"; expected one of: "
                         "horizontal, speed_mps, tolerance_m",
      "error: " + file + ":6:17: /objects/1/params/mass_kg (drone): expected a number > 0, got -3",
      "error: " + file + ":6:32: /objects/1/params/arm_length_m (drone): expected a number > 0, got 0",
  };
  const Result validate = campo("validate " + file);
  EXPECT_EQ(validate.exit_code, 2);
  EXPECT_EQ(lines_of(validate.err), expected) << validate.err;
  const Result run = campo("run " + file + " --out " + (dir_ / "run").string());
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(lines_of(run.err), expected) << run.err;
  EXPECT_FALSE(fs::exists(dir_ / "run"));

  // A planner that --planner replaces is not the one checked: its scene block belongs to the scene's
  // planner; the one chosen is checked once the scene loads (here it never does).
  const Result replaced = campo("run " + file + " --planner depth_reactive --out " + (dir_ / "run").string());
  EXPECT_EQ(replaced.exit_code, 2);
  EXPECT_EQ(lines_of(replaced.err),
            (std::vector<std::string>{expected[0], expected[3], expected[4]})) << replaced.err;
}

// The parameters' errors alone, of a scene otherwise valid: all of them, not the first.
TEST_F(AllErrorsCli, ParameterBlockErrorsOfAnOtherwiseValidScene) {
  const std::string file = write("only_params.json", R"({
  "objects": [
    {"alias": "drone", "type": "quadrotor",
     "planner": {"name": "straight", "params": {"speed_mps": 50, "tolerance_m": -1}},
     "mission": {"waypoints": [{"position_m": [5, 0, 1]}]}}
  ]
})");
  const Result r = campo("validate " + file);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(lines_of(r.err),
            (std::vector<std::string>{
                "error: " + file + ":4:49: /objects/0/planner/params/speed_mps (drone): expected a number in "
                                   "[0.01, 20], got 50",
                "error: " + file + ":4:66: /objects/0/planner/params/tolerance_m (drone): expected a number > 0, "
                                   "got -1",
            }))
      << r.err;

  // A sweep's run of it: both, each on its line after the run's name.
  const std::string spec =
      write("params_spec.json", R"({"campo_sweep": 1, "scenes": ["only_params.json"], "seeds": {"count": 1}})");
  const Result sweep = campo("validate " + spec);
  EXPECT_EQ(sweep.exit_code, 2);
  const std::vector<std::string> lines = lines_of(sweep.err);
  ASSERT_EQ(lines.size(), 2u) << sweep.err;
  EXPECT_THAT(lines[0], HasSubstr(":4:49: /objects/0/planner/params/speed_mps (drone): expected a number in"));
  EXPECT_THAT(lines[1], HasSubstr(":4:66: /objects/0/planner/params/tolerance_m (drone): expected a number > 0"));
}

TEST_F(AllErrorsCli, ManyErrorsAreBoundedThenCounted) {
  std::string objects;
  for (int i = 0; i < 23; ++i) {
    objects += (i == 0 ? "" : ",\n") + ("{\"alias\": \"b" + std::to_string(i) + "\", \"type\": \"sphere\", \"radius_m\": -1}");
  }
  const Result r = campo("validate " + write("many.json", "{\"objects\": [\n" + objects + "]}"));
  EXPECT_EQ(r.exit_code, 2);
  const std::vector<std::string> lines = lines_of(r.err);
  ASSERT_EQ(lines.size(), 21u) << r.err;
  EXPECT_THAT(lines[0], HasSubstr("many.json:2:35: /objects/0/radius_m (b0): expected a number in (0, 1e+06], got -1"));
  EXPECT_THAT(lines[19], HasSubstr("many.json:21:36: /objects/19/radius_m (b19): expected"));
  EXPECT_EQ(lines[20], "error: ... and 3 more errors");
}

TEST_F(AllErrorsCli, ValidateAndSweepReportEveryErrorOfASweepSpec) {
  const std::string spec = write("spec.json", R"({
  "campo_sweep": 1,
  "scenes": ["two_barriers"],
  "axes": [{"name": "speed", "values": [1, 2], "set": ["objects/drone/planner/params/speed_mps"]}],
  "seeds": {"count": 0},
  "colour": 1
})");
  const std::vector<std::string> expected = {
      "error: " + spec + ":4:56: /axes/0/set/0 (speed): expected a JSON pointer into the scene such as "
                         "\"/objects/drone/planner/name\" (without '='), got \"objects/drone/planner/params/speed_mps\"",
      "error: " + spec + ":5:13: /seeds/count: expected an integer in [1, 100000], got 0",
      "error: " + spec + ":6:3: /colour: unknown key \"colour\"; expected one of: axes, campo_sweep, description, "
                         "name, planners, plugins, sampling, scenes, seeds, set, start_jitter, table, time_limit_s, "
                         "vary_scene_with_seed",
  };
  const Result validate = campo("validate " + spec);
  EXPECT_EQ(validate.exit_code, 2);
  EXPECT_EQ(lines_of(validate.err), expected) << validate.err;
  const Result sweep = campo("sweep " + spec + " --out " + (dir_ / "out").string());
  EXPECT_EQ(sweep.exit_code, 2);
  EXPECT_EQ(lines_of(sweep.err), expected) << sweep.err;
  EXPECT_FALSE(fs::exists(dir_ / "out"));
}

TEST_F(AllErrorsCli, ValidateChecksAValidSweepSpecAndItsRuns) {
  const std::string spec = write("ok.json", R"({"campo_sweep": 1, "scenes": ["two_barriers"], "seeds": {"count": 2}})");
  const Result r = campo("validate " + spec);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "ok " + spec + ": sweep spec, 1 scenes, 2 runs\n");
}

}  // namespace
}  // namespace campo::testing
