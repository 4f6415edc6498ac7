// Planner plugins through the program, as a user loads them: --plugin on
// run, validate and sweep, a sweep spec's "plugins", --list-planners, the run
// record's provenance, and exit 2 with the file and what was expected for
// every plugin campo refuses (tests/plugins/ builds the fixture plugins).
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "campo/scene_loader.hpp"
#include "campo/version.hpp"
#include "tests/cli_support.hpp"

namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::StartsWith;

using campo::testing::Result;
using campo::testing::lines_of;
using campo::testing::slurp;
using PluginCli = campo::testing::CliTest;

std::string fixture(const std::string& name) { return (fs::path(CAMPO_TEST_PLUGIN_DIR) / (name + ".so")).string(); }

// A quadrotor without sensors, 2 m from its goal, flown by the two_planners fixture's planner.
constexpr const char* kGotoScene = R"j({"world": {"time_limit_s": 20}, "objects": [
  {"alias": "ground", "type": "plane"},
  {"alias": "drone", "type": "quadrotor", "pose": {"position_m": [0, 0, 1.5]},
   "planner": {"name": "fixture_goto", "params": {"speed_mps": 1.0}},
   "mission": {"waypoints": [{"position_m": [2, 0, 1.5]}]}}]})j";

TEST_F(PluginCli, VersionIsTheLibrarysVersion) {
  const Result r = campo("--version");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, StartsWith("campo " + std::string(campo::library_version()) + " (git "));
  EXPECT_EQ(campo::library_version(), CAMPO_VERSION_STRING);
}

