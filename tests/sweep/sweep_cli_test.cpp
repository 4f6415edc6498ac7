// `campo sweep` and `campo merge` run as a user would: parallel runs, resume
// after a kill, schedules that do not change results, shards, triage.
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sys/wait.h>
#include <unistd.h>

#include "campo/scene_loader.hpp"
#include "tests/cli_support.hpp"

namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::StartsWith;

using campo::testing::Result;
using campo::testing::lines_of;
using campo::testing::slurp;

// Two barriers with the straight planner, the scanner at 16 and 32 columns, one seed, 5 s: every run times out.
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

// Seed 000's reactive planner through the barriers: 3 resolutions x 6 seeds, noisy ranges and jittered starts.
constexpr const char* kReactiveSpec = R"({
  "campo_sweep": 1,
  "name": "reactive",
  "scenes": ["two_barriers"],
  "set": { "/objects/drone/sensors/scanner/noise_stddev_m": 0.01,
           "/objects/drone/sensors/scanner/resolution": [32, 32] },
  "axes": [ { "name": "resolution", "values": [32, 24, 16],
              "set": ["/objects/drone/sensors/scanner/resolution/0",
                      "/objects/drone/sensors/scanner/resolution/1"] } ],
  "seeds": { "first": 1, "count": 6 },
  "start_jitter": { "vehicle": "drone", "radius_m": 0.25 }
})";

// A line without what depends on the machine's speed: wall-clock times.
nlohmann::json without_wall_time(nlohmann::json line) {
  line.erase("wall_time_s");
  if (line["metrics"].is_object()) {
    nlohmann::json metrics;
    for (const auto& [key, value] : line["metrics"].items()) {
      const bool timed = key == "wall_time_s" || key.starts_with("planner_time_ms") || key.starts_with("replan_time_ms");
      if (!timed) metrics[key] = value;
    }
    line["metrics"] = metrics;
  }
  return line;
}

// results.jsonl by run ID, wall times removed; every ID must appear once.
std::map<std::string, nlohmann::json> results_by_id(const fs::path& file) {
  std::map<std::string, nlohmann::json> results;
  for (const std::string& text : lines_of(slurp(file))) {
    const nlohmann::json line = nlohmann::json::parse(text);
    EXPECT_TRUE(results.emplace(line["id"].get<std::string>(), without_wall_time(line)).second)
        << "run " << line["id"] << " recorded twice in " << file;
  }
  return results;
}

class SweepCli : public campo::testing::CliTest {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    write("tiny.json", kTinySpec);
    write("reactive.json", kReactiveSpec);
  }
  std::string spec(const char* name) const { return (dir_ / name).string(); }
  std::string out(const char* name) const { return (dir_ / name).string(); }
};

