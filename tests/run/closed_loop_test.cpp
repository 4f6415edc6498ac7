// Whole episodes with the real vehicles and the registry's planners.
#include <array>
#include <cstring>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "campo/episode.hpp"
#include "campo/planner_registry.hpp"
#include "campo/run_record.hpp"
#include "campo/scene_loader.hpp"
#include "campo/sensor_factory.hpp"
#include "campo/vehicle_factory.hpp"

namespace campo {
namespace {

// A bundled scene flown by the straight planner (these tests are about the loop, not the planners).
Scene bundled(const std::string& name, double time_limit_s) {
  Scene scene = load_scene(std::string(CAMPO_SOURCE_DIR) + "/scenes/" + name + ".json");
  scene.world.time_limit_s = time_limit_s;
  for (VehicleDef& v : scene.vehicles) v.planner = PlannerSpec{"straight", "", {nlohmann::json::object(), "test", ""}};
  return scene;
}

bool same_bits(const VehicleState& a, const VehicleState& b) {
  return std::memcmp(a.position_m.data(), b.position_m.data(), 3 * sizeof(double)) == 0 &&
         std::memcmp(a.orientation.coeffs().data(), b.orientation.coeffs().data(), 4 * sizeof(double)) == 0 &&
         std::memcmp(a.linear_velocity_mps.data(), b.linear_velocity_mps.data(), 3 * sizeof(double)) == 0 &&
         std::memcmp(a.angular_velocity_radps.data(), b.angular_velocity_radps.data(), 3 * sizeof(double)) == 0;
}

void expect_repeatable(const Scene& scene) {
  const EpisodeResult a = run_episode(scene, &make_vehicle, &create_planner);
  const EpisodeResult b = run_episode(scene, &make_vehicle, &create_planner);
  ASSERT_EQ(a.only().trajectory.size(), b.only().trajectory.size());
  for (std::size_t i = 0; i < a.only().trajectory.size(); ++i) {
    ASSERT_TRUE(same_bits(a.only().trajectory[i].state, b.only().trajectory[i].state)) << "sample " << i;
  }
  EXPECT_EQ(a.final_state_hash, b.final_state_hash);
  EXPECT_EQ(a.only().metrics.path_length_m, b.only().metrics.path_length_m);
  EXPECT_EQ(a.only().metrics.min_clearance_m, b.only().metrics.min_clearance_m);
  EXPECT_EQ(a.only().metrics.outcome, b.only().metrics.outcome);
}

TEST(ClosedLoop, QuadrotorEpisodeWithSensorIsBitIdenticalWhenRepeated) {
  Scene scene = bundled("trees_rolling_terrain", 6.0);
  scene.vehicles[0].sensors[0].range.noise_stddev_m = 0.02;  // noise is seeded too
  expect_repeatable(scene);
}

TEST(ClosedLoop, RoverEpisodeIsBitIdenticalWhenRepeated) { expect_repeatable(bundled("vineyard", 6.0)); }

TEST(ClosedLoop, StraightQuadrotorReachesAnOpenGoalAtTheSpeedLimit) {
  // two_barriers without the barriers: a clear 12 m flight at 0.6 m/s.
  Scene scene = bundled("two_barriers", 60.0);
  std::erase_if(scene.shapes, [](const Shape& s) { return s.type == ShapeType::cuboid; });
  const EpisodeResult r = run_episode(scene, &make_vehicle, &create_planner);
  EXPECT_EQ(r.only().metrics.outcome, Outcome::reached) << r.only().metrics.reason;
  // Reached on entering the 0.3 m tolerance: 11.7 m of the 12 m line, flown
  // straight. The ratio measures against the line to where it arrived: 1.
  EXPECT_NEAR(r.only().metrics.path_length_m, 12.0 - 0.3, 0.05);
  EXPECT_GE(r.only().metrics.path_ratio, 1.0);
  EXPECT_NEAR(r.only().metrics.path_ratio, 1.0, 0.002);
  // 12 m at 0.6 m/s is 20 s, plus acceleration and braking.
  EXPECT_GT(r.only().metrics.sim_time_s, 20.0);
  EXPECT_LT(r.only().metrics.sim_time_s, 26.0);
  for (const auto& s : r.only().trajectory) EXPECT_LE(s.state.linear_velocity_mps.norm(), 0.6 + 0.02);
}

TEST(ClosedLoop, StraightQuadrotorCollidesWithTheBarrier) {
  const EpisodeResult r = run_episode(bundled("two_barriers", 60.0), &make_vehicle, &create_planner);
  EXPECT_EQ(r.only().metrics.outcome, Outcome::collision);
  EXPECT_EQ(r.only().metrics.collisions, 1);
  // The barrier face is at x = 5.85; the body's half length 0.3 m touches it near x = 5.55.
  EXPECT_NEAR(r.only().trajectory.back().state.position_m.x(), 5.55, 0.05);
  // Stopped at the first touch: within one physics step's travel (0.6 m/s / 240 Hz) of it.
  EXPECT_LE(r.only().metrics.min_clearance_m, 0.0);
  EXPECT_GT(r.only().metrics.min_clearance_m, -0.6 / 240.0 - 1e-6);
  EXPECT_EQ(r.only().metrics.nearest_obstacle, "barrier_left");
}

TEST(ClosedLoop, StraightRoverDrivesUpItsInterRow) {
  Scene scene = bundled("vineyard", 40.0);
  scene.movers.clear();
  const EpisodeResult r = run_episode(scene, &make_vehicle, &create_planner);
  EXPECT_EQ(r.only().metrics.outcome, Outcome::timeout);
  // 0.5 m/s for 40 s, straight north along x = 0, between the canopies.
  const VehicleState end = r.only().trajectory.back().state;
  EXPECT_NEAR(end.position_m.y() - (-46.0), 20.0, 1.5);
  EXPECT_NEAR(end.position_m.x(), 0.0, 0.1);
  EXPECT_GT(r.only().metrics.min_clearance_m, 0.0);
}

TEST(ClosedLoop, DepthCameraAndLidarGiveTheSameEpisode) {
  // The same frustum from either source: the straight planner ignores it, but the
  // scans are taken from the physics state at the same times and must agree.
  Scene scene = bundled("two_barriers", 3.0);
  scene.vehicles[0].sensors[0].range.cols = scene.vehicles[0].sensors[0].range.rows = 32;
  Scene camera_scene = scene;
  camera_scene.vehicles[0].sensors[0].range.kind = RangeSensorKind::depth_camera;
  std::vector<RangeScan> lidar_scans, camera_scans;
  EpisodeOptions options;
  options.make_sensor = range_sensor_factory();
  options.on_scan = [&](std::size_t, std::size_t, const RangeScan& s) { lidar_scans.push_back(s); };
  const EpisodeResult a = run_episode(scene, &make_vehicle, &create_planner, options);
  options.on_scan = [&](std::size_t, std::size_t, const RangeScan& s) { camera_scans.push_back(s); };
  const EpisodeResult b = run_episode(camera_scene, &make_vehicle, &create_planner, options);
  EXPECT_EQ(a.final_state_hash, b.final_state_hash);
  ASSERT_EQ(lidar_scans.size(), camera_scans.size());
  ASSERT_EQ(lidar_scans.size(), 30u);  // 10 Hz for 3 s: t = 0, 0.1, ..., 2.9
  for (std::size_t i = 0; i < lidar_scans.size(); ++i) {
    int close = 0;
    for (std::size_t k = 0; k < lidar_scans[i].ranges_m.size(); ++k) {
      close += std::abs(lidar_scans[i].ranges_m[k] - camera_scans[i].ranges_m[k]) < 0.05f;
    }
    EXPECT_GE(close, 32 * 32 * 95 / 100) << "scan " << i;
  }
}

}  // namespace
}  // namespace campo

