#include "planners/dstar_lite_3d.hpp"

#include <algorithm>
#include <array>
#include <optional>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "campo/json_reader.hpp"
#include "closed_loop_support.hpp"
#include "grid/astar.hpp"
#include "metrics/mission_metrics.hpp"
#include "tests/scan_support.hpp"

namespace campo {
namespace {

using ::testing::HasSubstr;

ParamsBlock dstar_params(nlohmann::json values) { return {std::move(values), "scene.json", "/objects/2/planner/params"}; }

// Synthetic observations on seed 001's grid with take-off ground at z = 0:
// cell (x, y, z) has its centre at (0.75 + 1.5 x, 0.75 + 1.5 y, 7 (z - 2)).
Eigen::Vector3d cell_center(int x, int y, int z) { return {0.75 + 1.5 * x, 0.75 + 1.5 * y, 7.0 * (z - 2)}; }

struct Feed {
  std::vector<Waypoint> mission;
  RangeScan scan;
  std::vector<SensorReading> sensors{{"leddar", nullptr, nullptr, false}};

  Observation at(const Eigen::Vector3d& p, std::vector<Eigen::Vector3f> hits = {}) {
    scan.points = std::move(hits);
    sensors[0].scan = test_support::borrowed(scan);
    sensors[0].fresh = !scan.points.empty();
    Observation o;
    o.state.position_m = p;
    o.sensors = sensors;
    o.mission = mission;
    return o;
  }
};

Eigen::Vector3d goto_target(const PlanResult& r) {
  EXPECT_TRUE(std::holds_alternative<command::GoTo>(r.command));
  return std::get<command::GoTo>(r.command).target_m;
}

TEST(DStarLite3d, FliesCellToCellAndReplansAroundMappedHits) {
  Feed feed;
  feed.mission = {{cell_center(0, 0, 4), {}}, {cell_center(6, 0, 4), {}}};
  auto planner = make_dstar_lite_3d_planner({}, {VehicleType::quadrotor, nullptr});

  // Take-off: straight up two levels to the first waypoint, itself the target.
  PlanResult r = planner->plan(feed.at(cell_center(0, 0, 2)));
  EXPECT_EQ(r.status, PlanStatus::running);
  EXPECT_EQ(goto_target(r), cell_center(0, 0, 4));
  EXPECT_DOUBLE_EQ(std::get<command::GoTo>(r.command).speed_mps, 1.0);
  ASSERT_TRUE(r.decisions.replan.has_value());
  EXPECT_EQ(r.decisions.replan->index, 0);
  EXPECT_EQ(r.decisions.replan->sensor, "leddar");
  ASSERT_TRUE(r.decisions.planned_path.has_value());
  EXPECT_EQ(r.decisions.planned_path->size(), 3u);
  // The first call records the height map's frame (seed 001's grid), and no scan yet.
  EXPECT_EQ(dstar_lite_3d_record().height_map_grid.get(r.decisions.own),
            (HeightMapGrid{.origin_m = {0.0, 0.0}, .cell_size_m = 1.5, .columns = 100, .rows = 100}));
  EXPECT_TRUE(r.decisions.lidar_hits.empty());
  EXPECT_FALSE(dstar_lite_3d_record().height_map_columns.in(r.decisions.own));

  // Waypoint 0 reached: the next leg runs east along level 4, three cells ahead at a time.
  r = planner->plan(feed.at(cell_center(0, 0, 4) + Eigen::Vector3d(0.1, 0.0, 0.2)));
  EXPECT_EQ(r.decisions.reached_waypoints, std::vector<int>{0});
  EXPECT_EQ(goto_target(r), cell_center(3, 0, 4));
  ASSERT_TRUE(r.decisions.planned_path.has_value());
  EXPECT_EQ(r.decisions.planned_path->size(), 7u);
  EXPECT_FALSE(dstar_lite_3d_record().height_map_grid.in(r.decisions.own));  // once

  // A hit on a roof at level 4 in column (2, 0) blocks levels 0..4 there: only
  // those five cells go to D* Lite, and the new path avoids them.
  r = planner->plan(feed.at(cell_center(0, 0, 4), {Eigen::Vector3f(3.0f, 0.75f, 14.5f)}));
  ASSERT_TRUE(r.decisions.replan.has_value());
  EXPECT_EQ(r.decisions.replan->index, 2);
  EXPECT_EQ(dstar_lite_3d_record().changed_cells.get(r.decisions.replan->details), 5);
  EXPECT_GT(dstar_lite_3d_record().expansions.get(r.decisions.replan->details).value(), 0);
  EXPECT_GE(r.decisions.replan->time_ms, 0.0);
  ASSERT_TRUE(r.decisions.planned_path.has_value());
  for (const Eigen::Vector3d& point : *r.decisions.planned_path) {
    EXPECT_FALSE((point - Eigen::Vector3d(3.75, 0.75, point.z())).norm() < 0.1 && point.z() < 15.0)
        << point.transpose();
  }
  EXPECT_EQ(r.decisions.planned_path->back(), cell_center(6, 0, 4));
  // For the figures: the hit, and column (2, 0) whose top is now level 4 (centre z 14 m).
  EXPECT_EQ(r.decisions.lidar_hits, (std::vector<Eigen::Vector3d>{{3.0, 0.75, 14.5}}));
  EXPECT_EQ(dstar_lite_3d_record().height_map_columns.get(r.decisions.own), (std::vector<HeightMapColumn>{{2, 0, 14.0}}));

  const std::vector<Eigen::Vector3d> path = *r.decisions.planned_path;

  // The same hit again changes nothing: no replan while the vehicle stays in its cell.
  r = planner->plan(feed.at(cell_center(0, 0, 4), {Eigen::Vector3f(3.0f, 0.75f, 14.5f)}));
  EXPECT_FALSE(r.decisions.replan.has_value());
  EXPECT_EQ(r.decisions.lidar_hits.size(), 1u);
  EXPECT_FALSE(dstar_lite_3d_record().height_map_columns.in(r.decisions.own));

  // Moving one cell along the path moves D* Lite's start (k_m); the rest of
  // the plan holds, so no new path is recorded.
  r = planner->plan(feed.at(path[1]));
  ASSERT_TRUE(r.decisions.replan.has_value());
  EXPECT_EQ(r.decisions.replan->index, 3);
  EXPECT_EQ(dstar_lite_3d_record().changed_cells.get(r.decisions.replan->details), 0);
  EXPECT_FALSE(r.decisions.planned_path.has_value());
}

TEST(DStarLite3d, ReportsNoPathWhenTheGoalColumnIsBlocked) {
  Feed feed;
  feed.mission = {{cell_center(5, 5, 4), {}}};
  auto planner = make_dstar_lite_3d_planner({}, {VehicleType::quadrotor, nullptr});
  EXPECT_EQ(planner->plan(feed.at(cell_center(5, 0, 2))).status, PlanStatus::running);
  const PlanResult r = planner->plan(feed.at(cell_center(5, 0, 2), {Eigen::Vector3f(8.25f, 8.25f, 14.0f)}));
  EXPECT_EQ(r.status, PlanStatus::no_path);
  EXPECT_THAT(r.reason, HasSubstr("no path from cell [5,0,2] to mission waypoint 0 at cell [5,5,4]"));
  EXPECT_TRUE(std::holds_alternative<command::Hold>(r.command));
}

TEST(DStarLite3d, NeedsItsSensorAndReachesTheLastWaypoint) {
  Feed feed;
  feed.mission = {{cell_center(1, 1, 3), {}}};
  auto planner = make_dstar_lite_3d_planner(dstar_params({{"sensor", "lidar2"}}), {VehicleType::quadrotor, nullptr});
  PlanResult r = planner->plan(feed.at(cell_center(1, 1, 3)));
  EXPECT_EQ(r.status, PlanStatus::invalid_start);
  EXPECT_THAT(r.reason, HasSubstr("no sensor \"lidar2\""));
  planner = make_dstar_lite_3d_planner({}, {VehicleType::quadrotor, nullptr});
  r = planner->plan(feed.at(cell_center(1, 1, 3)));
  EXPECT_EQ(r.status, PlanStatus::reached);
  EXPECT_EQ(r.decisions.reached_waypoints, std::vector<int>{0});
}

TEST(DStarLite3d, ParsesParamsStrictly) {
  const DStarLite3dConfig c = parse_dstar_lite_3d_config(
      dstar_params({{"connectivity", "six"}, {"levels", 12}, {"ground_level", 3}, {"origin_m", {-75.0, -75.0}}}));
  EXPECT_EQ(c.connectivity, grid::Connectivity::six);
  EXPECT_EQ(c.levels, 12);
  EXPECT_EQ(c.ground_level, 3);
  EXPECT_EQ(c.origin_m, Eigen::Vector2d(-75.0, -75.0));
  const DStarLite3dConfig defaults = parse_dstar_lite_3d_config(dstar_params(nlohmann::json::object()));
  EXPECT_EQ(defaults.connectivity, grid::Connectivity::twenty_six);
  EXPECT_DOUBLE_EQ(defaults.speed_mps, 1.0);
  // A climb costs its length by default: 7 m over 1.5 m cells; 001's uniform cost is 1.
  EXPECT_DOUBLE_EQ(climb_cost_cells(defaults), 7.0 / 1.5);
  EXPECT_DOUBLE_EQ(climb_cost_cells(parse_dstar_lite_3d_config(dstar_params({{"climb_cost_cells", 1.0}}))), 1.0);
  auto planner = make_dstar_lite_3d_planner(dstar_params({{"speed_mps", 2.0}}), {VehicleType::quadrotor, nullptr});
  EXPECT_EQ(planner->parameters()["speed_mps"], 2.0);
  EXPECT_EQ(parse_dstar_lite_3d_config(dstar_params(planner->parameters())).speed_mps, 2.0);

  const auto expect_error = [](nlohmann::json values, const std::string& message) {
    try {
      parse_dstar_lite_3d_config(dstar_params(std::move(values)));
      ADD_FAILURE() << "accepted: " << message;
    } catch (const InputError& e) {
      EXPECT_THAT(e.what(), HasSubstr(message));
    }
  };
  expect_error({{"connectivity", "eight"}}, "scene.json: /objects/2/planner/params/connectivity");
  expect_error({{"ground_level", 9}}, "/objects/2/planner/params/ground_level");
  expect_error({{"speed", 1.0}}, "/objects/2/planner/params");
  expect_error({{"climb_cost_cells", -1.0}}, "/objects/2/planner/params/climb_cost_cells");
  // Issue 16: grids that GridGraph or memory could not take are input errors.
  expect_error({{"columns", 4000}, {"rows", 4000}, {"levels", 17}},
               "/objects/2/planner/params: expected columns x rows x levels <= 8000000 cells, got 4000 x 4000 x 17");
  EXPECT_NO_THROW(parse_dstar_lite_3d_config(dstar_params({{"columns", 1000}, {"rows", 1000}, {"levels", 8}})));
  expect_error({{"cell_size_m", 1e-300}}, "/objects/2/planner/params/cell_size_m");
  expect_error({{"level_spacing_m", 1e300}}, "/objects/2/planner/params/level_spacing_m");
  expect_error({{"cell_size_m", 0.01}, {"level_spacing_m", 20.0}}, "expected level_spacing_m / cell_size_m <= 1000");
  EXPECT_NO_THROW(parse_dstar_lite_3d_config(dstar_params({{"cell_size_m", 0.01}, {"level_spacing_m", 20.0}, {"climb_cost_cells", 1.0}})));
}

// Closed loop on seed 001's scenes (each a fraction of a second in Release),
// with optional --set style overrides.
EpisodeResult fly_dstar(const std::string& name, const std::vector<std::string>& overrides = {}) {
  return testing::run_bundled(name, "dstar_lite_3d", overrides);
}

using testing::waypoints_reached;

void expect_dstar_solved(const EpisodeResult& r, int waypoints, const char* what, double max_path_ratio = 1.25,
                   double min_clearance_m = 0.2) {
  SCOPED_TRACE(what);
  EXPECT_EQ(r.only().metrics.outcome, Outcome::reached) << r.only().metrics.reason;
  EXPECT_EQ(r.only().metrics.collisions, 0);
  EXPECT_GT(r.only().metrics.min_clearance_m, min_clearance_m);
  EXPECT_EQ(waypoints_reached(r), waypoints);
  EXPECT_LT(r.only().metrics.path_ratio, max_path_ratio);
  EXPECT_GT(r.only().metrics.replans, 0);
}

// Whether the track passes a box of the scene's 1-based cell table (rows
// northward, columns eastward, 1.5 m cells) between heights z0 and z1.
bool passes(const EpisodeResult& r, int row0, int row1, int col0, int col1, double z0_m, double z1_m) {
  for (const TrajectorySample& s : r.only().trajectory) {
    const Eigen::Vector3d& p = s.state.position_m;
    if (p.y() >= 1.5 * (row0 - 1) && p.y() <= 1.5 * row1 && p.x() >= 1.5 * (col0 - 1) && p.x() <= 1.5 * col1 &&
        p.z() >= z0_m && p.z() <= z1_m) {
      return true;
    }
  }
  return false;
}

// The gate metrics of a run by name, through their declarations (metrics/mission_metrics.hpp).
struct GateMeasure {
  bool measured = false;         ///< the run has the gate
  std::optional<double> time_s;  ///< when it was first inside; nullopt: never
};
GateMeasure gate(const EpisodeResult& r, const std::string& name) {
  const GateMetricFields fields(name);
  return {fields.passed.in(r.only().metrics.declared), get_unless_null(r.only().metrics.declared, fields.time_s)};
}

// The metrics of mission leg k of a run, through their declarations (metrics/mission_metrics.hpp).
struct LegMeasure {
  bool measured = false;  ///< the run has leg k
  std::optional<double> path_length_m;
  std::optional<double> lateral_before_climb_m;
};
LegMeasure leg(const EpisodeResult& r, std::size_t k) {
  const LegMetricFields fields(k);
  return {fields.path_length_m.in(r.only().metrics.declared), get_unless_null(r.only().metrics.declared, fields.path_length_m),
          get_unless_null(r.only().metrics.declared, fields.lateral_before_climb_m)};
}

TEST(DStarLite3dClosedLoop, ObstacleField) {
  const EpisodeResult r = fly_dstar("obstacle_field");
  expect_dstar_solved(r, 9, "obstacle_field");
  // At 28 m above ground the tall blocks on the route were mapped and avoided: the path changed on the way.
  int changed_paths = 0;
  for (const PlannerEvent& e : r.only().events) changed_paths += e.decisions.planned_path.has_value() ? 1 : 0;
  EXPECT_GT(changed_paths, 9);
  // Not 001 §5.1's slot (a deviation the scene states): the last leg comes south along column 46, where
  // passing west of the block at rows 49-50, columns 46-49 (column 45) is 6 cells shorter than the slot
  // at columns 50-51, under every cost and sensor setting of scenes/sweeps/behaviour_001.json.
  ASSERT_TRUE(gate(r, "slot").measured);
  EXPECT_FALSE(gate(r, "slot").time_s.has_value());
  EXPECT_TRUE(passes(r, 49, 50, 45, 45, 20.0, 33.0));
  EXPECT_FALSE(passes(r, 49, 50, 46, 49, 0.0, 36.0));
}

// The slot between the blocks at rows 49-50 (columns 46-49 and 52-55) is
// two cells wide. The SPEC route flies down column 46, where passing west of
// the block is 6 cells shorter than the slot, so a leg straight through the
// slot checks that the mapped slot is judged passable (seed 001 §5.1).
TEST(DStarLite3dClosedLoop, ObstacleFieldSlotIsPassable) {
  const EpisodeResult r = fly_dstar("obstacle_field", {R"(/objects/drone/mission/waypoints=[
      {"cell": [1, 16], "agl_m": 42}, {"cell": [60, 50], "agl_m": 42}, {"cell": [40, 51], "agl_m": 42},
      {"cell": [60, 50], "agl_m": 28}, {"cell": [40, 51], "agl_m": 28}])"});
  expect_dstar_solved(r, 5, "slot", 1.25, 0.2);
  // At 28 m the blocks (35 m) stand in the way: the drone flies through the slot, below their tops,
  // and the scene's gate says so (the legs at 42 m pass over it, above the gate's 35 m).
  EXPECT_TRUE(passes(r, 49, 50, 50, 51, 20.0, 33.0));
  ASSERT_TRUE(gate(r, "slot").measured);
  ASSERT_TRUE(gate(r, "slot").time_s.has_value());
  EXPECT_GT(*gate(r, "slot").time_s, 200.0);  // on the 28 m legs, after the 42 m ones
  EXPECT_FALSE(passes(r, 49, 50, 46, 49, 0.0, 36.0));
  EXPECT_FALSE(passes(r, 49, 50, 52, 55, 0.0, 36.0));
}

// With the scene's cost model (a climb of one level costs 2.5 cells) and the
// LIDAR pitched 35 deg down, on the way back at 28 m the drone weaves between
// the buildings it mapped from 42 m (001 §5.2) instead of climbing over them or
// going round them: it stays below their tops the whole leg.
TEST(DStarLite3dClosedLoop, Zigzag) {
  const EpisodeResult r = fly_dstar("zigzag");
  expect_dstar_solved(r, 4, "zigzag");
  // The weave with the whole map known: A* on the 8-connected plane of 1.5 m
  // cells with the four buildings (Tabella 5.3) blocked, cell (76, 16) to (1, 16).
  grid::GridGraph plane({100, 100, 1}, grid::Connectivity::eight);
  for (const auto& [row0, row1, col0, col1] : {std::array{24, 27, 16, 28}, std::array{39, 42, 6, 18},
                                               std::array{54, 57, 16, 28}, std::array{69, 72, 6, 18}}) {
    for (int row = row0; row <= row1; ++row) {
      for (int col = col0; col <= col1; ++col) plane.set_state({col - 1, row - 1, 0}, grid::CellState::blocked);
    }
  }
  const double weave_m = 1.5 * grid::to_cells(grid::AStar(plane).plan({15, 75, 0}, {15, 0, 0}).cost);
  EXPECT_NEAR(weave_m, 122.44, 0.01);
  // The 28 m lap (leg 3): no climb, within 10 % of that weave, and far
  // shorter than going round the buildings (153.7 m with a 7 m climb costing
  // its 4.67 cells and the LIDAR at 45 deg); the straight line is 112.5 m.
  ASSERT_TRUE(leg(r, 3).measured);
  ASSERT_FALSE(leg(r, 4).measured);  // four legs
  EXPECT_FALSE(leg(r, 3).lateral_before_climb_m.has_value());
  ASSERT_TRUE(leg(r, 3).path_length_m.has_value());
  EXPECT_LT(*leg(r, 3).path_length_m, 1.1 * weave_m);
  EXPECT_GT(*leg(r, 3).path_length_m, 112.5);
  double low_leg_top_m = 0.0;
  bool low_leg = false;
  for (const TrajectorySample& s : r.only().trajectory) {
    const Eigen::Vector3d& p = s.state.position_m;
    low_leg = low_leg || (p.y() > 100.0 && p.z() < 30.0);  // waypoint 3 reached at (76, 16, 28 m)
    if (low_leg) low_leg_top_m = std::max(low_leg_top_m, p.z());
  }
  EXPECT_TRUE(low_leg);
  EXPECT_LT(low_leg_top_m, 30.0);
  // Between the buildings, not around them all: beside the building at rows
  // 39-42 (columns 6-18) it flies in columns 19-28, the columns the buildings
  // north and south of it (16-28) block.
  EXPECT_TRUE(passes(r, 39, 42, 19, 28, 20.0, 30.0));
}

// Six-connected (the seed's 4 in plane + up/down) flies the same mission; its
// moves turn sharply next to walls, so less clearance is required.
TEST(DStarLite3dClosedLoop, ZigzagSixConnected) {
  expect_dstar_solved(fly_dstar("zigzag", {"/objects/drone/planner/params/connectivity=\"six\""}), 4, "six", 1.25, 0.05);
}

// The wall spans the map: coming back south at 28 m the drone climbs over it
// without first flying along it (001 §5.3): with the scene's cost model (2.5
// cells a level) and the LIDAR at 35 deg it moves less than 3 m sideways
// before topping its climb (with 4.67 cells a level and 45 deg it flew 19.6 m
// west along the wall first).
TEST(DStarLite3dClosedLoop, WallClimbedOver) {
  const EpisodeResult r = fly_dstar("wall");
  expect_dstar_solved(r, 4, "wall", 1.5);
  ASSERT_TRUE(leg(r, 3).measured);
  ASSERT_FALSE(leg(r, 4).measured);  // four legs
  ASSERT_TRUE(leg(r, 3).lateral_before_climb_m.has_value());
  EXPECT_LT(*leg(r, 3).lateral_before_climb_m, 3.0);
  // 45 m south at 28 m plus the climb over the wall and back.
  EXPECT_LT(*leg(r, 3).path_length_m, 75.0);
  // Both ways (north at 42 m, back south at 28 m) the drone crosses the wall
  // (rows 20-22: y 28.5..33) above its top: 30 m (Tabella 5.5) above the
  // highest ground under it, sin(x/5) <= 1.
  bool crossed = false;
  for (const TrajectorySample& s : r.only().trajectory) {
    if (s.state.position_m.y() > 28.5 && s.state.position_m.y() < 33.0) {
      crossed = true;
      EXPECT_GT(s.state.position_m.z(), 31.0);
    }
  }
  EXPECT_TRUE(crossed);
}

}  // namespace
}  // namespace campo