TEST_F(SweepCli, RunsEveryRunAndRecordsOneLineEach) {
  const Result sweep = campo("sweep " + spec("tiny.json") + " --out " + out("o") + " --keep-runs");
  ASSERT_EQ(sweep.exit_code, 0) << sweep.err;
  EXPECT_THAT(sweep.err, HasSubstr("tiny: 2 runs to do (0 already recorded)"));
  EXPECT_THAT(sweep.err, HasSubstr("progress: 2/2 done, 0 failed"));  // not a terminal: plain lines
  EXPECT_THAT(sweep.out, HasSubstr("tiny: 2 of 2 runs completed, 0 failed"));

  const auto results = lines_of(slurp(dir_ / "o" / "results.jsonl"));
  ASSERT_EQ(results.size(), 2u);
  nlohmann::json first = nlohmann::json::parse(results[0]);
  if (first["params"]["resolution"] != 16) first = nlohmann::json::parse(results[1]);  // in order of finishing
  EXPECT_EQ(first["id"].get<std::string>().size(), 16u);
  EXPECT_EQ(first["name"], "two_barriers__resolution-16__seed-1");
  EXPECT_EQ(first["planner"], "straight");
  EXPECT_EQ(first["status"], "completed");
  EXPECT_EQ(first["params"], nlohmann::json({{"resolution", 16}}));
  EXPECT_EQ(first["seed"], 1);
  EXPECT_EQ(first["run_dir"], "runs/two_barriers__resolution-16__seed-1");
  EXPECT_EQ(first["metrics"]["outcome"], "timeout");
  EXPECT_EQ(first["scene_sha256"].get<std::string>().size(), 64u);
  EXPECT_EQ(first["spec_sha256"].get<std::string>().size(), 64u);
  EXPECT_GT(first["wall_time_s"].get<double>(), 0.0);
  EXPECT_TRUE(first.contains("campo_version") && first.contains("git_rev"));
  // Each kept run's record, with the overrides of the manifest.
  const nlohmann::json record = nlohmann::json::parse(slurp(dir_ / "o" / first["run_dir"].get<std::string>() / "run.json"));
  EXPECT_EQ(record["overrides"], first["overrides"]);
  // The digest of the run's trajectory, as kept.
  EXPECT_EQ(first["trajectory_sha256"],
            campo::sha256_hex(slurp(dir_ / "o" / first["run_dir"].get<std::string>() / "trajectory.csv")));
  EXPECT_FALSE(fs::exists(dir_ / "o" / first["run_dir"].get<std::string>() / "map.png"));  // no --figures
  EXPECT_EQ(nlohmann::json::parse(slurp(dir_ / "o" / "sweep.json"))["runs"].size(), 2u);

  // Run again: everything is already recorded.
  const Result again = campo("sweep " + spec("tiny.json") + " --out " + out("o"));
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_THAT(again.err, HasSubstr("tiny: 0 runs to do (2 already recorded)"));
  EXPECT_EQ(lines_of(slurp(dir_ / "o" / "results.jsonl")).size(), 2u);
}

TEST_F(SweepCli, SeedsThatVaryNothingGiveIdenticalRunsAndTheTableSaysSo) {
  // Without start jitter or noise the straight planner flies the same path whatever the seed.
  nlohmann::json same = nlohmann::json::parse(kTinySpec);
  same.erase("start_jitter");
  same["axes"][0]["values"] = {16};
  same["seeds"]["count"] = 3;
  write("same.json", same.dump());
  ASSERT_EQ(campo("sweep " + spec("same.json") + " --out " + out("same") + " --jobs 2").exit_code, 0);
  const auto lines = lines_of(slurp(dir_ / "same" / "results.jsonl"));
  ASSERT_EQ(lines.size(), 3u);
  const nlohmann::json first = nlohmann::json::parse(lines[0]);
  for (const std::string& text : lines) {
    const nlohmann::json line = nlohmann::json::parse(text);
    EXPECT_EQ(line["trajectory_sha256"], first["trajectory_sha256"]);
    EXPECT_EQ(line["trajectory_sha256"].get<std::string>().size(), 64u);
  }
  Result table = campo("table " + out("same") + " --rows resolution --metrics success,path_ratio --no-chart --cell "
                       "mean-sd-ci --with-n");
  ASSERT_EQ(table.exit_code, 0) << table.err;
  EXPECT_THAT(table.out, HasSubstr("| 16 | 0% (n=3 identical runs: seeds vary nothing) | "));
  EXPECT_THAT(table.out, ::testing::Not(HasSubstr("[")));

  // The jittered starts of the same seeds differ: an interval again.
  same["start_jitter"] = nlohmann::json::parse(kTinySpec)["start_jitter"];
  write("jittered.json", same.dump());
  ASSERT_EQ(campo("sweep " + spec("jittered.json") + " --out " + out("jittered") + " --jobs 2").exit_code, 0);
  table = campo("table " + out("jittered") + " --rows resolution --metrics success,path_ratio --no-chart --cell "
                "mean-sd-ci --with-n");
  ASSERT_EQ(table.exit_code, 0) << table.err;
  EXPECT_THAT(table.out, HasSubstr("| 16 | 0% [0, 56] (n=3) | "));
  EXPECT_THAT(table.out, ::testing::Not(HasSubstr("identical")));
}

