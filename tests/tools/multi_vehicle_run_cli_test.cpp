// `campo run` of a scene with several vehicles names the files it wrote as run.json records them.
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

class MultiVehicleRunCli : public campo::testing::CliTest {};

TEST_F(MultiVehicleRunCli, TheWroteLineNamesEachVehiclesFiles) {
  // Two quadrotors 20 m apart, each flying 3 m with the straight planner.
  const std::string scene = write("two.json", R"({"objects": [
    {"alias": "ground", "type": "plane"},
    {"alias": "north", "type": "quadrotor", "pose": {"position_m": [0, 20, 1.5]}, "planner": {"name": "straight"},
     "mission": {"waypoints": [{"position_m": [3, 20, 1.5]}]}},
    {"alias": "south", "type": "quadrotor", "pose": {"position_m": [0, 0, 1.5]}, "planner": {"name": "straight"},
     "mission": {"waypoints": [{"position_m": [3, 0, 1.5]}]}}]})");
  const fs::path out = dir_ / "run";
  const Result r = campo("run " + scene + " --no-figures --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json record = nlohmann::json::parse(slurp(out / "run.json"));
  ASSERT_EQ(record.at("vehicles").size(), 2u);
  std::string files;
  for (const nlohmann::json& vehicle : record.at("vehicles")) {
    const std::string events = vehicle.at("event_log").at("file"), trajectory = vehicle.at("trajectory_file");
    EXPECT_TRUE(fs::is_regular_file(out / events)) << events;
    EXPECT_TRUE(fs::is_regular_file(out / trajectory)) << trajectory;
    files += ", " + events + ", " + trajectory;
  }
  EXPECT_THAT(r.out, HasSubstr("; wrote run.json" + files + ", scene.json to " + out.string() + "\n"));
  EXPECT_THAT(r.out, HasSubstr("events_north.jsonl, trajectory_north.csv, events_south.jsonl, trajectory_south.csv"));
  // No single-vehicle file names that were not written.
  EXPECT_FALSE(fs::exists(out / "trajectory.csv"));
  EXPECT_THAT(r.out, ::testing::Not(HasSubstr("trajectory.csv")));
}

}  // namespace
