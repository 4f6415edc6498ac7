// The closed loop with a kinematic stand-in vehicle, so the loop's own logic
// (rates, outcomes, metrics) is checked against hand-computed values.
#include "campo/episode.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>

#include <btBulletDynamicsCommon.h>
#include <gtest/gtest.h>

#include "campo/run_record.hpp"
#include "campo/scene_loader.hpp"

namespace campo {
namespace {

// Moves exactly at the commanded speed toward a GoTo target. Its collision
// shape is a kinematic sphere of radius 0.5 m in the world, so clearance and
// collisions are measured on it as on a real vehicle.
class PointVehicle final : public Vehicle {
 public:
  PointVehicle(World& world, const VehicleDef& def)
      : world_(world.bullet()), shape_(0.5), body_(btRigidBody::btRigidBodyConstructionInfo(0.0, nullptr, &shape_)) {
    state_.position_m = def.pose.translation();
    body_.setCollisionFlags(body_.getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
    body_.setUserIndex(kVehicleBodyTag);
    place();
    world_.addRigidBody(&body_);
  }
  ~PointVehicle() override { world_.removeRigidBody(&body_); }
  VehicleType type() const override { return VehicleType::quadrotor; }
  void command(const Command& c) override { command_ = c; }
  void pre_step(double dt) override {
    if (const auto* go = std::get_if<command::GoTo>(&command_)) {
      const Eigen::Vector3d d = go->target_m - estimated_state().position_m;
      const double step = std::min(d.norm(), go->speed_mps * dt);
      if (d.norm() > 0) state_.position_m += d.normalized() * step;
    }
    place();
  }
  VehicleState state() const override { return state_; }
  bool stable() const override { return true; }
  nlohmann::json actuators() const override { return {{"speed", 1.0}}; }
  nlohmann::json parameters() const override { return {{"kind", "point"}}; }

 private:
  void place() {
    body_.setWorldTransform(btTransform(btQuaternion::getIdentity(),
                                        btVector3(state_.position_m.x(), state_.position_m.y(), state_.position_m.z())));
  }
  btDiscreteDynamicsWorld& world_;
  btSphereShape shape_;
  btRigidBody body_;
  VehicleState state_;
  Command command_;
};

std::unique_ptr<Vehicle> make_point(World& world, const VehicleDef& def) {
  return std::make_unique<PointVehicle>(world, def);
}

// Goes to each waypoint in turn at 1 m/s; counts fresh scans.
class Follower final : public Planner {
 public:
  PlanResult plan(const Observation& o) override {
    PlanResult r;
    for (const auto& s : o.sensors) fresh_scans += s.fresh;
    while (next_ < o.mission.size() && (o.state.position_m - o.mission[next_].position_m).norm() < 1e-6) ++next_;
    if (next_ == o.mission.size()) {
      r.status = PlanStatus::reached;
      r.reason = "done";
      return r;
    }
    if (give_up_at >= 0 && o.time_s >= give_up_at) {
      r.status = PlanStatus::no_path;
      r.reason = "walled in";
      return r;
    }
    r.command = command::GoTo{o.mission[next_].position_m, 1.0, false};
    return r;
  }
  nlohmann::json parameters() const override { return nlohmann::json::object(); }
  static inline int fresh_scans = 0;
  static inline double give_up_at = -1;

