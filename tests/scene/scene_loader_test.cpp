#include "campo/scene_loader.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "scene/generators.hpp"
#include "scene/geodesy.hpp"

namespace campo {
namespace {

using ::testing::HasSubstr;

Scene parse(const std::string& text, const SceneLimits& limits = {}) {
  return parse_scene(parse_json_text(text, "inline.json", limits.json), "inline.json",
                     std::filesystem::temp_directory_path(), "", limits);
}

// The message of the InputError that parsing `text` throws ("" if none).
std::string error_of(const std::string& text, const SceneLimits& limits = {}) {
  try {
    parse(text, limits);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::string with_objects(const std::string& objects) {
  return R"({"objects": [)" + objects + "]}";
}

TEST(SceneLoader, ReadsPrimitivesWithDefaultsAndUnits) {
  const Scene scene = parse(with_objects(R"j(
    {"alias": "box", "type": "cuboid", "size_m": [1, 2, 3],
     "pose": {"position_m": [1, 2, 3], "rpy_deg": [0, 0, 90]}},
    {"alias": "can", "type": "cylinder", "radius_m": 0.5, "height_m": 2, "static": false, "mass_kg": 3},
    {"alias": "ball", "type": "sphere", "radius_m": 0.25, "color": [1, 0, 0]},
    {"alias": "tip", "type": "cone", "radius_m": 1, "height_m": 2},
    {"alias": "floor", "type": "plane"})j"));
  ASSERT_EQ(scene.shapes.size(), 5u);
  const Shape& box = scene.shapes[0];
  EXPECT_EQ(box.type, ShapeType::cuboid);
  EXPECT_EQ(box.size_m, Eigen::Vector3d(1, 2, 3));
  EXPECT_TRUE(box.pose.translation().isApprox(Eigen::Vector3d(1, 2, 3)));
  // Yaw 90 deg turns local x into world y.
  EXPECT_TRUE((box.pose.linear() * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitY()));
  EXPECT_TRUE(box.is_static);
  EXPECT_FALSE(scene.shapes[1].is_static);
  EXPECT_DOUBLE_EQ(scene.shapes[1].mass_kg, 3.0);
  EXPECT_DOUBLE_EQ(scene.shapes[2].color.r, 1.0);
  EXPECT_EQ(scene.shapes[4].type, ShapeType::plane);
  EXPECT_EQ(scene.name, "inline");
  EXPECT_DOUBLE_EQ(scene.world.physics_step_s, 1.0 / 240.0);
}

TEST(SceneLoader, ChildPosesAreRelativeToTheParent) {
  const Scene scene = parse(with_objects(R"j(
    {"alias": "base", "type": "dummy", "pose": {"position_m": [10, 0, 0], "rpy_deg": [0, 0, 90]},
     "children": [{"alias": "arm", "type": "sphere", "radius_m": 1,
                   "pose": {"position_m": [2, 0, 1]}}]})j"));
  ASSERT_EQ(scene.shapes.size(), 1u);
  EXPECT_TRUE(scene.shapes[0].pose.translation().isApprox(Eigen::Vector3d(10, 2, 1)));
  ASSERT_NE(scene.find_frame("base"), nullptr);
}

TEST(SceneLoader, AboveGroundPlacesOnTheTerrain) {
  const Scene scene = parse(with_objects(R"j(
    {"alias": "hill", "type": "heightfield", "expression": "0.5*x", "size_m": [20, 20], "spacing_m": 1},
    {"alias": "flag", "type": "dummy", "pose": {"position_m": [4, 1, 2], "above_ground": true}})j"));
  EXPECT_NEAR(scene.find_frame("flag")->pose.translation().z(), 0.5 * 4 + 2, 1e-12);
}

TEST(SceneLoader, ReadsWorldBlock) {
  const Scene scene = parse(R"j({"world": {"gravity_mps2": [0, 0, -3.7], "physics_step_s": 0.002,
    "control_rate_hz": 100, "sensor_rate_hz": 5, "time_limit_s": 60, "seed": 42,
    "geo_reference": {"latitude_deg": 40.821, "longitude_deg": 14.7035, "altitude_m": 12}},
    "objects": []})j");
  EXPECT_DOUBLE_EQ(scene.world.gravity_mps2.z(), -3.7);
  EXPECT_DOUBLE_EQ(scene.world.physics_step_s, 0.002);
  EXPECT_EQ(scene.world.seed, 42u);
  EXPECT_DOUBLE_EQ(scene.world.geo_reference.altitude_m, 12.0);
}

TEST(SceneLoader, ReadsVehicleSensorsAndMissionForms) {
  const Scene scene = parse(R"j({
    "world": {"geo_reference": {"latitude_deg": 40.821, "longitude_deg": 14.7035}},
    "objects": [
      {"alias": "ground", "type": "heightfield", "expression": "sin(x/5)", "size_m": [150, 150],
       "spacing_m": 0.75, "pose": {"position_m": [75, 75, 0]}},
      {"alias": "grid", "type": "grid_obstacles", "cell_size_m": 1.5, "rows": 100, "cols": 100},
      {"alias": "goal", "type": "dummy", "pose": {"position_m": [5, 6, 7]}},
      {"alias": "uav", "type": "quadrotor", "pose": {"position_m": [1, 2, 3]},
       "sensors": [{"alias": "front", "type": "lidar", "preset": "scanner3d", "resolution": [64, 32],
                    "range_m": [0.2, 8], "noise_stddev_m": 0.01}],
       "planner": {"name": "depthmap", "params": {"k": 2}},
       "mission": {"grid": "grid", "waypoints": [
         {"position_m": [1, 2, 3]}, {"frame": "goal"}, {"geodetic": [40.822, 14.7035, 10]},
         {"cell": [1, 16], "agl_m": 42}, {"position_m": [30, 40], "agl_m": 5, "heading_deg": 90}]}}]})j");
  ASSERT_EQ(scene.vehicles.size(), 1u);
  const VehicleDef& v = scene.vehicles[0];
  EXPECT_EQ(v.type, VehicleType::quadrotor);
  ASSERT_EQ(v.sensors.size(), 1u);
  EXPECT_EQ(v.sensors[0].range.preset, "scanner3d");
  EXPECT_EQ(v.sensors[0].range.cols, 64);
  EXPECT_EQ(v.sensors[0].range.rows, 32);
  EXPECT_DOUBLE_EQ(v.sensors[0].range.max_range_m, 8.0);
  EXPECT_EQ(v.planner.name, "depthmap");
  EXPECT_EQ(v.planner.params.values["k"], 2);
  EXPECT_EQ(v.planner.params.pointer, "/objects/3/planner/params");
  ASSERT_EQ(v.mission.size(), 5u);
  EXPECT_EQ(v.mission[1].position_m, Eigen::Vector3d(5, 6, 7));
  // 0.001 deg of latitude north is ~111 m.
  EXPECT_NEAR(v.mission[2].position_m.y(), 111.0, 0.5);
  EXPECT_NEAR(v.mission[2].position_m.x(), 0.0, 1e-6);
  // Cell (1, 16): x = 15.5 * 1.5, y = 0.5 * 1.5 (a terrain vertex), z = sin(x/5) + 42.
  EXPECT_NEAR(v.mission[3].position_m.x(), 23.25, 1e-12);
  EXPECT_NEAR(v.mission[3].position_m.y(), 0.75, 1e-12);
  EXPECT_NEAR(v.mission[3].position_m.z(), std::sin(23.25 / 5) + 42, 1e-9);
  EXPECT_NEAR(v.mission[4].position_m.z(), std::sin(30.0 / 5) + 5, 1e-2);
  EXPECT_EQ(v.mission[4].heading_deg, 90.0);
}

// Seed 001's conversion with its reference point placed off the grid, and
// geodetic waypoints given as [lat, lon] with a height above ground; gates
// are blocks of the mission grid's cells.
TEST(SceneLoader, ReadsSeed001GeodesyAndGates) {
  const Scene scene = parse(R"j({
    "world": {"geo_reference": {"latitude_deg": 40.82233, "longitude_deg": 14.70328,
                                "projection": "sphere_no_coslat", "position_m": [-0.75, 149.25]}},
    "objects": [
      {"alias": "ground", "type": "heightfield", "expression": "sin(x/5)", "size_m": [150, 150],
       "spacing_m": 0.75, "pose": {"position_m": [75, 75, 0]}},
      {"alias": "grid", "type": "grid_obstacles", "cell_size_m": 1.5, "rows": 100, "cols": 100},
      {"alias": "uav", "type": "quadrotor", "pose": {"position_m": [1, 2, 3]},
       "mission": {"grid": "grid", "gates": [{"name": "slot", "rows": [49, 50], "cols": [50, 51], "max_agl_m": 35},
                                             {"name": "gap2", "rows": [3, 3], "cols": [1, 100]}],
                   "waypoints": [{"geodetic": [40.8210, 14.7035], "agl_m": 42},
                                 {"geodetic": [40.8210, 14.7035, 7]}]}}]})j");
  EXPECT_EQ(scene.world.geo_reference.projection, GeoProjection::sphere_no_coslat);
  const VehicleDef& v = scene.vehicles.at(0);
  ASSERT_EQ(v.mission.size(), 2u);
  // 24.463 m east and 147.889 m south of the reference (hand-computed, 001 §4.2.3), from (-0.75, 149.25).
  EXPECT_NEAR(v.mission[0].position_m.x(), 23.713, 1e-3);
  EXPECT_NEAR(v.mission[0].position_m.y(), 1.361, 1e-3);
  // The terrain sampled every 0.75 m is within 2.8 mm of sin(x/5) between vertices.
  EXPECT_NEAR(v.mission[0].position_m.z(), std::sin(v.mission[0].position_m.x() / 5) + 42, 3e-3);
  EXPECT_NEAR(v.mission[1].position_m.z(), 7.0, 1e-9);
  ASSERT_EQ(v.gates.size(), 2u);
  EXPECT_EQ(v.gates[0].name, "slot");
  EXPECT_TRUE(v.gates[0].area_m.min().isApprox(Eigen::Vector2d(73.5, 72.0)));
  EXPECT_TRUE(v.gates[0].area_m.max().isApprox(Eigen::Vector2d(76.5, 75.0)));
  EXPECT_EQ(v.gates[0].max_agl_m, 35.0);
  EXPECT_FALSE(v.gates[1].max_agl_m.has_value());
  EXPECT_TRUE(v.gates[1].area_m.max().isApprox(Eigen::Vector2d(150.0, 4.5)));
}

TEST(SceneLoader, SameFileGivesTheSameScene) {
  const std::string text = with_objects(R"j(
    {"alias": "t", "type": "rolling_terrain", "size_m": [30, 30], "seed": 5},
    {"alias": "f", "type": "trees", "count": 10, "area_min_m": [-10, -10], "area_max_m": [10, 10], "seed": 9})j");
  const Scene a = parse(text), b = parse(text);
  ASSERT_EQ(a.shapes.size(), b.shapes.size());
  EXPECT_EQ(a.shapes[0].terrain->heights_m, b.shapes[0].terrain->heights_m);
  for (std::size_t i = 0; i < a.shapes.size(); ++i) {
    EXPECT_TRUE(a.shapes[i].pose.isApprox(b.shapes[i].pose, 0.0)) << i;
  }
}

// The fuzz target's entry: text loaded as if it were the file, its data paths
// beside that file, its provenance hash that of the text.
TEST(SceneLoader, TextLoadsAsTheFileItIsNamedAfter) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "campo_scene_loader_text";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "g.csv") << "1,2,3\n4,5,6\n";
  const std::string text = with_objects(R"j({"alias": "t", "type": "heightfield", "csv": "g.csv", "spacing_m": 0.5})j");
  const std::filesystem::path named = dir / "never_written.json";

