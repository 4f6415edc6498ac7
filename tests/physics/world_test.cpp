#include "campo/world.hpp"

#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>

#include "campo/scene_loader.hpp"

namespace campo {
namespace {

Scene parse(const std::string& text) {
  return parse_scene(nlohmann::json::parse(text), "inline.json", std::filesystem::temp_directory_path());
}

const char* kSineTerrain = R"j({"objects": [
  {"alias": "ground", "type": "heightfield", "expression": "sin(x/5) + 0.3*cos(y/3)",
   "size_m": [60, 40], "spacing_m": 0.5, "pose": {"position_m": [10, -5, 2]}}]})j";

TEST(World, TerrainHeightMatchesTheExpressionAtVertices) {
  const Scene scene = parse(kSineTerrain);
  const World world(scene);
  // Vertices lie every 0.5 m from the grid corner (-20, -25).
  for (double x = -20.0; x <= 40.0; x += 2.5) {
    for (double y = -25.0; y <= 15.0; y += 2.5) {
      const auto h = world.terrain_height(x, y);
      ASSERT_TRUE(h.has_value());
      EXPECT_NEAR(*h, std::sin(x / 5) + 0.3 * std::cos(y / 3), 1e-12) << x << "," << y;
    }
  }
  EXPECT_FALSE(world.terrain_height(45.0, 0.0).has_value());
}

TEST(World, TerrainHeightBetweenVerticesWithinInterpolationError) {
  const Scene scene = parse(kSineTerrain);
  const World world(scene);
  // Linear interpolation error on a triangle of edge h is at most h^2 * max|f''| (loose bound).
  const double bound = 0.5 * 0.5 * (1.0 / 25.0 + 0.3 / 9.0);
  for (double x = -19.9; x < 39.9; x += 0.37) {
    for (double y = -24.9; y < 14.9; y += 0.41) {
      const double exact = std::sin(x / 5) + 0.3 * std::cos(y / 3);
      EXPECT_NEAR(*world.terrain_height(x, y), exact, bound);
    }
  }
}

TEST(World, BulletRayTestAgreesWithTerrainHeight) {
  const Scene scene = parse(kSineTerrain);
  const World world(scene);
  for (double x = -19.7; x < 39.0; x += 1.93) {
    for (double y = -24.3; y < 14.0; y += 1.71) {
      const auto hit = world.ray_test({x, y, 50.0}, {x, y, -50.0});
      ASSERT_TRUE(hit.has_value());
      EXPECT_EQ(hit->shape, 0);
      EXPECT_NEAR(hit->point_m.z(), *world.terrain_height(x, y), 1e-6) << x << "," << y;
    }
  }
}

TEST(World, RayTestHitsPrimitivesAtAnalyticDistances) {
  const Scene scene = parse(R"j({"objects": [
    {"alias": "box", "type": "cuboid", "size_m": [2, 2, 2], "pose": {"position_m": [10, 0, 0]}},
    {"alias": "ball", "type": "sphere", "radius_m": 1.5, "pose": {"position_m": [0, 10, 0]}}]})j");
  const World world(scene);
  const auto box = world.ray_test({0, 0, 0}, {20, 0, 0});
  ASSERT_TRUE(box);
  EXPECT_NEAR(box->distance_m, 9.0, 1e-6);
  EXPECT_EQ(box->shape, 0);
  const auto ball = world.ray_test({0, 0, 0}, {0, 20, 0});
  ASSERT_TRUE(ball);
  EXPECT_NEAR(ball->distance_m, 8.5, 1e-6);
  EXPECT_FALSE(world.ray_test({0, 0, 5}, {20, 0, 5}));
}

TEST(World, FreeFallFollowsSymplecticEuler) {
  const Scene scene = parse(R"j({"world": {"physics_step_s": 0.01, "control_rate_hz": 50},
    "objects": [{"alias": "ball", "type": "sphere", "radius_m": 0.1, "static": false, "mass_kg": 1,
                 "pose": {"position_m": [0, 0, 100]}}]})j");
  World world(scene);
  for (int i = 0; i < 200; ++i) world.step();
  // v_{n+1} = v_n - g dt, z_{n+1} = z_n + v_{n+1} dt  =>  z_n = z_0 - g dt^2 n (n + 1) / 2.
  const double n = 200, dt = 0.01, g = 9.81;
  const BodyState s = world.shape_state(0);
  EXPECT_NEAR(s.position_m.z(), 100.0 - g * dt * dt * n * (n + 1) / 2, 1e-9);
  EXPECT_NEAR(s.linear_velocity_mps.z(), -g * dt * n, 1e-9);
  EXPECT_NEAR(world.time_s(), 2.0, 1e-12);
}

TEST(World, BodiesComeToRestOnTheTerrain) {
  const Scene scene = parse(R"j({"objects": [
    {"alias": "ground", "type": "heightfield", "expression": "0", "size_m": [20, 20], "spacing_m": 1},
    {"alias": "crate", "type": "cuboid", "size_m": [1, 1, 1], "static": false, "mass_kg": 5,
     "pose": {"position_m": [0.3, 0.2, 3]}}]})j");
  World world(scene);
  for (int i = 0; i < 240 * 3; ++i) world.step();
  const BodyState s = world.shape_state(1);
  EXPECT_NEAR(s.position_m.z(), 0.5, 0.02);
  EXPECT_LT(s.linear_velocity_mps.norm(), 1e-2);
}

TEST(World, MoversFollowTheirPath) {
  const Scene scene = parse(R"j({"objects": [
    {"alias": "walker", "type": "mover", "shape": {"type": "cylinder", "radius_m": 0.3, "height_m": 1.7},
     "path_m": [[0, 0, 1], [10, 0, 1]], "speed_mps": 2}]})j");
  World world(scene);
  for (int i = 0; i < 240; ++i) world.step();  // 1 s
  const auto hit = world.ray_test({2.0, -5.0, 1.0}, {2.0, 5.0, 1.0});
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->distance_m, 5.0 - 0.3, 1e-3);
  EXPECT_EQ(hit->shape, -1);
}

TEST(World, RebuildingFromTheSameSceneIsBitIdentical) {
  const Scene scene = parse(R"j({"objects": [
    {"alias": "ground", "type": "rolling_terrain", "size_m": [30, 30], "amplitude_m": 1, "seed": 3},
    {"alias": "a", "type": "sphere", "radius_m": 0.4, "static": false, "mass_kg": 1, "pose": {"position_m": [0.1, 0, 4]}},
    {"alias": "b", "type": "cuboid", "size_m": [0.5, 0.7, 0.3], "static": false, "mass_kg": 2,
     "pose": {"position_m": [0.3, 0.2, 6], "rpy_deg": [10, 20, 30]}},
    {"alias": "c", "type": "cylinder", "radius_m": 0.3, "height_m": 1, "static": false, "mass_kg": 1,
     "pose": {"position_m": [-2, 1, 3], "rpy_deg": [80, 0, 0]}}]})j");
  const auto run = [&scene] {
    World world(scene);
    for (int i = 0; i < 1200; ++i) world.step();
    return world.state_hash();
  };
  const std::uint64_t first = run();
  EXPECT_EQ(first, run());
  World untouched(scene);
  EXPECT_NE(first, untouched.state_hash());
}

}  // namespace
}  // namespace campo