 private:
  std::size_t next_ = 0;
};

std::unique_ptr<Planner> make_follower(const PlannerSpec&, const PlannerContext&) { return std::make_unique<Follower>(); }

// `extra_objects`: more objects, each followed by a comma.
Scene scene_with(const std::string& extra_world = "", const std::string& extra_objects = "") {
  return parse_scene(nlohmann::json::parse(R"j({"world": {"physics_step_s": 0.01, "control_rate_hz": 20,
    "sensor_rate_hz": 5, "time_limit_s": 30)j" + extra_world + R"j(}, "objects": [)j" + extra_objects + R"j(
    {"alias": "post", "type": "cylinder", "radius_m": 0.5, "height_m": 4, "pose": {"position_m": [5, 2, 2]}},
    {"alias": "v", "type": "quadrotor", "pose": {"position_m": [0, 0, 1]},
     "sensors": [{"alias": "s", "type": "lidar", "preset": "scanner3d", "resolution": [4, 4]}],
     "mission": {"waypoints": [{"position_m": [3, 0, 1]}, {"position_m": [3, 4, 1]}]}}]})j"),
                     "inline.json", std::filesystem::temp_directory_path());
}

class EpisodeTest : public ::testing::Test {
 protected:
  void SetUp() override {
    Follower::fresh_scans = 0;
    Follower::give_up_at = -1;
  }
};

TEST_F(EpisodeTest, ReachesTheGoalWithExactMetrics) {
  const Scene scene = scene_with();
  const EpisodeResult r = run_episode(scene, &make_point, &make_follower);
  const EpisodeMetrics& m = r.only().metrics;
  EXPECT_EQ(m.outcome, Outcome::reached);
  EXPECT_EQ(m.reason, "done");
  // 7 m at 1 m/s, planner at 20 Hz: the arrival is noticed at the next tick.
  EXPECT_NEAR(m.sim_time_s, 7.0, 0.05 + 1e-9);
  EXPECT_NEAR(m.path_length_m, 7.0, 1e-9);
  EXPECT_NEAR(m.path_ratio, 1.0, 1e-9);
  // Closest approach: the post axis (5, 2) is 2 m from the second leg at
  // (3, 2); less the post's and the vehicle's radius. Exact: GJK between the shapes.
  EXPECT_NEAR(m.min_clearance_m, 2.0 - 0.5 - 0.5, 1e-6);
  EXPECT_EQ(m.nearest_obstacle, "post");
  EXPECT_NEAR(m.min_clearance_time_s, 5.0, 0.01);
  // No ground in this scene.
  EXPECT_TRUE(std::isinf(m.min_ground_clearance_m));
  EXPECT_EQ(m.collisions, 0);
  EXPECT_EQ(m.planner_calls, static_cast<int>(r.only().trajectory.size()));
  EXPECT_NEAR(m.planner_calls, 7.0 * 20 + 1, 2);
  // Sensors at 5 Hz: one fresh scan per 4 planner calls.
  EXPECT_NEAR(Follower::fresh_scans, 7.0 * 5 + 1, 2);
  EXPECT_EQ(r.only().trajectory.front().time_s, 0.0);
  EXPECT_NEAR(r.only().trajectory[1].time_s, 0.05, 1e-12);
}

TEST_F(EpisodeTest, TimesOut) {
  const Scene scene = scene_with();
  Scene slow = scene;
  slow.world.time_limit_s = 2.0;
  const EpisodeResult r = run_episode(slow, &make_point, &make_follower);
  EXPECT_EQ(r.only().metrics.outcome, Outcome::timeout);
  EXPECT_NEAR(r.only().metrics.sim_time_s, 2.0, 1e-9);
  EXPECT_NEAR(r.only().metrics.path_length_m, 2.0, 1e-9);
}

TEST_F(EpisodeTest, StopsAtTheFirstCollisionOrCountsThem) {
  // A thin wall across the first leg: the sphere (radius 0.5) touches its
  // face at x = 2.005 when its centre reaches x = 1.505, at t = 1.505 s,
  // found after the physics step that ends at 1.51 s.
  const Scene scene = scene_with("", R"j({"alias": "wall", "type": "cuboid", "size_m": [0.095, 0.8, 2],
    "pose": {"position_m": [2.0525, 0, 1]}},)j");
  EpisodeResult r = run_episode(scene, &make_point, &make_follower);
  EXPECT_EQ(r.only().metrics.outcome, Outcome::collision);
  EXPECT_EQ(r.only().metrics.collisions, 1);
  EXPECT_NEAR(r.only().metrics.sim_time_s, 1.51, 1e-9);
  // The wall's face x = 2.005, straight ahead of the sphere's centre (0, 1).
  EXPECT_EQ(r.only().metrics.reason, "collision with wall at t = 1.510000 s, at (2.005, 0.000, 1.000) m");
  // Touching is clearance <= 0: the two always agree.
  EXPECT_LE(r.only().metrics.min_clearance_m, 0.0);
  EXPECT_NEAR(r.only().metrics.min_clearance_m, -0.005, 1e-6);
  EpisodeOptions keep_going;
  keep_going.stop_on_collision = false;
  r = run_episode(scene, &make_point, &make_follower, keep_going);
  EXPECT_EQ(r.only().metrics.outcome, Outcome::reached);
  EXPECT_EQ(r.only().metrics.collisions, 1);  // one contact episode, however long
  // Passing through, the sphere's centre crosses the wall: overlap of its radius plus half the wall.
  EXPECT_NEAR(r.only().metrics.min_clearance_m, -(0.5 + 0.0475), 3e-3);
}

