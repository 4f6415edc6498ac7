#pragma once
/// State-estimation noise (SPEC §6): what a vehicle's planner and
/// controllers believe is the true state plus an error drawn from a seeded
/// model of a GNSS/INS estimate (white position, altitude, velocity and
/// heading noise, plus a random-walk position bias). The error is drawn anew
/// at rate_hz and held in between, like the output of a real estimator.
#include <cstdint>

#include <Eigen/Core>

#include "campo/random.hpp"
#include "campo/state_noise.hpp"

namespace campo {

/// Estimated minus true state.
struct StateError {
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d velocity_mps = Eigen::Vector3d::Zero();
  double heading_rad = 0.0;  ///< about the world z axis
};

class StateEstimator {
 public:
  /// `seed`: the run's stream for this vehicle (Rng::derive_seed of the world seed).
  StateEstimator(const StateNoiseConfig& config, std::uint64_t seed);

  /// The error in force at simulation time t_s (non-decreasing between
  /// calls): a new draw when a period of 1/rate_hz has begun since the last
  /// one (every call when rate_hz is 0), else the last draw.
  const StateError& error_at(double t_s);

 private:
  void draw(double dt_s);

  StateNoiseConfig config_;
  Rng rng_;
  StateError error_;
  Eigen::Vector3d bias_m_ = Eigen::Vector3d::Zero();
  std::int64_t period_ = -1;  // index of the period of the last draw
  double last_draw_s_ = 0.0;
};

}  // namespace campo