  const Scene scene = load_scene_text(text, named);
  EXPECT_EQ(scene.source_path, named.string());
  EXPECT_EQ(scene.source_sha256, sha256_hex(text));
  ASSERT_EQ(scene.shapes.size(), 1u);
  const HeightGrid& grid = *scene.shapes[0].terrain;
  EXPECT_EQ(grid.cols, 3);
  EXPECT_EQ(grid.rows, 2);
  EXPECT_EQ(*std::min_element(grid.heights_m.begin(), grid.heights_m.end()), 1.0);
  EXPECT_EQ(*std::max_element(grid.heights_m.begin(), grid.heights_m.end()), 6.0);

  // The same bytes in a file give the same scene but for the file's name.
  std::ofstream(dir / "written.json") << text;
  const Scene from_file = load_scene(dir / "written.json");
  EXPECT_EQ(from_file.source_sha256, scene.source_sha256);
  EXPECT_EQ(from_file.shapes[0].terrain->heights_m, grid.heights_m);

  try {
    load_scene_text("{\"objects\": 1}", named);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), named.string());
    EXPECT_EQ(e.pointer(), "/objects");
  }
  std::filesystem::remove_all(dir);
}

// --- every kind of validation error, with its message ---------------------

TEST(SceneLoaderErrors, UnknownKeyNamesPointerAndAllowedKeys) {
  const std::string e = error_of(with_objects(R"j({"alias": "a", "type": "sphere", "radius_m": 1, "radius": 2})j"));
  EXPECT_THAT(e, HasSubstr("inline.json: /objects/0/radius (a): unknown key \"radius\"; expected one of:"));
  EXPECT_THAT(e, HasSubstr("radius_m"));
}

