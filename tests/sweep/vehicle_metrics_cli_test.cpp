// Sweeps of a scene with several vehicles (issue 33 point 4): results.jsonl keeps each vehicle's
// metrics beside the fleet's, and `campo table` and `campo plot` address them as ALIAS.METRIC (or
// plain names with --vehicle). Every value a table prints is checked against the run's own run.json,
// read independently from the kept run directory.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include "sweep/results.hpp"
#include "sweep/table.hpp"
#include "tests/cli_support.hpp"

namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using campo::testing::lines_of;
using campo::testing::Result;
using campo::testing::slurp;

// Two quadrotors 20 m apart, each flying 3 m straight ahead: a two-vehicle run of a few simulated seconds.
constexpr const char* kTwoDrones = R"({
  "campo_scene": 1,
  "name": "two_drones_apart",
  "world": { "time_limit_s": 20, "seed": 0 },
  "objects": [
    { "alias": "ground", "type": "plane" },
    { "alias": "a", "type": "quadrotor", "pose": { "position_m": [0, 0, 1.5] },
      "planner": { "name": "straight" },
      "mission": { "waypoints": [ { "position_m": [3, 0, 1.5] } ] } },
    { "alias": "b", "type": "quadrotor", "pose": { "position_m": [0, 20, 1.5] },
      "planner": { "name": "straight" },
      "mission": { "waypoints": [ { "position_m": [3, 20, 1.5] } ] } }
  ]
})";

// Two seeds; a's start jittered so that its path differs between them.
constexpr const char* kSpec = R"({
  "campo_sweep": 1,
  "name": "pair",
  "scenes": ["two_drones.json"],
  "seeds": { "first": 1, "count": 2 },
  "start_jitter": { "vehicle": "a", "radius_m": 0.5 }
})";

// One line of a tidy metric CSV: "<seed>,<metric>,<over>,<kind>,runs,failed,n,mean,...".
struct CsvLine {
  std::string row, metric, over, kind;
  int runs = 0, failed = 0, n = 0;
  double mean = 0.0;
};

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> cells{""};
  for (char c : line) {
    if (c == ',') {
      cells.emplace_back();
    } else {
      cells.back() += c;
    }
  }
  return cells;
}

std::vector<CsvLine> read_csv(const std::string& text) {
  std::vector<CsvLine> rows;
  const auto lines = lines_of(text);
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const auto c = split(lines[i]);
    rows.push_back({c.at(0), c.at(1), c.at(2), c.at(3), std::stoi(c.at(4)), std::stoi(c.at(5)), std::stoi(c.at(6)),
                    std::strtod(c.at(7).c_str(), nullptr)});
  }
  return rows;
}

class VehicleMetricsCli : public campo::testing::CliTest {
 protected:
  // One sweep for every test of the suite: two runs of a few seconds each.
  static void SetUpTestSuite() {
    suite_dir_ = fs::temp_directory_path() / ("campo_vehicle_metrics_" + std::to_string(::getpid()));
    fs::remove_all(suite_dir_);
    fs::create_directories(suite_dir_);
    std::ofstream(suite_dir_ / "two_drones.json") << kTwoDrones;
    std::ofstream(suite_dir_ / "pair.json") << kSpec;
    const std::string command = std::string(CAMPO_BINARY) + " sweep " + (suite_dir_ / "pair.json").string() +
                                " --out " + (suite_dir_ / "o").string() + " --keep-runs --jobs 2 >" +
                                (suite_dir_ / "sweep.out").string() + " 2>&1";
    sweep_status_ = std::system(command.c_str());
  }
  static void TearDownTestSuite() { fs::remove_all(suite_dir_); }

  void SetUp() override {
    CliTest::SetUp();
    ASSERT_EQ(sweep_status_, 0) << slurp(suite_dir_ / "sweep.out");
  }
  static std::string sweep() { return (suite_dir_ / "o").string(); }

  // Each run's run.json, by seed, read from its kept directory.
  static std::map<std::uint64_t, nlohmann::json> run_records() {
    std::map<std::uint64_t, nlohmann::json> records;
    for (const std::string& text : lines_of(slurp(suite_dir_ / "o" / "results.jsonl"))) {
      const nlohmann::json line = nlohmann::json::parse(text);
      records[line.at("seed").get<std::uint64_t>()] =
          nlohmann::json::parse(slurp(suite_dir_ / "o" / line.at("run_dir").get<std::string>() / "run.json"));
    }
    return records;
  }

