#pragma once
/// The configuration of state-estimation noise (SPEC §6), plain data: a
/// vehicle's description (scene.hpp) holds one, and the estimator that draws
/// the error (state_estimation.hpp, implemented in sensors/) reads it. Its own
/// header so that the scene description does not include the estimator.
namespace campo {

/// The "state_noise" block of a vehicle; every field defaults to 0 (no noise).
struct StateNoiseConfig {
  double position_stddev_m = 0.0;        ///< horizontal (x, y) white noise per axis, >= 0
  double altitude_stddev_m = 0.0;        ///< vertical (z) white noise, >= 0
  double velocity_stddev_mps = 0.0;      ///< white noise per axis, >= 0
  double heading_stddev_deg = 0.0;       ///< yaw white noise, >= 0
  double bias_walk_m_per_sqrt_s = 0.0;   ///< position bias random walk per axis, >= 0
  double rate_hz = 0.0;                  ///< new error this often; 0: at every planner call

  bool enabled() const {
    return position_stddev_m > 0.0 || altitude_stddev_m > 0.0 || velocity_stddev_mps > 0.0 ||
           heading_stddev_deg > 0.0 || bias_walk_m_per_sqrt_s > 0.0;
  }
};

}  // namespace campo