TEST(SceneLoaderErrors, UnknownTopLevelAndNestedKeys) {
  EXPECT_THAT(error_of(R"j({"objects": [], "gravity": 1})j"), HasSubstr("/gravity: unknown key"));
  EXPECT_THAT(error_of(R"j({"objects": [], "world": {"step": 1}})j"), HasSubstr("/world/step: unknown key"));
  EXPECT_THAT(error_of(with_objects(R"j({"alias": "a", "type": "dummy", "pose": {"xyz": [1,2,3]}})j")),
              HasSubstr("/objects/0/pose/xyz (a): unknown key"));
}

TEST(SceneLoaderErrors, WrongTypes) {
  EXPECT_THAT(error_of(with_objects(R"j({"alias": "a", "type": "cuboid", "size_m": [1, "2", 3]})j")),
              HasSubstr("/objects/0/size_m/1 (a): expected a number in (0, 1e+06], got \"2\""));
  EXPECT_THAT(error_of(with_objects(R"j({"alias": "a", "type": "cuboid", "size_m": [1, 2]})j")),
              HasSubstr("/objects/0/size_m (a): expected an array of 3 elements, got [1,2]"));
  EXPECT_THAT(error_of(with_objects(R"j({"alias": 7, "type": "sphere", "radius_m": 1})j")),
              HasSubstr("/objects/0/alias: expected a non-empty string, got 7"));
  EXPECT_THAT(error_of(with_objects(R"j({"alias": "a", "type": "sphere", "radius_m": 1, "static": "yes"})j")),
              HasSubstr("/objects/0/static (a): expected true or false"));
  EXPECT_THAT(error_of(R"j({"objects": {}})j"), HasSubstr("/objects: expected an array of 0 to"));
  EXPECT_THAT(error_of(R"j([1, 2])j"), HasSubstr("inline.json: expected an object, got [1,2]"));
}

TEST(SceneLoaderErrors, OutOfRangeValues) {
  EXPECT_THAT(error_of(with_objects(R"j({"alias": "a", "type": "cuboid", "size_m": [1, -1, 3]})j")),
              HasSubstr("/objects/0/size_m/1 (a): expected a number in (0, 1e+06], got -1"));
  EXPECT_THAT(error_of(R"j({"objects": [], "world": {"physics_step_s": 0}})j"),
              HasSubstr("/world/physics_step_s: expected a number in [1e-05, 0.1], got 0"));
  EXPECT_THAT(error_of(with_objects(R"j({"alias": "a", "type": "sphere", "radius_m": 1, "color": [0, 2, 0]})j")),
              HasSubstr("/objects/0/color/1 (a): expected a number in [0, 1], got 2"));
  EXPECT_THAT(error_of(with_objects(R"j({"alias": "t", "type": "trees", "count": -3})j")),
              HasSubstr("/objects/0/count (t): expected an integer in [0, 10000], got -3"));
  EXPECT_THAT(error_of(with_objects(R"j({"alias": "t", "type": "trees", "trunk_radius_m": [0.5, 0.2]})j")),
              HasSubstr("/objects/0/trunk_radius_m (t): expected [min, max] with min <= max"));
  EXPECT_THAT(error_of(R"j({"objects": [], "world": {"seed": -1}})j"),
              HasSubstr("/world/seed: expected an integer seed in [0, 18446744073709551615], got -1"));
}