// Signed distances to solids, for checking that a contact point lies on the surface touched.
double box_sdf(const Eigen::Vector3d& p, const Eigen::Vector3d& centre, const Eigen::Vector3d& half) {
  const Eigen::Vector3d q = (p - centre).cwiseAbs() - half;
  return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
}
double cylinder_sdf(const Eigen::Vector3d& p, const Eigen::Vector3d& centre, double radius, double height) {
  const Eigen::Vector2d q((p - centre).head<2>().norm() - radius, std::abs(p.z() - centre.z()) - 0.5 * height);
  return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
}

// One kind of body in the sphere's way (radius 0.5, from (0, 0, 1) toward
// (3, 0, 1) at 1 m/s, 0.01 s steps): the alias the collision must name and
// the touched body's signed distance function where the physics had it.
struct TouchCase {
  std::string kind;
  std::string objects;  // each followed by a comma
  std::string alias;
  bool ground;
  std::function<double(const Scene&, const CollisionEvent&)> surface;
};

std::vector<TouchCase> touch_cases() {
  return {
      {"box", R"j({"alias": "wall", "type": "cuboid", "size_m": [0.095, 0.8, 2], "pose": {"position_m": [2.0525, 0, 1]}},)j",
       "wall", false,
       [](const Scene&, const CollisionEvent& e) {
         return box_sdf(e.point_m, {2.0525, 0, 1}, {0.0475, 0.4, 1});
       }},
      {"cylinder", R"j({"alias": "pole", "type": "cylinder", "radius_m": 0.1, "height_m": 2, "pose": {"position_m": [2.6, 0.05, 1]}},)j",
       "pole", false,
       [](const Scene&, const CollisionEvent& e) { return cylinder_sdf(e.point_m, {2.6, 0.05, 1}, 0.1, 2); }},
      // A generated tree whose crown (centre 0.2 + 0.6 x 0.3 m up) the sphere meets over a trunk too
      // low to touch: crown and trunk are children of one compound in the physics.
      {"crown", R"j({"alias": "forest", "type": "trees", "area_min_m": [2.7, -0.15], "area_max_m": [2.9, -0.05],
         "count": 1, "min_spacing_m": 1, "trunk_radius_m": [0.1, 0.1], "trunk_height_m": [0.2, 0.2],
         "crown": "sphere", "crown_radius_m": [0.3, 0.3], "seed": 3},)j",
       "forest/tree0/crown", false,
       [](const Scene& scene, const CollisionEvent& e) {
         const Shape& crown = *scene.find_shape("forest/tree0/crown");
         return (e.point_m - crown.pose.translation()).norm() - crown.radius_m;
       }},
      // A mover crossing the route: measured where it was at the time of the collision.
      {"mover", R"j({"alias": "walker", "type": "mover", "shape": {"type": "cuboid", "size_m": [0.4, 0.4, 0.4]},
         "path_m": [[1.5, -4, 1.1], [1.5, 4, 1.1]], "speed_mps": 2},)j",
       "walker", false,
       [](const Scene& scene, const CollisionEvent& e) {
         return box_sdf(e.point_m, scene.movers.at(0).position_at(e.time_s), {0.2, 0.2, 0.2});
       }},
      {"plane", R"j({"alias": "floor", "type": "plane", "pose": {"position_m": [0, 0, 0.55]}},)j", "floor", true,
       [](const Scene&, const CollisionEvent& e) { return e.point_m.z() - 0.55; }},
      // A tilted plane as a heightfield: its triangles are the plane exactly. The sphere comes within
      // its radius of it at x = (0.7 - 0.5 sqrt(1.05)) / 0.2 = 0.94.
      {"heightfield", R"j({"alias": "hill", "type": "heightfield", "size_m": [40, 40], "spacing_m": 0.5,
         "expression": "0.2 * x + 0.1 * y + 0.3"},)j",
       "hill", true,
       [](const Scene&, const CollisionEvent& e) {
         return (e.point_m.z() - (0.2 * e.point_m.x() + 0.1 * e.point_m.y() + 0.3)) / std::sqrt(1.05);
       }},
  };
}

