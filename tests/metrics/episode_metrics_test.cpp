// The metrics of a run as pure functions of what the closed loop records
// (metrics/episode_metrics.hpp, cross_track_error, avoiding_time and to_json of
// campo/episode_record.hpp), against hand-computed values and a brute-force second method.
#include "metrics/episode_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace campo {
namespace {

TrajectorySample sample_at(double t, double x, double y, double z = 0.0) {
  TrajectorySample s;
  s.time_s = t;
  s.state.position_m = {x, y, z};
  return s;
}

Decisions planned(std::vector<Eigen::Vector3d> path) { return {.planned_path = std::move(path)}; }
Decisions avoiding(bool on) { return {.avoiding = on}; }

// Horizontal distance to the polyline, every segment tried.
double brute_force_distance(const std::vector<Eigen::Vector3d>& route, const Eigen::Vector3d& q) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 1 < route.size() || (i == 0 && route.size() == 1); ++i) {
    const Eigen::Vector2d a = route[i].head<2>(), b = route[std::min(i + 1, route.size() - 1)].head<2>();
    const Eigen::Vector2d p = q.head<2>();
    double t = 0.0;
    if ((b - a).squaredNorm() > 0.0) t = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
    best = std::min(best, (a + t * (b - a) - p).norm());
  }
  return best;
}

TEST(CrossTrackError, MatchesBruteForceOnRandomRoutes) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    // Routes: random walks (coherent, like a planner's) and, every third trial, scattered points;
    // a few of one or two points and some repeated points (zero-length segments).
    std::vector<PlannerEvent> events;
    std::vector<std::pair<double, std::vector<Eigen::Vector3d>>> routes;  // (time set, points)
    const int route_count = 1 + trial % 4;
    for (int r = 0; r < route_count; ++r) {
      const std::size_t n = trial == 1 && r == 0 ? 1 : trial == 2 ? 2 : 1 + rng() % 600;
      std::vector<Eigen::Vector3d> route;
      Eigen::Vector3d p(50.0 * unit(rng), 50.0 * unit(rng), 5.0 * unit(rng));
      for (std::size_t i = 0; i < n; ++i) {
        if (trial % 3 == 0) p = {60.0 * unit(rng), 60.0 * unit(rng), 0.0};
        else if (rng() % 10 != 0) p += Eigen::Vector3d(2.0 * unit(rng), 2.0 * unit(rng), unit(rng));
        route.push_back(p);
      }
      const double t = r == 0 ? 1.0 : 1.0 + 10.0 * r + (rng() % 3);  // also at a sample's exact time
      routes.emplace_back(t, route);
      events.push_back({t, planned(route)});
      if (rng() % 2) events.push_back({t + 0.5, avoiding(true)});  // other decisions are ignored
    }
    std::vector<TrajectorySample> trajectory;
    double sum = 0.0, max = 0.0;
    std::size_t measured = 0;
    for (int i = 0; i < 2000; ++i) {
      const double t = 0.05 * i;
      // Near the route mostly, sometimes far away.
      const double spread = i % 50 == 0 ? 500.0 : 70.0;
      trajectory.push_back(sample_at(t, spread * unit(rng), spread * unit(rng), 3.0 * unit(rng)));
      const std::vector<Eigen::Vector3d>* in_force = nullptr;
      for (const auto& [since, route] : routes) {
        if (since <= t) in_force = &route;
      }
      if (!in_force) continue;
      const double d = brute_force_distance(*in_force, trajectory.back().state.position_m);
      sum += d * d;
      max = std::max(max, d);
      ++measured;
    }
    const CrossTrack c = cross_track_error(trajectory, events);
    ASSERT_EQ(c.samples, measured) << "trial " << trial;
    EXPECT_NEAR(c.rms_m, std::sqrt(sum / measured), 1e-9) << "trial " << trial;
    EXPECT_NEAR(c.max_m, max, 1e-9) << "trial " << trial;
  }
}

TEST(CrossTrackError, MeasuresEachSampleAgainstTheRouteInForce) {
  // Route A along y = 0 from t = 1, route B along y = 10 from t = 2 (recorded at a sample's time).
  const std::vector<PlannerEvent> events{
      {1.0, planned({{0, 0, 0}, {10, 0, 0}})},
      {2.0, planned({{0, 10, 0}, {10, 10, 0}})},
  };
  const std::vector<TrajectorySample> trajectory{
      sample_at(0.5, 5, 100),  // before any route: skipped
      sample_at(1.0, 5, 3),    // A: 3
      sample_at(1.5, 13, 4),   // A: beyond the end, 5
      sample_at(2.0, 5, 6, 40),  // B: 4 (height ignored)
  };
  const CrossTrack c = cross_track_error(trajectory, events);
  EXPECT_EQ(c.samples, 3u);
  EXPECT_NEAR(c.rms_m, std::sqrt((9.0 + 25.0 + 16.0) / 3.0), 1e-12);
  EXPECT_NEAR(c.mean_m, (3.0 + 5.0 + 4.0) / 3.0, 1e-12);
  EXPECT_NEAR(c.max_m, 5.0, 1e-12);
}