// A rate whose period is not a whole number of physics steps would run at another rate.
TEST(SceneLoaderErrors, RatesThatDoNotDivideThePhysicsRate) {
  EXPECT_EQ(error_of(R"j({"objects": [], "world": {"control_rate_hz": 100}})j"),
            "inline.json: /world/control_rate_hz: expected a rate that divides the physics rate 240 Hz "
            "(1 / physics_step_s) into a whole number of steps, such as 240, 120, 80 or 60, got 100");
  // Faster than the physics.
  EXPECT_EQ(error_of(R"j({"objects": [], "world": {"control_rate_hz": 1000}})j"),
            "inline.json: /world/control_rate_hz: expected a rate that divides the physics rate 240 Hz "
            "(1 / physics_step_s) into a whole number of steps, such as 240 or 120, got 1000");
  EXPECT_EQ(error_of(R"j({"objects": [], "world": {"sensor_rate_hz": 7}})j"),
            "inline.json: /world/sensor_rate_hz: expected a rate that divides the physics rate 240 Hz "
            "(1 / physics_step_s) into a whole number of steps, such as 7.27272727273, 7.05882352941, 6.85714285714 or 6.66666666667, got 7");
  // A sensor's own rate.
  EXPECT_EQ(error_of(with_objects(R"j({"alias": "v", "type": "quadrotor", "sensors": [
      {"alias": "front", "type": "lidar", "preset": "leddar_vu8"},
      {"alias": "down", "type": "lidar", "preset": "leddar_vu8", "rate_hz": 25}]})j")),
            "inline.json: /objects/0/sensors/1/rate_hz (v/down): expected a rate that divides the physics rate 240 Hz "
            "(1 / physics_step_s) into a whole number of steps, such as 30, 26.6666666667, 24 or 21.8181818182, got 25");
  // The rate checked against the step, whichever of them the file sets.
  EXPECT_EQ(error_of(R"j({"objects": [], "world": {"physics_step_s": 0.002, "control_rate_hz": 60}})j"),
            "inline.json: /world/control_rate_hz: expected a rate that divides the physics rate 500 Hz "
            "(1 / physics_step_s) into a whole number of steps, such as 71.4285714286, 62.5, 55.5555555556 or 50, got 60");
  EXPECT_EQ(error_of(R"j({"objects": [], "world": {"physics_step_s": 0.01}})j"),
            "inline.json: /world/physics_step_s: expected a step that divides the period of the default "
            "control_rate_hz 60 Hz, or else /world/control_rate_hz set to a rate that divides the physics rate "
            "100 Hz (1 / physics_step_s) into a whole number of steps, such as 100, 50 or 33.3333333333, got 0.01");
}

TEST(SceneLoader, RatesThatDivideThePhysicsRateAreKeptAsGiven) {
  const Scene scene = parse(R"j({"world": {"control_rate_hz": 60, "sensor_rate_hz": 10}, "objects": [
      {"alias": "v", "type": "quadrotor", "sensors": [
        {"alias": "fast", "type": "lidar", "preset": "leddar_vu8", "rate_hz": 240},
        {"alias": "odd", "type": "lidar", "preset": "leddar_vu8", "rate_hz": 26.6666666667}]}]})j");
  EXPECT_EQ(scene.world.control_rate_hz, 60.0);
  EXPECT_EQ(scene.world.sensor_rate_hz, 10.0);
  EXPECT_EQ(scene.vehicles[0].sensors[1].range.rate_hz, 26.6666666667);
  // A step with its rates, whichever way they are written (0.004166666666666667 is the bundled scenes' 1/240).
  const Scene bundled = parse(R"j({"world": {"physics_step_s": 0.004166666666666667, "control_rate_hz": 48},
      "objects": []})j");
  EXPECT_EQ(steps_per_period(bundled.world.control_rate_hz, bundled.world.physics_step_s), 5);
  // The defaults, 60 Hz and 10 Hz, at 120 Hz physics.
  EXPECT_EQ(parse(R"j({"world": {"physics_step_s": 0.008333333333333333}, "objects": []})j").world.control_rate_hz,
            60.0);
}

TEST(StepsPerPeriod, WholeStepsOnlyWithinARelativeTolerance) {
  EXPECT_EQ(steps_per_period(60.0, 1.0 / 240.0), 4);
  EXPECT_EQ(steps_per_period(240.0, 1.0 / 240.0), 1);
  EXPECT_EQ(steps_per_period(0.1, 1.0 / 240.0), 2400);
  EXPECT_EQ(steps_per_period(240.0 / 9.0, 1.0 / 240.0), 9);
  EXPECT_EQ(steps_per_period(100.0, 1.0 / 240.0), 0);   // 2.4 steps
  EXPECT_EQ(steps_per_period(1000.0, 1.0 / 240.0), 0);  // faster than the physics
  EXPECT_EQ(steps_per_period(300.0, 1.0 / 240.0), 0);
  EXPECT_EQ(steps_per_period(60.0 * (1.0 + 1e-6), 1.0 / 240.0), 0);
  EXPECT_EQ(steps_per_period(60.0 * (1.0 + 1e-12), 1.0 / 240.0), 4);
  EXPECT_EQ(dividing_rates_near(100.0, 1.0 / 240.0), (std::vector<double>{240.0, 120.0, 80.0, 60.0}));
  EXPECT_EQ(dividing_rates_near(1000.0, 1.0 / 240.0), (std::vector<double>{240.0, 120.0}));
}