TEST_F(EpisodeTest, ACollisionNamesTheBodyTouchedAndWhere) {
  for (const TouchCase& c : touch_cases()) {
    SCOPED_TRACE(c.kind);
    const Scene scene = scene_with("", c.objects);
    const EpisodeResult r = run_episode(scene, &make_point, &make_follower);
    ASSERT_EQ(r.only().metrics.outcome, Outcome::collision);
    ASSERT_EQ(r.only().metrics.collision_events.size(), 1u);
    const CollisionEvent& e = r.only().metrics.collision_events.front();
    EXPECT_EQ(e.body, c.alias);
    EXPECT_EQ(e.ground, c.ground);
    EXPECT_DOUBLE_EQ(e.time_s, r.only().metrics.sim_time_s);
    // On the surface touched: the point's distance to it is GJK/EPA's precision
    // (double precision, relative to the scene's metres), far below the depth
    // the sphere can reach in one step (1 m/s x 0.01 s).
    EXPECT_NEAR(c.surface(scene, e), 0.0, 1e-6);
    const std::string with = c.ground ? "the ground (" + c.alias + ")" : c.alias;
    EXPECT_EQ(r.only().metrics.reason.rfind("collision with " + with + " at t = ", 0), 0u) << r.only().metrics.reason;
    EXPECT_NE(r.only().metrics.reason.find(" m"), std::string::npos);
    // run.json's list, as documented (docs/running.md).
    const nlohmann::json j = to_json(r.only().metrics).at("collision_events");
    ASSERT_EQ(j.size(), 1u);
    EXPECT_EQ(j[0].at("body"), c.alias);
    EXPECT_EQ(j[0].at("ground"), c.ground);
    EXPECT_EQ(j[0].at("time_s"), e.time_s);
    EXPECT_EQ(j[0].at("point_m"), nlohmann::json({e.point_m.x(), e.point_m.y(), e.point_m.z()}));
  }
}

TEST_F(EpisodeTest, CollisionEventsAreBoundedButAllCounted) {
  // A row of thin walls across the first leg, each passed through: one collision each.
  const int n = static_cast<int>(EpisodeMetrics::kMaxCollisionEvents) + 5;
  std::string objects;
  for (int i = 0; i < n; ++i) {
    // 1.2 m apart along y = 0, beyond the sphere's reach of each other.
    objects += R"j({"alias": "w)j" + std::to_string(i) + R"j(", "type": "cuboid", "size_m": [0.01, 0.2, 0.2], "pose": {"position_m": [)j" +
               std::to_string(2.0 + 1.2 * i) + R"j(, 0, 1]}},)j";
  }
  const Scene scene = parse_scene(nlohmann::json::parse(R"j({"world": {"physics_step_s": 0.01, "control_rate_hz": 20,
    "sensor_rate_hz": 5, "time_limit_s": 300}, "objects": [)j" + objects + R"j(
    {"alias": "v", "type": "quadrotor", "pose": {"position_m": [0, 0, 1]},
     "mission": {"waypoints": [{"position_m": [)j" + std::to_string(2.0 + 1.2 * n) + R"j(, 0, 1]}]}}]})j"),
                      "inline.json", std::filesystem::temp_directory_path());
  EpisodeOptions keep_going;
  keep_going.stop_on_collision = false;
  const EpisodeResult r = run_episode(scene, &make_point, &make_follower, keep_going);
  EXPECT_EQ(r.only().metrics.outcome, Outcome::reached);
  EXPECT_EQ(r.only().metrics.collisions, n);
  ASSERT_EQ(r.only().metrics.collision_events.size(), EpisodeMetrics::kMaxCollisionEvents);
  for (std::size_t i = 0; i < r.only().metrics.collision_events.size(); ++i) {
    EXPECT_EQ(r.only().metrics.collision_events[i].body, "w" + std::to_string(i));
  }
}

TEST_F(EpisodeTest, PlannerGivingUpAbortsWithItsReason) {
  Follower::give_up_at = 1.0;
  const EpisodeResult r = run_episode(scene_with(), &make_point, &make_follower);
  EXPECT_EQ(r.only().metrics.outcome, Outcome::aborted);
  EXPECT_EQ(r.only().metrics.reason, "no_path: walled in");
  EXPECT_NEAR(r.only().metrics.sim_time_s, 1.0, 1e-9);
}

