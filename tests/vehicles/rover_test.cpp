#include "vehicles/rover.hpp"

#include <cmath>
#include <filesystem>
#include <numbers>
#include <stdexcept>
#include <string>

#include <btBulletDynamicsCommon.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "campo/scene_loader.hpp"
#include "tests/vehicles/vehicle_test_support.hpp"
#include "tests/test_units.hpp"

namespace campo {
namespace {

using test::parse;

using ::testing::HasSubstr;

using namespace campo::test_units;

const char* kFlat = R"j({"objects": [{"alias": "ground", "type": "plane"}]})j";

// Flat for x < 0, then a 10 degree ramp up along +x to the edge at x = 25.
const char* kRamp = R"j({"objects": [{"alias": "ground", "type": "heightfield",
  "expression": "max(0, tan(10*_pi/180)*x)", "size_m": [50, 12], "spacing_m": 0.5}]})j";

const char* kBoxAhead = R"j({"objects": [{"alias": "ground", "type": "plane"},
  {"alias": "wall", "type": "cuboid", "size_m": [0.5, 4, 1], "pose": {"position_m": [4, 0, 0.5]}}]})j";

// A person walking across the rover's position.
const char* kWalker = R"j({"objects": [{"alias": "ground", "type": "plane"},
  {"alias": "walker", "type": "mover", "shape": {"type": "cylinder", "radius_m": 0.25, "height_m": 1.7},
   "path_m": [[0, -4, 0.85], [0, 4, 0.85]], "speed_mps": 1.0}]})j";

Eigen::Isometry3d start_at(double x, double y, double z, double yaw_rad = 0.0) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  t.translation() = Eigen::Vector3d(x, y, z);
  return t;
}

// A scene, its world and a rover in it, stepped as the episode loop does.
struct Sim {
  Sim(const char* scene_json, const Eigen::Isometry3d& start, const RoverConfig& config = {})
      : scene(parse(scene_json)), world(scene), rover(world, config, start) {}

  void step() {
    rover.pre_step(scene.world.physics_step_s);
    world.step();
  }
  void run(double seconds) {
    const long steps = std::lround(seconds / scene.world.physics_step_s);
    for (long i = 0; i < steps; ++i) step();
  }
  // Forward speed and yaw rate in the body frame.
  BodyTwist body_rates() const {
    const VehicleState s = rover.state();
    const Eigen::Matrix3d r = s.orientation.toRotationMatrix();
    return {s.linear_velocity_mps.dot(r.col(0)), s.angular_velocity_radps.dot(r.col(2))};
  }

  Scene scene;
  World world;
  Rover rover;
};

ParamsBlock params(const std::string& json) {
  return {nlohmann::json::parse(json), "scenes/field.json", "/objects/2/params"};
}

TEST(RoverConfig, EmptyParamsGiveThePreset) {
  const RoverConfig c = parse_rover_config(params("{}"));
  EXPECT_EQ(to_json(c), to_json(RoverConfig{}));
  EXPECT_EQ(c.chassis_size_m, Eigen::Vector3d(1.5, 1.0, 0.35));
}

TEST(RoverConfig, OverridesReplaceTheirFieldsOnly) {
  const RoverConfig c = parse_rover_config(
      params(R"({"wheel_radius_m": 0.25, "chassis_size_m": [1.2, 0.8, 0.3], "joint_solver_iterations": 8})"));
  EXPECT_EQ(c.wheel_radius_m, 0.25);
  EXPECT_EQ(c.chassis_size_m, Eigen::Vector3d(1.2, 0.8, 0.3));
  EXPECT_EQ(c.joint_solver_iterations, 8);
  EXPECT_EQ(c.half_track_m, RoverConfig{}.half_track_m);
}