TEST_F(SweepCli, WithoutKeepRunsOnlyTheResultsAreWritten) {
  const Result sweep = campo("sweep " + spec("tiny.json") + " --out " + out("o") + " --jobs 1");
  ASSERT_EQ(sweep.exit_code, 0) << sweep.err;
  EXPECT_THAT(sweep.err, HasSubstr("1 at a time"));
  std::set<std::string> files;
  for (const auto& entry : fs::directory_iterator(dir_ / "o")) files.insert(entry.path().filename().string());
  EXPECT_EQ(files, (std::set<std::string>{"results.jsonl", "sweep.json"}));
  EXPECT_TRUE(nlohmann::json::parse(lines_of(slurp(dir_ / "o" / "results.jsonl"))[0])["run_dir"].is_null());
}

// A run whose kept files cannot be written is recorded as failed with the
// system's reason, and a resumed sweep runs it again (without --retry-failed).
TEST_F(SweepCli, ARunWhoseFilesCannotBeWrittenIsFailedAndRedoneOnResume) {
  // A file where the first run's directory should be.
  const fs::path blocker = dir_ / "o" / "runs" / "two_barriers__resolution-16__seed-1";
  fs::create_directories(blocker.parent_path());
  std::ofstream(blocker) << "in the way";
  const Result sweep = campo("sweep " + spec("tiny.json") + " --out " + out("o") + " --keep-runs");
  // The one failure is the place to write: exit 2, said in the last line.
  EXPECT_EQ(sweep.exit_code, 2);
  EXPECT_THAT(sweep.err, HasSubstr("error: " + out("o") + ": the files of 1 runs could not be written"));
  EXPECT_THAT(sweep.err, HasSubstr("failed: two_barriers__resolution-16__seed-1"));
  EXPECT_THAT(sweep.err, HasSubstr("completed, but its files could not be written"));
  std::map<std::string, nlohmann::json> by_name;
  for (const std::string& text : lines_of(slurp(dir_ / "o" / "results.jsonl"))) {
    const nlohmann::json line = nlohmann::json::parse(text);
    by_name[line["name"]] = line;
  }
  ASSERT_EQ(by_name.size(), 2u);
  const nlohmann::json& blocked = by_name["two_barriers__resolution-16__seed-1"];
  EXPECT_EQ(blocked["status"], "failed");
  // The system's reason, not only "cannot write".
  EXPECT_THAT(blocked["files_error"].get<std::string>(), HasSubstr(blocker.string()));
  EXPECT_THAT(blocked["files_error"].get<std::string>(),
              HasSubstr("is a regular file, expected a directory"));
  EXPECT_EQ(by_name["two_barriers__resolution-32__seed-1"]["run_dir"], "runs/two_barriers__resolution-32__seed-1");
  // Room again: the same command does that run, and only it.
  fs::remove(blocker);
  const Result resumed = campo("sweep " + spec("tiny.json") + " --out " + out("o") + " --keep-runs");
  EXPECT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_THAT(resumed.err, HasSubstr("1 runs to do (1 already recorded)"));
  EXPECT_TRUE(fs::is_regular_file(blocker / "run.json"));
  EXPECT_TRUE(fs::is_regular_file(blocker / "events.jsonl"));
  const nlohmann::json last = nlohmann::json::parse(lines_of(slurp(dir_ / "o" / "results.jsonl")).back());
  EXPECT_EQ(last["name"], "two_barriers__resolution-16__seed-1");
  EXPECT_EQ(last["status"], "completed");
  const Result table = campo("table " + out("o") + " --format csv --no-chart");
  EXPECT_EQ(table.exit_code, 0) << table.err;
}

