// The closed loop with a kinematic stand-in vehicle, so the loop's own logic
// (rates, outcomes, metrics) is checked against hand-computed values.
#include "sim/episode.hpp"

#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>

#include "sim/run_record.hpp"
#include "sim/scene_loader.hpp"

namespace campo {
namespace {

// Moves exactly at the commanded speed toward a GoTo target; collides when
// its x passes `wall_x`.
class PointVehicle final : public Vehicle {
 public:
  explicit PointVehicle(const VehicleDef& def) { state_.position_m = def.pose.translation(); }
  VehicleType type() const override { return VehicleType::quadrotor; }
  void command(const Command& c) override { command_ = c; }
  void pre_step(double dt) override {
    if (const auto* go = std::get_if<command::GoTo>(&command_)) {
      const Eigen::Vector3d d = go->target_m - state_.position_m;
      const double step = std::min(d.norm(), go->speed_mps * dt);
      if (d.norm() > 0) state_.position_m += d.normalized() * step;
    }
  }
  VehicleState state() const override { return state_; }
  bool stable() const override { return true; }
  double bounding_radius_m() const override { return 0.5; }
  bool in_collision() const override { return state_.position_m.x() > wall_x; }
  nlohmann::json actuators() const override { return {{"speed", 1.0}}; }
  nlohmann::json parameters() const override { return {{"kind", "point"}}; }
  static inline double wall_x = 1e9;

 private:
  VehicleState state_;
  Command command_;
};

std::unique_ptr<Vehicle> make_point(World&, const VehicleDef& def) { return std::make_unique<PointVehicle>(def); }

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

Scene scene_with(const std::string& extra_world = "") {
  return parse_scene(nlohmann::json::parse(R"j({"world": {"physics_step_s": 0.01, "control_rate_hz": 20,
    "sensor_rate_hz": 5, "time_limit_s": 30)j" + extra_world + R"j(}, "objects": [
    {"alias": "post", "type": "cylinder", "radius_m": 0.5, "height_m": 4, "pose": {"position_m": [5, 2, 2]}},
    {"alias": "v", "type": "quadrotor", "pose": {"position_m": [0, 0, 1]},
     "sensors": [{"alias": "s", "type": "lidar", "preset": "scanner3d", "resolution": [4, 4]}],
     "mission": {"waypoints": [{"position_m": [3, 0, 1]}, {"position_m": [3, 4, 1]}]}}]})j"),
                     "inline.json", std::filesystem::temp_directory_path());
}

class EpisodeTest : public ::testing::Test {
 protected:
  void SetUp() override {
    PointVehicle::wall_x = 1e9;
    Follower::fresh_scans = 0;
    Follower::give_up_at = -1;
  }
};

TEST_F(EpisodeTest, ReachesTheGoalWithExactMetrics) {
  const Scene scene = scene_with();
  const EpisodeResult r = run_episode(scene, &make_point, &make_follower);
  const EpisodeMetrics& m = r.metrics;
  EXPECT_EQ(m.outcome, Outcome::reached);
  EXPECT_EQ(m.reason, "done");
  // 7 m at 1 m/s, planner at 20 Hz: the arrival is noticed at the next tick.
  EXPECT_NEAR(m.sim_time_s, 7.0, 0.05 + 1e-9);
  EXPECT_NEAR(m.path_length_m, 7.0, 1e-9);
  EXPECT_NEAR(m.path_ratio, 1.0, 1e-9);
  // Closest approach: the post axis (5, 2) is 2 m from the second leg; minus post and vehicle radius.
  EXPECT_NEAR(m.min_clearance_m, 2.0 - 0.5 - 0.5, 0.06);
  EXPECT_EQ(m.collisions, 0);
  EXPECT_EQ(m.planner_calls, static_cast<int>(r.trajectory.size()));
  EXPECT_NEAR(m.planner_calls, 7.0 * 20 + 1, 2);
  // Sensors at 5 Hz: one fresh scan per 4 planner calls.
  EXPECT_NEAR(Follower::fresh_scans, 7.0 * 5 + 1, 2);
  EXPECT_EQ(r.trajectory.front().time_s, 0.0);
  EXPECT_NEAR(r.trajectory[1].time_s, 0.05, 1e-12);
}

TEST_F(EpisodeTest, TimesOut) {
  const Scene scene = scene_with();
  Scene slow = scene;
  slow.world.time_limit_s = 2.0;
  const EpisodeResult r = run_episode(slow, &make_point, &make_follower);
  EXPECT_EQ(r.metrics.outcome, Outcome::timeout);
  EXPECT_NEAR(r.metrics.sim_time_s, 2.0, 1e-9);
  EXPECT_NEAR(r.metrics.path_length_m, 2.0, 1e-9);
}

TEST_F(EpisodeTest, StopsAtTheFirstCollisionOrCountsThem) {
  const Scene scene = scene_with();
  PointVehicle::wall_x = 1.505;
  EpisodeResult r = run_episode(scene, &make_point, &make_follower);
  EXPECT_EQ(r.metrics.outcome, Outcome::collision);
  EXPECT_EQ(r.metrics.collisions, 1);
  EXPECT_NEAR(r.metrics.sim_time_s, 1.51, 1e-9);
  EpisodeOptions keep_going;
  keep_going.stop_on_collision = false;
  r = run_episode(scene, &make_point, &make_follower, keep_going);
  EXPECT_EQ(r.metrics.outcome, Outcome::reached);
  EXPECT_EQ(r.metrics.collisions, 1);  // one contact episode, however long
}

TEST_F(EpisodeTest, PlannerGivingUpAbortsWithItsReason) {
  Follower::give_up_at = 1.0;
  const EpisodeResult r = run_episode(scene_with(), &make_point, &make_follower);
  EXPECT_EQ(r.metrics.outcome, Outcome::aborted);
  EXPECT_EQ(r.metrics.reason, "no_path: walled in");
  EXPECT_NEAR(r.metrics.sim_time_s, 1.0, 1e-9);
}

TEST_F(EpisodeTest, MetricsJsonUsesTheDocumentedNames) {
  const nlohmann::json j = to_json(run_episode(scene_with(), &make_point, &make_follower).metrics);
  for (const char* key : {"outcome", "reason", "sim_time_s", "wall_time_s", "path_length_m", "path_ratio",
                          "min_clearance_m", "collisions", "planner_time_ms_mean", "planner_time_ms_max"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_EQ(j["outcome"], "reached");
}

TEST_F(EpisodeTest, RecordsTrajectoryAndRunFile) {
  const Scene scene = scene_with();
  const EpisodeResult r = run_episode(scene, &make_point, &make_follower);
  const std::string csv = trajectory_csv(r);
  const auto header_end = csv.find('\n');
  const std::string header = csv.substr(0, header_end);
  EXPECT_EQ(header.rfind("time_s,x_m,y_m,z_m,roll_deg,pitch_deg,yaw_deg,", 0), 0u);
  EXPECT_NE(header.find(",command,"), std::string::npos);
  EXPECT_EQ(header.substr(header.rfind(',') + 1), "speed");  // actuator columns come last
  const auto rows = static_cast<std::size_t>(std::count(csv.begin(), csv.end(), '\n')) - 1;
  EXPECT_EQ(rows, r.trajectory.size());
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
  EXPECT_TRUE(run["provenance"].contains("campo_version"));
}

}  // namespace
}  // namespace campo