  // The value of a vehicle's metric in a run.json.
  static double vehicle_metric(const nlohmann::json& record, const std::string& alias, const std::string& metric) {
    for (const nlohmann::json& vehicle : record.at("vehicles")) {
      if (vehicle.at("alias") == alias) return vehicle.at("metrics").at(metric).get<double>();
    }
    ADD_FAILURE() << "no vehicle " << alias;
    return 0.0;
  }

  static inline fs::path suite_dir_;
  static inline int sweep_status_ = -1;
};

TEST_F(VehicleMetricsCli, ResultsLinesKeepEachVehiclesMetricsAsRunJsonHasThem) {
  const auto records = run_records();
  ASSERT_EQ(records.size(), 2u);
  for (const std::string& text : lines_of(slurp(fs::path(sweep()) / "results.jsonl"))) {
    const nlohmann::json line = nlohmann::json::parse(text);
    const nlohmann::json& record = records.at(line.at("seed").get<std::uint64_t>());
    EXPECT_EQ(line.at("metrics"), record.at("metrics"));  // the fleet's
    ASSERT_EQ(line.at("vehicles").size(), 2u);
    for (std::size_t v = 0; v < 2; ++v) {
      EXPECT_EQ(line["vehicles"][v].at("alias"), record["vehicles"][v].at("alias"));
      EXPECT_EQ(line["vehicles"][v].at("metrics"), record["vehicles"][v].at("metrics"));
    }
  }
  // a's jitter moves its start, so the seeds differ in a's path and not in b's.
  EXPECT_NE(vehicle_metric(records.at(1), "a", "path_length_m"), vehicle_metric(records.at(2), "a", "path_length_m"));
}

TEST_F(VehicleMetricsCli, TablesAddressAVehiclesMetricAndTheFleetsByName) {
  const Result r = campo("table " + sweep() +
                         " --rows seed --metrics a.path_ratio,b.path_length_m,makespan_s,min_vehicle_distance_m,"
                         "success,a.success,all_reached --format csv --no-chart");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto records = run_records();
  const auto rows = read_csv(r.out);
  ASSERT_EQ(rows.size(), 2u * 7u);
  for (const CsvLine& row : rows) {
    const nlohmann::json& record = records.at(std::stoull(row.row));
    const nlohmann::json& fleet = record.at("metrics");
    EXPECT_EQ(row.runs, 1);
    EXPECT_EQ(row.n, 1) << row.metric;
    double expected = 0.0;
    if (row.metric == "a.path_ratio") expected = vehicle_metric(record, "a", "path_ratio");
    if (row.metric == "b.path_length_m") expected = vehicle_metric(record, "b", "path_length_m");
    if (row.metric == "makespan_s") expected = fleet.at("makespan_s").get<double>();
    if (row.metric == "min_vehicle_distance_m") expected = fleet.at("min_vehicle_distance_m").get<double>();
    if (row.metric == "success") expected = fleet.at("outcome") == "reached" ? 1.0 : 0.0;
    if (row.metric == "all_reached") expected = fleet.at("all_reached").get<bool>() ? 1.0 : 0.0;
    if (row.metric == "a.success") {
      for (const nlohmann::json& v : record.at("vehicles")) {
        if (v.at("alias") == "a") expected = v.at("metrics").at("outcome") == "reached" ? 1.0 : 0.0;
      }
    }
    EXPECT_EQ(row.mean, expected) << row.metric << " of seed " << row.row;  // CSV numbers in full precision
    const bool rate = row.metric == "success" || row.metric == "a.success" || row.metric == "all_reached";
    EXPECT_EQ(row.kind, rate ? "rate" : "mean") << row.metric;
  }
  // Both drones reach their goals 20 m apart: the least distance is at least 20 m less the jitter and their size.
  EXPECT_GT(records.at(1).at("metrics").at("min_vehicle_distance_m").get<double>(), 18.0);

  // --vehicle: plain names are that vehicle's; ALIAS.METRIC still any vehicle's.
  const Result b = campo("table " + sweep() + " --vehicle b --rows seed --metrics path_ratio,a.path_ratio --format csv");
  ASSERT_EQ(b.exit_code, 0) << b.err;
  for (const CsvLine& row : read_csv(b.out)) {
    const nlohmann::json& record = records.at(std::stoull(row.row));
    EXPECT_EQ(row.mean, vehicle_metric(record, row.metric == "a.path_ratio" ? "a" : "b", "path_ratio")) << row.metric;
  }
  EXPECT_THAT(b.out, HasSubstr(",b.path_ratio,all,mean,"));
  // Without --rows: the summary table, of b's metrics.
  const Result summary = campo("table " + sweep() + " --vehicle b --format csv --no-chart");
  ASSERT_EQ(summary.exit_code, 0) << summary.err;
  const auto lines = lines_of(summary.out);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_THAT(lines[1], ::testing::StartsWith("two_drones_apart,2,1,2,"));  // scene, runs, success rate, reached
}

