#include "planners/rover_route.hpp"

#include <algorithm>
#include <array>
#include <fstream>
#include <limits>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "campo/json_reader.hpp"
#include "campo/planner_registry.hpp"
#include "campo/scene_loader.hpp"
#include "closed_loop_support.hpp"

namespace campo {
namespace {

using ::testing::HasSubstr;

ParamsBlock rover_params(nlohmann::json values) { return {std::move(values), "scene.json", "/objects/3/planner/params"}; }

TEST(RoverRoute, ParsesParamsStrictlyAndRoundTrips) {
  const RoverRouteConfig defaults = parse_rover_route_config(rover_params(nlohmann::json::object()));
  EXPECT_EQ(defaults.global, GlobalRoute::dubins);
  EXPECT_EQ(defaults.local, LocalAvoidance::follow_the_gap);
  EXPECT_DOUBLE_EQ(defaults.follow_the_gap.activation_range_m, 3.5);  // 003 §3.6

  const RoverRouteConfig c = parse_rover_route_config(rover_params(
      {{"global", "rrt_star"}, {"local", "vfh_plus"}, {"turning_radius_m", 3.0},
       {"pure_pursuit", {{"lookahead_m", 2.5}}}, {"rrt_star", {{"seed", 9}, {"max_iterations", 100}}}}));
  EXPECT_EQ(c.global, GlobalRoute::rrt_star);
  EXPECT_EQ(c.local, LocalAvoidance::vfh_plus);
  EXPECT_DOUBLE_EQ(c.pure_pursuit.lookahead_m, 2.5);
  EXPECT_EQ(c.rrt_star.seed, 9u);
  EXPECT_EQ(c.rrt_star.max_iterations, 100);

  // The effective parameters read back as the same configuration.
  auto planner = make_rover_route_planner(rover_params({{"turning_radius_m", 3.0}, {"follow_the_gap", {{"k_width", 2.0}}}}),
                                          {VehicleType::rover, nullptr});
  const RoverRouteConfig back = parse_rover_route_config(rover_params(planner->parameters()));
  EXPECT_DOUBLE_EQ(back.turning_radius_m, 3.0);
  EXPECT_DOUBLE_EQ(back.follow_the_gap.k_width, 2.0);

  const auto expect_error = [](nlohmann::json values, const std::string& message) {
    try {
      parse_rover_route_config(rover_params(std::move(values)));
      ADD_FAILURE() << "accepted: " << message;
    } catch (const InputError& e) {
      EXPECT_THAT(e.what(), HasSubstr(message));
    }
  };
  expect_error({{"global", "prm"}}, "/objects/3/planner/params/global");
  expect_error({{"pure_pursuit", {{"lookahead", 2.0}}}}, "/objects/3/planner/params/pure_pursuit");
  expect_error({{"turning_radius_m", 0.0}}, "/objects/3/planner/params/turning_radius_m");
  expect_error({{"vfh_plus", {{"mu_target", 1.0}}}}, "mu");  // mu1 > mu2 + mu3
}

TEST(RoverRoute, FormerLiteralTunablesAreWrittenOnlyWhenChanged) {
  // At their defaults they stay out of parameters(), as before they were fields.
  const nlohmann::json defaults =
      make_rover_route_planner(rover_params(nlohmann::json::object()), {VehicleType::rover, nullptr})->parameters();
  for (const char* key : {"guard_step_s", "guard_reverse_speed_mps", "avoid_stop_heading_deg", "blocked_turn_rad",
                          "memory_margin_m", "memory_cell_m", "see_through_margin_m", "vfh_grid_resolution_m",
                          "vfh_grid_margin_m", "rejoin_behind_m", "rejoin_ahead_m", "record_path_step_m"}) {
    EXPECT_FALSE(defaults.contains(key)) << key;
  }
  EXPECT_TRUE(defaults.contains("guard_horizon_s"));
  EXPECT_FALSE(defaults.contains("sensor"));

  // The behaviour they had: 60 deg is pi / 3 exactly, so the stop test is the one it was.
  const RoverRouteConfig c = parse_rover_route_config(rover_params(nlohmann::json::object()));
  EXPECT_EQ(c.avoid_stop_heading_deg * M_PI / 180.0, M_PI / 3.0);
  EXPECT_EQ(c.guard_step_s, 0.1);
  EXPECT_EQ(c.guard_reverse_speed_mps, 0.2);
  EXPECT_EQ(c.blocked_turn_rad, 0.35);
  EXPECT_EQ(c.rejoin_ahead_m, 30.0);

  // Changed, they are written and read back.
  const nlohmann::json changed =
      make_rover_route_planner(rover_params({{"guard_step_s", 0.05}, {"rejoin_ahead_m", 12.5}, {"sensor", "front"}}),
                               {VehicleType::rover, nullptr})
          ->parameters();
  EXPECT_EQ(changed["guard_step_s"], 0.05);
  EXPECT_EQ(changed["rejoin_ahead_m"], 12.5);
  EXPECT_EQ(changed["sensor"], "front");
  const RoverRouteConfig back = parse_rover_route_config(rover_params(changed));
  EXPECT_EQ(back.guard_step_s, 0.05);
  EXPECT_EQ(back.rejoin_ahead_m, 12.5);
  EXPECT_EQ(back.memory_cell_m, 0.05);

  try {
    parse_rover_route_config(rover_params({{"guard_step_s", 0.0}}));
    ADD_FAILURE() << "accepted guard_step_s 0";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "scene.json: /objects/3/planner/params/guard_step_s: expected a number in [0.01, 1], got 0.0");
  }
}

// A rover at the origin with a mission of the given waypoints (x, y) and
// one box obstacle, planned by rover_route with `params`.
Scene far_scene(const std::vector<std::array<double, 2>>& waypoints, nlohmann::json planner_params) {
  nlohmann::json wps = nlohmann::json::array();
  for (const auto& w : waypoints) wps.push_back({{"position_m", {w[0], w[1], 0.0}}});
  const nlohmann::json document = {
      {"campo_scene", 1},
      {"name", "far"},
      {"objects",
       {{{"alias", "ground"}, {"type", "plane"}},
        {{"alias", "box"}, {"type", "cuboid"}, {"size_m", {1.0, 1.0, 1.0}}, {"pose", {{"position_m", {5.0, 5.0, 0.5}}}}},
        {{"alias", "rover"},
         {"type", "rover"},
         {"pose", {{"position_m", {0.0, 0.0, 0.4}}}},
         {"sensors", {{{"alias", "scanner"}, {"type", "lidar"}, {"preset", "planar180"}}}},
         {"planner", {{"name", "rover_route"}, {"params", std::move(planner_params)}}},
         {"mission", {{"waypoints", wps}}}}}}};
  return parse_scene(document, "far.json", CAMPO_SOURCE_DIR);
}

std::string creation_error(const Scene& scene) {
  const VehicleDef& rover = scene.vehicles.front();
  try {
    create_planner(rover.planner, {rover.type, &scene, &rover});
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// Issue 16: a waypoint 1,400 km away made the rover's route (a point every
// route_step_m) take 850 MB. The limit is checked when the planner is
// created, which `campo validate` does too, and names the waypoint.
TEST(RoverRoute, FarWaypointsAreRefusedAtCreation) {
  EXPECT_EQ(creation_error(far_scene({{10.0, 0.0}, {20.0, 10.0}}, nlohmann::json::object())), "");
  // Dubins: 900 km at 0.1 m is 9 million points, over 1 million (the loader takes coordinates up to 1,000 km).
  EXPECT_THAT(creation_error(far_scene({{10.0, 0.0}, {9e5, 0.0}, {0.0, 0.0}}, nlohmann::json::object())),
              HasSubstr("far.json: /objects/2/mission/waypoints/1: expected a waypoint nearer the previous one"));
  // Just inside: 99 km at 0.1 m; just outside with a finer step.
  EXPECT_EQ(creation_error(far_scene({{9.9e4, 0.0}}, nlohmann::json::object())), "");
  EXPECT_THAT(creation_error(far_scene({{9.9e4, 0.0}}, {{"route_step_m", 0.05}})),
              HasSubstr("/objects/2/mission/waypoints/0: expected a waypoint nearer"));
  // A* and RRT*: the occupancy grid over obstacles, start and waypoints.
  // 300 m x 300 m at 0.1 m is 9 million cells (inside); 500 m x 500 m is 25 million.
  for (const char* global : {"astar", "rrt_star"}) {
    SCOPED_TRACE(global);
    EXPECT_EQ(creation_error(far_scene({{300.0, 0.0}, {300.0, 300.0}}, {{"global", global}})), "");
    EXPECT_THAT(creation_error(far_scene({{300.0, 0.0}, {500.0, 500.0}}, {{"global", global}})),
                HasSubstr("far.json: /objects/2/mission/waypoints/1: expected a waypoint nearer the obstacles and starts"));
    EXPECT_EQ(creation_error(far_scene({{500.0, 500.0}}, {{"global", global}, {"occupancy_resolution_m", 0.2}})), "");
  }
}

// The bundled vineyard with --set style overrides, in closed loop (1-2 s each in Release).
EpisodeResult drive(const std::vector<std::string>& overrides) {
  return testing::run_bundled("vineyard", "rover_route", overrides);
}

// min_clearance_m is measured from the rover's bounding sphere (0.9 m, its
// half-diagonal), so a route 0.8 m from the rows reads as 0 without touching.
void expect_route_driven(const EpisodeResult& r, const char* what, double min_clearance_m = 0.1,
                         double max_path_ratio = 1.05) {
  SCOPED_TRACE(what);
  EXPECT_EQ(r.only().metrics.outcome, Outcome::reached) << r.only().metrics.reason;
  EXPECT_EQ(r.only().metrics.collisions, 0);
  EXPECT_EQ(testing::waypoints_reached(r), 6);
  // Row by row: three 89 m rows and two 4 m row switches, about 272 m.
  EXPECT_GT(r.only().metrics.path_length_m, 260.0);
  EXPECT_LT(r.only().metrics.path_ratio, max_path_ratio);
  EXPECT_GE(r.only().metrics.min_clearance_m, min_clearance_m);
}

const char* kNoStaticObstacles = "/objects/field/obstacle_count=0";
const char* kFollowTheGap = "/objects/rover/planner/params/local=follow_the_gap";
const char* kWalkerAway = R"(/objects/walker/path_m=[[-30, -60, 0.85], [-31, -60, 0.85]])";

// Dubins route + pure pursuit along the rows, no obstacle in the way: the
// rover stays on the route (the Dubins arcs are drivable at 2 m radius).
TEST(RoverRouteClosedLoop, FollowsTheDubinsRouteRowByRow) {
  const EpisodeResult r = drive({kNoStaticObstacles, kWalkerAway, kFollowTheGap});
  expect_route_driven(r, "no obstacles");
  EXPECT_LT(r.only().metrics.cross_track_rms_m, 0.1);
  EXPECT_LT(r.only().metrics.cross_track_max_m, 0.4);
}

// Seed 003 Fig. 46: a walker crosses the first inter-row left to right in
// front of the rover; follow-the-gap steers round it, then pure pursuit resumes.
// Whether an avoidance episode started between t0 and t1 (s) and ended.
bool avoided_between(const EpisodeResult& r, double t0, double t1) {
  double t_on = -1.0;
  for (const PlannerEvent& e : r.only().events) {
    if (!e.decisions.avoiding) continue;
    if (*e.decisions.avoiding) {
      t_on = e.time_s;
    } else if (t_on > t0 && t_on < t1) {
      return true;
    }
  }
  return false;
}

TEST(RoverRouteClosedLoop, AvoidsTheWalkerCrossingItsPath) {
  const EpisodeResult r = drive({kNoStaticObstacles, kFollowTheGap});
  expect_route_driven(r, "walker");
  EXPECT_GT(r.only().metrics.avoiding_time_s, 1.0);
  EXPECT_TRUE(avoided_between(r, 55.0, 75.0));  // the walker crosses y = 20 from t = 58 s
}

// The bundled scene as it is: 12 random boxes between the rows and the
// walker, VFH+ (robot radius 0.55 m) as the local planner: every row driven,
// no collision; the detours and the stops behind obstacles lengthen the run.
TEST(RoverRouteClosedLoop, VfhPlusGetsPastTheStaticObstaclesAndTheWalker) {
  const EpisodeResult r = drive({});
  expect_route_driven(r, "bundled vineyard", 0.0, 1.25);
  EXPECT_GT(r.only().metrics.avoiding_time_s, 10.0);
}

// Slowed by the first box, the rover reaches the walker's crossing (y = 20)
// at about 72 s, when the bundled walker (from 58 s) has crossed; starting it
// at 65 s makes it cross in front of the rover. (The bundled time suits the
// route without boxes, where the rover gets there sooner; a walker waiting
// beside the row until 65 s walks into the flank of the passing rover.)
constexpr const char* kWalkerMeetsTheRoverAfterTheFirstBox = "/objects/walker/start_time_s=65";

TEST(RoverRouteClosedLoop, VfhPlusAvoidsTheWalkerAfterTheFirstBox) {
  const EpisodeResult r = drive({kWalkerMeetsTheRoverAfterTheFirstBox});
  expect_route_driven(r, "boxes and walker, vfh_plus", 0.0, 1.25);
  EXPECT_TRUE(avoided_between(r, 64.0, 75.0));  // the walker, after the first box (52-62 s)
}

TEST(RoverRouteClosedLoop, VfhPlusAvoidsTheWalkerWithoutBoxes) {
  const EpisodeResult r = drive({kNoStaticObstacles});
  expect_route_driven(r, "walker, vfh_plus");
  EXPECT_TRUE(avoided_between(r, 55.0, 75.0));  // the walker crosses y = 20 from t = 58 s
}

// The same with follow-the-gap: its free-space gaps (free_range_m) head for
// the 2 m passage beside each box at once. 003's gaps (free_range_m = 0)
// split the canopy walls into gaps and stand off behind the boxes for
// minutes (343 s avoiding in all).
void expect_boxes_passed_by_follow_the_gap(const EpisodeResult& r, const char* what) {
  expect_route_driven(r, what, 0.0, 1.25);
  EXPECT_GT(r.only().metrics.avoiding_time_s, 10.0);
  EXPECT_LT(r.only().metrics.avoiding_time_s, 100.0);
}

TEST(RoverRouteClosedLoop, FollowTheGapGetsPastTheStaticObstaclesAndTheWalker) {
  const EpisodeResult r = drive({kFollowTheGap, kWalkerMeetsTheRoverAfterTheFirstBox});
  expect_boxes_passed_by_follow_the_gap(r, "boxes and walker, follow-the-gap");
  EXPECT_TRUE(avoided_between(r, 64.0, 75.0));  // after the first box (52-62 s)
}

TEST(RoverRouteClosedLoop, FollowTheGapGetsPastTheStaticObstacles) {
  expect_boxes_passed_by_follow_the_gap(drive({kFollowTheGap, kWalkerAway}), "boxes, follow-the-gap");
}

TEST(RoverRouteClosedLoop, RrtStarAsTheGlobalPlanner) {
  const EpisodeResult r = drive({kNoStaticObstacles, kWalkerAway, kFollowTheGap, "/objects/rover/planner/params/global=rrt_star"});
  expect_route_driven(r, "rrt_star", 0.0);  // its route keeps clearance_m = 0.8 m from the rows
  EXPECT_EQ(rover_route_record().global.get(r.only().events.front().decisions.replan.value().details), "rrt_star");
}

// Each A* leg leaves its waypoint and reaches the next straight along their
// headings, so the headland turns are the Dubins half circles round the row
// ends; searched between the waypoints themselves, the route cut over the row
// ends, the rover's bounding sphere touching them (min_clearance_m 0).
TEST(RoverRouteClosedLoop, AStarAsTheGlobalPlanner) {
  const EpisodeResult r = drive({kNoStaticObstacles, kWalkerAway, kFollowTheGap, "/objects/rover/planner/params/global=astar"});
  expect_route_driven(r, "astar", 0.5);
  EXPECT_LT(r.only().metrics.cross_track_rms_m, 0.1);
  EXPECT_LT(r.only().metrics.cross_track_max_m, 0.4);
  EXPECT_EQ(rover_route_record().global.get(r.only().events.front().decisions.replan.value().details), "astar");
}

// ---------------------------------------------------------------- seed 003 Fig. 45 and Fig. 46

// Avoidance episodes [on, off] (s), from the avoiding decisions.
std::vector<std::pair<double, double>> avoidance_episodes(const EpisodeResult& r) {
  std::vector<std::pair<double, double>> out;
  double on = -1.0;
  for (const PlannerEvent& e : r.only().events) {
    if (!e.decisions.avoiding) continue;
    if (*e.decisions.avoiding) {
      on = e.time_s;
    } else if (on >= 0.0) {
      out.emplace_back(on, e.time_s);
      on = -1.0;
    }
  }
  if (on >= 0.0) out.emplace_back(on, r.only().metrics.sim_time_s);
  return out;
}

// Cross-track error (against the route the planner recorded) of the samples between t0 and t1.
CrossTrack cross_track_between(const EpisodeResult& r, double t0, double t1) {
  const auto from =
      std::find_if(r.only().trajectory.begin(), r.only().trajectory.end(), [&](const auto& s) { return s.time_s >= t0; });
  const auto to = std::find_if(from, r.only().trajectory.end(), [&](const auto& s) { return s.time_s > t1; });
  return cross_track_error({&*from, static_cast<std::size_t>(to - from)}, r.only().events);
}

// Closest approach (x, y) of the rover's centre to a point while avoiding, m.
double nearest_while_avoiding(const EpisodeResult& r, const Eigen::Vector2d& point) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& [on, off] : avoidance_episodes(r)) {
    for (const TrajectorySample& s : r.only().trajectory) {
      if (s.time_s >= on && s.time_s <= off) best = std::min(best, (s.state.position_m.head<2>() - point).norm());
    }
  }
  return best;
}

// Seed 003 Fig. 45 (scenes/vineyard_obstacles.json): a box in the first
// inter-row, one on the headland turn and a cluster of three in the second
// inter-row, all in the route's way; follow-the-gap steers round each and
// pure pursuit brings the rover back onto the route after each.
void expect_fig45_obstacles_avoided(const EpisodeResult& r, double max_avoiding_s) {
  EXPECT_EQ(r.only().metrics.outcome, Outcome::reached) << r.only().metrics.reason;
  EXPECT_EQ(testing::waypoints_reached(r), 4);
  EXPECT_EQ(r.only().metrics.collisions, 0);
  EXPECT_GT(r.only().metrics.min_clearance_m, 0.05);  // true clearance of chassis and wheels
  EXPECT_LT(r.only().metrics.avoiding_time_s, max_avoiding_s);
  // Each obstacle was avoided: the rover came within 3 m of it while the local planner steered.
  for (const auto& [name, at] : {std::pair{"box_row", Eigen::Vector2d(-0.5, -6.0)},
                                 std::pair{"box_turn", Eigen::Vector2d(2.5, 19.0)},
                                 std::pair{"cluster", Eigen::Vector2d(4.2, 3.0)}}) {
    EXPECT_LT(nearest_while_avoiding(r, at), 3.0) << name;
  }
  // Back on the route after every avoidance: within 0.1 m of it before the
  // next one starts (or the run ends), and no avoidance of the three lasts long.
  const auto episodes = avoidance_episodes(r);
  ASSERT_GE(episodes.size(), 3u);
  for (std::size_t i = 0; i < episodes.size(); ++i) {
    const double next = i + 1 < episodes.size() ? episodes[i + 1].first : r.only().metrics.sim_time_s;
    if (next - episodes[i].second < 2.0) continue;  // a flicker of the corridor test, the same obstacle
    const CrossTrack after = cross_track_between(r, next - 1.0, next);
    EXPECT_LT(after.max_m, 0.1) << "before " << next << " s";
  }
}

TEST(RoverRouteClosedLoop, Fig45ObstaclesOnTheRouteAreAvoidedAndTheRouteRejoined) {
  const EpisodeResult r = testing::run_bundled("vineyard_obstacles", "rover_route");
  expect_fig45_obstacles_avoided(r, 60.0);
  EXPECT_LT(r.only().metrics.cross_track_max_m, 1.6);  // the widest detour: round the cluster
}

// 003's own gaps (range steps, free_range_m 0): the rover headed for the
// box's corner, stopped there and turned in place toward a heading straight
// on, forever (on this scene from 7.6 s to 813 s behind the first box, then at
// the headland box until the 900 s limit). Now its gaps' edges are grown by R
// and, stopped with the heading straight on, it turns away from the obstacle.
TEST(RoverRouteClosedLoop, Fig45With003GapsDoesNotStandBehindTheBoxes) {
  const EpisodeResult r = testing::run_bundled("vineyard_obstacles", "rover_route",
                                               {"/objects/rover/planner/params/follow_the_gap/free_range_m=0"});
  expect_fig45_obstacles_avoided(r, 60.0);
  for (const auto& [on, off] : avoidance_episodes(r)) EXPECT_LT(off - on, 30.0) << "from " << on << " s";
}

// The same on the bundled vineyard's 12 boxes (before: 608 s, 344 s of it avoiding).
TEST(RoverRouteClosedLoop, FollowTheGapWith003GapsGetsPastTheBundledBoxes) {
  const EpisodeResult r =
      drive({kFollowTheGap, kWalkerAway, "/objects/rover/planner/params/follow_the_gap/free_range_m=0"});
  expect_route_driven(r, "boxes, 003's gaps", 0.0, 1.25);
  EXPECT_LT(r.only().metrics.avoiding_time_s, 100.0);
}

// Seed 003 Fig. 46 (scenes/vineyard_gap.json): a person on the left of the
// route; follow-the-gap first takes the opening on the right (a); the person
// walks right across the route (b), cutting it off, and the rover switches to
// the opening on the left (c), passes behind the person and rejoins the route (d).
TEST(RoverRouteClosedLoop, Fig46SwitchesToTheLeftGapWhenTheWalkerCutsOffTheRight) {
  const EpisodeResult r = testing::run_bundled("vineyard_gap", "rover_route");
  EXPECT_EQ(r.only().metrics.outcome, Outcome::reached) << r.only().metrics.reason;
  EXPECT_EQ(r.only().metrics.collisions, 0);
  EXPECT_GT(r.only().metrics.min_clearance_m, 0.3);
  // The chosen gaps, their centres and headings relative to the route (positive left).
  struct Choice {
    double t, center_deg, heading_deg;
  };
  std::vector<Choice> choices;
  for (const PlannerEvent& e : r.only().events) {
    const std::optional<GapDecision> gap = rover_route_record().gap.get(e.decisions.own);
    if (!gap || !gap->chosen) continue;
    const ChosenGap& g = *gap->chosen;
    choices.push_back({e.time_s, g.center_deg, g.heading_deg});
  }
  ASSERT_FALSE(choices.empty());
  // (a) right first, while the person stands (walks from 8 s).
  EXPECT_LT(choices.front().center_deg, 0.0);
  EXPECT_LT(choices.front().heading_deg, 0.0);
  EXPECT_LT(choices.front().t, 8.0);
  // (c) the first opening on the left comes after the person set off, heading left.
  const auto left = std::find_if(choices.begin(), choices.end(), [](const Choice& c) { return c.center_deg > 0.0; });
  ASSERT_NE(left, choices.end());
  EXPECT_GT(left->t, 8.0);
  EXPECT_GT(left->heading_deg, 0.0);
  // ...and the rover keeps to the left opening: no later choice is right of the route.
  for (auto c = left; c != choices.end(); ++c) EXPECT_GT(c->center_deg, 0.0) << "at " << c->t << " s";
  // (d) it passed behind (north of, left of) the person, then back onto the route.
  const Scene scene = [] {
    const std::string file = std::string(CAMPO_SOURCE_DIR) + "/scenes/vineyard_gap.json";
    return parse_scene(nlohmann::json::parse(std::ifstream(file)), file, CAMPO_SOURCE_DIR);
  }();
  const Mover& walker = scene.movers.front();
  const auto passing = std::find_if(r.only().trajectory.begin(), r.only().trajectory.end(), [&](const TrajectorySample& s) {
    return s.state.position_m.x() >= walker.path_m.front().x();
  });
  ASSERT_NE(passing, r.only().trajectory.end());
  EXPECT_GT(passing->state.position_m.y(), walker.position_at(passing->time_s).y() + 0.8);
  EXPECT_LT(cross_track_between(r, r.only().metrics.sim_time_s - 3.0, r.only().metrics.sim_time_s).max_m, 0.1);
}

}  // namespace
}  // namespace campo