namespace campo {
namespace {

TEST(ClosedLoop, RecordsTheHeightAboveTheGroundBelow) {
  // Straight and level over a slope z = 0.1 x (its triangles are exactly that plane).
  const Scene scene = parse_scene(nlohmann::json::parse(R"j({"world": {"time_limit_s": 30}, "objects": [
    {"alias": "slope", "type": "heightfield", "size_m": [40, 40], "spacing_m": 0.5, "expression": "0.1 * x"},
    {"alias": "drone", "type": "quadrotor", "pose": {"position_m": [0, 0, 2.5]},
     "mission": {"waypoints": [{"position_m": [8, 0, 2.5]}]}, "planner": {"name": "straight"}}]})j"),
                                  "inline.json", std::filesystem::temp_directory_path());
  const EpisodeResult r = run_episode(scene, &make_vehicle, &create_planner);
  ASSERT_EQ(r.only().metrics.outcome, Outcome::reached) << r.only().metrics.reason;
  for (const TrajectorySample& s : r.only().trajectory) {
    EXPECT_NEAR(s.height_above_ground_m, s.state.position_m.z() - 0.1 * s.state.position_m.x(), 1e-9);
  }
  EXPECT_NEAR(r.only().trajectory.back().height_above_ground_m, 2.5 - 0.8, 0.1);  // level flight, rising ground
  const std::string csv = trajectory_csv(r.only());
  EXPECT_NE(csv.substr(0, csv.find('\n')).find(",height_above_ground_m"), std::string::npos);
}


