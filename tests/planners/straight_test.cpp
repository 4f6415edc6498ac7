#include "planners/straight.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "campo/json_reader.hpp"
#include "campo/planner_registry.hpp"

namespace campo {
namespace {

Observation at(const Eigen::Vector3d& p, const std::vector<Waypoint>& mission, VehicleType type = VehicleType::quadrotor) {
  Observation o;
  o.vehicle = type;
  o.state.position_m = p;
  o.mission = mission;
  return o;
}

TEST(StraightPlanner, HeadsForEachWaypointInTurn) {
  const std::vector<Waypoint> mission{{{10, 0, 2}, {}}, {{10, 10, 2}, {}}};
  auto planner = make_straight_planner({}, {VehicleType::quadrotor, nullptr});
  PlanResult r = planner->plan(at({0, 0, 2}, mission));
  EXPECT_EQ(r.status, PlanStatus::running);
  ASSERT_TRUE(std::holds_alternative<command::GoTo>(r.command));
  EXPECT_EQ(std::get<command::GoTo>(r.command).target_m, mission[0].position_m);
  EXPECT_DOUBLE_EQ(std::get<command::GoTo>(r.command).speed_mps, 0.6);
  r = planner->plan(at({9.9, 0, 2}, mission));  // within 0.3 m
  EXPECT_EQ(std::get<command::GoTo>(r.command).target_m, mission[1].position_m);
  EXPECT_EQ(r.decisions.reached_waypoints, std::vector<int>{0});
  r = planner->plan(at({10, 9.8, 2.1}, mission));
  EXPECT_EQ(r.status, PlanStatus::reached);
  EXPECT_TRUE(std::holds_alternative<command::Hold>(r.command));
}

TEST(StraightPlanner, RoverIgnoresAltitudeAndParamsOverride) {
  const std::vector<Waypoint> mission{{{5, 0, 0}, {}}};
  ParamsBlock params{nlohmann::json::parse(R"({"speed_mps": 1.5, "tolerance_m": 1.0})"), "scene.json", "/objects/0/planner/params"};
  auto planner = make_straight_planner(params, {VehicleType::rover, nullptr});
  EXPECT_EQ(planner->plan(at({4.2, 0, 0.4}, mission, VehicleType::rover)).status, PlanStatus::reached);
  EXPECT_EQ(planner->parameters()["speed_mps"], 1.5);
}

TEST(PlannerRegistry, CreatesByNameAndRejectsUnknownNamesAndParams) {
  PlannerSpec spec;
  spec.name = "straight";
  EXPECT_NE(create_planner(spec, {VehicleType::quadrotor, nullptr}), nullptr);
  spec.name = "";
  EXPECT_NE(create_planner(spec, {VehicleType::quadrotor, nullptr}), nullptr);  // the default
  spec.name = "teleport";
  spec.name_pointer = "/objects/2/planner/name";
  spec.params.file = "scene.json";
  try {
    create_planner(spec, {VehicleType::quadrotor, nullptr});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr(
                              "scene.json: /objects/2/planner/name: unknown planner \"teleport\"; expected one of: straight"));
  }
  spec.name = "straight";
  spec.params = {nlohmann::json::parse(R"({"speed": 2})"), "scene.json", "/objects/2/planner/params"};
  EXPECT_THROW(create_planner(spec, {VehicleType::quadrotor, nullptr}), InputError);
}

}  // namespace
}  // namespace campo