TEST_F(EpisodeTest, MetricsJsonUsesTheDocumentedNames) {
  const nlohmann::json j = to_json(run_episode(scene_with(), &make_point, &make_follower).only().metrics);
  for (const char* key : {"outcome", "reason", "sim_time_s", "wall_time_s", "path_length_m", "path_ratio",
                          "min_clearance_m", "collisions", "planner_time_ms_mean", "planner_time_ms_max",
                          "cross_track_rms_m", "cross_track_mean_m", "cross_track_max_m", "avoiding_time_s"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_EQ(j["outcome"], "reached");
}

// Stepping an Episode from outside with a planner's decisions is the same run as run_episode, bit for bit.
TEST_F(EpisodeTest, SteppedFromOutsideIsTheSameRun) {
  const Scene scene = scene_with();
  const EpisodeResult looped = run_episode(scene, &make_point, &make_follower);
  Episode episode(scene, &make_point);
  Follower follower;
  int calls = 0;
  while (!episode.done()) {
    EXPECT_NEAR(episode.observation().time_s, calls * 0.05, 1e-12);  // 20 Hz control
    episode.step(follower.plan(episode.observation()));
    ++calls;
    EXPECT_EQ(episode.metrics_so_far().planner_calls, calls);
  }
  EXPECT_LT((episode.observation().state.position_m - Eigen::Vector3d(3, 4, 1)).norm(), 1e-9);  // where it ended
  EXPECT_THROW(episode.step(PlanResult{}), std::logic_error);
  const EpisodeResult stepped = episode.finish();
  EXPECT_EQ(stepped.final_state_hash, looped.final_state_hash);
  EXPECT_EQ(stepped.only().metrics.outcome, Outcome::reached);
  EXPECT_EQ(stepped.only().metrics.planner_calls, looped.only().metrics.planner_calls);
  EXPECT_EQ(stepped.only().metrics.path_length_m, looped.only().metrics.path_length_m);
  EXPECT_EQ(stepped.only().trajectory.size(), looped.only().trajectory.size());
  EXPECT_THROW(episode.finish(), std::logic_error);
}

// A planner that throws ends its run as failed, with what it said; bad input stays bad input.
TEST_F(EpisodeTest, APlannerThatThrowsEndsTheRunAsFailed) {
  struct Thrower final : Planner {
    explicit Thrower(bool input) : input_error(input) {}
    PlanResult plan(const Observation& o) override {
      if (o.time_s < 1.0) return {PlanStatus::running, command::GoTo{{3, 0, 1}, 1.0, false}, "", {}};
      if (input_error) throw InputError("params.json", "/gain", "a gain the planner can use");
      throw std::runtime_error("division by zero in the gain schedule");
    }
    nlohmann::json parameters() const override { return {{"thrower", true}}; }
    bool input_error;
  };
  const Scene scene = scene_with();
  const EpisodeResult r = run_episode(scene, &make_point, [](const PlannerSpec&, const PlannerContext&) {
    return std::unique_ptr<Planner>(std::make_unique<Thrower>(false));
  });
  EXPECT_EQ(r.only().metrics.outcome, Outcome::failed);
  EXPECT_EQ(to_string(r.only().metrics.outcome), "failed");
  EXPECT_EQ(r.only().metrics.reason, "the planner raised an error: division by zero in the gain schedule");
  // Everything up to the failure is kept: 20 calls in the first second, then the one that threw (not counted).
  EXPECT_EQ(r.only().metrics.planner_calls, 20);
  EXPECT_NEAR(r.only().metrics.path_length_m, 1.0, 0.02);
  EXPECT_EQ(r.only().planner_parameters["thrower"], true);
  EXPECT_THROW(run_episode(scene, &make_point,
                           [](const PlannerSpec&, const PlannerContext&) {
                             return std::unique_ptr<Planner>(std::make_unique<Thrower>(true));
                           }),
               InputError);
}

TEST_F(EpisodeTest, RecordsTrajectoryAndRunFile) {
  const Scene scene = scene_with();
  const EpisodeResult r = run_episode(scene, &make_point, &make_follower);
  const std::string csv = trajectory_csv(r.only());
  const auto header_end = csv.find('\n');
  const std::string header = csv.substr(0, header_end);
  EXPECT_EQ(header.rfind("time_s,x_m,y_m,z_m,roll_deg,pitch_deg,yaw_deg,", 0), 0u);
  EXPECT_NE(header.find(",command,"), std::string::npos);
  EXPECT_EQ(header.substr(header.rfind(',') + 1), "speed");  // actuator columns come last
  const auto rows = static_cast<std::size_t>(std::count(csv.begin(), csv.end(), '\n')) - 1;
  EXPECT_EQ(rows, r.only().trajectory.size());
  // Every row has as many fields as the header.
  const auto fields = std::count(header.begin(), header.end(), ',');
  std::size_t start = header_end + 1;
  while (start < csv.size()) {
    const auto end = csv.find('\n', start);
    EXPECT_EQ(std::count(csv.begin() + static_cast<long>(start), csv.begin() + static_cast<long>(end), ','), fields);
    start = end + 1;
  }
  const nlohmann::json run = run_json(scene, r, {}, {"/world/seed=3"});
  EXPECT_EQ(run["metrics"]["outcome"], "reached");
  EXPECT_EQ(run["overrides"][0], "/world/seed=3");
  EXPECT_EQ(run["parameters"]["vehicle"]["parameters"]["kind"], "point");
  EXPECT_EQ(run["parameters"]["mission"].size(), 2u);
  EXPECT_EQ(run["parameters"]["sensors"][0]["resolution"], nlohmann::json({4, 4}));
  // No state noise given: every key there, all zero.
  EXPECT_EQ(run["parameters"]["vehicle"]["state_noise"]["position_stddev_m"], 0.0);
  EXPECT_EQ(run["parameters"]["vehicle"]["state_noise"].size(), 6u);
  EXPECT_TRUE(run["provenance"].contains("campo_version"));
}

// ---------------------------------------------------------------- decisions recorded

Decisions planned(std::vector<Eigen::Vector3d> path) { return {.planned_path = std::move(path)}; }
Decisions avoiding(bool on) { return {.avoiding = on}; }

// Records a route 0.5 m left of the first leg and right of the second and avoids between t = 1 and t = 2.
class RouteRecorder final : public Planner {
 public:
  PlanResult plan(const Observation& o) override {
    PlanResult r = inner_.plan(o);
    if (o.time_s == 0.0) r.decisions = planned({{0, 0.5, 1}, {3.5, 0.5, 1}, {3.5, 4, 1}});
    if (std::abs(o.time_s - 1.0) < 1e-9) r.decisions = avoiding(true);
    if (std::abs(o.time_s - 2.0) < 1e-9) r.decisions = avoiding(false);
    return r;
  }
  nlohmann::json parameters() const override { return nlohmann::json::object(); }

 private:
  Follower inner_;
};

TEST_F(EpisodeTest, MeasuresCrossTrackAndAvoidingFromTheDecisions) {
  const EpisodeResult r = run_episode(scene_with(), &make_point, [](const PlannerSpec&, const PlannerContext&) {
    return std::unique_ptr<Planner>(std::make_unique<RouteRecorder>());
  });
  const EpisodeMetrics& m = r.only().metrics;
  ASSERT_EQ(m.outcome, Outcome::reached);
  // Both legs run 0.5 m beside the route, except near the corner, where the route is nearer.
  EXPECT_NEAR(m.cross_track_max_m, 0.5, 1e-9);
  EXPECT_GT(m.cross_track_rms_m, 0.45);
  EXPECT_LE(m.cross_track_rms_m, 0.5 + 1e-9);
  EXPECT_NEAR(m.avoiding_time_s, 1.0, 1e-9);
  const nlohmann::json j = to_json(m);
  EXPECT_EQ(j["cross_track_max_m"], m.cross_track_max_m);
  EXPECT_EQ(j["avoiding_time_s"], m.avoiding_time_s);
  // The plain follower records neither.
  const EpisodeMetrics plain = run_episode(scene_with(), &make_point, &make_follower).only().metrics;
  EXPECT_EQ(plain.cross_track_rms_m, 0.0);
  EXPECT_EQ(plain.cross_track_max_m, 0.0);
  EXPECT_EQ(plain.avoiding_time_s, 0.0);
}

}  // namespace
}  // namespace campo