TEST_F(PluginCli, ListPlannersNamesEachPlannersSource) {
  Result r = campo("run --list-planners");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::vector<std::string> lines = lines_of(r.out);
  ASSERT_EQ(lines.size(), 4u) << r.out;
  EXPECT_EQ(lines[0], "straight (built-in): head for each mission waypoint in turn in a straight line");
  for (const std::string& line : lines) EXPECT_THAT(line, HasSubstr(" (built-in): "));

  r = campo("run --list-planners --plugin " + fixture("two_planners"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  lines = lines_of(r.out);
  ASSERT_EQ(lines.size(), 6u) << r.out;
  EXPECT_EQ(lines[4], "fixture_goto (" + fixture("two_planners") + "): fixture: straight to each waypoint");
  EXPECT_EQ(lines[5], "fixture_hold (" + fixture("two_planners") + "): fixture: hold the start, then give up");
}

TEST_F(PluginCli, RunsAPluginsPlannerAndRecordsItsFileAndDigest) {
  const std::string scene = write("goto.json", kGotoScene);
  const std::string out = (dir_ / "out").string();
  const Result r = campo("run " + scene + " --plugin " + fixture("two_planners") + " --no-figures --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json record = nlohmann::json::parse(slurp(dir_ / "out" / "run.json"));
  EXPECT_EQ(record["metrics"]["outcome"], "reached");
  EXPECT_EQ(record["parameters"]["planner"]["parameters"], (nlohmann::json{{"speed_mps", 1.0}}));
  EXPECT_EQ(record["provenance"]["planner"],
            (nlohmann::json{{"name", "fixture_goto"},
                            {"source", fixture("two_planners")},
                            {"sha256", campo::sha256_hex(slurp(fixture("two_planners")))}}));

  // A built-in planner's record says so.
  const Result straight = campo("run " + scene + " --planner straight --no-figures --out " + out + "2");
  ASSERT_EQ(straight.exit_code, 0) << straight.err;
  EXPECT_EQ(nlohmann::json::parse(slurp(dir_ / "out2" / "run.json"))["provenance"]["planner"],
            (nlohmann::json{{"name", "straight"}, {"source", "built-in"}}));
}

TEST_F(PluginCli, APluginsPlannerWithoutItsPluginIsAnUnknownPlanner) {
  const Result r = campo("run " + write("goto.json", kGotoScene) + " --out " + (dir_ / "out").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("/objects/1/planner/name (drone): unknown planner \"fixture_goto\"; expected one of: straight"));
  EXPECT_THAT(r.err, HasSubstr("--plugin PATH"));
  EXPECT_FALSE(fs::exists(dir_ / "out"));
}

TEST_F(PluginCli, ValidateChecksAPluginPlannersParameters) {
  const std::string good = write("goto.json", kGotoScene);
  std::string text = kGotoScene;
  text.replace(text.find("\"speed_mps\": 1.0"), 16, "\"speed_mps\": 99");
  const std::string bad = write("bad.json", text);
  Result r = campo("validate --plugin " + fixture("two_planners") + " " + good);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("ok " + good));
  r = campo("validate --plugin " + fixture("two_planners") + " " + bad);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("bad.json:4:51: /objects/1/planner/params/speed_mps (drone): expected a number in [0.1, 5]"));
}

TEST_F(PluginCli, EveryRefusedPluginExitsTwoNamingTheFileAndWhatWasExpected) {
  const std::string copy = (dir_ / "copy.so").string();
  fs::copy_file(fixture("two_planners"), copy);
  const std::string missing = (dir_ / "missing.so").string();
  struct Case {
    std::string plugins;
    std::vector<std::string> said;
  };
  const std::vector<Case> cases = {
      {"--plugin " + missing, {"command line: --plugin: plugin " + missing + ": cannot load it (", "No such file"}},
      {"--plugin " + fixture("not_a_plugin"),
       {"plugin " + fixture("not_a_plugin") + ": not a campo planner plugin", "campo_plugin_abi_version"}},
      {"--plugin " + fixture("abi_mismatch"),
       {"plugin " + fixture("abi_mismatch") + ": built against campo plugin ABI version 999",
        "loads plugin ABI version " + std::to_string(CAMPO_PLUGIN_ABI_VERSION), "rebuild it against this campo"}},
      {"--plugin " + fixture("no_planner"), {"plugin " + fixture("no_planner") + ": registers no planner"}},
      {"--plugin " + fixture("name_clash"),
       {"plugin " + fixture("name_clash") + ": registers planner \"straight\", a name already taken by the built-in"}},
      {"--plugin " + fixture("two_planners") + " --plugin " + copy,
       {"plugin " + copy + ": registers planner \"fixture_goto\", a name already taken by planner \"fixture_goto\" "
                           "of " + fixture("two_planners")}},
  };
  for (const Case& c : cases) {
    for (const std::string& command : {"run --list-planners " + c.plugins,
                                       "run " + c.plugins + " --out " + (dir_ / "out").string(),
                                       "validate " + c.plugins + " " + write("goto.json", kGotoScene)}) {
      const Result r = campo(command);
      EXPECT_EQ(r.exit_code, 2) << command;
      for (const std::string& text : c.said) EXPECT_THAT(r.err, HasSubstr(text)) << command;
      EXPECT_TRUE(r.out.empty()) << command;
    }
  }
  EXPECT_FALSE(fs::exists(dir_ / "out"));
}

TEST_F(PluginCli, ASweepSpecsPluginsReachEveryRunsProcess) {
  fs::create_directories(dir_ / "specs");
  fs::copy_file(fixture("two_planners"), dir_ / "plugins.so");
  write("goto.json", kGotoScene);
  // Relative to the spec file: ../plugins.so and ../goto.json.
  const std::string spec = write("specs/spec.json", R"({
    "campo_sweep": 1,
    "plugins": ["../plugins.so"],
    "scenes": ["../goto.json"],
    "axes": [ { "name": "speed", "values": [0.5, 1.0], "set": ["/objects/drone/planner/params/speed_mps"] } ]
  })");
  const std::string out = (dir_ / "out").string();
  const Result r = campo("sweep " + spec + " --out " + out + " --jobs 2");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<std::string> lines = lines_of(slurp(dir_ / "out" / "results.jsonl"));
  ASSERT_EQ(lines.size(), 2u);
  for (const std::string& line : lines) {
    const nlohmann::json result = nlohmann::json::parse(line);
    EXPECT_EQ(result["status"], "completed") << line;
    EXPECT_EQ(result["metrics"]["outcome"], "reached") << line;
  }
  const nlohmann::json manifest = nlohmann::json::parse(slurp(dir_ / "out" / "sweep.json"));
  const std::string plugin = (dir_ / "plugins.so").lexically_normal().string();
  EXPECT_EQ(manifest["plugins"], (nlohmann::json::array({{{"path", plugin},
                                                          {"sha256", campo::sha256_hex(slurp(plugin))},
                                                          {"planners", {"fixture_goto", "fixture_hold"}}}})));

  // Resuming with another plugin file is another sweep.
  std::ofstream(dir_ / "plugins.so", std::ios::app) << "bytes after the ELF sections change the digest alone";
  const Result resumed = campo("sweep " + spec + " --out " + out);
  EXPECT_EQ(resumed.exit_code, 2);
  EXPECT_THAT(resumed.err, HasSubstr("sweep.json: /plugins: expected the sweep this directory holds"));
}

