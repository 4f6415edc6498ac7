#include "vehicles/quadrotor.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <filesystem>
#include <functional>
#include <numbers>
#include <stdexcept>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "campo/json_reader.hpp"
#include "campo/scene_loader.hpp"
#include "tests/vehicles/quadrotor_flight.hpp"
#include "tests/vehicles/vehicle_test_support.hpp"
#include "tests/test_units.hpp"

namespace campo {
namespace {

using test::parse;
using test::at;
using test::wrap;
using test::kGround;

using ::testing::HasSubstr;

using namespace campo::test_units;


// A ground plane and a 4 m wide wall whose near face is at x = 3.
const char* kWall = R"j({"objects": [{"alias": "ground", "type": "plane"},
  {"alias": "wall", "type": "cuboid", "size_m": [0.2, 4, 4], "pose": {"position_m": [3.1, 0, 2]}}]})j";

// A quadrotor flight starting 2 m up unless told otherwise.
struct Flight : test::QuadrotorFlight {
  explicit Flight(const char* scene_json, const Eigen::Isometry3d& start = at({0.0, 0.0, 2.0}),
                  const QuadrotorConfig& config = {})
      : QuadrotorFlight(scene_json, start, config) {}
};

TEST(Quadrotor, StartsAtHoverSpeedAndDoesNotDrop) {
  Flight f(kGround);
  const double hover = hover_rotor_speed(model_of(QuadrotorConfig{}, f.scene.world.gravity_mps2));
  for (const double w : f.quad.rotor_speeds()) EXPECT_DOUBLE_EQ(w, hover);
  double lowest = 2.0;
  f.fly(command::Hold{{0.0, 0.0, 2.0}, {}}, 0.5, [&] { lowest = std::min(lowest, f.s().position_m.z()); });
  EXPECT_GT(lowest, 2.0 - 1e-3);
}

TEST(Quadrotor, RotorForcesActForOneStepOnly) {
  Flight f(kGround);
  f.fly(command::Hold{{0.0, 0.0, 2.0}, {}}, 0.5);
  // A step without pre_step: Bullet has cleared the rotor forces, only gravity acts.
  const double vz = f.s().linear_velocity_mps.z();
  f.world.step();
  EXPECT_NEAR(f.s().linear_velocity_mps.z() - vz, -9.81 * f.scene.world.physics_step_s, 1e-9);
}

TEST(Quadrotor, HoverHoldsAltitude) {
  Flight f(kGround, at({1.0, -1.0, 1.5}, 0.5));
  double worst = 0.0;
  f.fly(command::Hold{{1.0, -1.0, 1.5}, {}}, 6.0, [&] {
    if (f.t() > 1.0) worst = std::max(worst, std::abs(f.s().position_m.z() - 1.5));
  });
  EXPECT_LT(worst, 0.05);
  EXPECT_NEAR(wrap(f.s().yaw_rad() - 0.5), 0.0, 1e-3);
  EXPECT_FALSE(f.world.vehicle_clearance().touching());
}

TEST(Quadrotor, PositionStepSettlesWithoutOvershoot) {
  Flight f(kGround);
  const Eigen::Vector3d target(2.0, 0.0, 2.0);
  double max_x = 0.0;
  double settled_at = -1.0;
  f.fly(command::Hold{target, {}}, 10.0, [&] {
    const Eigen::Vector3d p = f.s().position_m;
    max_x = std::max(max_x, p.x());
    // Settled: within 3 % of the 2 m step from then on.
    if ((p - target).norm() > 0.03 * 2.0) settled_at = -1.0;
    else if (settled_at < 0.0) settled_at = f.t();
  });
  EXPECT_LT(max_x - 2.0, 0.1 * 2.0);
  ASSERT_GE(settled_at, 0.0) << "never settled";
  EXPECT_LT(settled_at, 8.0);
  RecordProperty("settling_time_s", std::to_string(settled_at));
  RecordProperty("overshoot_m", std::to_string(max_x - 2.0));
}

TEST(Quadrotor, GoToRespectsTheSpeedLimitAndReachesTheTarget) {
  Flight f(kGround);
  const Eigen::Vector3d start(0.0, 0.0, 2.0);
  const Eigen::Vector3d target(4.0, 3.0, 2.5);
  const double speed = 0.6;
  double max_horizontal = 0.0;
  double max_cross_track = 0.0;
  const Eigen::Vector3d dir = (target - start).normalized();
  f.fly(command::GoTo{target, speed, true}, 14.0, [&] {
    const VehicleState s = f.s();
    max_horizontal = std::max(max_horizontal, s.linear_velocity_mps.head<2>().norm());
    const Eigen::Vector3d off = s.position_m - start;
    max_cross_track = std::max(max_cross_track, (off - off.dot(dir) * dir).norm());
  });
  EXPECT_LE(max_horizontal, speed + 0.02);
  EXPECT_LT(max_cross_track, 0.1);
  EXPECT_LT((f.s().position_m - target).norm(), 0.05);
  // It faced the target on the way.
  EXPECT_NEAR(wrap(f.s().yaw_rad() - std::atan2(3.0, 4.0)), 0.0, 0.05);
}

