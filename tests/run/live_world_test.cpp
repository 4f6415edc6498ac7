// One live world: the LIDAR, the depth camera and clearance see every body
// where the physics has it, dynamic bodies as well as movers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "campo/episode.hpp"
#include "campo/planner_registry.hpp"
#include "campo/scene_loader.hpp"
#include "campo/sensor_factory.hpp"
#include "campo/vehicle_factory.hpp"
#include "sensors/raycaster.hpp"

namespace campo {
namespace {

// A quadrotor flying `goal_x_m` east at 1.5 m with depth_reactive and a
// 64 x 64 scanner of range 10 m, `sensor` "lidar" (ray cast) or
// "depth_camera" (OSMesa), among `objects` (JSON objects, each followed by a comma).
Scene flight_among(const std::string& objects, double goal_x_m = 12.0, const std::string& sensor = "lidar") {
  const std::string goal = R"j({"alias": "goal", "type": "dummy", "pose": {"position_m": [)j" +
                           std::to_string(goal_x_m) + ", 0, 1.5]}},";
  const std::string drone = R"j({"alias": "drone", "type": "quadrotor", "pose": {"position_m": [0, 0, 1.5]},
     "sensors": [{"alias": "scanner", "type": ")j" + sensor + R"j(", "preset": "scanner3d", "resolution": [64, 64],
                  "mount": {"position_m": [0.15, 0, 0]}}],
     "planner": {"name": "depth_reactive"},
     "mission": {"waypoints": [{"frame": "goal"}]}})j";
  const std::string text = R"j({"world": {"time_limit_s": 120}, "objects": [{"alias": "ground", "type": "plane"},)j" +
                           objects + goal + drone + "]}";
  return parse_scene(nlohmann::json::parse(text), "inline.json", std::filesystem::temp_directory_path());
}

double max_lateral_m(const EpisodeResult& r) {
  double y = 0.0;
  for (const TrajectorySample& s : r.only().trajectory) y = std::max(y, std::abs(s.state.position_m.y()));
  return y;
}

EpisodeOptions with_sensors() {
  EpisodeOptions options;
  options.make_sensor = &make_range_sensor;
  return options;
}

// Flies among `objects` with the sensor, which must get it to the goal without collision.
EpisodeResult fly_to_goal(const std::string& objects, double goal_x_m, const std::string& sensor) {
  EpisodeResult r =
      run_episode(flight_among(objects, goal_x_m, sensor), &make_vehicle, &create_planner, with_sensors());
  EXPECT_EQ(r.only().metrics.outcome, Outcome::reached) << r.only().metrics.reason;
  EXPECT_EQ(r.only().metrics.collisions, 0);
  return r;
}

TEST(LiveWorld, TheLidarSeesADynamicBoxWhereItFell) {
  // A 0.4 m box released at 1.5 m lands on the ground: a ray cast down from
  // above meets its top at 0.4 m, not at 1.7 m where it started.
  const Scene scene = flight_among(
      R"j({"alias": "box", "type": "cuboid", "size_m": [0.4, 0.4, 0.4],
    "static": false, "mass_kg": 1, "pose": {"position_m": [6, 0, 1.5]}},)j");
  World world(scene);
  for (int k = 0; k < 480; ++k) world.step();  // 2 s
  std::vector<Eigen::Isometry3d> poses;
  world.moving_body_poses(poses);
  ASSERT_EQ(poses.size(), 1u);
  // It lands flat (it may slide a little on the way).
  const Eigen::Vector3d landed = poses[0].translation();
  EXPECT_NEAR(landed.z(), 0.2, 0.01);
  EXPECT_LT((landed.head<2>() - Eigen::Vector2d(6.0, 0.0)).norm(), 0.5);
  RayCaster caster(scene);
  caster.set_poses(poses);
  const std::vector<Eigen::Vector3f> down{-Eigen::Vector3f::UnitZ()};
  std::vector<RayHit> hit(1);
  caster.cast({landed.x(), landed.y(), 3.0}, down, 0.0f, 10.0f, hit);
  EXPECT_EQ(hit[0].shape, 1);  // the box (scene shape 1)
  EXPECT_NEAR(hit[0].distance_m, 3.0 - 0.4, 0.01);
}

TEST(LiveWorld, ABoxThatFellOffTheRouteIsFlownStraightOver) {
  // Placed on the route at flight altitude 11 m ahead, beyond the scanner's
  // 10 m, the box falls to the ground in half a second, long before the
  // drone gets near: the way is clear. (A sensor that saw the box where the
  // scene file put it would see it hanging on the route.)
  for (const std::string sensor : {"lidar", "depth_camera"}) {
    SCOPED_TRACE(sensor);
    const EpisodeResult r = fly_to_goal(R"j({"alias": "box", "type": "cuboid", "size_m": [0.4, 0.4, 0.4],
      "static": false, "mass_kg": 1, "pose": {"position_m": [11, 0, 1.5]}},)j",
                                        18.0, sensor);
    EXPECT_EQ(r.only().metrics.waypoints_planned, 0);
    EXPECT_LT(max_lateral_m(r), 0.3);
    // Its nearest approach is to the box on the ground, below: about 1.44 - 0.4.
    EXPECT_EQ(r.only().metrics.nearest_obstacle, "box");
    EXPECT_NEAR(r.only().metrics.min_clearance_m, 1.5 - 0.06 - 0.4, 0.05);
  }
}

TEST(LiveWorld, ABoxPushedIntoTheRouteByAMoverIsAvoided) {
  // A 2 m tall box stands beside the route; a mover slides it across the
  // route during the first seconds and stays there, beside it.
  for (const std::string sensor : {"lidar", "depth_camera"}) {
    SCOPED_TRACE(sensor);
    const EpisodeResult r = fly_to_goal(R"j({"alias": "crate", "type": "cuboid", "size_m": [1, 1, 2],
      "static": false, "mass_kg": 5, "friction": 0.5, "pose": {"position_m": [6, 3, 1]}},
      {"alias": "pusher", "type": "mover", "shape": {"type": "cuboid", "size_m": [1.5, 0.5, 2]},
       "path_m": [[6, 4.25, 1], [6, 0.75, 1]], "speed_mps": 0.6},)j",
                                        12.0, sensor);
    EXPECT_GT(r.only().metrics.min_clearance_m, 0.0);
    // The crate now covers the route: the drone went around it.
    EXPECT_GE(r.only().metrics.waypoints_planned, 1);
    EXPECT_GT(max_lateral_m(r), 0.5);
  }
}

}  // namespace
}  // namespace campo
