// Runs the `campo` executable as a user would and checks exit codes and files.
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sys/wait.h>

#include "campo/scene_loader.hpp"
#include "render/run_files.hpp"
#include "run/event_log.hpp"
#include "tests/cli_support.hpp"

namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

using campo::testing::Result;
using campo::testing::slurp;
using Cli = campo::testing::CliTest;

std::vector<std::vector<double>> read_csv(const fs::path& path) {
  std::vector<std::vector<double>> rows;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::stringstream s(line);
    std::string cell;
    while (std::getline(s, cell, ',')) row.push_back(std::stod(cell));
    rows.push_back(row);
  }
  return rows;
}

TEST_F(Cli, VersionAndHelp) {
  const Result version = campo("--version");
  EXPECT_EQ(version.exit_code, 0);
  EXPECT_THAT(version.out, HasSubstr("campo 0."));
  for (const char* sub : {"run", "render", "validate", "scan", "bench"}) {
    const Result help = campo(std::string(sub) + " --help");
    EXPECT_EQ(help.exit_code, 0) << sub;
    EXPECT_THAT(help.out, HasSubstr("Usage")) << sub;
  }
}

TEST_F(Cli, ValidatesEveryBundledScene) {
  // The shell expands the glob; each file gets its "ok" line.
  const Result all = campo("validate " + std::string(CAMPO_SOURCE_DIR) + "/scenes/*.json");
  EXPECT_EQ(all.exit_code, 0) << all.err;
  for (const char* name : {"two_barriers", "trees_rolling_terrain", "obstacle_field", "zigzag", "wall", "bridge",
                           "vineyard", "vineyard_obstacles", "vineyard_gap"}) {
    EXPECT_THAT(all.out, HasSubstr(std::string("ok ") + CAMPO_SOURCE_DIR + "/scenes/" + name + ".json"));
  }
}

TEST_F(Cli, InvalidSceneExitsTwoWithPointer) {
  std::ofstream(dir_ / "bad.json") << R"({"objects": [{"alias": "a", "type": "cuboid", "size_m": [1, -2, 1]}]})";
  const Result r = campo("validate " + (dir_ / "bad.json").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("bad.json:1:61: /objects/0/size_m/1 (a): expected a number in (0, 1e+06], got -2"));
}

// validate refuses exactly what run refuses, with run's message: no vehicle, a first vehicle without a
// mission, a sensor rate out of range, and another vehicle's bad planner parameters (run checks them too).
TEST_F(Cli, ValidateRefusesExactlyWhatRunRefuses) {
  const std::string drone = R"({"alias": "drone", "type": "quadrotor", "pose": {"position_m": [0, 0, 1.5]},
      "mission": {"waypoints": [{"position_m": [5, 0, 1.5]}]}})";
  struct Case {
    std::string file;
    std::string message;
  };
  for (const Case& c : {
           Case{write("no_vehicle.json", R"({"objects": [{"alias": "ground", "type": "plane"}]})"),
                "no_vehicle.json:1:2: /objects: expected a scene with a vehicle to run"},
           Case{write("no_mission.json", R"({"objects": [{"alias": "drone", "type": "quadrotor"}]})"),
                "no_mission.json:1:14: /objects/0 (drone): expected vehicle \"drone\" to have a mission"},
           Case{write("slow_sensor.json", R"({"objects": [{"alias": "drone", "type": "quadrotor",
                "sensors": [{"alias": "s", "type": "lidar", "preset": "leddar_vu8", "rate_hz": 1e-14}],
                "mission": {"waypoints": [{"position_m": [5, 0, 1.5]}]}}]})"),
                "slow_sensor.json:2:85: /objects/0/sensors/0/rate_hz (drone/s): expected 0 (world.sensor_rate_hz) or a number in "
                "[0.01, 10000], got 1e-14"},
           // Every vehicle runs (issue 33): a second one without a mission is refused, named.
           Case{write("second.json", R"({"objects": [{"alias": "ground", "type": "plane"}, )" + drone +
                R"(, {"alias": "other", "type": "quadrotor", "pose": {"position_m": [3, 0, 1.5]}}]})"),
                "second.json:2:65: /objects/2 (other): expected vehicle \"other\" to have a mission"},
       }) {
    const Result validate = campo("validate " + c.file);
    EXPECT_EQ(validate.exit_code, 2) << c.file;
    EXPECT_THAT(validate.err, HasSubstr("error: " + (dir_ / c.message).string())) << c.file;
    const Result run = campo("run " + c.file + " --out " + (dir_ / "run").string());
    EXPECT_EQ(run.exit_code, 2) << c.file;
    EXPECT_THAT(run.err, HasSubstr("error: " + (dir_ / c.message).string())) << c.file;
    EXPECT_FALSE(fs::exists(dir_ / "run")) << c.file;
  }
  // Whichever vehicle --vehicle chooses.
  const std::string two = write("two.json", R"({"objects": [)" + drone + R"(, {"alias": "idle", "type": "rover"}]})");
  const Result validate = campo("validate " + two);
  EXPECT_EQ(validate.exit_code, 2);
  EXPECT_THAT(validate.err, HasSubstr("/objects/1 (idle): expected vehicle \"idle\" to have a mission"));
  EXPECT_EQ(campo("run " + two + " --vehicle drone --out " + (dir_ / "run").string()).exit_code, 2);
  EXPECT_FALSE(fs::exists(dir_ / "run"));
}