TEST_F(VehicleMetricsCli, TheDefaultTableOfSeveralVehiclesIsTheFleets) {
  const Result r = campo("table " + sweep());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("| Scene | Success rate (%) | Makespan (s), all runs | Collisions, all runs | "
                               "Min vehicle distance (m), all runs | Normalized path length of a, all runs | "
                               "Normalized path length of b, all runs |"));
  EXPECT_THAT(r.out, HasSubstr("| two_drones_apart | 100% | "));
  EXPECT_THAT(r.err, HasSubstr("no chart: the runs have several vehicles"));
  // The means are those of the two run.json files.
  const auto records = run_records();
  const Result csv = campo("table " + sweep() + " --format csv --no-chart");
  ASSERT_EQ(csv.exit_code, 0) << csv.err;
  const auto rows = read_csv(csv.out);
  ASSERT_EQ(rows.size(), 6u);
  EXPECT_EQ(rows[0].metric, "success");
  EXPECT_EQ(rows[4].metric, "a.path_ratio");
  EXPECT_EQ(rows[5].metric, "b.path_ratio");
  const double makespan = (records.at(1)["metrics"]["makespan_s"].get<double>() +
                           records.at(2)["metrics"]["makespan_s"].get<double>()) / 2.0;
  EXPECT_DOUBLE_EQ(rows[1].mean, makespan);
  const double ratio = (vehicle_metric(records.at(1), "a", "path_ratio") + vehicle_metric(records.at(2), "a", "path_ratio")) / 2.0;
  EXPECT_DOUBLE_EQ(rows[4].mean, ratio);
}

// With one axis, the fleet's table has a row per axis value; --vehicle charts that vehicle against it.
TEST_F(VehicleMetricsCli, OneAxisGivesTheFleetsRowsAndAVehiclesChart) {
  write("two_drones.json", kTwoDrones);
  write("axis.json", R"({"campo_sweep": 1, "name": "axis", "scenes": ["two_drones.json"],
    "axes": [{"name": "goal_x_m", "values": [3, 5], "set": ["/objects/a/mission/waypoints/0/position_m/0"]}],
    "seeds": {"first": 1, "count": 1}})");
  const std::string out = (dir_ / "axis").string();
  const Result sweep = campo("sweep " + (dir_ / "axis.json").string() + " --out " + out + " --jobs 2");
  ASSERT_EQ(sweep.exit_code, 0) << sweep.err;
  const Result r = campo("table " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("| Goal x (m) | Success rate (%) | Makespan (s), all runs |"));
  EXPECT_THAT(r.out, HasSubstr("\n| 3 | 100% | "));
  EXPECT_THAT(r.out, HasSubstr("\n| 5 | 100% | "));
  EXPECT_FALSE(fs::exists(dir_ / "axis" / "chart.png"));
  const Result a = campo("table " + out + " --vehicle a");
  ASSERT_EQ(a.exit_code, 0) << a.err;
  EXPECT_THAT(a.out, HasSubstr("| Scene | Goal x (m) | Runs | Success |"));  // the summary table, of a
  EXPECT_TRUE(fs::exists(dir_ / "axis" / "chart.png"));
}