TEST(Quadrotor, FaceTurnsTowardThePointAndHoldsPosition) {
  Flight f(kGround);
  // 120 degrees to the left.
  const Eigen::Vector3d point(5.0 * std::cos(2.0 * kPi / 3.0), 5.0 * std::sin(2.0 * kPi / 3.0), 2.0);
  double drift = 0.0;
  double settled_at = -1.0;
  f.fly(command::Face{point}, 6.0, [&] {
    const VehicleState s = f.s();
    drift = std::max(drift, (s.position_m - Eigen::Vector3d(0.0, 0.0, 2.0)).norm());
    if (std::abs(wrap(s.yaw_rad() - 2.0 * kPi / 3.0)) > 2.0 * kPi / 180.0) settled_at = -1.0;
    else if (settled_at < 0.0) settled_at = f.t();
  });
  ASSERT_GE(settled_at, 0.0) << "never settled";
  EXPECT_LT(settled_at, 4.0);
  EXPECT_LT(drift, 0.05);
}

TEST(Quadrotor, AltitudeChangesHeightAtTheSpeedLimitAndKeepsXY) {
  Flight f(kGround, at({1.0, 1.0, 1.0}));
  double max_vz = 0.0;
  f.fly(command::Altitude{3.0}, 8.0, [&] { max_vz = std::max(max_vz, f.s().linear_velocity_mps.z()); });
  EXPECT_NEAR(f.s().position_m.z(), 3.0, 0.02);
  EXPECT_LT((f.s().position_m.head<2>() - Eigen::Vector2d(1.0, 1.0)).norm(), 0.02);
  EXPECT_LE(max_vz, QuadrotorControllerConfig{}.speed_limit_mps + 0.02);
  EXPECT_GT(max_vz, QuadrotorControllerConfig{}.speed_limit_mps - 0.05);
}

TEST(Quadrotor, StableWhenSettledNotWhileMoving) {
  Flight f(kGround);
  f.fly(command::Hold{{0.0, 0.0, 2.0}, {}}, 1.0);
  EXPECT_TRUE(f.quad.stable());
  bool ever_stable_while_moving = false;
  f.fly(command::GoTo{{3.0, 0.0, 2.0}, 0.6, false}, 3.0, [&] {
    if (f.t() > 1.5 && f.quad.stable()) ever_stable_while_moving = true;
  });
  EXPECT_FALSE(ever_stable_while_moving);
  f.fly(command::GoTo{{3.0, 0.0, 2.0}, 0.6, false}, 6.0);
  EXPECT_TRUE(f.quad.stable());
}

TEST(Quadrotor, CollisionWhenFlownIntoAWall) {
  Flight f(kWall);
  bool hit = false;
  double hit_x = 0.0;
  f.fly(command::GoTo{{5.0, 0.0, 2.0}, 0.6, false}, 8.0, [&] {
    if (!hit && f.world.vehicle_clearance().touching()) {
      hit = true;
      hit_x = f.s().position_m.x();
    }
  });
  ASSERT_TRUE(hit);
  // The box (half length 0.3 m) touches the wall face at x = 3.
  EXPECT_NEAR(hit_x, 3.0 - 0.3, 0.05);
}

TEST(Quadrotor, RepeatedRunIsBitIdentical) {
  const auto run = [] {
    Flight f(kGround);
    f.fly(command::GoTo{{2.0, 1.0, 2.5}, 0.6, true}, 2.0);
    f.fly(command::Face{{0.0, 5.0, 2.0}}, 1.0);
    return f.s();
  };
  const VehicleState a = run();
  const VehicleState b = run();
  const auto bits = [](const Eigen::Vector3d& v) {
    return std::array{std::bit_cast<std::uint64_t>(v.x()), std::bit_cast<std::uint64_t>(v.y()),
                      std::bit_cast<std::uint64_t>(v.z())};
  };
  EXPECT_EQ(bits(a.position_m), bits(b.position_m));
  EXPECT_EQ(bits(a.linear_velocity_mps), bits(b.linear_velocity_mps));
  EXPECT_EQ(bits(a.angular_velocity_radps), bits(b.angular_velocity_radps));
  EXPECT_EQ(bits(a.orientation.vec()), bits(b.orientation.vec()));
  EXPECT_EQ(std::bit_cast<std::uint64_t>(a.orientation.w()), std::bit_cast<std::uint64_t>(b.orientation.w()));
}

