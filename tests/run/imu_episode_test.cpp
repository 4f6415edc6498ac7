// IMUs in the closed loop: a hovering quadrotor reads gravity up at each IMU's own rate, and the
// turn rate while it turns (checked against the heading it actually turned through); a rover
// circling reads the centripetal acceleration of the speed and turn rate it actually had; a run
// records every sample in imu.csv and the IMUs' configuration in run.json.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "campo/episode.hpp"
#include "campo/scene_loader.hpp"
#include "campo/vehicle_factory.hpp"
#include "session/imu_record.hpp"
#include "session/run_session.hpp"

namespace campo {
namespace {

// Physics at 400 Hz, control at 50 Hz; the IMUs sample at 200 Hz ("fast"), 25 Hz ("slow") and
// the control rate ("control", with white noise).
constexpr const char* kImus = R"j([
  {"alias": "fast", "type": "imu", "rate_hz": 200},
  {"alias": "slow", "type": "imu", "rate_hz": 25},
  {"alias": "control", "type": "imu", "accel_noise_density_mps2_per_sqrt_hz": 0.002,
   "gyro_noise_density_radps_per_sqrt_hz": 0.0002, "seed": 4}])j";

std::string scene_text(const std::string& vehicle, const std::string& planner, const std::string& goal) {
  return R"j({"campo_scene": 1, "name": "imu",
    "world": {"physics_step_s": 0.0025, "control_rate_hz": 50, "sensor_rate_hz": 10, "time_limit_s": 30, "seed": 3},
    "objects": [{"alias": "ground", "type": "plane"},
      {"alias": "body", "type": ")j" +
         vehicle + R"j(", "pose": {"position_m": [0, 0, )j" + (vehicle == "quadrotor" ? "2" : "0.2") +
         R"j(]}, "sensors": )j" + kImus + R"j(, )j" + planner + R"j("mission": {"waypoints": [{"position_m": )j" +
         goal + "}]}}]}";
}

Scene scene_of(const std::string& vehicle) {
  return load_scene_text(scene_text(vehicle, "", vehicle == "quadrotor" ? "[0, 0, 2]" : "[10, 0, 0]"),
                         std::filesystem::temp_directory_path() / "imu.json");
}

PlanResult running(Command c) {
  PlanResult r;
  r.command = std::move(c);
  return r;
}

const ImuReading& imu(const Observation& o, std::string_view alias) {
  for (const ImuReading& r : o.imus) {
    if (r.alias == alias) return r;
  }
  throw std::logic_error("no IMU " + std::string(alias));
}

TEST(ImuEpisode, TheSceneDeclaresItsImus) {
  const Scene scene = scene_of("quadrotor");
  const VehicleDef& def = scene.vehicles.at(0);
  ASSERT_EQ(def.imus.size(), 3u);
  EXPECT_TRUE(def.sensors.empty());  // IMUs are not range sensors
  EXPECT_EQ(def.imus[0].imu.rate_hz, 200.0);
  EXPECT_EQ(def.imus[2].imu.accel_noise_density_mps2_per_sqrt_hz, 0.002);
  // A rate that does not divide the physics rate, and a bad value, are refused at their pointers.
  std::string bad = scene_text("quadrotor", "", "[0, 0, 2]");
  bad.replace(bad.find("\"rate_hz\": 25"), 13, "\"rate_hz\": 30");
  try {
    load_scene_text(bad, "imu.json");
    ADD_FAILURE() << "a 30 Hz IMU under 400 Hz physics was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/objects/1/sensors/1/rate_hz"), std::string::npos) << e.what();
  }
  std::string negative = scene_text("quadrotor", "", "[0, 0, 2]");
  negative.replace(negative.find("\"seed\": 4"), 9, "\"gyro_bias_instability_radps\": -1");
  try {
    load_scene_text(negative, "imu.json");
    ADD_FAILURE() << "a negative bias instability was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/objects/1/sensors/2/gyro_bias_instability_radps"), std::string::npos)
        << e.what();
  }
}