// A spec's "table" names vehicle metrics as the options do; --vehicle reads its plain names as that vehicle's.
TEST_F(VehicleMetricsCli, TheSpecsTableTakesVehicleMetrics) {
  const fs::path copy = dir_ / "copy";
  fs::copy(sweep(), copy, fs::copy_options::recursive);
  nlohmann::json manifest = nlohmann::json::parse(slurp(copy / "sweep.json"));
  manifest["spec"]["table"] = {{"rows", "seed"}, {"metrics", {"b.path_length_m", "path_length_m@reached"}}};
  write("copy/sweep.json", manifest.dump());
  // Without --vehicle the plain name is the run's, which has no path length: the error names the spec.
  const Result fleet = campo("table " + copy.string() + " --no-chart");
  EXPECT_EQ(fleet.exit_code, 2);
  EXPECT_THAT(fleet.err, HasSubstr("sweep.json: /spec/table/metrics: expected a metric of the runs ("));
  const Result a = campo("table " + copy.string() + " --vehicle a --format csv --no-chart");
  ASSERT_EQ(a.exit_code, 0) << a.err;
  const auto records = run_records();
  const auto rows = read_csv(a.out);
  ASSERT_EQ(rows.size(), 4u);
  for (const CsvLine& row : rows) {
    const bool own = row.metric == "a.path_length_m";
    EXPECT_TRUE(own || row.metric == "b.path_length_m") << row.metric;
    EXPECT_EQ(row.over, own ? "reached" : "all");
    EXPECT_EQ(row.mean, vehicle_metric(records.at(std::stoull(row.row)), own ? "a" : "b", "path_length_m"));
  }
}

TEST_F(VehicleMetricsCli, UnknownVehiclesAndMetricsAreErrorsListingWhatExists) {
  const Result alias = campo("table " + sweep() + " --rows seed --metrics c.path_ratio --no-chart");
  EXPECT_EQ(alias.exit_code, 2);
  EXPECT_THAT(alias.err, HasSubstr("--metrics: expected ALIAS.METRIC with a vehicle of the runs (a, b), got \"c\""));
  const Result metric = campo("table " + sweep() + " --rows seed --metrics a.path_ratoi --no-chart");
  EXPECT_EQ(metric.exit_code, 2);
  EXPECT_THAT(metric.err, HasSubstr("expected a metric of vehicle a (a.success, "));
  EXPECT_THAT(metric.err, HasSubstr("a.path_ratio, "));
  EXPECT_THAT(metric.err, HasSubstr("got \"a.path_ratoi\""));
  // A plain name that is no fleet metric: the fleet's are listed, and the vehicles.
  const Result plain = campo("table " + sweep() + " --rows seed --metrics path_ratio --no-chart");
  EXPECT_EQ(plain.exit_code, 2);
  EXPECT_THAT(plain.err, HasSubstr("makespan_s"));
  EXPECT_THAT(plain.err, HasSubstr("or ALIAS.METRIC of a vehicle (a, b)), got \"path_ratio\""));
  const Result vehicle = campo("table " + sweep() + " --vehicle c --no-chart");
  EXPECT_EQ(vehicle.exit_code, 2);
  EXPECT_THAT(vehicle.err, HasSubstr("--vehicle: expected a vehicle of run "));
  EXPECT_THAT(vehicle.err, HasSubstr(" (a, b), got \"c\""));
  const Result plot = campo("plot " + sweep() + " --x seed --y a.nothing --out " + (dir_ / "p.png").string());
  EXPECT_EQ(plot.exit_code, 2);
  EXPECT_THAT(plot.err, HasSubstr("--y: expected a metric of vehicle a"));
  EXPECT_FALSE(fs::exists(dir_ / "p.png"));
}

TEST_F(VehicleMetricsCli, PlotsDrawAVehiclesMetric) {
  const Result r = campo("plot " + sweep() + " --x seed --y a.path_ratio --out " + (dir_ / "a.png").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir_ / "a.png"));
  // The same with --vehicle a and the plain name: the same figure, byte for byte.
  const Result v = campo("plot " + sweep() + " --vehicle a --x seed --y path_ratio --out " + (dir_ / "v.png").string());
  ASSERT_EQ(v.exit_code, 0) << v.err;
  EXPECT_EQ(slurp(dir_ / "a.png"), slurp(dir_ / "v.png"));
}