TEST(Quadrotor, RejectsTwist) {
  Flight f(kGround);
  EXPECT_THROW(f.quad.command(command::Twist{1.0, 0.0}), std::invalid_argument);
}

TEST(Quadrotor, ReportsActuatorsAndParameters) {
  Flight f(kGround);
  f.fly(command::Hold{{0.0, 0.0, 2.0}, {}}, 0.1);
  const nlohmann::json a = f.quad.actuators();
  ASSERT_EQ(a.at("rotor_speed_radps").size(), 4u);
  ASSERT_EQ(a.at("rotor_speed_command_radps").size(), 4u);
  EXPECT_NEAR(a.at("thrust_n").get<double>(), 1.5 * 9.81, 0.05);
  EXPECT_EQ(f.quad.parameters(), to_json(QuadrotorConfig{}));
  EXPECT_EQ(f.quad.type(), VehicleType::quadrotor);
}

// The message of the InputError parsing `params` throws ("" if none).
std::string error_of(const std::string& params) {
  try {
    parse_quadrotor_config({nlohmann::json::parse(params), "scene.json", "/objects/2/params"});
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(QuadrotorConfig, PresetHoversNearSixtyPercentOfMaxRotorSpeed) {
  const QuadrotorConfig c;
  const double hover = hover_rotor_speed(model_of(c, {0.0, 0.0, -9.81}));
  EXPECT_NEAR(hover / c.max_rotor_speed_radps, 0.6, 0.02);
}

TEST(QuadrotorConfig, AppliesOverridesOnThePreset) {
  const QuadrotorConfig c = parse_quadrotor_config(
      {nlohmann::json::parse(R"j({"mass_kg": 1.8, "inertia_kgm2": [0.03, 0.03, 0.06],
        "controller": {"speed_limit_mps": 1.0, "rate_rp": {"kp": 20}}})j"),
       "scene.json", "/objects/2/params"});
  EXPECT_EQ(c.mass_kg, 1.8);
  EXPECT_EQ(c.inertia_kgm2, Eigen::Vector3d(0.03, 0.03, 0.06));
  EXPECT_EQ(c.controller.speed_limit_mps, 1.0);
  EXPECT_EQ(c.controller.rate_rp.kp, 20.0);
  EXPECT_EQ(c.controller.rate_rp.ki, QuadrotorControllerConfig{}.rate_rp.ki);
  EXPECT_EQ(c.arm_length_m, QuadrotorConfig{}.arm_length_m);
}

TEST(QuadrotorConfig, ToJsonRoundTrips) {
  const nlohmann::json preset = to_json(QuadrotorConfig{});
  EXPECT_TRUE(preset.contains("thrust_coefficient"));
  EXPECT_TRUE(preset.at("controller").at("velocity_xy").contains("integral_limit"));
  const QuadrotorConfig again = parse_quadrotor_config({preset, "scene.json", "/p"});
  EXPECT_EQ(to_json(again), preset);
}

TEST(QuadrotorConfig, RejectsUnknownKeysNamingFileAndPointer) {
  const std::string top = error_of(R"j({"mass_kg": 1.5, "wingspan_m": 2})j");
  EXPECT_THAT(top, HasSubstr("scene.json"));
  EXPECT_THAT(top, HasSubstr("/objects/2/params/wingspan_m"));
  EXPECT_THAT(top, HasSubstr("unknown key"));
  const std::string nested = error_of(R"j({"controller": {"rate_rp": {"kp": 1, "kq": 2}}})j");
  EXPECT_THAT(nested, HasSubstr("scene.json"));
  EXPECT_THAT(nested, HasSubstr("/objects/2/params/controller/rate_rp/kq"));
}

TEST(QuadrotorConfig, RejectsBadValuesNamingThePointer) {
  EXPECT_THAT(error_of(R"j({"mass_kg": -1})j"), HasSubstr("/objects/2/params/mass_kg"));
  EXPECT_THAT(error_of(R"j({"inertia_kgm2": [0.1, 0.1]})j"), HasSubstr("/objects/2/params/inertia_kgm2"));
  EXPECT_THAT(error_of(R"j({"controller": {"position": {"ki": "high"}}})j"),
              HasSubstr("/objects/2/params/controller/position/ki"));
  EXPECT_THAT(error_of(R"j({"min_rotor_speed_radps": 1200})j"),
              HasSubstr("/objects/2/params/max_rotor_speed_radps"));
  EXPECT_THAT(error_of(R"j({"mass_kg": 10})j"), HasSubstr("cannot lift"));
  EXPECT_THAT(error_of(R"j({"bounding_radius_m": 0.2})j"), HasSubstr("unknown key \"bounding_radius_m\""));
  EXPECT_THAT(error_of(R"j([1, 2])j"), HasSubstr("/objects/2/params"));
}

}  // namespace
}  // namespace campo
