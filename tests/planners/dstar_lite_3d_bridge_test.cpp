// Closed loop on the bundled `bridge` scene: seed 001's known limit (001 §6,
// "a bridge would be reconstructed as a hill; the vehicle could avoid it by
// flying over it, but could not consider flying under it") with column
// mapping, and lifted by octomap mapping.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "campo/json_reader.hpp"
#include "campo/scene_loader.hpp"
#include "closed_loop_support.hpp"
#include "planners/dstar_lite_3d.hpp"
#include "tests/scan_support.hpp"

namespace campo {
namespace {

// The scene's deck: rows 20-22 (y 28.5..33 m), underside 19 m, top 22 m (world z).
constexpr double kDeckSouthM = 28.5;
constexpr double kDeckNorthM = 33.0;
constexpr double kDeckBottomM = 19.0;
constexpr double kDeckTopM = 22.0;

ParamsBlock bridge_params(nlohmann::json values) { return {std::move(values), "scene.json", "/objects/2/planner/params"}; }

// Seed 001's grid with take-off ground at z = 0: cell (x, y, z) has its centre
// at (0.75 + 1.5 x, 0.75 + 1.5 y, 7 (z - 2)).
Eigen::Vector3d bridge_cell_center(int x, int y, int z) { return {0.75 + 1.5 * x, 0.75 + 1.5 * y, 7.0 * (z - 2)}; }

// Flies east along level 4 (14 m) from cell (0, 0) to (6, 0); the first scan,
// from the vehicle, returns hits on the underside of an overhang at 19 m over
// columns 2-4, rows 0-11 (going round it, 24 cells, costs more than climbing
// two levels over it and back, 21). The planned path's highest point is returned.
double highest_planned_z(const std::string& mapping) {
  auto planner = make_dstar_lite_3d_planner(bridge_params({{"mapping", mapping}}), {VehicleType::quadrotor, nullptr});
  const std::vector<Waypoint> mission{{bridge_cell_center(6, 0, 4), {}}};
  RangeScan scan;
  scan.sensor_pose.translation() = bridge_cell_center(0, 0, 4);
  for (int x = 2; x <= 4; ++x) {
    for (int y = 0; y <= 11; ++y) scan.points.emplace_back(0.75f + 1.5f * x, 0.75f + 1.5f * y, 19.0f);
  }
  std::vector<SensorReading> sensors{{"leddar", nullptr, test_support::borrowed(scan), true}};
  Observation o;
  o.state.position_m = bridge_cell_center(0, 0, 4);
  o.sensors = sensors;
  o.mission = mission;
  const PlanResult r = planner->plan(o);
  EXPECT_EQ(r.status, PlanStatus::running);
  double highest = -1e9;
  for (const Eigen::Vector3d& p : r.decisions.planned_path.value()) highest = std::max(highest, p.z());
  return highest;
}

TEST(DStarLite3dOctomap, AnOverhangBlocksOnlyItsOwnLevel) {
  // Columns: the hits at 19 m (level 5) block levels 0-5 below them, so the
  // path climbs to level 6 (28 m) over the three columns.
  EXPECT_DOUBLE_EQ(highest_planned_z("columns"), 28.0);
  // Octomap: the voxels at 18.75-19.5 m (0.75 m voxels) grown by the
  // vehicle's radius (0.5 m) reach down to 18.25 m, inside level 5
  // (17.5..24.5 m) only; level 4 stays free and the
  // path runs straight along it.
  EXPECT_DOUBLE_EQ(highest_planned_z("octomap"), 14.0);
}

TEST(DStarLite3dOctomap, ParsesItsSettingsStrictly) {
  const DStarLite3dConfig c = parse_dstar_lite_3d_config(
      bridge_params({{"mapping", "octomap"}, {"octomap", {{"resolution_m", 0.25}, {"vehicle_radius_m", 1.0}}}}));
  EXPECT_EQ(c.mapping, Mapping3d::octomap);
  EXPECT_DOUBLE_EQ(c.octomap.resolution_m, 0.25);
  EXPECT_DOUBLE_EQ(c.octomap.vehicle_radius_m, 1.0);
  EXPECT_DOUBLE_EQ(c.octomap.probability_hit, 0.7);
  EXPECT_EQ(parse_dstar_lite_3d_config(bridge_params(nlohmann::json::object())).mapping, Mapping3d::columns);
  // The effective parameters read back the same.
  auto planner = make_dstar_lite_3d_planner(bridge_params({{"mapping", "octomap"}}), {VehicleType::quadrotor, nullptr});
  EXPECT_EQ(planner->parameters()["mapping"], "octomap");
  EXPECT_DOUBLE_EQ(parse_dstar_lite_3d_config(bridge_params(planner->parameters())).octomap.resolution_m, 0.75);

  const auto expect_error = [](nlohmann::json values, const std::string& message) {
    try {
      parse_dstar_lite_3d_config(bridge_params(std::move(values)));
      ADD_FAILURE() << "accepted: " << message;
    } catch (const InputError& e) {
      EXPECT_THAT(e.what(), ::testing::HasSubstr(message));
    }
  };
  expect_error({{"mapping", "voxels"}}, "scene.json: /objects/2/planner/params/mapping");
  expect_error({{"octomap", {{"resolution_m", 0.5}}}},
               "/objects/2/planner/params/octomap: octomap settings need \"mapping\": \"octomap\"");
  expect_error({{"mapping", "octomap"}, {"octomap", {{"resolution_m", 0.0}}}},
               "/objects/2/planner/params/octomap/resolution_m");
  expect_error({{"mapping", "octomap"}, {"octomap", {{"probability_miss", 0.5}}}},
               "/objects/2/planner/params/octomap/probability_miss");
  expect_error({{"mapping", "octomap"}, {"octomap", {{"radius_m", 0.5}}}}, "/objects/2/planner/params/octomap");
}

// The constants above are the scene's deck; the route flies north along
// column 16 at 14 m above ground, below the underside over the whole route
// (ground sin(x/5) <= 1 m), and the underside is in the level above the
// route's (levels 7 m apart, route level 14 m, deck level 21 m).
TEST(DStarLite3dBridge, SceneHasTheDeckAcrossTheRoute) {
  const Scene scene = load_scene(std::string(CAMPO_SOURCE_DIR) + "/scenes/bridge.json");
  const auto deck =
      std::find_if(scene.shapes.begin(), scene.shapes.end(), [](const Shape& s) { return s.alias == "deck"; });
  ASSERT_NE(deck, scene.shapes.end());
  const Eigen::Vector3d lo = deck->pose.translation() - 0.5 * deck->size_m;
  const Eigen::Vector3d hi = deck->pose.translation() + 0.5 * deck->size_m;
  EXPECT_DOUBLE_EQ(lo.y(), kDeckSouthM);
  EXPECT_DOUBLE_EQ(hi.y(), kDeckNorthM);
  EXPECT_DOUBLE_EQ(lo.z(), kDeckBottomM);
  EXPECT_DOUBLE_EQ(hi.z(), kDeckTopM);
  EXPECT_LE(lo.x(), 0.0);
  EXPECT_GE(hi.x(), 150.0);  // across the whole map: no way around it
  const auto& mission = scene.vehicles.at(0).mission;
  ASSERT_EQ(mission.size(), 2u);
  for (const Waypoint& w : mission) {
    EXPECT_DOUBLE_EQ(w.position_m.x(), 23.25);
    EXPECT_NEAR(w.position_m.z(), std::sin(23.25 / 5) + 14.0, 1e-9);
  }
  EXPECT_LT(mission[0].position_m.y(), kDeckSouthM);
  EXPECT_GT(mission[1].position_m.y(), kDeckNorthM);
}

EpisodeResult fly_bridge(const std::string& mapping) {
  return testing::run_bundled("bridge", "dstar_lite_3d", {"/objects/drone/planner/params/mapping=\"" + mapping + "\""});
}

struct Crossing {
  bool crossed = false;
  double lowest_m = std::numeric_limits<double>::infinity();
  double highest_m = -std::numeric_limits<double>::infinity();
};

// Heights of the track while it is over or under the deck's span.
Crossing crossing(const EpisodeResult& r) {
  Crossing c;
  for (const TrajectorySample& s : r.only().trajectory) {
    const Eigen::Vector3d& p = s.state.position_m;
    if (p.y() < kDeckSouthM || p.y() > kDeckNorthM) continue;
    c.crossed = true;
    c.lowest_m = std::min(c.lowest_m, p.z());
    c.highest_m = std::max(c.highest_m, p.z());
  }
  return c;
}

void expect_reached(const EpisodeResult& r) {
  EXPECT_EQ(r.only().metrics.outcome, Outcome::reached) << r.only().metrics.reason;
  EXPECT_EQ(r.only().metrics.collisions, 0);
  EXPECT_EQ(testing::waypoints_reached(r), 2);
  EXPECT_GT(r.only().metrics.min_clearance_m, 0.2);
}

// Columns (001): the underside's hits block every level below them, so the
// deck is a hill and the drone climbs over it, above its top.
TEST(DStarLite3dBridge, ColumnsClimbOverTheDeck) {
  const EpisodeResult r = fly_bridge("columns");
  expect_reached(r);
  const Crossing c = crossing(r);
  ASSERT_TRUE(c.crossed);
  EXPECT_GT(c.lowest_m, kDeckTopM);
}

// Octomap: the rays under the deck are free, the deck's voxels block only the
// level it fills, and the drone flies under it at the route's altitude.
TEST(DStarLite3dBridge, OctomapFliesUnderTheDeck) {
  const EpisodeResult r = fly_bridge("octomap");
  expect_reached(r);
  const Crossing c = crossing(r);
  ASSERT_TRUE(c.crossed);
  EXPECT_LT(c.highest_m, kDeckBottomM);
  // It mapped with the octree: planning cells were blocked (the deck's level, the piers).
  int blocked_events = 0;
  for (const PlannerEvent& e : r.only().events) blocked_events += dstar_lite_3d_record().blocked_cells.in(e.decisions.own) ? 1 : 0;
  EXPECT_GT(blocked_events, 0);
}

}  // namespace
}  // namespace campo