// The actuator records of the trajectory, built in place by the vehicles, are
// the objects the nested initializer lists they replaced give from the same
// numbers: the same keys, floating-point values and text.
TEST(ClosedLoop, ActuatorRecordsAreTheObjectsOfTheirInitializerLists) {
  const EpisodeResult drone = run_episode(bundled("trees_rolling_terrain", 1.0), &make_vehicle, &create_planner);
  ASSERT_FALSE(drone.only().trajectory.empty());
  for (const TrajectorySample& s : drone.only().trajectory) {
    const nlohmann::json& a = s.actuators;
    const auto speeds = [](const nlohmann::json& j) {
      std::array<double, 4> w{};
      EXPECT_EQ(j.size(), 4u);
      for (std::size_t i = 0; i < 4; ++i) {
        EXPECT_TRUE(j.at(i).is_number_float());
        w[i] = j.at(i).get<double>();
      }
      return w;
    };
    ASSERT_EQ(a.size(), 3u);
    const nlohmann::json former = {{"rotor_speed_command_radps", speeds(a.at("rotor_speed_command_radps"))},
                                   {"rotor_speed_radps", speeds(a.at("rotor_speed_radps"))},
                                   {"thrust_n", a.at("thrust_n").get<double>()}};
    EXPECT_EQ(a, former);
    EXPECT_EQ(a.dump(), former.dump());
  }
  const EpisodeResult rover = run_episode(bundled("vineyard", 1.0), &make_vehicle, &create_planner);
  ASSERT_FALSE(rover.only().trajectory.empty());
  for (const TrajectorySample& s : rover.only().trajectory) {
    const nlohmann::json& a = s.actuators;
    ASSERT_EQ(a.size(), 4u);
    nlohmann::json former = nlohmann::json::object();
    for (const char* wheel : {"front_left", "front_right", "rear_left", "rear_right"}) {
      const nlohmann::json& w = a.at(wheel);
      ASSERT_EQ(w.size(), 2u);
      EXPECT_TRUE(w.at("command_radps").is_number_float());
      EXPECT_TRUE(w.at("speed_radps").is_number_float());
      former[std::string(wheel)] = {{"command_radps", w.at("command_radps").get<double>()},
                                    {"speed_radps", w.at("speed_radps").get<double>()}};
    }
    EXPECT_EQ(a, former);
    EXPECT_EQ(a.dump(), former.dump());
  }
}
}  // namespace
}  // namespace campo