TEST(ImuEpisode, AHoveringQuadrotorReadsGravityUpAndItsTurnRate) {
  const Scene scene = scene_of("quadrotor");
  Episode episode(scene, &make_vehicle);
  const double tick = 1.0 / 50.0;
  double previous_slow_time = -1.0;
  int slow_fresh = 0, ticks = 0;
  Eigen::Vector3d hover_sum = Eigen::Vector3d::Zero(), control_sum = Eigen::Vector3d::Zero();
  int hover_samples = 0;
  // 4 s holding its place.
  for (int k = 0; k < 200; ++k, ++ticks) {
    const Observation& o = episode.observation();
    const ImuReading& fast = imu(o, "fast");
    const ImuReading& slow = imu(o, "slow");
    ASSERT_TRUE(fast.valid);
    // The fast IMU sampled at this very tick (200 Hz divides the control rate's steps), the slow one every 0.04 s.
    EXPECT_NEAR(fast.time_s, o.time_s, 1e-9);
    EXPECT_TRUE(fast.fresh);
    if (slow.fresh) {
      ++slow_fresh;
      if (previous_slow_time >= 0.0) EXPECT_NEAR(slow.time_s - previous_slow_time, 0.04, 1e-9);
      previous_slow_time = slow.time_s;
    }
    if (o.time_s > 1.0) {
      hover_sum += fast.specific_force_mps2;
      control_sum += imu(o, "control").specific_force_mps2;
      ++hover_samples;
      EXPECT_NEAR(fast.angular_rate_radps.norm(), 0.0, 0.02) << o.time_s;
    }
    episode.step(running(command::Hold{{0.0, 0.0, 2.0}, 0.0}));
  }
  EXPECT_NEAR(slow_fresh, ticks / 2, 1);
  const Eigen::Vector3d hover = hover_sum / hover_samples;
  EXPECT_NEAR(hover.x(), 0.0, 0.02);
  EXPECT_NEAR(hover.y(), 0.0, 0.02);
  EXPECT_NEAR(hover.z(), 9.81, 0.02);
  // The noisy IMU agrees within its noise (0.002 / sqrt(0.02) per sample, averaged) and the hover's unsteadiness.
  EXPECT_NEAR((control_sum / hover_samples - hover).norm(), 0.0, 0.02);

  // Turning in place at 0.5 rad/s: the gyroscope reads the rate at which the heading turned.
  const double rate = 0.5;
  for (int k = 0; k < 75; ++k) episode.step(running(command::Velocity{Eigen::Vector3d::Zero(), rate}));
  const double yaw_start = episode.observation().state.yaw_rad();
  double gyro_sum = 0.0;
  const int turning_ticks = 50;
  for (int k = 0; k < turning_ticks; ++k) {
    const ImuReading& fast = imu(episode.observation(), "fast");
    gyro_sum += fast.angular_rate_radps.z();
    EXPECT_NEAR(fast.specific_force_mps2.z(), 9.81, 0.1);
    episode.step(running(command::Velocity{Eigen::Vector3d::Zero(), rate}));
  }
  double turned = episode.observation().state.yaw_rad() - yaw_start;
  turned = std::remainder(turned, 2.0 * std::numbers::pi);
  const double mean_gyro = gyro_sum / turning_ticks;
  // The samples are taken at the ticks t0 .. t0 + 49 dt, the heading measured over t0 .. t0 + 50 dt:
  // equal for a steady turn (2 % for the controller's ripple).
  EXPECT_NEAR(mean_gyro, turned / (turning_ticks * tick), 0.02 * rate);
  EXPECT_NEAR(mean_gyro, rate, 0.05 * rate);
}

TEST(ImuEpisode, ACirclingRoverReadsItsCentripetalAcceleration) {
  const Scene scene = scene_of("rover");
  Episode episode(scene, &make_vehicle);
  const command::Twist twist{1.0, 0.5};
  for (int k = 0; k < 150; ++k) episode.step(running(twist));  // 3 s to settle on the circle
  // Over 4 s: the mean lateral specific force against the speed times the turn rate it had.
  const int ticks = 200;
  double lateral = 0.0, rate = 0.0, speed = 0.0;
  for (int k = 0; k < ticks; ++k) {
    const Observation& o = episode.observation();
    const ImuReading& fast = imu(o, "fast");
    lateral += fast.specific_force_mps2.y();
    rate += fast.angular_rate_radps.z();
    speed += o.state.linear_velocity_mps.head<2>().norm();
    episode.step(running(twist));
  }
  lateral /= ticks;
  rate /= ticks;
  speed /= ticks;
  ASSERT_GT(speed, 0.5);
  ASSERT_GT(rate, 0.25);
  // a = v w toward the centre, on the left (+y) of a rover turning left.
  EXPECT_NEAR(lateral, speed * rate, 0.1 * speed * rate);
}

