#include "campo/state_estimation.hpp"

#include <cmath>
#include <filesystem>
#include <numbers>

#include <gtest/gtest.h>

#include "campo/episode.hpp"
#include "campo/planner_registry.hpp"
#include "campo/scene_loader.hpp"
#include "campo/vehicle_factory.hpp"

namespace campo {
namespace {

TEST(StateEstimator, NoNoiseIsTheTruth) {
  StateEstimator estimator(StateNoiseConfig{}, 7);
  const StateError& e = estimator.error_at(3.0);
  EXPECT_EQ(e.position_m, Eigen::Vector3d::Zero());
  EXPECT_EQ(e.velocity_mps, Eigen::Vector3d::Zero());
  EXPECT_EQ(e.heading_rad, 0.0);
}

TEST(StateEstimator, DrawsAtItsRateAndHoldsInBetween) {
  StateNoiseConfig c;
  c.position_stddev_m = 1.0;
  c.rate_hz = 5.0;
  StateEstimator estimator(c, 7);
  const Eigen::Vector3d first = estimator.error_at(0.0).position_m;
  EXPECT_EQ(estimator.error_at(0.1).position_m, first);
  EXPECT_EQ(estimator.error_at(0.19).position_m, first);
  const Eigen::Vector3d second = estimator.error_at(0.2).position_m;  // period 1 begins at exactly 1/5 s
  EXPECT_NE(second, first);
  EXPECT_EQ(first.z(), 0.0);  // no altitude noise asked
  // Same seed, same errors; another seed, others.
  StateEstimator again(c, 7), other(c, 8);
  EXPECT_EQ(again.error_at(0.0).position_m, first);
  EXPECT_NE(other.error_at(0.0).position_m, first);
}

TEST(StateEstimator, StandardDeviationsAndBiasWalkAsConfigured) {
  StateNoiseConfig c;
  c.position_stddev_m = 0.5;
  c.altitude_stddev_m = 2.0;
  c.heading_stddev_deg = 3.0;
  StateEstimator estimator(c, 11);
  const int n = 20000;
  double sx = 0.0, sz = 0.0, sh = 0.0;
  for (int k = 0; k < n; ++k) {
    const StateError& e = estimator.error_at(0.01 * k);
    sx += e.position_m.x() * e.position_m.x();
    sz += e.position_m.z() * e.position_m.z();
    sh += e.heading_rad * e.heading_rad;
  }
  // Sample standard deviations within 3 % (their own sd is about 0.5 %).
  EXPECT_NEAR(std::sqrt(sx / n), 0.5, 0.015);
  EXPECT_NEAR(std::sqrt(sz / n), 2.0, 0.06);
  EXPECT_NEAR(std::sqrt(sh / n), 3.0 * std::numbers::pi / 180.0, 0.03 * 3.0 * std::numbers::pi / 180.0);

  // A bias walk alone: after T seconds the bias has variance b^2 T, whatever the draw rate.
  StateNoiseConfig walk;
  walk.bias_walk_m_per_sqrt_s = 0.1;
  walk.rate_hz = 10.0;
  double sum_squares = 0.0;
  const int runs = 2000;
  for (int seed = 0; seed < runs; ++seed) {
    StateEstimator w(walk, static_cast<std::uint64_t>(seed));
    for (int k = 0; k <= 100; ++k) w.error_at(0.1 * k);  // 10 s
    sum_squares += w.error_at(10.0).position_m.x() * w.error_at(10.0).position_m.x();
  }
  EXPECT_NEAR(std::sqrt(sum_squares / runs), 0.1 * std::sqrt(10.0), 0.1 * std::sqrt(10.0) * 0.05);
}

Scene open_flight(const std::string& noise) {
  return parse_scene(nlohmann::json::parse(R"j({"world": {"time_limit_s": 60, "seed": 4}, "objects": [
    {"alias": "ground", "type": "plane"},
    {"alias": "drone", "type": "quadrotor", "pose": {"position_m": [0, 0, 1.5]},
     "planner": {"name": "straight", "params": {"tolerance_m": 0.1}}, )j" + noise + R"j(
     "mission": {"waypoints": [{"position_m": [8, 0, 1.5]}]}}]})j"),
                     "inline.json", std::filesystem::temp_directory_path());
}

TEST(StateEstimation, ThePlannerAndControllerActOnTheEstimate) {
  const EpisodeResult truth = run_episode(open_flight(""), &make_vehicle, &create_planner);
  ASSERT_EQ(truth.only().metrics.outcome, Outcome::reached);
  for (const TrajectorySample& s : truth.only().trajectory) EXPECT_EQ(s.estimated_position_m, s.state.position_m);

  // A constant error: one draw (rate 0.001 Hz) of 1 m horizontal noise.
  const Scene noisy = open_flight(R"j("state_noise": {"position_stddev_m": 1.0, "rate_hz": 0.001},)j");
  const EpisodeResult r = run_episode(noisy, &make_vehicle, &create_planner);
  ASSERT_EQ(r.only().metrics.outcome, Outcome::reached) << r.only().metrics.reason;
  const Eigen::Vector3d offset = r.only().trajectory.front().estimated_position_m - r.only().trajectory.front().state.position_m;
  EXPECT_GT(offset.head<2>().norm(), 0.05);
  for (const TrajectorySample& s : r.only().trajectory) {
    EXPECT_NEAR((s.estimated_position_m - s.state.position_m - offset).norm(), 0.0, 1e-9);
  }
  // The drone stops where it believes the goal is: off the true goal by the error.
  const Eigen::Vector3d end = r.only().trajectory.back().state.position_m;
  EXPECT_NEAR((end + offset - Eigen::Vector3d(8, 0, 1.5)).head<2>().norm(), 0.0, 0.1 + 1e-6);
  // Seeded: the same run again is identical.
  const EpisodeResult again = run_episode(noisy, &make_vehicle, &create_planner);
  EXPECT_EQ(again.final_state_hash, r.final_state_hash);
}

}  // namespace
}  // namespace campo