TEST_F(PluginCli, ATriagedRunsReproCommandLoadsThePlugins) {
  fs::copy_file(fixture("two_planners"), dir_ / "plugins.so");
  write("goto.json", kGotoScene);
  // fixture_hold gives up after 1 s: the run completes without reaching its goal, so it is triaged.
  const std::string spec = write("spec.json", R"({"campo_sweep": 1, "plugins": ["plugins.so"], "scenes": ["goto.json"],
                                                  "planners": ["fixture_hold"]})");
  const Result r = campo("sweep " + spec + " --out " + (dir_ / "out").string() + " --triage");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json line = nlohmann::json::parse(lines_of(slurp(dir_ / "out" / "results.jsonl")).at(0));
  EXPECT_EQ(line["metrics"]["outcome"], "aborted");
  const std::string repro = line["triage"]["repro"];
  EXPECT_THAT(repro, HasSubstr(" --plugin " + (dir_ / "plugins.so").string() + " "));
  // The command reruns the run alone, with the plugin's planner, to the same outcome.
  ASSERT_THAT(repro, StartsWith("campo run "));
  const Result rerun = campo(repro.substr(std::string("campo ").size()));
  ASSERT_EQ(rerun.exit_code, 0) << rerun.err;
  const fs::path rerun_dir = dir_ / "out" / line["triage"]["dir"].get<std::string>() / "rerun";
  const nlohmann::json record = nlohmann::json::parse(slurp(rerun_dir / "run.json"));
  EXPECT_EQ(record["metrics"]["outcome"], "aborted");
  EXPECT_EQ(record["metrics"]["reason"], line["metrics"]["reason"]);
  EXPECT_EQ(record["provenance"]["planner"]["name"], "fixture_hold");
}

TEST_F(PluginCli, SweepLoadsPluginsFromTheCommandLineToo) {
  write("goto.json", kGotoScene);
  const std::string spec = write("spec.json", R"({"campo_sweep": 1, "scenes": ["goto.json"],
                                                  "seeds": {"first": 1, "count": 3}})");
  Result r = campo("sweep " + spec + " --list");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("unknown planner \"fixture_goto\""));
  r = campo("sweep " + spec + " --list --plugin " + fixture("two_planners"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(lines_of(r.out).size(), 3u);
}

TEST_F(PluginCli, ASweepSpecsPluginsAreCheckedLikeItsOtherKeys) {
  write("goto.json", kGotoScene);
  struct Case {
    std::string plugins;
    std::string said;
  };
  const std::vector<Case> cases = {
      {R"("x.so")", ":1:45: /plugins: expected an array"},
      {R"([3])", ":1:57: /plugins/0: expected a non-empty string"},
      {R"(["a.so", "./a.so"])", ":1:65: /plugins/1: expected plugins named once each"},
      {R"(["missing.so"])", ": /plugins/0: plugin " + (dir_ / "missing.so").string() + ": cannot load it ("},
      {"[\"" + fixture("no_planner") + "\"]",
       ": /plugins/0: plugin " + fixture("no_planner") + ": registers no planner"},
  };
  for (const Case& c : cases) {
    const std::string spec =
        write("spec.json", R"({"campo_sweep": 1, "scenes": ["goto.json"], "plugins": )" + c.plugins + "}");
    const Result r = campo("sweep " + spec + " --out " + (dir_ / "out").string());
    EXPECT_EQ(r.exit_code, 2) << c.plugins;
    EXPECT_THAT(r.err, HasSubstr(spec + c.said)) << c.plugins;
    EXPECT_FALSE(fs::exists(dir_ / "out")) << c.plugins;
  }
}

}  // namespace