// A killed run's staging directory on this host is removed by the next
// output into the same place; another host's (a shard on a shared file
// system) is left alone.
TEST_F(SweepCli, StaleStagingDirectoriesOfThisHostAreCleaned) {
  const Result first = campo("run --set /world/time_limit_s=0.5 --no-figures --no-replan-depth --out " + out("r"));
  ASSERT_EQ(first.exit_code, 0) << first.err;
  // A process that has ended: its PID is free.
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  ::waitpid(child, nullptr, 0);
  char host[256] = {};
  ::gethostname(host, sizeof host - 1);
  const fs::path stale = dir_ / "r" / (".staging-" + std::string(host) + "-" + std::to_string(child));
  const fs::path other = dir_ / "r" / ".staging-another-host.example-1";
  const fs::path live = dir_ / "r" / (".staging-" + std::string(host) + "-" + std::to_string(::getpid()));
  for (const fs::path& d : {stale, other, live}) fs::create_directories(d / "depth");
  const Result second = campo("run --set /world/time_limit_s=0.5 --no-figures --no-replan-depth --out " + out("r"));
  ASSERT_EQ(second.exit_code, 0) << second.err;
  EXPECT_FALSE(fs::exists(stale));
  EXPECT_TRUE(fs::exists(other));
  EXPECT_TRUE(fs::exists(live));
}

// Failed runs are recorded, so a rerun skips them unless asked to retry.
TEST_F(SweepCli, FailedRunsAreRetriedOnlyWhenAsked) {
  // 16 x 16 flies in about 0.2 s of wall time (a second under the sanitizers), 1024 x 1024 takes many.
  write("slow.json", R"({"campo_sweep": 1, "name": "slow", "scenes": ["two_barriers"],
    "set": {"/objects/drone/sensors/scanner/resolution": [16, 16]},
    "axes": [{"name": "resolution", "values": [16, 1024],
              "set": ["/objects/drone/sensors/scanner/resolution/0", "/objects/drone/sensors/scanner/resolution/1"]}]})");
  EXPECT_EQ(campo("sweep " + spec("slow.json") + " --out " + out("o") + " --time-limit 3").exit_code, 1);
  const Result again = campo("sweep " + spec("slow.json") + " --out " + out("o") + " --time-limit 3");
  EXPECT_EQ(again.exit_code, 1);
  EXPECT_THAT(again.err, HasSubstr("0 runs to do (2 already recorded)"));
  const Result retry = campo("sweep " + spec("slow.json") + " --out " + out("o") + " --time-limit 3 --retry-failed");
  EXPECT_EQ(retry.exit_code, 1);
  EXPECT_THAT(retry.err, HasSubstr("1 runs to do (1 already recorded)"));
  EXPECT_EQ(lines_of(slurp(dir_ / "o" / "results.jsonl")).size(), 3u);
}

// A run that goes on past its wall-clock limit is killed and recorded; the
// others complete. A 1024 x 1024 scanner takes many seconds, 16 x 16 about 0.2 s (a second under the
// sanitizers: the depth planner climbs over a barrier at 16 px, a 64 s flight).
TEST_F(SweepCli, ARunPastItsTimeLimitIsKilledAndRecorded) {
  write("slow.json", R"({"campo_sweep": 1, "name": "slow", "scenes": ["two_barriers"], "time_limit_s": 3,
    "set": {"/objects/drone/sensors/scanner/resolution": [16, 16]},
    "axes": [{"name": "resolution", "values": [16, 1024],
              "set": ["/objects/drone/sensors/scanner/resolution/0", "/objects/drone/sensors/scanner/resolution/1"]}]})");
  const Result sweep = campo("sweep " + spec("slow.json") + " --out " + out("o") + " --triage");
  EXPECT_EQ(sweep.exit_code, 1);
  std::map<int, nlohmann::json> by_resolution;
  for (const std::string& text : lines_of(slurp(dir_ / "o" / "results.jsonl"))) {
    const nlohmann::json line = nlohmann::json::parse(text);
    by_resolution[line["params"]["resolution"].get<int>()] = line;
  }
  ASSERT_EQ(by_resolution.size(), 2u);
  EXPECT_EQ(by_resolution[16]["status"], "completed");
  EXPECT_EQ(by_resolution[16]["metrics"]["outcome"], "reached");
  EXPECT_FALSE(by_resolution[16].contains("triage"));
  const nlohmann::json& killed = by_resolution[1024];
  EXPECT_EQ(killed["status"], "failed");
  EXPECT_THAT(killed["reason"].get<std::string>(), StartsWith("exceeded the time limit of 3 s and was killed"));
  EXPECT_LT(killed["wall_time_s"].get<double>(), 7.0);
  // No record to draw from, but the command that reruns it.
  EXPECT_THAT(killed["triage"]["repro"].get<std::string>(), StartsWith("campo run "));
  EXPECT_TRUE(fs::exists(dir_ / "o" / killed["triage"]["dir"].get<std::string>() / "repro.sh"));
}