// Below 0.01 Hz a sensor's period would exceed 10^7 physics steps; 1e-14 Hz once ran
// dividing_rates_near() past 2^53 into std::bad_alloc. The same reader serves --set and sweep axes.
TEST(SceneLoaderErrors, SensorRatesHaveARange) {
  const auto sensor_with_rate = [](const std::string& rate) {
    return with_objects(R"j({"alias": "v", "type": "quadrotor", "sensors": [
        {"alias": "down", "type": "lidar", "preset": "leddar_vu8", "rate_hz": )j" + rate + "}]}");
  };
  for (const std::string rate : {"1e-14", "0.001", "-1", "10001", "1e+300"}) {
    EXPECT_EQ(error_of(sensor_with_rate(rate)),
              "inline.json: /objects/0/sensors/0/rate_hz (v/down): expected 0 (world.sensor_rate_hz) or a number in "
              "[0.01, 10000], got " + rate)
        << rate;
  }
  EXPECT_THAT(error_of(sensor_with_rate("\"fast\"")), HasSubstr("/objects/0/sensors/0/rate_hz (v/down): expected a finite number, got \"fast\""));
  // The ends of the range: 0.01 Hz is 24000 steps at 240 Hz physics; 0 is the world's rate.
  EXPECT_EQ(parse(sensor_with_rate("0.01")).vehicles[0].sensors[0].range.rate_hz, 0.01);
  EXPECT_EQ(parse(sensor_with_rate("0")).vehicles[0].sensors[0].range.rate_hz, 0.0);
  EXPECT_EQ(parse(R"j({"world": {"physics_step_s": 0.0001, "control_rate_hz": 100, "sensor_rate_hz": 100},
      "objects": [{"alias": "v", "type": "quadrotor",
      "sensors": [{"alias": "s", "type": "lidar", "preset": "leddar_vu8", "rate_hz": 10000}]}]})j")
                .vehicles[0].sensors[0].range.rate_hz,
            10000.0);
}

// However slow the rate (or none), a few rates, from counted loops: no 2^53 treadmill.
TEST(StepsPerPeriod, DividingRatesNearIsBoundedForAnyRate) {
  for (const double rate : {1e-14, 1e-300, 0.0, -1.0, std::nan("")}) {
    const std::vector<double> rates = dividing_rates_near(rate, 1.0 / 240.0);
    EXPECT_LE(rates.size(), 4u) << rate;
    EXPECT_GE(rates.size(), 2u) << rate;
    for (const double r : rates) EXPECT_TRUE(r > 0.0 && r <= 240.0) << rate << " gave " << r;
  }
  // 1e-14 Hz lies 2.4e16 steps out: listed from 2^52 steps, slowest last.
  const std::vector<double> slow = dividing_rates_near(1e-14, 1.0 / 240.0);
  EXPECT_DOUBLE_EQ(slow.back(), 240.0 / (4503599627370496.0 + 1.0));
  EXPECT_TRUE(std::is_sorted(slow.rbegin(), slow.rend()));
}

TEST(SceneLoaderErrors, SeedsAreIntegersReadExactly) {
  // Beyond 2^53, where a double would round: read exactly.
  EXPECT_EQ(parse(R"j({"objects": [], "world": {"seed": 18446744073709551615}})j").world.seed,
            18446744073709551615u);
  EXPECT_EQ(parse(R"j({"objects": [], "world": {"seed": 9007199254740993}})j").world.seed, 9007199254740993u);
  EXPECT_EQ(error_of(R"j({"objects": [], "world": {"seed": 18446744073709551616}})j"),
            "inline.json: /world/seed: expected an integer seed in [0, 18446744073709551615], got 1.8446744073709552e+19");
  EXPECT_THAT(error_of(R"j({"objects": [], "world": {"seed": 1.5}})j"),
              HasSubstr("/world/seed: expected an integer seed in [0, 18446744073709551615], got 1.5"));
  EXPECT_THAT(error_of(R"j({"objects": [], "world": {"seed": 3.0}})j"),
              HasSubstr("/world/seed: expected an integer seed in [0, 18446744073709551615], got 3.0"));
  EXPECT_THAT(error_of(with_objects(R"j({"alias": "t", "type": "rolling_terrain", "size_m": [10, 10], "seed": -2})j")),
              HasSubstr("/objects/0/seed (t): expected an integer seed in [0, 18446744073709551615], got -2"));
}

TEST(SceneLoaderErrors, UnknownTypeAndMissingKeys) {
  EXPECT_THAT(error_of(with_objects(R"j({"alias": "a", "type": "torus"})j")),
              HasSubstr("/objects/0/type (a): expected one of \"cuboid\", \"cylinder\""));
  EXPECT_THAT(error_of(with_objects(R"j({"alias": "a", "type": "cuboid"})j")),
              HasSubstr("/objects/0 (a): missing required key \"size_m\""));
  EXPECT_THAT(error_of(with_objects(R"j({"type": "plane"})j")),
              HasSubstr("/objects/0: missing required key \"alias\""));
  EXPECT_THAT(error_of(R"j({})j"), HasSubstr("inline.json: missing required key \"objects\""));
}

