// Several vehicles in one world (issue 33): each senses the others where the
// physics has them and never itself, vehicles collide with each other and both
// count it naming the other, the end rule, the least distance between them,
// and the single-vehicle API's refusals. Expected values come from the
// geometry of the vehicles' collision boxes (quadrotor: 0.6 x 0.6 x 0.12 m).
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include "campo/episode.hpp"
#include "campo/planner_registry.hpp"
#include "campo/run_record.hpp"
#include "campo/scene_loader.hpp"
#include "campo/sensor_factory.hpp"
#include "campo/vehicle_factory.hpp"

namespace campo {
namespace {

constexpr double kHalfBox_m = 0.3;  // a quadrotor's collision box, half its length and width (preset)

// A quadrotor at (x, y, z) facing `yaw_deg`, with one forward and one backward
// single-beam sensor of `type`, flying the `straight` planner to `goal`.
nlohmann::json drone(const std::string& alias, double x, double y, double z, double yaw_deg, nlohmann::json goal,
                     const std::string& type = "lidar") {
  const auto beam = [&](const std::string& name, double sensor_yaw_deg) {
    return nlohmann::json{{"alias", name},
                          {"type", type},
                          {"fov_deg", {1, 1}},
                          {"resolution", {1, 1}},
                          {"range_m", {0.01, 20}},
                          {"mount", {{"rpy_deg", {0, 0, sensor_yaw_deg}}}}};
  };
  return {{"alias", alias},
          {"type", "quadrotor"},
          {"pose", {{"position_m", {x, y, z}}, {"rpy_deg", {0, 0, yaw_deg}}}},
          {"sensors", {beam("front", 0), beam("back", 180)}},
          {"planner", {{"name", "straight"}}},
          {"mission", {{"waypoints", {{{"position_m", goal}}}}}}};
}

Scene fleet_scene(nlohmann::json vehicles, double time_limit_s = 30.0, const std::string& end = "all") {
  nlohmann::json objects = {{{"alias", "ground"}, {"type", "plane"}}};
  for (auto& v : vehicles) objects.push_back(std::move(v));
  const nlohmann::json document = {{"world", {{"time_limit_s", time_limit_s}}}, {"end", end}, {"objects", objects}};
  return parse_scene(document, "inline.json", std::filesystem::temp_directory_path());
}

PlanResult hold_at(const Observation& o) {
  PlanResult plan;
  plan.command = command::Hold{o.state.position_m, std::nullopt};
  return plan;
}

// The first scan of each (vehicle, sensor) of an episode whose vehicles hold where they start.
std::map<std::pair<std::size_t, std::size_t>, RangeScan> first_scans(const Scene& scene, SensorFactory factory) {
  std::map<std::pair<std::size_t, std::size_t>, RangeScan> scans;
  EpisodeOptions options;
  options.make_sensor = std::move(factory);
  options.on_scan = [&](std::size_t vehicle, std::size_t sensor, const RangeScan& scan) {
    scans.try_emplace({vehicle, sensor}, scan);
  };
  Episode episode(scene, &make_vehicle, options);
  return scans;
}

void expect_sees_each_other(const SensorFactory& factory, const char* what) {
  // Face to face 4 m apart (centres), each sensor at its vehicle's centre.
  const Scene scene = fleet_scene({drone("a", 0, 0, 2, 0, {10, 0, 2}), drone("b", 4, 0, 2, 180, {-10, 0, 2})});
  const auto scans = first_scans(scene, factory);
  ASSERT_EQ(scans.size(), 4u) << what;
  // Forward: the other's near face, 4 - 0.3 m away (the first scan is at t = 0, where they start).
  for (const std::size_t v : {0u, 1u}) {
    const RangeScan& front = scans.at({v, 0});
    ASSERT_EQ(front.hits.at(0), 1) << what << " vehicle " << v;
    EXPECT_NEAR(front.ranges_m.at(0), 4.0 - kHalfBox_m, 2e-3) << what << " vehicle " << v;
    // Backward: nothing (not its own box, which the sensor sits inside).
    EXPECT_EQ(scans.at({v, 1}).hits.at(0), 0) << what << " vehicle " << v;
  }
}

TEST(MultiVehicle, EachSensorSeesTheOtherVehicleNeverItsOwn) {
  expect_sees_each_other(&make_lidar_sensor, "lidar");
}

TEST(MultiVehicle, DepthCamerasSeeTheOtherVehicleToo) {
  const Scene scene = fleet_scene({drone("a", 0, 0, 2, 0, {10, 0, 2}, "depth_camera"),
                                drone("b", 4, 0, 2, 180, {-10, 0, 2}, "depth_camera")});
  const auto scans = first_scans(scene, range_sensor_factory());
  ASSERT_EQ(scans.size(), 4u);
  for (const std::size_t v : {0u, 1u}) {
    ASSERT_EQ(scans.at({v, 0}).hits.at(0), 1) << "vehicle " << v;
    EXPECT_NEAR(scans.at({v, 0}).ranges_m.at(0), 4.0 - kHalfBox_m, 5e-3) << "vehicle " << v;
    EXPECT_EQ(scans.at({v, 1}).hits.at(0), 0) << "vehicle " << v;
  }
}

TEST(MultiVehicle, AVehicleAloneSeesNothingWhereTheOtherWouldBe) {
  // An array of one, said so: a braced json of one json is a copy with clang, an array with GCC.
  const Scene scene = fleet_scene(nlohmann::json::array({drone("a", 0, 0, 2, 0, {10, 0, 2})}));
  const auto scans = first_scans(scene, &make_lidar_sensor);
  EXPECT_EQ(scans.at({0, 0}).hits.at(0), 0);
}

TEST(MultiVehicle, VehiclesThatCollideBothCountItNamingTheOther) {
  // Head-on along x at the same height, each flying to where the other starts.
  const Scene scene = fleet_scene({drone("a", 0, 0, 2, 0, {4, 0, 2}), drone("b", 4, 0, 2, 180, {0, 0, 2})});
  const EpisodeResult r = run_episode(scene, &make_vehicle, &create_planner);
  ASSERT_EQ(r.vehicles.size(), 2u);
  for (const auto& [self, other] : {std::pair{0, 1}, std::pair{1, 0}}) {
    const EpisodeMetrics& m = r.vehicles[self].metrics;
    EXPECT_EQ(m.outcome, Outcome::collision) << r.vehicles[self].alias << ": " << m.reason;
    ASSERT_FALSE(m.collision_events.empty());
    EXPECT_EQ(m.collision_events.front().body, r.vehicles[other].alias);
    EXPECT_FALSE(m.collision_events.front().ground);
    EXPECT_NE(m.reason.find("collision with " + r.vehicles[other].alias), std::string::npos) << m.reason;
    // They met halfway, at the same instant.
    EXPECT_NEAR(m.collision_events.front().point_m.x(), 2.0, 0.1);
    EXPECT_EQ(m.collision_events.front().time_s, r.vehicles[other].metrics.collision_events.front().time_s);
    EXPECT_LE(m.separations.at(0).min_distance_m, 0.0);
  }
  EXPECT_EQ(r.fleet.outcome, Outcome::collision);
  EXPECT_TRUE(r.fleet.any_collision);
  EXPECT_EQ(r.fleet.collisions, 2);
  EXPECT_FALSE(r.fleet.all_reached);
  EXPECT_TRUE(std::isnan(r.fleet.makespan_s));
}

TEST(MultiVehicle, TheEndRuleStopsTheOthersAtTheFirstFailureOrLetsThemFinish) {
  const nlohmann::json pair = {drone("a", 0, 0, 2, 0, {4, 0, 2}), drone("b", 4, 0, 2, 180, {0, 0, 2})};
  nlohmann::json vehicles = pair;
  vehicles.push_back(drone("far", 0, 30, 2, 0, {6, 30, 2}));
  {
    const EpisodeResult all = run_episode(fleet_scene(vehicles, 60.0, "all"), &make_vehicle, &create_planner);
    EXPECT_EQ(all.vehicles[2].metrics.outcome, Outcome::reached) << all.vehicles[2].metrics.reason;
    EXPECT_GT(all.vehicles[2].metrics.sim_time_s, all.vehicles[0].metrics.sim_time_s);
    EXPECT_EQ(all.fleet.sim_time_s, all.vehicles[2].metrics.sim_time_s);
    EXPECT_EQ(all.fleet.vehicles_reached, 1);
  }
  {
    const EpisodeResult first = run_episode(fleet_scene(vehicles, 60.0, "first_failure"), &make_vehicle, &create_planner);
    const EpisodeMetrics& far = first.vehicles[2].metrics;
    EXPECT_EQ(far.outcome, Outcome::stopped) << far.reason;
    EXPECT_NE(far.reason.find("collision"), std::string::npos) << far.reason;
    EXPECT_EQ(far.sim_time_s, first.vehicles[0].metrics.sim_time_s);
    // The run is judged by the failure that ended it, not by the vehicle it stopped.
    EXPECT_EQ(first.fleet.outcome, Outcome::collision);
    EXPECT_EQ(first.fleet.reason.rfind("a: collision with b", 0), 0u) << first.fleet.reason;
  }
}

TEST(MultiVehicle, TheLeastDistanceIsTheGapBetweenTheirBoxes) {
  // Side by side 5 m apart across y, holding for a second: the gap between the boxes is 5 - 2 * 0.3 m.
  const Scene scene = fleet_scene({drone("a", 0, 0, 2, 0, {10, 0, 2}), drone("b", 0, 5, 2, 0, {10, 5, 2})}, 1.0);
  Episode episode(scene, &make_vehicle);
  while (!episode.done()) episode.step({hold_at(episode.observation(0)), hold_at(episode.observation(1))});
  const EpisodeResult r = episode.finish();
  for (const VehicleResult& v : r.vehicles) {
    EXPECT_EQ(v.metrics.outcome, Outcome::timeout);
    ASSERT_EQ(v.metrics.separations.size(), 1u);
    EXPECT_NEAR(v.metrics.separations[0].min_distance_m, 5.0 - 2 * kHalfBox_m, 0.01) << v.alias;
    EXPECT_EQ(v.metrics.separations[0].other, v.alias == "a" ? "b" : "a");
  }
  EXPECT_NEAR(r.fleet.min_vehicle_distance_m, 5.0 - 2 * kHalfBox_m, 0.01);
  EXPECT_EQ(r.fleet.min_vehicle_distance_pair, "a|b");
  // In run.json, under each vehicle's name.
  const nlohmann::json record = run_json(scene, r, {}, {});
  EXPECT_EQ(record.at("vehicles").at(0).at("metrics").at("min_distance_to_b_m").get<double>(),
            r.vehicles[0].metrics.separations[0].min_distance_m);
  EXPECT_EQ(record.at("vehicles").at(1).at("trajectory_file"), "trajectory_b.csv");
  EXPECT_EQ(record.at("metrics").at("outcome"), "timeout");
}

TEST(MultiVehicle, ACommandAVehicleCannotFollowNamesItAndChangesNothing) {
  const Scene scene = fleet_scene({drone("a", 0, 0, 2, 0, {10, 0, 2}), drone("b", 0, 5, 2, 0, {10, 5, 2})}, 0.5);
  const auto run = [&](bool bad_first) {
    Episode episode(scene, &make_vehicle);
    if (bad_first) {
      PlanResult twist;
      twist.command = command::Twist{1.0, 0.0};  // a quadrotor follows no body velocities
      std::vector<PlanResult> plans{hold_at(episode.observation(0)), twist};
      try {
        episode.step(std::move(plans));
        ADD_FAILURE() << "a Twist for a quadrotor was taken";
      } catch (const VehicleCommandError& e) {
        EXPECT_EQ(e.vehicle(), 1u);
        EXPECT_EQ(std::string(e.what()).rfind("b: ", 0), 0u) << e.what();
      }
    }
    while (!episode.done()) episode.step({hold_at(episode.observation(0)), hold_at(episode.observation(1))});
    return episode.finish().final_state_hash;
  };
  EXPECT_EQ(run(true), run(false));
}

TEST(MultiVehicle, TheSingleVehicleApiRefusesSeveral) {
  const Scene scene = fleet_scene({drone("a", 0, 0, 2, 0, {10, 0, 2}), drone("b", 0, 5, 2, 0, {10, 5, 2})}, 0.2);
  Episode episode(scene, &make_vehicle);
  EXPECT_EQ(episode.vehicle_count(), 2u);
  EXPECT_THROW(episode.step(hold_at(episode.observation(0))), std::logic_error);
  EXPECT_THROW(episode.step(std::vector<PlanResult>{hold_at(episode.observation(0))}), std::invalid_argument);  // one for two
  episode.fail("stopped by the test");
  const EpisodeResult r = episode.finish();
  EXPECT_THROW((void)r.only(), std::logic_error);
  EXPECT_EQ(r.vehicles[1].metrics.outcome, Outcome::failed);
}

TEST(MultiVehicle, RunsAreBitIdentical) {
  const Scene scene = fleet_scene({drone("a", 0, 0, 2, 0, {4, 1, 2}), drone("b", 4, 0, 2.5, 180, {0, -1, 2.5})});
  const EpisodeResult first = run_episode(scene, &make_vehicle, &create_planner);
  const EpisodeResult second = run_episode(scene, &make_vehicle, &create_planner);
  EXPECT_EQ(first.final_state_hash, second.final_state_hash);
  for (std::size_t v = 0; v < 2; ++v) {
    EXPECT_EQ(trajectory_csv(first.vehicles[v]), trajectory_csv(second.vehicles[v]));
  }
}

}  // namespace
}  // namespace campo