// With --videos, a run that did not reach its goal (out of simulated time here) gets video.mp4
// beside its figures; one that reached gets none.
TEST_F(SweepCli, VideosOfTheRunsThatDidNotReachTheirGoal) {
  write("short.json", R"({"campo_sweep": 1, "name": "short", "scenes": ["two_barriers"],
    "set": {"/objects/drone/sensors/scanner/resolution": [16, 16]},
    "axes": [{"name": "limit", "values": [3, 300], "set": ["/world/time_limit_s"]}]})");
  EXPECT_EQ(campo("sweep " + spec("short.json") + " --out " + out("none") + " --videos").exit_code, 2);
  const Result sweep = campo("sweep " + spec("short.json") + " --out " + out("o") + " --figures --videos");
  ASSERT_EQ(sweep.exit_code, 0) << sweep.err;
  int videos = 0;
  for (const std::string& text : lines_of(slurp(dir_ / "o" / "results.jsonl"))) {
    const nlohmann::json line = nlohmann::json::parse(text);
    const bool reached = line["metrics"]["outcome"] == "reached";
    EXPECT_EQ(reached, line["params"]["limit"] == 300) << text;
    EXPECT_FALSE(line.contains("files_error")) << text;
    const fs::path video = dir_ / "o" / line["run_dir"].get<std::string>() / "video.mp4";
    EXPECT_EQ(fs::exists(video), !reached) << video;
    videos += fs::exists(video);
  }
  EXPECT_EQ(videos, 1);
}

// Kill the sweep (SIGKILL, no chance to clean up) while it runs, run the
// same command again: every run is recorded exactly once and the results are
// those of a sweep that was never interrupted.
TEST_F(SweepCli, ResumesAfterAKillLosingNothing) {
  const fs::path results = dir_ / "killed" / "results.jsonl";
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    const std::string command = std::string("exec ") + CAMPO_BINARY + " sweep " + spec("reactive.json") + " --out " +
                                out("killed") + " --jobs 1 >/dev/null 2>&1";
    ::execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  // Wait for a few finished runs, then kill.
  std::size_t recorded = 0;
  for (int i = 0; i < 30000 && recorded < 3; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    recorded = fs::exists(results) ? lines_of(slurp(results)).size() : 0;
  }
  ::kill(pid, SIGKILL);
  ::waitpid(pid, nullptr, 0);
  const std::size_t before = lines_of(slurp(results)).size();
  ASSERT_GE(before, 3u);
  ASSERT_LT(before, 18u) << "the sweep finished before it could be killed";

  const Result resumed = campo("sweep " + spec("reactive.json") + " --out " + out("killed") + " --jobs 2");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  const Result whole = campo("sweep " + spec("reactive.json") + " --out " + out("whole") + " --jobs 2");
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  const auto after_kill = results_by_id(results);
  const auto uninterrupted = results_by_id(dir_ / "whole" / "results.jsonl");
  EXPECT_EQ(after_kill.size(), 18u);
  EXPECT_EQ(after_kill, uninterrupted);
}