TEST(RoverConfig, RejectsUnknownKeysNamingFileAndPointer) {
  try {
    parse_rover_config(params(R"({"wheel_radius": 0.3})"));
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("scenes/field.json"));
    EXPECT_THAT(e.what(), HasSubstr("/objects/2/params/wheel_radius"));
    EXPECT_THAT(e.what(), HasSubstr("unknown key"));
    EXPECT_THAT(e.what(), HasSubstr("wheel_radius_m"));  // listed among the allowed keys
  }
}

TEST(RoverConfig, RejectsOutOfRangeValuesNamingThePointer) {
  try {
    parse_rover_config(params(R"({"max_wheel_torque_nm": -5})"));
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("scenes/field.json: /objects/2/params/max_wheel_torque_nm"));
    EXPECT_THAT(e.what(), HasSubstr("> 0"));
  }
  EXPECT_THROW(parse_rover_config(params(R"({"joint_solver_iterations": 0})")), InputError);
  EXPECT_THROW(parse_rover_config(params(R"({"chassis_size_m": [1, 1]})")), InputError);
  EXPECT_THROW(parse_rover_config(params(R"([1, 2])")), InputError);
}

TEST(RoverConfig, RejectsWheelsThatDoNotReachBelowTheChassis) {
  try {
    parse_rover_config(params(R"({"axle_drop_m": -0.1})"));
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("/objects/2/params/axle_drop_m"));
  }
}

TEST(RoverConfig, JsonListsEveryParameterAndReadsBack) {
  RoverConfig c;
  c.max_wheel_accel_radps2 = 6.0;
  const nlohmann::json j = to_json(c);
  EXPECT_EQ(j.size(), 29u);
  EXPECT_EQ(to_json(parse_rover_config({j, "x.json", ""})), j);
}

TEST(Rover, SettlesOnItsWheelsAtTheRestHeight) {
  Sim sim(kFlat, start_at(2.0, -1.0, 0.45, 0.3));
  sim.run(2.0);
  const VehicleState s = sim.rover.state();
  EXPECT_NEAR(s.position_m.z(), 0.4, 0.005);  // wheel radius + axle drop
  EXPECT_NEAR(s.position_m.x(), 2.0, 0.01);
  EXPECT_NEAR(s.position_m.y(), -1.0, 0.01);
  EXPECT_NEAR(s.yaw_rad(), 0.3, 1e-3);
  EXPECT_TRUE(sim.rover.stable());
  EXPECT_FALSE(sim.world.vehicle_clearance().touching());
  EXPECT_EQ(sim.rover.type(), VehicleType::rover);
}

TEST(Rover, MeasuredBodyRatesMatchTheTwistOnFlatGround) {
  const BodyTwist commands[] = {{0.5, 0.0}, {1.0, 0.0}, {-0.5, 0.0}, {0.5, 0.3},
                                {1.0, -0.5}, {0.0, 0.5}, {0.0, -1.0}};
  for (const BodyTwist& c : commands) {
    SCOPED_TRACE("v = " + std::to_string(c.v_mps) + ", w = " + std::to_string(c.w_radps));
    Sim sim(kFlat, start_at(0, 0, 0.4));
    sim.rover.command(command::Twist{c.v_mps, c.w_radps});
    sim.run(2.0);
    for (int i = 0; i < 240; ++i) {
      sim.step();
      const BodyTwist m = sim.body_rates();
      ASSERT_NEAR(m.v_mps, c.v_mps, 0.1 * std::abs(c.v_mps) + 0.01);
      ASSERT_NEAR(m.w_radps, c.w_radps, 0.1 * std::abs(c.w_radps) + 0.01);
    }
  }
}

TEST(Rover, ClimbsATenDegreeSlope) {
  Sim sim(kRamp, start_at(-3.0, 0, 0.4));
  sim.rover.command(command::Twist{0.8, 0.0});
  sim.run(14.0);
  const VehicleState s = sim.rover.state();
  // Progress along the slope past its foot at x = 0.
  const double up_slope = s.position_m.x() / std::cos(10 * kDeg);
  EXPECT_GT(up_slope, 7.0);
  EXPECT_NEAR(s.position_m.z(), std::tan(10 * kDeg) * s.position_m.x() + 0.4 / std::cos(10 * kDeg), 0.02);
  EXPECT_NEAR(s.position_m.y(), 0.0, 0.1);
  EXPECT_NEAR(sim.body_rates().v_mps, 0.8, 0.08);
  EXPECT_FALSE(sim.world.vehicle_clearance().touching());
}