// A results line of several vehicles, read strictly: each vehicle's metrics kept beside the fleet's,
// which hold no path metrics; a line of one vehicle reads as before.
TEST(VehicleResultsLines, AreReadStrictly) {
  const fs::path file = fs::temp_directory_path() / ("campo_vehicle_lines_" + std::to_string(::getpid()) + ".jsonl");
  const nlohmann::json vehicle = {{"outcome", "reached"}, {"path_length_m", 3.0}, {"path_ratio", 1.0},
                                  {"sim_time_s", 4.0}, {"collisions", 0}};
  nlohmann::json line = {{"id", "x"}, {"scene", "s"}, {"params", nlohmann::json::object()}, {"seed", 1},
                         {"status", "completed"}, {"overrides", nlohmann::json::array()},
                         {"metrics", {{"outcome", "timeout"}, {"sim_time_s", 5.0}, {"collisions", 1},
                                      {"all_reached", false}}},
                         {"vehicles", {{{"alias", "a"}, {"metrics", vehicle}},
                                       {{"alias", "b"}, {"metrics", vehicle}}}}};
  line["vehicles"][1]["metrics"]["outcome"] = "timeout";
  const auto read = [&](const nlohmann::json& text) {
    std::ofstream(file) << text.dump() << "\n";
    return campo::read_results(file);
  };
  const campo::RunResult run = read(line).runs.at(0);
  ASSERT_EQ(run.vehicles.size(), 2u);
  EXPECT_EQ(run.vehicles[1].alias, "b");
  EXPECT_TRUE(run.metrics.fleet);
  EXPECT_EQ(run.metrics.collisions, 1);
  EXPECT_EQ(campo::metric_value(run, "a.success"), 1.0);
  EXPECT_EQ(campo::metric_value(run, "b.success"), 0.0);
  EXPECT_EQ(campo::metric_value(run, "b.path_ratio@reached"), std::nullopt);  // b did not reach its goal
  EXPECT_EQ(campo::metric_value(run, "a.path_ratio@reached"), 1.0);
  EXPECT_EQ(campo::metric_value(run, "c.path_ratio"), std::nullopt);          // no such vehicle in this run
  EXPECT_EQ(campo::metric_value(run, "success"), 0.0);
  // Seen from b: its metrics are the plain names.
  const campo::RunResult b = campo::vehicle_run(run, "b", "f", "--vehicle");
  EXPECT_EQ(b.metrics.outcome, "timeout");
  EXPECT_EQ(b.metrics.path_length_m, 3.0);
  EXPECT_FALSE(b.metrics.fleet);
  // Each vehicle needs its metrics, with what a table reads; an alias appears once; a failed run has none.
  nlohmann::json bad = line;
  bad["vehicles"][0]["metrics"].erase("path_ratio");
  EXPECT_THROW(read(bad), campo::InputError);
  bad = line;
  bad["vehicles"][1]["alias"] = "a";
  try {
    read(bad);
    ADD_FAILURE() << "a repeated alias was read";
  } catch (const campo::InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("/vehicles/1: expected a vehicle alias once (\"a\" appears twice)"));
  }
  bad = line;
  bad["status"] = "failed";
  bad["reason"] = "r";
  bad["metrics"] = nullptr;
  EXPECT_THROW(read(bad), campo::InputError);
  fs::remove(file);
}

// The names tables and plots take apart.
TEST(VehicleMetricNames, SplitAtTheLastDotBeforeTheSuffix) {
  EXPECT_EQ(campo::split_vehicle_metric("path_ratio").vehicle, "");
  EXPECT_EQ(campo::split_vehicle_metric("drone.path_ratio").vehicle, "drone");
  EXPECT_EQ(campo::split_vehicle_metric("drone.path_ratio").metric, "path_ratio");
  // Aliases may hold dots; "@reached" stays with the metric.
  EXPECT_EQ(campo::split_vehicle_metric("uav.1.path_ratio@reached").vehicle, "uav.1");
  EXPECT_EQ(campo::split_vehicle_metric("uav.1.path_ratio@reached").metric, "path_ratio@reached");
  EXPECT_EQ(campo::vehicle_metric_name("path_ratio", "rover"), "rover.path_ratio");
  EXPECT_EQ(campo::vehicle_metric_name("drone.path_ratio", "rover"), "drone.path_ratio");
  EXPECT_EQ(campo::metric_label("drone.path_length_m"), "Path length of drone (m)");
  EXPECT_EQ(campo::metric_label("rover.success"), "Success rate of rover (%)");
  EXPECT_EQ(campo::metric_heading("drone.path_ratio@reached"), "Normalized path length of drone, reached runs");
  // A vehicle's metric has the support of the same metric of one vehicle.
  EXPECT_TRUE(campo::non_negative_metric("drone.path_ratio"));
  EXPECT_FALSE(campo::non_negative_metric("drone.min_clearance_m"));
}

}  // namespace