// The same runs under other schedules: one process at a time, two, and two
// shards run in reverse order and merged. Only wall times may differ.
TEST_F(SweepCli, ResultsDoNotDependOnJobsOrderOrShards) {
  ASSERT_EQ(campo("sweep " + spec("reactive.json") + " --out " + out("serial") + " --jobs 1").exit_code, 0);
  ASSERT_EQ(campo("sweep " + spec("reactive.json") + " --out " + out("parallel") + " --jobs 2").exit_code, 0);
  const Result shard2 = campo("sweep " + spec("reactive.json") + " --out " + out("shard2") + " --shard 2/2 --jobs 2");
  ASSERT_EQ(shard2.exit_code, 0) << shard2.err;
  EXPECT_THAT(shard2.err, HasSubstr("9 runs to do in shard 2/2"));
  ASSERT_EQ(campo("sweep " + spec("reactive.json") + " --out " + out("shard1") + " --shard 1/2 --jobs 1").exit_code, 0);
  const Result merge = campo("merge " + out("shard2") + " " + out("shard1") + " --out " + out("merged"));
  ASSERT_EQ(merge.exit_code, 0) << merge.err;
  EXPECT_THAT(merge.out, HasSubstr("merged 18 runs from 2 directories"));

  const auto serial = results_by_id(dir_ / "serial" / "results.jsonl");
  ASSERT_EQ(serial.size(), 18u);
  // The seeds and resolutions really differ (a sweep of identical runs would prove nothing).
  std::set<std::string> paths;
  for (const auto& [id, line] : serial) paths.insert(line["metrics"]["path_length_m"].dump());
  EXPECT_GT(paths.size(), 10u);
  EXPECT_EQ(results_by_id(dir_ / "parallel" / "results.jsonl"), serial);
  EXPECT_EQ(results_by_id(dir_ / "merged" / "results.jsonl"), serial);
  // The merged manifest is the whole sweep's, in expansion order.
  const nlohmann::json manifest = nlohmann::json::parse(slurp(dir_ / "merged" / "sweep.json"));
  EXPECT_FALSE(manifest.contains("shard"));
  const auto merged_lines = lines_of(slurp(dir_ / "merged" / "results.jsonl"));
  for (std::size_t i = 0; i < merged_lines.size(); ++i) {
    EXPECT_EQ(nlohmann::json::parse(merged_lines[i])["id"], manifest["runs"][i]["id"]);
  }
  // A shard's directory is that shard's: another shard is refused there.
  const Result mixed = campo("sweep " + spec("reactive.json") + " --out " + out("shard1") + " --shard 2/2");
  EXPECT_EQ(mixed.exit_code, 2);
  EXPECT_THAT(mixed.err, HasSubstr("sweep.json: /shard: expected the sweep this directory holds"));
}

TEST_F(SweepCli, MergeRefusesAnotherSpecUnlessAllowed) {
  ASSERT_EQ(campo("sweep " + spec("tiny.json") + " --out " + out("a")).exit_code, 0);
  std::string other = kTinySpec;
  other.replace(other.find("\"count\": 1"), 10, "\"count\": 2");
  write("other.json", other);
  ASSERT_EQ(campo("sweep " + spec("other.json") + " --out " + out("b")).exit_code, 0);
  const Result refused = campo("merge " + out("a") + " " + out("b") + " --out " + out("m"));
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_THAT(refused.err, HasSubstr("b/sweep.json: /spec_sha256: expected the spec_sha256 of"));
  EXPECT_FALSE(fs::exists(dir_ / "m"));
  const Result allowed = campo("merge " + out("a") + " " + out("b") + " --out " + out("m") + " --allow-mismatch");
  ASSERT_EQ(allowed.exit_code, 0) << allowed.err;
  // Seed 1 runs are the same runs in both: 2 + 4 lines, 2 duplicates.
  EXPECT_THAT(allowed.out, HasSubstr("merged 4 runs from 2 directories into"));
  EXPECT_THAT(allowed.out, HasSubstr("2 duplicate lines dropped"));
}