TEST(Rover, HoldStopsWithoutDriftingOnFlatGround) {
  Sim sim(kFlat, start_at(0, 0, 0.4));
  sim.rover.command(command::Twist{1.0, 0.2});
  sim.run(3.0);
  sim.rover.command(command::Hold{});
  sim.run(1.0);
  EXPECT_TRUE(sim.rover.stable());
  const Eigen::Vector3d stopped = sim.rover.state().position_m;
  sim.run(5.0);
  EXPECT_LT((sim.rover.state().position_m - stopped).norm(), 0.02);
  for (const double w : sim.rover.wheel_speeds_radps()) EXPECT_NEAR(w, 0.0, 0.05);
}

TEST(Rover, HoldStopsWithoutDriftingOnTheSlope) {
  Sim sim(kRamp, start_at(-2.0, 0, 0.4));
  sim.rover.command(command::Twist{0.8, 0.0});
  sim.run(8.0);
  ASSERT_GT(sim.rover.state().position_m.x(), 3.0);  // on the slope
  sim.rover.command(command::Hold{});
  sim.run(1.0);
  const Eigen::Vector3d stopped = sim.rover.state().position_m;
  sim.run(5.0);
  EXPECT_LT((sim.rover.state().position_m - stopped).norm(), 0.02);
  EXPECT_TRUE(sim.rover.stable());
}

TEST(Rover, OdometryAgreesWithGroundTruthDrivingStraight) {
  Sim sim(kFlat, start_at(1.0, 2.0, 0.4, 0.5));
  sim.rover.command(command::Twist{1.0, 0.0});
  sim.run(8.0);
  const VehicleState s = sim.rover.state();
  const PlanarPose& odometry = sim.rover.odometry();
  const double true_distance = (s.position_m.head<2>() - Eigen::Vector2d(1.0, 2.0)).norm();
  const double odometry_distance = std::hypot(odometry.x_m - 1.0, odometry.y_m - 2.0);
  ASSERT_GT(true_distance, 7.0);
  EXPECT_NEAR(odometry_distance, true_distance, 0.03 * true_distance);
  EXPECT_NEAR(odometry.yaw_rad, s.yaw_rad(), 0.01);
  EXPECT_NEAR(std::atan2(odometry.y_m - 2.0, odometry.x_m - 1.0), 0.5, 0.01);
}

TEST(Rover, AccelerationLimitBoundsTheWheelCommands) {
  RoverConfig config;
  config.max_wheel_accel_radps2 = 4.0;
  Sim sim(kFlat, start_at(0, 0, 0.4), config);
  const double max_step = 4.0 * sim.scene.world.physics_step_s + 1e-12;
  auto previous = sim.rover.wheel_commands_radps();
  const auto check_steps = [&](double seconds) {
    for (int i = 0; i < std::lround(seconds / sim.scene.world.physics_step_s); ++i) {
      sim.step();
      const auto now = sim.rover.wheel_commands_radps();
      for (int w = 0; w < Rover::kWheels; ++w) ASSERT_LE(std::abs(now[w] - previous[w]), max_step);
      previous = now;
    }
  };
  sim.rover.command(command::Twist{1.0, 0.0});
  check_steps(0.5);
  // Half a second at 4 rad/s^2 reaches at most 2 rad/s of the 5 rad/s needed.
  EXPECT_LT(sim.rover.wheel_commands_radps()[0], 2.0 + 1e-9);
  check_steps(3.0);
  EXPECT_NEAR(sim.body_rates().v_mps, 1.0, 0.05);
  sim.rover.command(command::Hold{});
  check_steps(0.5);
  EXPECT_GT(sim.body_rates().v_mps, 0.3);  // still braking gently
  check_steps(2.0);
  EXPECT_TRUE(sim.rover.stable());
}