TEST_F(Cli, ScanWritesAllOutputsMatchingGeometry) {
  const std::string scene = std::string(CAMPO_SOURCE_DIR) + "/scenes/two_barriers.json";
  const fs::path out = dir_ / "scan";
  const Result r = campo("scan " + scene + " --sensor scanner3d --res 32x16 --pose 0,0,1.5,0,0,0 --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto ranges = read_csv(out / "ranges.csv");
  const auto hits = read_csv(out / "hits.csv");
  ASSERT_EQ(ranges.size(), 16u);
  ASSERT_EQ(hits.size(), 16u);
  for (const auto& row : ranges) ASSERT_EQ(row.size(), 32u);

  // Pixel (col 15, row 7) looks at azimuth 1.40625 deg left, elevation 2.8125 deg up and hits
  // the barrier face at x = 5.85: range = 5.85 / (cos(el) cos(az)).
  const double deg = std::numbers::pi / 180.0;
  const double az = (45.0 - 15.5 * 90.0 / 32.0) * deg, el = (45.0 - 7.5 * 90.0 / 16.0) * deg;
  EXPECT_NEAR(ranges[7][15], 5.85 / (std::cos(el) * std::cos(az)), 1e-3);
  EXPECT_EQ(hits[7][15], 1.0);
  // Looking up at the sky (row 0) nothing is hit within 10 m: max range, hit 0.
  EXPECT_EQ(hits[0][0], 0.0);
  EXPECT_DOUBLE_EQ(ranges[0][0], 10.0);

  const cv::Mat depth = cv::imread((out / "depth.png").string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(depth.type(), CV_16U);
  ASSERT_EQ(depth.cols, 32);
  ASSERT_EQ(depth.rows, 16);
  EXPECT_NEAR(depth.at<std::uint16_t>(7, 15), ranges[7][15] / 10.0 * 65535.0, 1.0 + 65535e-5);
  EXPECT_EQ(depth.at<std::uint16_t>(0, 0), 65535);

  int hit_count = 0;
  for (const auto& row : hits) for (double h : row) hit_count += h == 1.0;
  EXPECT_THAT(slurp(out / "points.ply"), HasSubstr("element vertex " + std::to_string(hit_count) + "\n"));

  const auto record = nlohmann::json::parse(slurp(out / "scan.json"));
  EXPECT_EQ(record["sensor"]["resolution"], nlohmann::json({32, 16}));
  EXPECT_EQ(record["provenance"]["scene"]["sha256"], campo::sha256_hex(slurp(scene)));
  EXPECT_EQ(record["hits"], hit_count);
}

TEST_F(Cli, ScanDefaultsToTheVehicleSensorAndIsDeterministic) {
  const std::string scene = std::string(CAMPO_SOURCE_DIR) + "/scenes/trees_rolling_terrain.json";
  ASSERT_EQ(campo("scan " + scene + " --res 48x48 --out " + (dir_ / "a").string()).exit_code, 0);
  ASSERT_EQ(campo("scan " + scene + " --res 48x48 --out " + (dir_ / "b").string()).exit_code, 0);
  EXPECT_EQ(slurp(dir_ / "a" / "ranges.csv"), slurp(dir_ / "b" / "ranges.csv"));
  EXPECT_EQ(slurp(dir_ / "a" / "scan.json"), slurp(dir_ / "b" / "scan.json"));
  EXPECT_EQ(read_csv(dir_ / "a" / "ranges.csv").size(), 48u);
}

TEST_F(Cli, BadScanInputExitsTwoAndWritesNothing) {
  const std::string scene = std::string(CAMPO_SOURCE_DIR) + "/scenes/two_barriers.json";
  const fs::path out = dir_ / "never";
  Result r = campo("scan " + scene + " --sensor scanner3d --res 32by16 --out " + out.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--res: expected COLSxROWS"));
  r = campo("scan " + scene + " --sensor scanner3d --range 5,1 --out " + out.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("/range_m: expected [min, max]"));
  r = campo("scan " + scene + " --sensor lidar9000 --out " + out.string());
  EXPECT_EQ(r.exit_code, 2);
  r = campo("scan " + (dir_ / "missing.json").string() + " --out " + out.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_FALSE(fs::exists(out));
}

const char* const kBundled[] = {"two_barriers", "trees_rolling_terrain", "obstacle_field",     "zigzag",
                                "wall",         "bridge",                "vineyard",           "vineyard_obstacles",
                                "vineyard_gap", "mesh_buildings",        "dem_terrain",        "gusty_barriers"};

TEST_F(Cli, RunsEveryBundledSceneWithTheStraightPlanner) {
  for (const char* name : kBundled) {
    const fs::path out = dir_ / name;
    const Result r = campo("run " + std::string(CAMPO_SOURCE_DIR) + "/scenes/" + name +
                           ".json --planner straight --set /world/time_limit_s=20 --out " + out.string());
    ASSERT_EQ(r.exit_code, 0) << name << ": " << r.err;
    for (const char* file : {"run.json", "trajectory.csv", "scene.json", "map.png", "side.png"}) {
      EXPECT_TRUE(fs::exists(out / file)) << name << "/" << file;
    }
    const auto run = nlohmann::json::parse(slurp(out / "run.json"));
    const auto& m = run["metrics"];
    for (const char* key : {"outcome", "reason", "sim_time_s", "wall_time_s", "path_length_m", "path_ratio",
                            "min_clearance_m", "collisions", "planner_time_ms_mean", "planner_time_ms_max"}) {
      EXPECT_TRUE(m.contains(key)) << name << ": " << key;
    }
    EXPECT_THAT((std::vector<std::string>{"reached", "collision", "timeout", "aborted"}),
                ::testing::Contains(m["outcome"].get<std::string>()));
    EXPECT_LE(m["sim_time_s"].get<double>(), 20.0 + 1e-9) << name;
    EXPECT_EQ(run["parameters"]["planner"]["name"], "straight");
    EXPECT_EQ(run["provenance"]["scene"]["sha256"],
              campo::sha256_hex(slurp(std::string(CAMPO_SOURCE_DIR) + "/scenes/" + name + ".json")));
    EXPECT_EQ(run["overrides"][0], "/world/time_limit_s=20");
    EXPECT_EQ(cv::imread((out / "map.png").string()).empty(), false);
  }
}

TEST_F(Cli, RunWithoutASceneUsesTheBundledDefault) {
  const Result r = campo("run --set /world/time_limit_s=3 --out " + (dir_ / "default").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto run = nlohmann::json::parse(slurp(dir_ / "default" / "run.json"));
  EXPECT_EQ(run["provenance"]["scene"]["name"], "two_barriers");
}

TEST_F(Cli, RunIsReproducibleAndRecordsTheSeed) {
  const std::string scene = std::string(CAMPO_SOURCE_DIR) + "/scenes/trees_rolling_terrain.json";
  const std::string args = "run " + scene + " --seed 7 --set /world/time_limit_s=5 --out ";
  ASSERT_EQ(campo(args + (dir_ / "a").string()).exit_code, 0);
  ASSERT_EQ(campo(args + (dir_ / "b").string()).exit_code, 0);
  EXPECT_EQ(slurp(dir_ / "a" / "trajectory.csv"), slurp(dir_ / "b" / "trajectory.csv"));
  auto a = nlohmann::json::parse(slurp(dir_ / "a" / "run.json"));
  auto b = nlohmann::json::parse(slurp(dir_ / "b" / "run.json"));
  EXPECT_EQ(a["parameters"]["world"]["seed"], 7);
  // Everything but the measured wall-clock figures is identical.
  for (auto* j : {&a, &b}) {
    for (const char* key : {"wall_time_s", "planner_time_ms_mean", "planner_time_ms_max", "replan_time_ms_median",
                            "replan_time_ms_max"}) {
      (*j)["metrics"].erase(key);
    }
  }
  EXPECT_EQ(a, b);
  // The decisions too, but for their measured times.
  std::vector<campo::RecordedRun> runs{campo::load_run_dir(dir_ / "a"), campo::load_run_dir(dir_ / "b")};
  for (campo::RecordedRun& run : runs) {
    for (campo::PlannerEvent& event : run.events) {
      if (!event.decisions.replan) continue;
      event.decisions.replan->time_ms = 0.0;
      for (const char* key : {"dilation_ms", "search_ms"}) event.decisions.replan->details.erase(key);
    }
  }
  EXPECT_FALSE(runs[0].events.empty());
  EXPECT_EQ(runs[0].events, runs[1].events);
}

// A mapping planner records every scan's LIDAR hits (tens of thousands a
// scan): run.json stays small whatever the run's length, every line of
// events.jsonl is bounded, and the figures read them back.
TEST_F(Cli, ARunWithManyBigEventsKeepsItsRecordBounded) {
  const std::string scene = std::string(CAMPO_SOURCE_DIR) + "/scenes/two_barriers.json";
  const fs::path out = dir_ / "d3";
  const Result r = campo("run " + scene + " --planner dstar_lite_3d --set /world/time_limit_s=8 --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("wrote run.json, events.jsonl, trajectory.csv, scene.json, map.png, side.png"));
  // run.json: no per-step data (the scene's parameters and the metrics only).
  EXPECT_LT(fs::file_size(out / "run.json"), 64u << 10);
  const nlohmann::json record = nlohmann::json::parse(slurp(out / "run.json"));
  EXPECT_FALSE(record.contains("events"));
  EXPECT_EQ(record["event_log"]["file"], "events.jsonl");
  const std::vector<std::string> lines = campo::testing::lines_of(slurp(out / "events.jsonl"));
  ASSERT_EQ(record["event_log"]["count"], lines.size());
  std::size_t thinned = 0, hits = 0;
  for (const std::string& line : lines) {
    EXPECT_LE(line.size(), campo::kEventLineMaxBytes);
    const nlohmann::json event = nlohmann::json::parse(line);
    const nlohmann::json& d = event["decisions"];
    if (!d.contains("lidar_hits")) continue;
    ++hits;
    EXPECT_LE(d["lidar_hits"].size(), campo::kEventArrayMaxEntries);
    // The scanner's scans hit far more than that: each says how many it had.
    if (d.contains("thinned")) {
      ++thinned;
      EXPECT_GT(d["thinned"]["/lidar_hits"].get<std::size_t>(), campo::kEventArrayMaxEntries);
    }
  }
  EXPECT_GT(hits, 10u);
  EXPECT_EQ(record["event_log"]["bounded"], thinned);
  EXPECT_GT(thinned, 10u);
  // The readers read it: the run directory, the figures redrawn.
  const campo::RecordedRun run = campo::load_run_dir(out);
  EXPECT_EQ(run.events.size(), lines.size());
  EXPECT_GT(run.view.sensor_hits.size(), 10 * campo::kEventArrayMaxEntries);
  const Result render = campo("render " + out.string() + " --kind map --out " + (dir_ / "redrawn").string());
  EXPECT_EQ(render.exit_code, 0) << render.err;
  EXPECT_TRUE(fs::is_regular_file(dir_ / "redrawn" / "d3" / "map.png"));
}

TEST_F(Cli, BadRunInputExitsTwoAndWritesNothing) {
  const std::string scene = std::string(CAMPO_SOURCE_DIR) + "/scenes/two_barriers.json";
  const fs::path out = dir_ / "never";
  Result r = campo("run " + scene + " --set /world/physics_step_s=-1 --out " + out.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("two_barriers.json: /world/physics_step_s: expected a number in [1e-05, 0.1], got -1"));
  r = campo("run " + scene + " --set /objects/nobody/pose=1 --out " + out.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("no element with alias \"nobody\""));
  r = campo("run " + scene + " --planner teleport --out " + out.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("unknown planner \"teleport\""));
  r = campo("run " + scene + " --set /objects/drone/params/mass_kg=-3 --out " + out.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("/objects/4/params/mass_kg"));
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(Cli, RatesThatDoNotDivideThePhysicsRateExitTwoAndWriteNothing) {
  const std::string scene = std::string(CAMPO_SOURCE_DIR) + "/scenes/two_barriers.json";
  const fs::path out = dir_ / "never";
  Result r = campo("run " + scene + " --set /world/control_rate_hz=100 --out " + out.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("two_barriers.json: /world/control_rate_hz: expected a rate that divides the physics "
                               "rate 240 Hz (1 / physics_step_s) into a whole number of steps, such as 240, 120, 80 "
                               "or 60, got 100"));
  r = campo("run " + scene + " --set /world/control_rate_hz=1000 --out " + out.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("two_barriers.json: /world/control_rate_hz: expected a rate that divides the physics "
                               "rate 240 Hz (1 / physics_step_s) into a whole number of steps, such as 240 or 120, "
                               "got 1000"));
  r = campo("run " + scene + " --set /objects/drone/sensors/0/rate_hz=7 --out " + out.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("two_barriers.json: /objects/4/sensors/0/rate_hz (drone/scanner): expected a rate that divides the "
                               "physics rate 240 Hz (1 / physics_step_s) into a whole number of steps, such as "
                               "7.27272727273, 7.05882352941, 6.85714285714 or 6.66666666667, got 7"));
  // The physics step changed alone: the scene's 60 Hz control no longer fits 100 Hz physics.
  r = campo("run " + scene + " --set /world/physics_step_s=0.01 --out " + out.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("two_barriers.json:7:5: /world/control_rate_hz: expected a rate that divides the physics "
                               "rate 100 Hz (1 / physics_step_s) into a whole number of steps, such as 100, 50 or "
                               "33.3333333333, got 60"));
  r = campo("validate " + write("rates.json", R"({"world": {"sensor_rate_hz": 7}, "objects": []})"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("rates.json:1:12: /world/sensor_rate_hz: expected a rate that divides the physics rate"));
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(Cli, RatesThatDivideThePhysicsRateRunAsGivenAndAreRecorded) {
  const std::string scene = std::string(CAMPO_SOURCE_DIR) + "/scenes/two_barriers.json";
  const fs::path out = dir_ / "run";
  const Result r = campo("run " + scene + " --planner straight --set /world/control_rate_hz=60 --set "
                         "/world/sensor_rate_hz=10 --set /world/time_limit_s=2 --record-depth 1 --no-figures "
                         "--no-replan-depth --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto run = nlohmann::json::parse(slurp(out / "run.json"));
  EXPECT_EQ(run["parameters"]["world"]["control_rate_hz"], 60);
  EXPECT_EQ(run["parameters"]["world"]["sensor_rate_hz"], 10);
  // What ran: a planner call every 4 steps and a scan every 24 over 2 s of 240 Hz physics.
  EXPECT_EQ(campo::testing::lines_of(slurp(out / "trajectory.csv")).size(), 1u + 2 * 60);
  EXPECT_EQ(std::distance(fs::directory_iterator(out / "depth"), fs::directory_iterator()), 2 * 10);
}

TEST_F(Cli, SeedsAreIntegersFromZeroTo2To64Minus1) {
  const std::string scene = std::string(CAMPO_SOURCE_DIR) + "/scenes/two_barriers.json";
  const fs::path out = dir_ / "never";
  for (const char* seed : {"-1", "1.5", "1e3", "18446744073709551616", "seven", "' 7'"}) {
    const Result r = campo("run " + scene + " --seed " + seed + " --out " + out.string());
    EXPECT_EQ(r.exit_code, 2) << seed;
    EXPECT_THAT(r.err, HasSubstr("command line: --seed: expected an integer seed in [0, 18446744073709551615], got \""))
        << seed;
  }
  Result r = campo("run " + scene + " --seed=-1 --out " + out.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("command line: --seed: expected an integer seed in [0, 18446744073709551615], got \"-1\""));
  r = campo("run " + scene + " --set /world/seed=-3 --out " + out.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("two_barriers.json: /world/seed: expected an integer seed in [0, 18446744073709551615], got -3"));
  r = campo("run " + scene + " --set /world/seed=2.0 --out " + out.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("two_barriers.json: /world/seed: expected an integer seed in [0, 18446744073709551615], got 2.0"));
  r = campo("scan " + scene + " --sensor leddar_vu8 --seed -1 --out " + out.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("command line: --seed: expected an integer seed in [0, 18446744073709551615], got \"-1\""));
  EXPECT_FALSE(fs::exists(out));

  // The largest seed runs and is recorded exactly (beyond 2^53, where a double would round it).
  const fs::path big = dir_ / "big";
  r = campo("run " + scene + " --planner straight --seed 18446744073709551615 --set /world/time_limit_s=1 "
            "--no-figures --no-replan-depth --out " + big.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto run = nlohmann::json::parse(slurp(big / "run.json"));
  EXPECT_EQ(run["parameters"]["world"]["seed"].get<std::uint64_t>(), 18446744073709551615u);
  EXPECT_EQ(run["overrides"].back(), "/world/seed=18446744073709551615");
  EXPECT_THAT(slurp(big / "run.json"), HasSubstr("\"seed\": 18446744073709551615"));
}

TEST_F(Cli, BenchEpisodesRunsBothVehicles) {
  // A short episode per case: the rover in the vineyard runs `straight` without the scene's rover_route parameters.
  const Result r = campo("bench episodes --episode-time 1 --json " + (dir_ / "bench.json").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // Six single-vehicle cases, then fleets of 1, 2, 4 and 8 quadrotors over an empty field and the vineyard.
  EXPECT_EQ(campo::testing::lines_of(r.out).size(), 14u) << r.out;
  const auto figures = nlohmann::json::parse(campo::testing::slurp(dir_ / "bench.json"))["figures"];
  ASSERT_EQ(figures.size(), 14u);
  const int resolutions[] = {0, 64, 256};
  for (std::size_t i = 6; i < figures.size(); ++i) {
    EXPECT_EQ(figures[i]["vehicles"], 1 << ((i - 6) % 4)) << figures[i];
    EXPECT_EQ(figures[i]["field"], i < 10 ? "field" : "vineyard") << figures[i];
    EXPECT_NEAR(figures[i]["sim_time_s"].get<double>(), 1.0, 1e-9) << figures[i];
    EXPECT_GT(figures[i]["cost_per_vehicle_vs_one"].get<double>(), 0.0) << figures[i];
  }
  for (std::size_t i = 0; i < 6; ++i) {
    const auto& j = figures[i];
    EXPECT_EQ(j["vehicle"], i < 3 ? "quadrotor" : "rover");
    EXPECT_EQ(j["scene"], i < 3 ? "trees_rolling_terrain" : "vineyard");
    EXPECT_EQ(j["sensor_resolution"], resolutions[i % 3]);
    EXPECT_NEAR(j["sim_time_s"].get<double>(), 1.0, 1e-9) << j;
    EXPECT_GT(j["real_time_factor"].get<double>(), 0.0);
  }
}

TEST_F(Cli, RenderRedrawsFiguresFromRunFilesAlone) {
  const std::string scene = std::string(CAMPO_SOURCE_DIR) + "/scenes/two_barriers.json";
  const fs::path a = dir_ / "run_a", b = dir_ / "run_b";
  ASSERT_EQ(campo("run " + scene + " --set /world/time_limit_s=4 --record-depth 10 --out " + a.string()).exit_code, 0);
  ASSERT_EQ(campo("run " + scene + " --seed 3 --no-figures --set /world/time_limit_s=3 --out " + b.string()).exit_code, 0);
  EXPECT_FALSE(fs::exists(b / "map.png"));
  EXPECT_TRUE(fs::exists(a / "depth"));

  // The scene file may change or vanish: figures come from the run directory.
  const fs::path redrawn = dir_ / "redrawn";
  Result r = campo("render " + a.string() + " --kind map --kind side --kind depth --kind snapshot --out " + redrawn.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // The same files give the same bytes as the figures campo run drew.
  EXPECT_EQ(slurp(redrawn / "run_a" / "map.png"), slurp(a / "map.png"));
  EXPECT_EQ(slurp(redrawn / "run_a" / "side.png"), slurp(a / "side.png"));
  EXPECT_FALSE(cv::imread((redrawn / "run_a" / "snapshot.png").string()).empty());
  EXPECT_FALSE(fs::is_empty(redrawn / "run_a" / "depth_figures"));

  r = campo("render " + a.string() + " " + b.string() + " --kind overlay --out " + redrawn.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(cv::imread((redrawn / "overlay.png").string()).empty());

  r = campo("render " + b.string() + " --kind depth --out " + redrawn.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("no recorded depth maps"));
  r = campo("render " + (dir_ / "nothing").string());
  EXPECT_EQ(r.exit_code, 2);
}

TEST_F(Cli, RenderDrawsAReplanningStepFromItsRecordedDepthMap) {
  const std::string scene = std::string(CAMPO_SOURCE_DIR) + "/scenes/two_barriers.json";
  const fs::path run = dir_ / "run";
  Result r = campo("run " + scene + " --set \"/objects/drone/sensors/scanner/resolution=[32,32]\"" +
                   " --set /world/time_limit_s=8 --no-figures --out " + run.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_TRUE(fs::exists(run / "replans" / "replan_0000.png"));

  r = campo("render " + run.string() + " --kind depth --step 0");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* name : {"replan_0000_grey.png", "replan_0000_colour.png"}) {
    const fs::path file = run / "depth_figures" / name;
    EXPECT_THAT(r.out, HasSubstr(file.string()));
    const cv::Mat image = cv::imread(file.string());
    ASSERT_FALSE(image.empty()) << name;
    EXPECT_GT(image.cols, 3 * 256) << name;  // depth, dilated and thresholded panels
  }
  // Step 0 found a new waypoint: its figure shows the thresholded map too. The
  // same files give the same bytes.
  const std::string first = slurp(run / "depth_figures" / "replan_0000_colour.png");
  r = campo("render " + run.string() + " --kind depth --step all --out " + (dir_ / "all").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(slurp(dir_ / "all" / "run" / "depth_figures" / "replan_0000_colour.png"), first);

  r = campo("render " + run.string() + " --kind depth --step 999");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("run.json: /events: no replanning step 999"));
  r = campo("render " + run.string() + " --kind depth --step -1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--step: expected a replanning step"));
  r = campo("render " + run.string() + " --kind map --step 0");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("add --kind depth"));
  fs::remove(run / "replans" / "replan_0001.png");
  r = campo("render " + run.string() + " --kind depth --step 1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("replan_0001.png: missing"));

  // Only depth_reactive records replanning steps to draw.
  const fs::path straight = dir_ / "straight";
  ASSERT_EQ(campo("run " + scene + " --planner straight --no-figures --set /world/time_limit_s=1 --out " +
                  straight.string()).exit_code, 0);
  r = campo("render " + straight.string() + " --kind depth --step 0");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("/parameters/planner/name: expected \"depth_reactive\""));
}

TEST_F(Cli, ScanWithTheDepthCameraMatchesTheLidar) {
  const std::string scene = std::string(CAMPO_SOURCE_DIR) + "/scenes/two_barriers.json";
  const std::string pose = " --res 64x64 --pose 0,0,1.5,0,0,0 --out ";
  ASSERT_EQ(campo("scan " + scene + " --sensor scanner3d" + pose + (dir_ / "lidar").string()).exit_code, 0);
  const Result r = campo("scan " + scene + " --sensor depth_camera" + pose + (dir_ / "camera").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto lidar = read_csv(dir_ / "lidar" / "ranges.csv");
  const auto camera = read_csv(dir_ / "camera" / "ranges.csv");
  ASSERT_EQ(camera.size(), 64u);
  int close = 0;
  for (int row = 0; row < 64; ++row) {
    for (int col = 0; col < 64; ++col) close += std::abs(lidar[row][col] - camera[row][col]) < 0.05;
  }
  EXPECT_GT(close, 64 * 64 * 95 / 100);
  EXPECT_EQ(nlohmann::json::parse(slurp(dir_ / "camera" / "scan.json"))["sensor"]["type"], "depth_camera");
}

}  // namespace

namespace campo {
namespace {

TEST_F(Cli, FiguresDrawDynamicBodiesWhereTheRunLeftThem) {
  // A box released 2 m up falls while the drone flies (until the time limit): run.json records
  // where it landed, and the figures' scene has it there.
  const std::string scene = write("drop.json", R"j({"world": {"time_limit_s": 3}, "objects": [
    {"alias": "ground", "type": "plane"},
    {"alias": "box", "type": "cuboid", "size_m": [0.4, 0.4, 0.4], "static": false, "mass_kg": 1,
     "pose": {"position_m": [3, 0, 2]}},
    {"alias": "drone", "type": "quadrotor", "pose": {"position_m": [0, 0, 1.5]},
     "mission": {"waypoints": [{"position_m": [0, 5, 1.5]}]}, "planner": {"name": "straight"}}]})j");
  const Result r = campo("run " + scene + " --out " + (dir_ / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const RecordedRun run = load_run_dir(dir_ / "out");
  const auto& poses = run.record.at("final_body_poses");
  ASSERT_EQ(poses.size(), 1u);
  EXPECT_EQ(poses[0].at("alias"), "box");
  EXPECT_NEAR(poses[0].at("position_m").at(2).get<double>(), 0.2, 0.01);
  const Shape* box = run.scene.find_shape("box");
  ASSERT_NE(box, nullptr);
  EXPECT_NEAR(box->pose.translation().z(), 0.2, 0.01);
}

}  // namespace
}  // namespace campo