// Triage of runs that did not reach their goal: the map, the depth map at the
// last step, and a command that reruns the run alone to the same metrics.
TEST_F(SweepCli, TriageKeepsFiguresAndACommandThatReproducesTheRun) {
  const Result sweep = campo("sweep " + spec("tiny.json") + " --out " + out("o") + " --triage");
  ASSERT_EQ(sweep.exit_code, 0) << sweep.err;
  const nlohmann::json line = nlohmann::json::parse(lines_of(slurp(dir_ / "o" / "results.jsonl"))[0]);
  ASSERT_TRUE(line.contains("triage"));
  const fs::path triage = dir_ / "o" / line["triage"]["dir"].get<std::string>();
  EXPECT_EQ(line["triage"]["dir"], "triage/" + line["name"].get<std::string>());
  const cv::Mat map = cv::imread((triage / "map.png").string());
  EXPECT_FALSE(map.empty());
  const cv::Mat depth = cv::imread((triage / "depth.png").string(), cv::IMREAD_UNCHANGED);
  ASSERT_FALSE(depth.empty());
  EXPECT_EQ(depth.depth(), CV_16U);
  EXPECT_EQ(slurp(triage / "repro.sh").find("#!/bin/sh\n"), 0u);
  EXPECT_NE(fs::status(triage / "repro.sh").permissions() & fs::perms::owner_exec, fs::perms::none);

  std::string command = line["triage"]["repro"].get<std::string>();
  ASSERT_THAT(command, StartsWith("campo run "));
  command.replace(0, 5, CAMPO_BINARY);
  ASSERT_EQ(std::system((command + " >/dev/null 2>&1").c_str()), 0) << command;
  const nlohmann::json rerun = nlohmann::json::parse(slurp(triage / "rerun" / "run.json"));
  EXPECT_EQ(without_wall_time({{"metrics", rerun["metrics"]}}), without_wall_time({{"metrics", line["metrics"]}}));
}

TEST_F(SweepCli, ListPrintsTheManifestWithStableIds) {
  const Result r = campo("sweep " + spec("reactive.json") + " --list");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto lines = lines_of(r.out);
  ASSERT_EQ(lines.size(), 18u);
  EXPECT_EQ(nlohmann::json::parse(lines[0])["name"], "two_barriers__resolution-32__seed-1");
  EXPECT_EQ(campo("sweep " + spec("reactive.json") + " --list").out, r.out);
  const Result shard = campo("sweep " + spec("reactive.json") + " --list --shard 3/4");
  ASSERT_EQ(shard.exit_code, 0) << shard.err;
  const auto part = lines_of(shard.out);
  ASSERT_EQ(part.size(), 4u);  // runs 3, 7, 11, 15
  EXPECT_EQ(part[1], lines[6]);
  EXPECT_THAT(r.err, HasSubstr("18 runs"));
  EXPECT_FALSE(fs::exists(dir_ / "o"));
}