TEST(Rover, DrivingIntoABoxIsACollision) {
  Sim sim(kBoxAhead, start_at(0, 0, 0.4));
  sim.rover.command(command::Twist{1.0, 0.0});
  bool collided = false;
  for (int i = 0; i < 240 * 6 && !collided; ++i) {
    sim.step();
    collided = sim.world.vehicle_clearance().touching();
    // The front of the chassis (x + 0.75) reaches the wall face (x = 3.75) at x = 3.
    if (!collided) ASSERT_LT(sim.rover.state().position_m.x(), 3.02);
  }
  EXPECT_TRUE(collided);
  EXPECT_GT(sim.rover.state().position_m.x(), 2.9);
}

TEST(Rover, DrivingOnTheGroundAloneIsNoCollision) {
  Sim sim(kRamp, start_at(-4.0, 0, 0.4));
  const command::Twist moves[] = {{1.0, 0.0}, {0.6, 0.4}, {0.0, -0.8}, {-0.5, 0.0}, {0.8, -0.3}};
  for (const auto& move : moves) {
    sim.rover.command(move);
    for (int i = 0; i < 240 * 3; ++i) {
      sim.step();
      ASSERT_FALSE(sim.world.vehicle_clearance().touching()) << "t = " << sim.world.time_s();
    }
  }
}

TEST(Rover, AMoverHittingTheRoverIsACollision) {
  Sim sim(kWalker, start_at(0, 0, 0.4));
  sim.rover.command(command::Hold{});
  bool collided = false;
  for (int i = 0; i < 240 * 5 && !collided; ++i) {
    sim.step();
    collided = sim.world.vehicle_clearance().touching();
  }
  EXPECT_TRUE(collided);
  // The walker (radius 0.25) reaches the chassis side (y = -0.5) after 3.25 m.
  EXPECT_NEAR(sim.world.time_s(), 3.25, 0.1);
}

TEST(Rover, RepeatRunsAreBitIdentical) {
  const auto run = [] {
    Sim sim(kRamp, start_at(-3.0, 0.5, 0.45, 0.2));
    sim.rover.command(command::Twist{0.9, 0.3});
    sim.run(3.0);
    sim.rover.command(command::GoTo{{6.0, -1.0, 0.0}, 0.7, true});
    sim.run(6.0);
    sim.rover.command(command::Hold{});
    sim.run(1.0);
    return std::make_pair(sim.rover.state(), sim.rover.odometry());
  };
  const auto [a, odometry_a] = run();
  const auto [b, odometry_b] = run();
  EXPECT_EQ(a.position_m, b.position_m);
  EXPECT_EQ(a.orientation.coeffs(), b.orientation.coeffs());
  EXPECT_EQ(a.linear_velocity_mps, b.linear_velocity_mps);
  EXPECT_EQ(a.angular_velocity_radps, b.angular_velocity_radps);
  EXPECT_EQ(odometry_a.x_m, odometry_b.x_m);
  EXPECT_EQ(odometry_a.y_m, odometry_b.y_m);
  EXPECT_EQ(odometry_a.yaw_rad, odometry_b.yaw_rad);
}

TEST(Rover, GoToTurnsTowardTheTargetAndStopsThere) {
  Sim sim(kFlat, start_at(0, 0, 0.4));
  const Eigen::Vector3d target(-3.0, 4.0, 0.0);  // behind and to the left
  sim.rover.command(command::GoTo{target, 0.8, true});
  double closest = 1e9;
  for (int i = 0; i < 240 * 15; ++i) {
    sim.step();
    const double distance = (sim.rover.state().position_m - target).head<2>().norm();
    closest = std::min(closest, distance);
    ASSERT_LT(distance, closest + 0.05) << "moving away again at t = " << sim.world.time_s();
    ASSERT_LT(sim.body_rates().v_mps, 0.8 * 1.05);  // a few % of transient overshoot
  }
  EXPECT_LT((sim.rover.state().position_m - target).head<2>().norm(), 0.3);
  EXPECT_TRUE(sim.rover.stable());
}