TEST(CrossTrackError, IsZeroWithoutAPlannedPath) {
  const std::vector<TrajectorySample> trajectory{sample_at(0.0, 1, 2), sample_at(1.0, 3, 4)};
  const std::vector<PlannerEvent> events{{0.0, {.planned_waypoint = Eigen::Vector3d(1, 1, 1)}}, {0.5, avoiding(true)}};
  const CrossTrack c = cross_track_error(trajectory, events);
  EXPECT_EQ(c.samples, 0u);
  EXPECT_EQ(c.rms_m, 0.0);
  EXPECT_EQ(c.max_m, 0.0);
  // An empty planned path leaves no route until the next.
  const std::vector<PlannerEvent> cleared{{0.0, planned({{0, 0, 0}, {9, 0, 0}})}, {0.5, planned({})}};
  const CrossTrack c2 = cross_track_error(trajectory, cleared);
  EXPECT_EQ(c2.samples, 1u);
  EXPECT_NEAR(c2.max_m, 2.0, 1e-12);
}

TEST(AvoidingTime, AddsTheIntervalsBetweenOnAndOff) {
  const std::vector<PlannerEvent> events{
      {1.0, avoiding(true)},
      {1.5, avoiding(true)},   // already on: nothing changes
      {3.0, avoiding(false)},  // 2 s
      {4.0, avoiding(false)},  // already off
      {5.0, {.replan = ReplanDecision{.time_ms = 1.0}}},
      {6.5, avoiding(true)},
      {7.0, avoiding(false)},  // 0.5 s
      {9.0, avoiding(true)},   // on until the end: 1.25 s
  };
  EXPECT_NEAR(avoiding_time(events, 10.25), 2.0 + 0.5 + 1.25, 1e-12);
  EXPECT_NEAR(avoiding_time(std::span(events).first(7), 10.25), 2.5, 1e-12);
  EXPECT_EQ(avoiding_time({}, 10.0), 0.0);
}

TEST(CountDecisions, CountsEachKindAndTakesTheMedianReplanTime) {
  const Eigen::Vector3d p(1, 2, 3);
  const std::vector<PlannerEvent> events{
      {0.0, {.planned_waypoint = p, .replan = ReplanDecision{.time_ms = 4.0}}},
      {0.5, {.reached_intermediate = p}},
      {1.0, {.planned_waypoint = p, .discarded_waypoint = p, .replan = ReplanDecision{.time_ms = 1.0}}},
      {1.5, {.avoiding = true}},  // counted nowhere
      {2.0, {.replan = ReplanDecision{.time_ms = 10.0}}},
  };
  EpisodeMetrics m;
  count_decisions(events, m);
  EXPECT_EQ(m.waypoints_planned, 2);
  EXPECT_EQ(m.waypoints_reached, 1);
  EXPECT_EQ(m.waypoints_discarded, 1);
  EXPECT_EQ(m.replans, 3);
  EXPECT_EQ(m.replan_time_ms_median, 4.0);  // of 1, 4, 10
  EXPECT_EQ(m.replan_time_ms_max, 10.0);
  // An even count: the mean of the middle two (4 and 1).
  EpisodeMetrics two;
  count_decisions(std::span(events).first(3), two);
  EXPECT_EQ(two.replan_time_ms_median, 2.5);
  EXPECT_EQ(two.replan_time_ms_max, 4.0);
  // No replans: the times stay zero.
  EpisodeMetrics none;
  count_decisions(std::span(events).subspan(1, 1), none);
  EXPECT_EQ(none.replans, 0);
  EXPECT_EQ(none.replan_time_ms_median, 0.0);
  EXPECT_EQ(none.replan_time_ms_max, 0.0);
}

TEST(NominalRoute, StraightLegsThroughWhereEachWaypointWasReached) {
  const std::vector<Waypoint> mission{{{3, 4, 0}}, {{3, 4, 12}}};
  const Eigen::Vector3d start(0, 0, 0);
  // 5 + 12 in 3D; a rover counts the horizontal 5 alone.
  const std::vector<std::optional<Eigen::Vector3d>> not_reached(2);
  EXPECT_DOUBLE_EQ(nominal_route_m(VehicleType::quadrotor, start, mission, not_reached), 17.0);
  EXPECT_DOUBLE_EQ(nominal_route_m(VehicleType::rover, start, mission, not_reached), 5.0);
  // The first waypoint reached 1 m short, at (3, 3, 0): legs of sqrt(9 + 9) and sqrt(1 + 144).
  const std::vector<std::optional<Eigen::Vector3d>> reached{Eigen::Vector3d(3, 3, 0), std::nullopt};
  EXPECT_DOUBLE_EQ(nominal_route_m(VehicleType::quadrotor, start, mission, reached),
                   std::sqrt(18.0) + std::sqrt(145.0));
  EXPECT_EQ(nominal_route_m(VehicleType::quadrotor, start, {}, {}), 0.0);
  EXPECT_DOUBLE_EQ(path_ratio(34.0, 17.0), 2.0);
  EXPECT_EQ(path_ratio(5.0, 0.0), 0.0);   // no route: no ratio
  EXPECT_EQ(path_ratio(5.0, 1e-10), 0.0);
}