TEST_F(SweepCli, BadInputWritesNothing) {
  std::string bad = kTinySpec;
  bad.replace(bad.find("/resolution/0"), 13, "/resolutoin/0");
  write("bad.json", bad);
  const Result r = campo("sweep " + spec("bad.json") + " --out " + out("o"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("bad.json:4:14: /scenes/0: run two_barriers__resolution-16__seed-1: "));
  EXPECT_THAT(r.err, HasSubstr("resolutoin"));
  EXPECT_FALSE(fs::exists(dir_ / "o"));
  const Result shard = campo("sweep " + spec("tiny.json") + " --out " + out("o") + " --shard 3/2");
  EXPECT_EQ(shard.exit_code, 2);
  EXPECT_THAT(shard.err, HasSubstr("command line: --shard: expected K/N with 1 <= K <= N"));
  EXPECT_FALSE(fs::exists(dir_ / "o"));
}

TEST_F(SweepCli, HelpHasExamples) {
  for (const char* sub : {"sweep", "merge", "table", "plot"}) {
    const Result help = campo(std::string(sub) + " --help");
    EXPECT_EQ(help.exit_code, 0) << sub;
    EXPECT_THAT(help.out, HasSubstr("Usage")) << sub;
    EXPECT_THAT(help.out, HasSubstr("Example: campo " + std::string(sub))) << sub;
  }
}

// One name per scene: a scene file whose "name" differs from its file name is called by its "name" in
// the sweep's runs, results and tables, as its run.json's provenance calls it; two files of one name
// are refused. The overhead the sweep reports per run is never negative.
TEST_F(SweepCli, AScenesNameIsTheOneItsRunsResultsAndTablesUse) {
  nlohmann::json scene = nlohmann::json::parse(slurp(fs::path(CAMPO_SOURCE_DIR) / "scenes" / "two_barriers.json"));
  scene["name"] = "barriers_renamed";
  write("field_copy.json", scene.dump());
  nlohmann::json spec_json = nlohmann::json::parse(kTinySpec);
  spec_json["scenes"] = {"field_copy.json"};
  spec_json["axes"][0]["values"] = {16};
  write("renamed.json", spec_json.dump());
  const Result sweep = campo("sweep " + spec("renamed.json") + " --out " + out("renamed") + " --keep-runs --jobs 1");
  ASSERT_EQ(sweep.exit_code, 0) << sweep.err;
  const nlohmann::json line = nlohmann::json::parse(lines_of(slurp(dir_ / "renamed" / "results.jsonl")).at(0));
  EXPECT_EQ(line["scene"], "barriers_renamed");
  EXPECT_THAT(line["name"].get<std::string>(), StartsWith("barriers_renamed__resolution-16__seed-1"));
  const nlohmann::json record =
      nlohmann::json::parse(slurp(dir_ / "renamed" / line["run_dir"].get<std::string>() / "run.json"));
  EXPECT_EQ(record["provenance"]["scene"]["name"], line["scene"]);
  // The same scene run alone has that name too.
  const Result run = campo("run " + spec("field_copy.json") + " --set /world/time_limit_s=1 --out " + out("alone"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(nlohmann::json::parse(slurp(dir_ / "alone" / "run.json"))["provenance"]["scene"]["name"],
            "barriers_renamed");
  const Result table = campo("table " + out("renamed") + " --rows scene --metrics success --no-chart");
  ASSERT_EQ(table.exit_code, 0) << table.err;
  EXPECT_THAT(table.out, HasSubstr("| barriers_renamed |"));
  EXPECT_THAT(table.out, ::testing::Not(HasSubstr("field_copy")));

  // The overhead per run: wall time of the run's process minus the run's own time, measured from before the fork.
  const std::size_t at = sweep.err.find("sweep overhead: ");
  ASSERT_NE(at, std::string::npos) << sweep.err;
  EXPECT_GE(std::stod(sweep.err.substr(at + 16)), 0.0) << sweep.err;

  // Two files of one name would be one scene in every table: refused, naming both.
  write("field_other.json", scene.dump());
  spec_json["scenes"] = {"field_copy.json", "field_other.json"};
  write("twice.json", spec_json.dump());
  const Result twice = campo("sweep " + spec("twice.json") + " --list");
  EXPECT_EQ(twice.exit_code, 2);
  EXPECT_THAT(twice.err, HasSubstr("/scenes/1: expected scenes with distinct names"));
  EXPECT_THAT(twice.err, HasSubstr("is named \"barriers_renamed\" as the scene at /scenes/0"));
}

}  // namespace