TEST(Rover, FaceTurnsInPlaceTowardThePoint) {
  Sim sim(kFlat, start_at(1.0, 1.0, 0.4));
  sim.rover.command(command::Face{{1.0, 6.0, 0.0}});
  sim.run(5.0);
  const VehicleState s = sim.rover.state();
  EXPECT_NEAR(s.yaw_rad(), std::numbers::pi / 2, 3 * kDeg);
  EXPECT_LT((s.position_m - Eigen::Vector3d(1.0, 1.0, 0.4)).head<2>().norm(), 0.1);
  EXPECT_TRUE(sim.rover.stable());
}

TEST(Rover, RejectsCommandsItCannotFollow) {
  Sim sim(kFlat, start_at(0, 0, 0.4));
  EXPECT_THROW(sim.rover.command(command::Altitude{2.0}), std::invalid_argument);
  EXPECT_THROW(sim.rover.command(command::GoTo{{1, 0, 0}, 0.0, true}), std::invalid_argument);
  EXPECT_THROW(sim.rover.command(command::GoTo{{1, 0, 0}, std::nan(""), true}), std::invalid_argument);
  EXPECT_THROW(sim.rover.command(command::Twist{INFINITY, 0.0}), std::invalid_argument);
  EXPECT_THROW(sim.rover.command(command::Face{{std::nan(""), 0, 0}}), std::invalid_argument);
  EXPECT_NO_THROW(sim.rover.command(command::Face{{1, 1, 0}}));
}

TEST(Rover, StartsAboveSlopedGroundInsteadOfInsideIt) {
  // The chassis centre 0.4 m above the ground under it would bury the front wheels.
  Sim sim(kRamp, start_at(5.0, 0.0, std::tan(10 * kDeg) * 5.0 + 0.4));
  sim.run(2.0);
  EXPECT_FALSE(sim.world.vehicle_clearance().touching());
  const Eigen::Vector3d up = sim.rover.state().orientation * Eigen::Vector3d::UnitZ();
  EXPECT_NEAR(std::acos(up.z()), 10 * kDeg, 1 * kDeg);
  EXPECT_LT(std::abs(sim.rover.state().position_m.x() - 5.0), 0.2);
}

TEST(Rover, ReportsEveryWheelAndItsParameters) {
  Sim sim(kFlat, start_at(0, 0, 0.4));
  sim.rover.command(command::Twist{0.5, 0.0});
  sim.run(1.0);
  const nlohmann::json a = sim.rover.actuators();
  ASSERT_EQ(a.size(), 4u);
  for (const char* wheel : {"front_left", "front_right", "rear_left", "rear_right"}) {
    EXPECT_NEAR(a.at(wheel).at("command_radps").get<double>(), 2.5, 0.1) << wheel;
    EXPECT_NEAR(a.at(wheel).at("speed_radps").get<double>(), 2.5, 0.1) << wheel;
  }
  EXPECT_EQ(sim.rover.parameters(), to_json(RoverConfig{}));
}

TEST(Rover, RemovesItsBodiesFromTheWorld) {
  const Scene scene = parse(kFlat);
  World world(scene);
  const int objects = world.bullet().getNumCollisionObjects();
  {
    Rover rover(world, RoverConfig{}, start_at(0, 0, 0.4));
    EXPECT_EQ(world.bullet().getNumCollisionObjects(), objects + 5);
    EXPECT_EQ(world.bullet().getNumConstraints(), 4);
    world.step();
  }
  EXPECT_EQ(world.bullet().getNumCollisionObjects(), objects);
  EXPECT_EQ(world.bullet().getNumConstraints(), 0);
  world.step();
}

}  // namespace
}  // namespace campo