TEST(ClearanceMinima, KeepsTheNearestObstacleWithItsTimeAndTheLowestGround) {
  Scene scene;
  scene.shapes.resize(2);
  scene.shapes[1].alias = "forest/tree1";
  scene.movers.resize(1);
  scene.movers[0].shape.alias = "truck";
  EXPECT_EQ(body_name(scene, 1), "forest/tree1");
  EXPECT_EQ(body_name(scene, -1), "truck");

  ClearanceMinima minima;
  EpisodeMetrics empty;
  minima.write(scene, empty);  // nothing measured: infinite, no obstacle named
  EXPECT_TRUE(std::isinf(empty.min_clearance_m));
  EXPECT_TRUE(empty.nearest_obstacle.empty());
  // Before anything is measured the cutoffs are infinite; then the minima so far, never below the touch search.
  EXPECT_TRUE(std::isinf(minima.obstacle_cutoff()));
  const auto clearance = [](double obstacle_m, int obstacle, double ground_m) {
    Clearance c;
    c.obstacle_m = obstacle_m;
    c.obstacle = obstacle;
    c.ground_m = ground_m;
    return c;
  };
  minima.update(clearance(3.0, 1, 2.0), 0.5);
  minima.update(clearance(1.5, -1, 4.0), 1.0);  // the truck, nearer
  minima.update(clearance(1.5, 1, 0.7), 2.0);   // as near again: the first one stays
  minima.update(clearance(2.0, 1, 1.0), 3.0);
  EXPECT_EQ(minima.obstacle_cutoff(), 1.5);
  EXPECT_EQ(minima.ground_cutoff(), 0.7);
  minima.update(clearance(-0.2, 1, -0.1), 4.0);  // overlapping
  EXPECT_EQ(minima.obstacle_cutoff(), ClearanceMinima::kTouchSearch_m);
  EpisodeMetrics m;
  minima.write(scene, m);
  EXPECT_EQ(m.min_clearance_m, -0.2);
  EXPECT_EQ(m.nearest_obstacle, "forest/tree1");
  EXPECT_EQ(m.min_clearance_time_s, 4.0);
  EXPECT_EQ(m.min_ground_clearance_m, -0.1);
  ClearanceMinima truck;
  truck.update(clearance(1.5, -1, 4.0), 1.0);
  truck.update(clearance(1.5, 1, 0.7), 2.0);
  truck.write(scene, m);
  EXPECT_EQ(m.nearest_obstacle, "truck");
  EXPECT_EQ(m.min_clearance_time_s, 1.0);
}

TEST(MetricsJson, NullWhenUnmeasuredWithTheDeclaredFieldsBeside) {
  EpisodeMetrics m;
  m.outcome = Outcome::timeout;
  m.min_clearance_m = std::numeric_limits<double>::infinity();
  m.min_ground_clearance_m = 2.5;
  EXPECT_FALSE(to_json(m).contains("leg0_path_length_m"));  // nothing declared: null adds nothing
  m.declared = {{"leg0_path_length_m", 12.5}, {"leg0_lateral_before_climb_m", nullptr}, {"gate_slot_passed", true}};
  m.collision_events = {{1.5, "wall", false, Eigen::Vector3d(1, 2, 3)}};
  const nlohmann::json j = to_json(m);
  EXPECT_EQ(j["outcome"], "timeout");
  EXPECT_TRUE(j["min_clearance_m"].is_null());  // no obstacles
  EXPECT_TRUE(j["nearest_obstacle"].is_null());
  EXPECT_TRUE(j["min_clearance_time_s"].is_null());
  EXPECT_EQ(j["min_ground_clearance_m"], 2.5);
  EXPECT_EQ(j["leg0_path_length_m"], 12.5);
  ASSERT_TRUE(j.contains("leg0_lateral_before_climb_m"));
  EXPECT_TRUE(j["leg0_lateral_before_climb_m"].is_null());
  EXPECT_EQ(j["gate_slot_passed"], true);
  EXPECT_EQ(j.size(), to_json(EpisodeMetrics()).size() + 3);
  EXPECT_EQ(j["collision_events"],
            nlohmann::json::parse(R"([{"time_s": 1.5, "body": "wall", "ground": false, "point_m": [1, 2, 3]}])"));
  for (const Outcome o : {Outcome::reached, Outcome::collision, Outcome::timeout, Outcome::aborted, Outcome::failed}) {
    m.outcome = o;
    EXPECT_EQ(to_json(m)["outcome"], to_string(o));
  }
  EXPECT_EQ(to_string(Outcome::collision), "collision");
  EXPECT_EQ(to_string(Outcome::failed), "failed");
}

}  // namespace
}  // namespace campo