TEST(ImuEpisode, ARunRecordsEverySampleAndTheImus) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "campo_imu_run";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::filesystem::path scene = dir / "imu.json";
  std::ofstream(scene) << scene_text("quadrotor", R"j("planner": {"name": "straight"}, )j", "[2, 0, 2]");
  RunRequest request;
  request.scene = scene;
  request.out = dir / "run";
  request.figures = false;
  const ExecutedRun run = execute_run(request);
  const double sim_time = run.record.at("metrics").at("sim_time_s").get<double>();
  ASSERT_GT(sim_time, 0.5);

  // run.json lists the IMUs with every field.
  const nlohmann::json& imus = run.record.at("parameters").at("imus");
  ASSERT_EQ(imus.size(), 3u);
  EXPECT_EQ(imus[1].at("alias"), "slow");
  EXPECT_EQ(imus[1].at("rate_hz"), 25.0);
  EXPECT_EQ(imus[2].at("accel_noise_density_mps2_per_sqrt_hz"), 0.002);
  EXPECT_TRUE(imus[0].contains("mount"));

  std::ifstream csv(request.out / "imu.csv");
  ASSERT_TRUE(csv) << "no imu.csv";
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "time_s,alias,f_x_mps2,f_y_mps2,f_z_mps2,w_x_radps,w_y_radps,w_z_radps");
  int slow = 0, control = 0, fast = 0;
  double previous_slow = -1.0;
  while (std::getline(csv, line)) {
    std::stringstream row(line);
    std::string time, alias, fz;
    std::getline(row, time, ',');
    std::getline(row, alias, ',');
    for (int i = 0; i < 3; ++i) std::getline(row, fz, ',');
    EXPECT_NEAR(std::stod(fz), 9.81, 3.0) << line;  // a gentle flight: about 1 g up
    if (alias == "slow") {
      if (previous_slow >= 0.0) EXPECT_NEAR(std::stod(time) - previous_slow, 0.04, 1e-6) << line;
      previous_slow = std::stod(time);
      ++slow;
    }
    control += alias == "control";
    fast += alias == "fast";
  }
  // Every sample of every IMU at its own rate: one per tick, one per other tick, and the fast one's
  // samples between the ticks too.
  const int run_ticks = static_cast<int>(std::lround(sim_time * 50.0));
  EXPECT_NEAR(control, run_ticks, 2);
  EXPECT_NEAR(slow, run_ticks / 2, 2);
  EXPECT_NEAR(fast, static_cast<int>(std::lround(sim_time * 200.0)), 8);
  std::filesystem::remove_all(dir);
}

TEST(ImuEpisode, TheFilesAreNamedAsTheTrajectoriesAndHoldEveryRow) {
  EpisodeResult one, two;
  one.vehicles.resize(1);
  two.vehicles.resize(2);
  one.vehicles[0].alias = two.vehicles[0].alias = "east";
  two.vehicles[1].alias = "west";
  EXPECT_EQ(imu_file(one, 0), "imu.csv");
  EXPECT_EQ(imu_file(two, 1), "imu_west.csv");
  VehicleDef def;
  def.imus = {{"a", {}}, {"b", {}}};
  // Zero() spelled out: `{}` would value-initialise an Eigen vector, which leaves it uninitialised.
  const std::string csv = imu_csv(def, {{1, 0.25, {0.5, -1.0, 9.81}, {0.0, 0.125, -2.0}}, {0, 0.5, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()}});
  EXPECT_EQ(csv,
            "time_s,alias,f_x_mps2,f_y_mps2,f_z_mps2,w_x_radps,w_y_radps,w_z_radps\n"
            "0.250000,b,0.5,-1,9.81,0,0.125,-2\n"
            "0.500000,a,0,0,0,0,0,0\n");
}

}  // namespace
}  // namespace campo