TEST(SceneLoaderErrors, DuplicateAliasesNameBothPlaces) {
  EXPECT_THAT(error_of(with_objects(R"j({"alias": "a", "type": "plane"},
      {"alias": "b", "type": "dummy", "children": [{"alias": "a", "type": "dummy"}]})j")),
              HasSubstr("/objects/1/children/0/alias (b/a): duplicate alias \"a\" (first used at /objects/0/alias)"));
  EXPECT_THAT(error_of(with_objects(R"j({"alias": "bad/name", "type": "plane"})j")),
              HasSubstr("/objects/0/alias: expected an alias of 1-64 letters"));
}

TEST(SceneLoaderErrors, DanglingReferences) {
  EXPECT_THAT(error_of(with_objects(R"j({"alias": "v", "type": "rover",
      "mission": {"waypoints": [{"frame": "nowhere"}]}})j")),
              HasSubstr("/objects/0/mission/waypoints/0/frame (v): expected the alias of a dummy object, got \"nowhere\""));
  EXPECT_THAT(error_of(with_objects(R"j({"alias": "v", "type": "rover",
      "mission": {"grid": "missing", "waypoints": [{"cell": [1, 1], "agl_m": 1}]}})j")),
              HasSubstr("/objects/0/mission/grid (v): expected the alias of a grid_obstacles object"));
  EXPECT_THAT(error_of(with_objects(R"j({"alias": "v", "type": "rover",
      "mission": {"waypoints": [{"cell": [1, 1], "agl_m": 1}]}})j")),
              HasSubstr("/objects/0/mission/waypoints/0/cell (v): expected a mission with \"grid\""));
  EXPECT_THAT(error_of(with_objects(R"j({"alias": "v", "type": "quadrotor",
      "sensors": [{"alias": "s", "type": "lidar", "preset": "kinect"}]})j")),
              HasSubstr("/objects/0/sensors/0/preset (v/s): expected one of \"scanner3d\""));
  EXPECT_THAT(error_of(with_objects(R"j({"alias": "d", "type": "dummy", "pose": {"position_m": [0, 0, 1], "above_ground": true}})j")),
              HasSubstr("/objects/0/pose/above_ground (d): expected ground below the object: no terrain below (0, 0); "
                        "declare the terrain (heightfield, plane or rolling_terrain) before this object"));
}

TEST(SceneLoaderErrors, GeodeticWaypointsAndGates) {
  const std::string grid = R"j({"alias": "ground", "type": "plane"},
      {"alias": "g", "type": "grid_obstacles", "cell_size_m": 1.5, "rows": 10, "cols": 10},)j";
  EXPECT_THAT(error_of(with_objects(grid + R"j({"alias": "v", "type": "quadrotor",
      "mission": {"waypoints": [{"geodetic": [40.8, 14.7]}]}})j")),
              HasSubstr("/objects/2/mission/waypoints/0/geodetic (v): expected [lat, lon, alt], or [lat, lon] with \"agl_m\""));
  EXPECT_THAT(error_of(with_objects(grid + R"j({"alias": "v", "type": "quadrotor",
      "mission": {"waypoints": [{"geodetic": [40.8, 14.7, 3], "agl_m": 2}]}})j")),
              HasSubstr("/objects/2/mission/waypoints/0/agl_m (v): expected no \"agl_m\" with a geodetic [lat, lon, alt]"));
  EXPECT_THAT(error_of(R"j({"world": {"geo_reference": {"projection": "utm"}}, "objects": []})j"),
              HasSubstr("/world/geo_reference/projection: expected one of \"wgs84_enu\""));
  EXPECT_THAT(error_of(with_objects(grid + R"j({"alias": "v", "type": "quadrotor",
      "mission": {"gates": [{"name": "s", "rows": [1, 1], "cols": [1, 1]}], "waypoints": [{"position_m": [0, 0, 1]}]}})j")),
              HasSubstr("/objects/2/mission/gates (v): expected a mission with \"grid\""));
  EXPECT_THAT(error_of(with_objects(grid + R"j({"alias": "v", "type": "quadrotor",
      "mission": {"grid": "g", "gates": [{"name": "s", "rows": [1, 11], "cols": [1, 1]}],
                  "waypoints": [{"position_m": [0, 0, 1]}]}})j")),
              HasSubstr("/objects/2/mission/gates/0/rows/1 (v): expected"));
  EXPECT_THAT(error_of(with_objects(grid + R"j({"alias": "v", "type": "quadrotor",
      "mission": {"grid": "g", "gates": [{"name": "Slot", "rows": [1, 1], "cols": [1, 1]}],
                  "waypoints": [{"position_m": [0, 0, 1]}]}})j")),
              HasSubstr("/objects/2/mission/gates/0/name (v): expected a name of lower-case letters"));
  EXPECT_THAT(error_of(with_objects(grid + R"j({"alias": "v", "type": "quadrotor",
      "mission": {"grid": "g", "gates": [{"name": "s", "rows": [1, 1], "cols": [1, 1]},
                                         {"name": "s", "rows": [2, 2], "cols": [1, 1]}],
                  "waypoints": [{"position_m": [0, 0, 1]}]}})j")),
              HasSubstr("/objects/2/mission/gates/1/name (v): expected a gate name not used before"));
}

TEST(SceneLoaderErrors, UnreadableDataFiles) {
  EXPECT_THAT(error_of(with_objects(R"j({"alias": "t", "type": "heightfield", "csv": "no_such_file.csv"})j")),
              HasSubstr("/objects/0/csv (t): expected a readable file, but"));
  EXPECT_THAT(error_of(with_objects(R"j({"alias": "t", "type": "heightfield"})j")),
              HasSubstr("/objects/0 (t): expected exactly one height source"));
  EXPECT_THAT(error_of(with_objects(R"j({"alias": "t", "type": "heightfield", "expression": "sin(x/"})j")),
              HasSubstr("/objects/0/expression (t): "));
}

TEST(SceneLoaderErrors, InconsistentValues) {
  EXPECT_THAT(error_of(with_objects(R"j({"alias": "a", "type": "sphere", "radius_m": 1, "static": false})j")),
              HasSubstr("/objects/0 (a): a non-static shape needs \"mass_kg\" > 0"));
  EXPECT_THAT(error_of(with_objects(R"j({"alias": "v", "type": "rover", "sensors": [
      {"alias": "s", "type": "lidar", "range_m": [5, 1]}]})j")),
              HasSubstr("/objects/0/sensors/0/range_m (v/s): expected [min, max] with 0 <= min < max"));
  EXPECT_THAT(error_of(with_objects(R"j({"alias": "v", "type": "rover", "sensors": [
      {"alias": "s", "type": "lidar"}, {"alias": "s", "type": "lidar"}]})j")),
              HasSubstr("/objects/0/sensors/1/alias (v/s): duplicate sensor alias \"s\""));
  EXPECT_THAT(error_of(with_objects(R"j({"alias": "g", "type": "grid_obstacles", "rows": 10, "cols": 10,
      "boxes": [{"rows": [5, 3], "cols": 1, "height_m": 2}]})j")),
              HasSubstr("/objects/0/boxes/0/rows/1 (g): expected an integer in [5, 10], got 3"));
  EXPECT_THAT(error_of(with_objects(R"j({"alias": "t", "type": "heightfield", "expression": "x",
      "pose": {"rpy_deg": [10, 0, 0]}})j")),
              HasSubstr("/objects/0/pose (t): expected a heightfield pose without roll or pitch"));
}

