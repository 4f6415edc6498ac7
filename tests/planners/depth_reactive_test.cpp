#include "planners/depth_reactive.hpp"

#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "campo/episode.hpp"
#include "campo/json_reader.hpp"
#include "campo/planner_registry.hpp"
#include "campo/scene_loader.hpp"
#include "campo/sensor_factory.hpp"
#include "campo/vehicle_factory.hpp"
#include "sensors/lidar.hpp"
#include "tests/scan_support.hpp"

namespace campo {
namespace {

using ::testing::HasSubstr;

ParamsBlock params(nlohmann::json values) { return {std::move(values), "scene.json", "/objects/4/planner/params"}; }

// A hovering drone at (0, 0, 1.5) facing +x whose 32 x 32 scanner reads `range_m` everywhere.
struct Hover {
  RangeSensorConfig config = *sensor_preset("scanner3d");
  RangeScan scan;
  std::vector<SensorReading> readings;
  std::vector<Waypoint> mission;
  Observation observation;

  Hover(float range_m, const Eigen::Vector3d& target) {
    config.cols = config.rows = 32;
    config.mount = Pose{};
    begin_scan(scan, config, 0.0, Eigen::Isometry3d(Eigen::Translation3d(0.0, 0.0, 1.5)));
    std::fill(scan.ranges_m.begin(), scan.ranges_m.end(), range_m);
    std::fill(scan.hits.begin(), scan.hits.end(), range_m < config.max_range_m ? 1 : 0);
    readings = {SensorReading{"scanner", &config, test_support::borrowed(scan), true}};
    mission = {Waypoint{target, std::nullopt}};
    observation.vehicle = VehicleType::quadrotor;
    observation.state.position_m = {0.0, 0.0, 1.5};
    observation.stable = true;
    observation.sensors = readings;
    observation.mission = mission;
  }
};

std::unique_ptr<Planner> planner() { return make_depth_reactive_planner(params(nlohmann::json::object()), {}); }

TEST(DepthReactive, ParametersAreStrict) {
  EXPECT_NO_THROW(make_depth_reactive_planner(params({{"layers", 9}, {"structuring_element", "disc"}}), {}));
  try {
    make_depth_reactive_planner(params({{"layer", 9}}), {});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("scene.json: /objects/4/planner/params/layer: unknown key"));
  }
  EXPECT_THROW(make_depth_reactive_planner(params({{"layer_radii", "linear"}}), {}), InputError);
  EXPECT_THROW(make_depth_reactive_planner(params({{"safety_radius_m", 0.0}}), {}), InputError);
  const nlohmann::json effective = planner()->parameters();
  EXPECT_EQ(effective["layers"], 18);
  EXPECT_EQ(effective["layer_radii"], "margin");
  // The effective parameters read back as they are.
  const nlohmann::json again = make_depth_reactive_planner(params(effective), {})->parameters();
  EXPECT_EQ(again, effective);
}

TEST(DepthReactive, FliesToAVisibleTarget) {
  Hover hover(10.0f, {6.0, 0.0, 1.5});  // nothing in range
  const PlanResult r = planner()->plan(hover.observation);
  EXPECT_EQ(r.status, PlanStatus::running);
  const auto* go = std::get_if<command::GoTo>(&r.command);
  ASSERT_NE(go, nullptr);
  EXPECT_EQ(go->target_m, Eigen::Vector3d(6.0, 0.0, 1.5));
  ASSERT_TRUE(r.decisions.replan.has_value());
  EXPECT_EQ(depth_reactive_record().visibility.get(r.decisions.replan->details), "visible");
  EXPECT_EQ(depth_reactive_record().action.get(r.decisions.replan->details), "fly");
  EXPECT_EQ(r.decisions.replan->index, 0);
}

TEST(DepthReactive, WaitsForAScanTakenAtRest) {
  Hover hover(10.0f, {6.0, 0.0, 1.5});
  hover.observation.stable = false;
  const auto p = planner();
  EXPECT_TRUE(std::holds_alternative<command::Hold>(p->plan(hover.observation).command));
  hover.observation.time_s = 0.05;
  hover.observation.stable = true;  // still since 0.05 s; the scan is from 0 s
  EXPECT_TRUE(std::holds_alternative<command::Hold>(p->plan(hover.observation).command));
  hover.scan.time_s = 0.1;
  hover.observation.time_s = 0.1;
  EXPECT_TRUE(std::holds_alternative<command::GoTo>(p->plan(hover.observation).command));
}

TEST(DepthReactive, TurnsTowardTheTargetFirst) {
  Hover hover(10.0f, {0.0, 6.0, 1.5});  // to the left
  const PlanResult r = planner()->plan(hover.observation);
  const auto* face = std::get_if<command::Face>(&r.command);
  ASSERT_NE(face, nullptr);
  EXPECT_EQ(face->point_m, Eigen::Vector3d(0.0, 6.0, 1.5));
  EXPECT_TRUE(r.decisions.empty());
}

TEST(DepthReactive, ClimbsWhenTheTargetIsFarAboveTheFieldOfView) {
  Hover hover(10.0f, {2.0, 0.0, 6.0});  // 66 deg up; 20 deg allowed: climb to 6 - 2 tan 20
  const PlanResult r = planner()->plan(hover.observation);
  const auto* altitude = std::get_if<command::Altitude>(&r.command);
  ASSERT_NE(altitude, nullptr);
  EXPECT_NEAR(altitude->z_m, 6.0 - 2.0 * std::tan(20.0 * M_PI / 180.0), 1e-9);
}

TEST(DepthReactive, AnUnreachableTargetEndsTheRun) {
  Hover hover(5.1f, {5.0, 0.0, 1.5});  // a wall 0.1 m behind the target: within the 0.25 m safety radius
  const PlanResult r = planner()->plan(hover.observation);
  EXPECT_EQ(r.status, PlanStatus::no_path);
  EXPECT_THAT(r.reason, HasSubstr("target unreachable"));
  ASSERT_TRUE(r.decisions.replan.has_value());
  EXPECT_EQ(depth_reactive_record().visibility.get(r.decisions.replan->details), "unreachable");
}

TEST(DepthReactive, WallFollowingWhenTheDilatedMapIsFull) {
  Hover hover(1.0f, {8.0, 0.0, 1.5});  // a wall 1 m ahead fills the whole map
  const auto p = planner();
  const PlanResult first = p->plan(hover.observation);
  EXPECT_EQ(first.status, PlanStatus::running);
  ASSERT_TRUE(first.decisions.replan.has_value());
  EXPECT_EQ(depth_reactive_record().visibility.get(first.decisions.replan->details), "invisible");
  EXPECT_EQ(depth_reactive_record().candidates.get(first.decisions.replan->details), 0);
  EXPECT_EQ(depth_reactive_record().action.get(first.decisions.replan->details), "wall_following");
  // Then it looks 60 deg to the left of the goal direction.
  hover.observation.time_s = 1.0 / 60.0;
  const PlanResult second = p->plan(hover.observation);
  const auto* face = std::get_if<command::Face>(&second.command);
  ASSERT_NE(face, nullptr);
  const Eigen::Vector3d look = face->point_m - hover.observation.state.position_m;
  EXPECT_NEAR(std::atan2(look.y(), look.x()), 60.0 * M_PI / 180.0, 1e-9);
}

TEST(DepthReactive, FindsAWaypointBesideABarrier) {
  // A barrier 4 m ahead over the left part of the view (columns 0..19 of 32, y > 0 side).
  Hover hover(10.0f, {9.0, 0.0, 1.5});
  for (int row = 0; row < 32; ++row) {
    for (int col = 0; col < 20; ++col) {
      hover.scan.ranges_m[row * 32 + col] = 4.0f;
      hover.scan.hits[row * 32 + col] = 1;
    }
  }
  const PlanResult r = planner()->plan(hover.observation);
  ASSERT_TRUE(r.decisions.replan.has_value());
  EXPECT_EQ(depth_reactive_record().action.get(r.decisions.replan->details), "new_waypoint");
  ASSERT_TRUE(r.decisions.planned_waypoint.has_value());
  const Eigen::Vector3d w = *r.decisions.planned_waypoint;
  EXPECT_LT(w.y(), 0.0);           // to the right, where it is free
  // Beyond the barrier's edge: every pixel of the barrier reads 4 m, so the
  // waypoint lies farther than 4 m from the sensor (edge + vehicle radius).
  EXPECT_GT(depth_reactive_record().new_waypoint_range_m.get(r.decisions.replan->details).value(), 4.0);
  EXPECT_NEAR(w.z(), 1.5, 0.3);    // about level: climbing costs more
}

// Closed loop on the seed 000 scenes at coarse resolutions.
EpisodeResult fly(const std::string& name, int resolution, RangeSensorKind source = RangeSensorKind::lidar,
                  std::uint64_t seed = 0, double noise_stddev_m = 0.0) {
  Scene scene = load_scene(std::string(CAMPO_SOURCE_DIR) + "/scenes/" + name + ".json");
  scene.world.seed = seed;
  SensorDef& sensor = scene.vehicles.front().sensors.front();
  sensor.range.cols = sensor.range.rows = resolution;
  sensor.range.noise_stddev_m = noise_stddev_m;
  sensor.range.kind = source;
  EpisodeOptions options;
  options.make_sensor = range_sensor_factory();
  return run_episode(scene, &make_vehicle, &create_planner, options);
}

void expect_solved(const EpisodeResult& r, const char* what) {
  SCOPED_TRACE(what);
  EXPECT_EQ(r.only().metrics.outcome, Outcome::reached) << r.only().metrics.reason;
  EXPECT_EQ(r.only().metrics.collisions, 0);
  EXPECT_GE(r.only().metrics.waypoints_planned, 1);  // the straight line is blocked
  EXPECT_LT(r.only().metrics.path_ratio, 1.25);  // a sanity bound; the 1.10 target is the sweep table's
  EXPECT_GT(r.only().metrics.min_clearance_m, 0.0);
}

TEST(DepthReactiveClosedLoop, TwoBarriersThroughTheGap) {
  const EpisodeResult r = fly("two_barriers", 64);
  expect_solved(r, "64 x 64");
  // Through the gap (y in 0.5..2.5 at the barriers' x = 6), not around either barrier.
  for (const TrajectorySample& s : r.only().trajectory) {
    if (std::abs(s.state.position_m.x() - 6.0) < 0.2) {
      EXPECT_GT(s.state.position_m.y(), 0.5);
      EXPECT_LT(s.state.position_m.y(), 2.5);
    }
  }
}

// At 32 x 32 and 16 x 16 the margin, widened by the errors of a coarse pixel,
// closes the 2 m gap as seen from the start (docs/planners.md, "Safety at
// coarse resolutions"): the drone climbs over a barrier instead, safely.
TEST(DepthReactiveClosedLoop, TwoBarriersAtCoarseResolutions) {
  for (const int resolution : {16, 32}) {
    const EpisodeResult r = fly("two_barriers", resolution);
    SCOPED_TRACE(std::to_string(resolution) + " px");
    EXPECT_EQ(r.only().metrics.outcome, Outcome::reached) << r.only().metrics.reason;
    EXPECT_EQ(r.only().metrics.collisions, 0);
    EXPECT_GT(r.only().metrics.min_clearance_m, 0.07);  // the margin less the drone's bounding radius
  }
}

TEST(DepthReactiveClosedLoop, TreesOnRollingTerrain) { expect_solved(fly("trees_rolling_terrain", 32), "32 x 32"); }

// Seed 000 Fig. 5.5: over the 2.1 m hill of the bundled trees the drone
// follows the slope, climbing well over 1.5 m while staying between 0.75 m
// and 2.5 m above the ground beneath it (it starts and ends 1.6 m above it).
TEST(DepthReactiveClosedLoop, TreesFollowTheTerrainWithinAHeightBand) {
  const EpisodeResult r = fly("trees_rolling_terrain", 64);
  ASSERT_EQ(r.only().metrics.outcome, Outcome::reached) << r.only().metrics.reason;
  double z_min = INFINITY, z_max = -INFINITY, agl_min = INFINITY, agl_max = -INFINITY;
  for (const TrajectorySample& s : r.only().trajectory) {
    z_min = std::min(z_min, s.state.position_m.z());
    z_max = std::max(z_max, s.state.position_m.z());
    agl_min = std::min(agl_min, s.height_above_ground_m);
    agl_max = std::max(agl_max, s.height_above_ground_m);
  }
  EXPECT_GE(z_max - z_min, 1.5);
  EXPECT_GE(agl_min, 0.75);
  EXPECT_LE(agl_max, 2.5);
}

// A reduced seed 000 Table 5.1: noisy 64 x 64 and 32 x 32 scans, two seeds
// each, on the trees. The thesis's worst run was 1.07 and none above 1.10;
// campo asserts success, no run above 1.15 and 5 cm of true clearance.
TEST(DepthReactiveClosedLoop, ReducedTable5_1OnTheTrees) {
  for (const int resolution : {64, 32}) {
    for (const std::uint64_t seed : {1u, 2u}) {
      const EpisodeResult r = fly("trees_rolling_terrain", resolution, RangeSensorKind::lidar, seed, 0.01);
      SCOPED_TRACE(std::to_string(resolution) + " px, seed " + std::to_string(seed));
      EXPECT_EQ(r.only().metrics.outcome, Outcome::reached) << r.only().metrics.reason;
      EXPECT_EQ(r.only().metrics.collisions, 0);
      EXPECT_LE(r.only().metrics.path_ratio, 1.15);
      EXPECT_GE(r.only().metrics.min_clearance_m, 0.05);
    }
  }
}

TEST(DepthReactiveClosedLoop, TwoBarriersWithTheDepthCamera) {
  // At 32 x 32 over a barrier, not through the gap (TwoBarriersAtCoarseResolutions).
  const EpisodeResult r = fly("two_barriers", 32, RangeSensorKind::depth_camera);
  EXPECT_EQ(r.only().metrics.outcome, Outcome::reached) << r.only().metrics.reason;
  EXPECT_EQ(r.only().metrics.collisions, 0);
  EXPECT_GE(r.only().metrics.waypoints_planned, 1);
  EXPECT_GT(r.only().metrics.min_clearance_m, 0.07);
}

}  // namespace
}  // namespace campo
