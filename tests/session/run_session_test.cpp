// The session room: one run from its typed request to its directory, one sweep item to its typed
// result and results line, with the figure writer injected where a test needs a figure to fail.
#include <filesystem>
#include <stdexcept>
#include <string>
#include <unistd.h>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/output_dir.hpp"
#include "render/run_figures.hpp"
#include "scene/scene_overrides.hpp"
#include "session/run_session.hpp"
#include "session/sweep_item.hpp"
#include "sweep/results.hpp"

namespace campo {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

const fs::path kScene = fs::path(CAMPO_SOURCE_DIR) / "scenes/two_barriers.json";

class Session : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("campo_session_test_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // A short run of the bundled two_barriers (1 s of simulated time: it ends in a timeout).
  RunRequest short_run() const {
    RunRequest request;
    request.scene = kScene;
    request.overrides = {parse_override("/world/time_limit_s=1")};
    request.record_replans = false;
    request.out = dir_ / "run";
    return request;
  }

  fs::path dir_;
};

// The figure writer is injected: one that fails on the map costs the map alone; the run's own files
// and the other figures are written, and the failure says whether it was the place to write (bad
// input) or a bug.
TEST_F(Session, AFigureThatFailsCostsOnlyThatFigure) {
  RunRequest request = short_run();
  request.write_figure = [](const RecordedRun& run, FigureKind kind, const fs::path& dir, const FigureFormats& formats) {
    if (kind == FigureKind::map) throw OutputError(dir / "map.png", "cannot write: no space left");
    if (kind == FigureKind::side) throw std::runtime_error("side view broke");
    write_figure(run, kind, dir, formats);
  };
  const SimulatedRun run = simulate_run(request, {});
  {
    StagedOutput out(request.out);
    const std::vector<FigureFailure> failures = write_run_files(run, request, out);
    out.commit();
    ASSERT_EQ(failures.size(), 2u);
    EXPECT_EQ(failures[0].figure, "map");
    EXPECT_TRUE(failures[0].bad_input);
    EXPECT_THAT(failures[0].message, HasSubstr("map.png: cannot write: no space left"));
    EXPECT_EQ(failures[1].figure, "side");
    EXPECT_FALSE(failures[1].bad_input);
    EXPECT_EQ(failures[1].message, "side view broke");
  }
  for (const char* file : {"run.json", "events.jsonl", "trajectory.csv", "scene.json"}) {
    EXPECT_TRUE(fs::is_regular_file(request.out / file)) << file;
  }
  EXPECT_FALSE(fs::exists(request.out / "map.png"));
  EXPECT_FALSE(fs::exists(request.out / "side.png"));
  EXPECT_EQ(run.record["metrics"]["outcome"], "timeout");
}

// The same through execute_run, which `campo run` calls: the run is kept and its failures returned.
TEST_F(Session, ExecuteRunKeepsARunWhoseFigureFailed) {
  RunRequest request = short_run();
  request.write_figure = [](const RecordedRun&, FigureKind kind, const fs::path& dir, const FigureFormats&) {
    if (kind == FigureKind::map) throw OutputError(dir / "map.png", "cannot write: injected");
  };
  const ExecutedRun run = execute_run(request);
  ASSERT_EQ(run.figure_failures.size(), 1u);
  EXPECT_EQ(run.figure_failures[0].figure, "map");
  EXPECT_TRUE(fs::is_regular_file(request.out / "run.json"));
  EXPECT_FALSE(fs::exists(request.out / "map.png"));
}

// What `campo run` prints for them, word for word, and the exit it chooses: 2 when every failure was
// bad input (the place to write), 1 when one was a bug.
TEST(FigureFailureReport, NamesEachFigureAndKeepsTheRun) {
  const FigureFailureReport input = figure_failure_report({{"map", "out/map.png: cannot write", true}}, "out");
  EXPECT_EQ(input.text,
            "error: map figure: out/map.png: cannot write\n"
            "the run completed and its files are kept in out; only the figures above are missing "
            "(campo render out redraws them)\n");
  EXPECT_TRUE(input.bad_input);
  const FigureFailureReport bug =
      figure_failure_report({{"map", "a", true}, {"side", "b", false}}, "d");
  EXPECT_THAT(bug.text, HasSubstr("error: map figure: a\ninternal error: side figure: b\n"));
  EXPECT_FALSE(bug.bad_input);
}

// Typed overrides: parsed once from text, or made from pointer and value; run.json records their texts.
TEST_F(Session, RecordsTheOverridesAsGiven) {
  RunRequest request = short_run();
  request.figures = false;
  request.overrides.push_back(make_override("/world/seed", 7));
  request.overrides.push_back(parse_override("/objects/drone/planner/params/speed_mps=1.5"));
  const SimulatedRun run = simulate_run(request, {});
  EXPECT_EQ(run.record["overrides"],
            nlohmann::json({"/world/time_limit_s=1", "/world/seed=7", "/objects/drone/planner/params/speed_mps=1.5"}));
  EXPECT_EQ(run.document["world"]["seed"], 7);
  EXPECT_EQ(run.document["world"]["time_limit_s"], 1);
}

TEST(SceneOverride, TextAndValue) {
  const SceneOverride parsed = parse_override("/a/b=[1,2]");
  EXPECT_EQ(parsed.pointer, "/a/b");
  EXPECT_EQ(parsed.value, nlohmann::json({1, 2}));
  EXPECT_EQ(parsed.text, "/a/b=[1,2]");
  EXPECT_EQ(parse_override("/a=text").value, "text");  // not JSON: a string
  const SceneOverride made = make_override("/w", nlohmann::json{{"k", "v"}});
  EXPECT_EQ(made.text, R"(/w={"k":"v"})");
  // Not PATH=VALUE: refused when applied, naming --set and the text.
  nlohmann::json document = nlohmann::json::object();
  try {
    apply_override(document, parse_override("world/seed"));
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(std::string(e.what()), HasSubstr("--set world/seed"));
  }
}

SweepRun sweep_run(const std::vector<SceneOverride>& overrides) {
  SweepRun run;
  run.id = "0123456789abcdef";
  run.name = "two_barriers__seed-1";
  run.scene = "two_barriers";
  run.planner = "straight";
  run.scene_file = kScene;
  run.params = nlohmann::json::object();
  run.seed = 1;
  run.overrides = overrides;
  run.scene_sha256 = "ab";
  return run;
}

// One sweep item: a completed run's typed result, its line (assembled once) with the overrides' texts,
// the run's directory when kept; the result crosses the process boundary as JSON unchanged.
TEST_F(Session, SweepItemCompletesAndItsLineRecordsIt) {
  const SweepRun run = sweep_run({make_override("/world/time_limit_s", 1), make_override("/world/seed", 1)});
  SweepItemOptions options;
  options.keep_runs = true;
  const SweepItemResult result = run_sweep_item(run, dir_, options);
  ASSERT_TRUE(result.completed) << result.reason;
  EXPECT_TRUE(result.kept_run_dir);
  EXPECT_TRUE(result.files_error.empty()) << result.files_error;
  EXPECT_FALSE(result.reached());
  EXPECT_TRUE(fs::is_regular_file(dir_ / "runs" / run.name / "run.json"));
  EXPECT_FALSE(fs::exists(dir_ / "runs" / run.name / "map.png"));  // no figures asked for
  const SweepItemResult sent = sweep_item_result_from_json(nlohmann::json::parse(to_json(result).dump()));
  const nlohmann::json line = result_line(run, sent, {2.5, "cd", std::nullopt});
  EXPECT_EQ(line, result_line(run, result, {2.5, "cd", std::nullopt}));
  EXPECT_EQ(line["status"], "completed");
  EXPECT_EQ(line["run_dir"], "runs/" + run.name);
  EXPECT_EQ(line["overrides"], nlohmann::json({"/world/time_limit_s=1", "/world/seed=1"}));
  EXPECT_EQ(line["metrics"]["outcome"], "timeout");
  EXPECT_EQ(line["wall_time_s"], 2.5);
  EXPECT_EQ(line["spec_sha256"], "cd");
  EXPECT_EQ(line["trajectory_sha256"].get<std::string>().size(), 64u);
  EXPECT_FALSE(line.contains("reason"));
  EXPECT_FALSE(line.contains("triage"));
  // The record kept has the same overrides and metrics.
  const nlohmann::json record = nlohmann::json::parse(read_text_file((dir_ / "runs" / run.name / "run.json").string()));
  EXPECT_EQ(record["overrides"], line["overrides"]);
  EXPECT_EQ(record["metrics"], line["metrics"]);
}

// A run that cannot start is a failed item with its reason (not an exception), and its line says so.
TEST_F(Session, SweepItemWithBadInputFails) {
  const SweepRun run = sweep_run({parse_override("/world/physics_step_s=-1")});
  const SweepItemResult result = run_sweep_item(run, dir_, {});
  EXPECT_FALSE(result.completed);
  EXPECT_FALSE(result.files_failed);
  EXPECT_THAT(result.reason, HasSubstr("/world/physics_step_s"));
  ResultLineContext context{0.5, "cd", ResultLineContext::Triage{"triage/x", "campo run x"}};
  const nlohmann::json line = result_line(run, result, context);
  EXPECT_EQ(line["status"], "failed");
  EXPECT_EQ(line["reason"], result.reason);
  EXPECT_TRUE(line["metrics"].is_null());
  EXPECT_TRUE(line["run_dir"].is_null());
  EXPECT_EQ(line["scene_sha256"], "ab");
  EXPECT_EQ(line["triage"], nlohmann::json({{"dir", "triage/x"}, {"repro", "campo run x"}}));
  EXPECT_FALSE(fs::exists(dir_));
}

// A job that returned nothing: the pool's reason and the last line the process wrote.
TEST(SweepItem, AFailedJobKeepsItsLastOutputLine) {
  JobOutcome outcome;
  outcome.reason = "killed by signal 11 (Segmentation fault)";
  outcome.stderr_tail = "first\nlast words";
  EXPECT_EQ(failed_job_item(outcome).reason, "killed by signal 11 (Segmentation fault); last output: last words");
  outcome.stderr_tail.clear();
  EXPECT_EQ(failed_job_item(outcome).reason, outcome.reason);
}

// The repro command reruns the run alone with its overrides' texts, quoted for the shell.
TEST(SweepItem, ReproCommandQuotesTheOverrides) {
  const SweepRun run = sweep_run({parse_override("/world/name=a b")});
  const std::string command = repro_command(run, "/tmp/t");
  EXPECT_THAT(command, HasSubstr(" --set '/world/name=a b' --out /tmp/t/rerun"));
  EXPECT_EQ(command.rfind("campo run ", 0), 0u);
}

}  // namespace
}  // namespace campo