TEST(SceneLoaderErrors, SyntaxErrorsReportLineAndColumn) {
  EXPECT_THAT(error_of("{\n  \"objects\": [\n    {\"alias\": \"a\",}\n  ]\n}"),
              HasSubstr("inline.json: invalid JSON at line 3, column"));
}

TEST(SceneLoaderErrors, LimitsStopHostileFiles) {
  SceneLimits limits;
  limits.max_objects = 3;
  EXPECT_THAT(error_of(with_objects(R"j({"alias": "a", "type": "plane"}, {"alias": "b", "type": "plane"},
      {"alias": "c", "type": "plane"}, {"alias": "d", "type": "plane"})j"), limits),
              HasSubstr("expected an array of 0 to 3 elements"));
  limits = {};
  limits.max_child_depth = 2;
  EXPECT_THAT(error_of(with_objects(R"j({"alias": "a", "type": "dummy", "children": [
      {"alias": "b", "type": "dummy", "children": [{"alias": "c", "type": "dummy", "children": [
      {"alias": "d", "type": "dummy"}]}]}]})j"), limits),
              HasSubstr("expected children nested at most 2 deep"));
  EXPECT_THAT(error_of(std::string(100, '[') + std::string(100, ']')), HasSubstr("nesting deeper than 32 levels"));
  limits = {};
  limits.json.max_file_bytes = 64;
  EXPECT_THAT(error_of(with_objects(std::string(100, ' ')), limits), HasSubstr("file too large"));
  EXPECT_THAT(error_of(with_objects(R"j({"alias": "t", "type": "rolling_terrain", "size_m": [100000, 100000], "spacing_m": 0.1})j")),
              HasSubstr("/objects/0 (t): expected a grid of at most 16777216 vertices"));
  EXPECT_THAT(error_of(with_objects(R"j({"alias": "t", "type": "trees", "count": 20000})j")),
              HasSubstr("/objects/0/count (t): expected an integer in [0, 10000]"));
  EXPECT_THAT(error_of(with_objects(R"j({"alias": "v", "type": "vineyard", "row_count": 400, "post_spacing_m": 0.01})j")),
              HasSubstr("/objects/0 (v): expected at most 100000 posts"));
  limits = {};
  limits.max_shapes = 5;
  EXPECT_THAT(error_of(with_objects(R"j({"alias": "t", "type": "trees", "count": 10, "min_spacing_m": 0.1})j"), limits),
              HasSubstr("/objects/0 (t): expected a scene of at most 5 shapes"));
}

TEST(SceneLoaderErrors, MissingFileIsAnInputError) {
  try {
    load_scene("/nonexistent/scene.json");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("/nonexistent/scene.json: cannot read"));
  }
}

TEST(SceneLoader, HashesTheFileBytes) {
  const auto path = std::filesystem::temp_directory_path() / "campo_hash_test.json";
  std::ofstream(path) << R"j({"objects": []})j";
  const Scene scene = load_scene(path);
  EXPECT_EQ(scene.source_sha256, sha256_hex(R"j({"objects": []})j"));
  // SHA-256 of "abc" (FIPS 180-2 test vector).
  EXPECT_EQ(sha256_hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace campo

namespace campo {
namespace {

// The full example in docs/scene-format.md stays valid.
TEST(SceneLoader, DocumentedExampleIsValid) {
  std::ifstream in(std::string(CAMPO_SOURCE_DIR) + "/docs/scene-format.md");
  std::stringstream doc;
  doc << in.rdbuf();
  const std::string text = doc.str();
  const auto begin = text.find("```json\n");
  ASSERT_NE(begin, std::string::npos);
  const auto end = text.find("```", begin + 8);
  const Scene scene = parse(text.substr(begin + 8, end - begin - 8));
  EXPECT_EQ(scene.name, "example");
  EXPECT_EQ(scene.vehicles.at(0).mission.size(), 4u);
  EXPECT_EQ(scene.movers.size(), 1u);
  EXPECT_NE(scene.find_shape("chimney"), nullptr);
}

}  // namespace
}  // namespace campo

namespace campo {
namespace {

TEST(SceneLoader, GridKeysReplaceAPresetsBeams) {
  const Scene scene = parse(R"({"objects": [{"alias": "r", "type": "rover", "sensors": [
      {"alias": "a", "type": "lidar", "preset": "planar180"},
      {"alias": "b", "type": "lidar", "preset": "planar180", "resolution": [361, 1]}]}]})");
  EXPECT_EQ(scene.vehicles[0].sensors[0].range.beam_count(), 181);
  EXPECT_TRUE(scene.vehicles[0].sensors[1].range.beams.empty());
  EXPECT_EQ(scene.vehicles[0].sensors[1].range.beam_count(), 361);
  EXPECT_THAT(error_of(R"({"objects": [{"alias": "r", "type": "rover", "sensors": [
      {"alias": "a", "type": "lidar", "beams": [[0, 0]], "resolution": [4, 4]}]}]})"),
              HasSubstr("/objects/0/sensors/0 (r/a): expected either \"beams\" or a grid"));
}

}  // namespace
}  // namespace campo

namespace campo {
namespace {

TEST(SceneLoader, DepthCamerasTakeAGridWithoutNoise) {
  const Scene scene = parse(R"({"objects": [{"alias": "d", "type": "quadrotor", "sensors": [
      {"alias": "cam", "type": "depth_camera", "preset": "scanner3d", "resolution": [64, 48]}]}]})");
  EXPECT_EQ(scene.vehicles[0].sensors[0].range.kind, RangeSensorKind::depth_camera);
  EXPECT_EQ(scene.vehicles[0].sensors[0].range.cols, 64);
  EXPECT_THAT(error_of(R"({"objects": [{"alias": "d", "type": "quadrotor", "sensors": [
      {"alias": "cam", "type": "depth_camera", "preset": "planar180"}]}]})"),
              HasSubstr("/objects/0/sensors/0 (d/cam): expected a depth camera with a beam grid"));
  EXPECT_THAT(error_of(R"({"objects": [{"alias": "d", "type": "quadrotor", "sensors": [
      {"alias": "cam", "type": "depth_camera", "fov_deg": [170, 90]}]}]})"),
              HasSubstr("expected a depth camera field of view of at most 150 deg"));
  EXPECT_THAT(error_of(R"({"objects": [{"alias": "d", "type": "quadrotor", "sensors": [
      {"alias": "cam", "type": "depth_camera", "noise_stddev_m": 0.01}]}]})"),
              HasSubstr("expected a depth camera without \"noise_stddev_m\""));
}

// The kind is the sensor's configuration's: a preset gives the other fields, not the kind, and what a
// depth camera cannot have is judged on the values (from the block or its preset), once they read cleanly.
TEST(SceneLoader, ADepthCamerasRequirementsAreOnItsValues) {
  const auto sensor = [](const std::string& block) {
    return R"({"objects": [{"alias": "d", "type": "quadrotor", "sensors": [{"alias": "cam", )" + block + "}]}]}";
  };
  const Scene camera = parse(sensor(R"("type": "depth_camera", "preset": "leddar_vu8", "resolution": [8, 8],
      "fov_deg": [48, 48], "noise_stddev_m": 0, "dropout_probability": 0)"));
  const RangeSensorConfig& c = camera.vehicles[0].sensors[0].range;
  EXPECT_EQ(c.kind, RangeSensorKind::depth_camera);
  EXPECT_EQ(c.preset, "leddar_vu8");
  EXPECT_TRUE(c.beams.empty());
  EXPECT_EQ(c.max_range_m, 100.0);  // the preset's
  // The same values a LIDAR may have.
  const Scene lidar = parse(sensor(R"("type": "lidar", "preset": "planar180", "noise_stddev_m": 0.01,
      "dropout_probability": 0.1)"));
  EXPECT_EQ(lidar.vehicles[0].sensors[0].range.kind, RangeSensorKind::lidar);
  EXPECT_EQ(lidar.vehicles[0].sensors[0].range.beams.size(), 181u);
  EXPECT_THAT(error_of(sensor(R"("type": "depth_camera", "dropout_probability": 0.1)")),
              HasSubstr("/objects/0/sensors/0 (d/cam): expected a depth camera without \"noise_stddev_m\" or "
                        "\"dropout_probability\" (only the LIDAR models them)"));
  EXPECT_THAT(error_of(sensor(R"("type": "depth_camera", "beams": [[0, 0]])")),
              HasSubstr("/objects/0/sensors/0 (d/cam): expected a depth camera with a beam grid"));
  EXPECT_THAT(error_of(sensor(R"("type": "depth_camera", "preset": "scanner3d", "fov_deg": [90, 150.5])")),
              HasSubstr("/objects/0/sensors/0 (d/cam): expected a depth camera field of view of at most 150 deg "
                        "each way"));
  EXPECT_EQ(parse(sensor(R"("type": "depth_camera", "fov_deg": [150, 150])")).vehicles[0].sensors[0].range.fov_h_deg,
            150.0);
  // A field in error: the requirements would judge a value the file did not give, so they are not checked.
  const std::string bad_range = error_of(sensor(R"("type": "depth_camera", "fov_deg": [170, 90], "range_m": [5, 1])"));
  EXPECT_THAT(bad_range, HasSubstr("/objects/0/sensors/0/range_m"));
  EXPECT_THAT(bad_range, ::testing::Not(HasSubstr("depth camera")));
}

}  // namespace
}  // namespace campo

namespace campo {
namespace {

TEST(SceneLoader, ReadsStateNoiseStrictly) {
  const Scene scene = parse(with_objects(R"j({"alias": "d", "type": "quadrotor",
    "state_noise": {"position_stddev_m": 0.5, "altitude_stddev_m": 0.2, "velocity_stddev_mps": 0.1,
                    "heading_stddev_deg": 2, "bias_walk_m_per_sqrt_s": 0.05, "rate_hz": 5}})j"));
  const StateNoiseConfig& n = scene.vehicles.front().state_noise;
  EXPECT_EQ(n.position_stddev_m, 0.5);
  EXPECT_EQ(n.altitude_stddev_m, 0.2);
  EXPECT_EQ(n.velocity_stddev_mps, 0.1);
  EXPECT_EQ(n.heading_stddev_deg, 2.0);
  EXPECT_EQ(n.bias_walk_m_per_sqrt_s, 0.05);
  EXPECT_EQ(n.rate_hz, 5.0);
  // Absent: no noise at all.
  EXPECT_FALSE(parse(with_objects(R"j({"alias": "d", "type": "quadrotor"})j")).vehicles.front().state_noise.enabled());
  EXPECT_THAT(error_of(with_objects(R"j({"alias": "d", "type": "quadrotor",
    "state_noise": {"position_stddev_m": -1}})j")),
              HasSubstr("inline.json: /objects/0/state_noise/position_stddev_m (d): expected a number in [0, 1000]"));
  EXPECT_THAT(error_of(with_objects(R"j({"alias": "d", "type": "quadrotor", "state_noise": {"gps": 1}})j")),
              HasSubstr("/objects/0/state_noise/gps (d): unknown key"));
}

}  // namespace
}  // namespace campo
