#pragma once
/// The inertial measurement unit ("imu" sensor): what an ideal IMU at a mount
/// measures between two states of its carrier, and the datasheet error model
/// (white noise, bias instability, bias random walk) laid over it.
#include <cstdint>

#include <Eigen/Geometry>

#include "campo/random.hpp"
#include "campo/scene.hpp"

namespace campo {

/// One sample of an IMU, in its own frame.
struct ImuSample {
  Eigen::Vector3d specific_force_mps2 = Eigen::Vector3d::Zero();  ///< accelerometer
  Eigen::Vector3d angular_rate_radps = Eigen::Vector3d::Zero();    ///< gyroscope
};

/// The carrier's motion at one instant, world frame: what an IMU's reading
/// depends on (the closed loop fills it from the vehicle's state).
struct CarrierMotion {
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  ///< body to world
  Eigen::Vector3d linear_velocity_mps = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_velocity_radps = Eigen::Vector3d::Zero();
};

/// What an ideal IMU mounted at `mount` (carrier body frame) measures over
/// the `period_s` from `before` to `now`:
///  - specific force: the mount point's mean acceleration over the period
///    (its velocity change over the period, the lever arm's centripetal and
///    tangential terms included) minus gravity, turned into the IMU frame at
///    the middle of the period (halfway between the two orientations), as an
///    integrating (delta-velocity) accelerometer reports it: a body circling
///    at speed v on radius r reads 2 v sin(w T / 2) / T = v^2 / r (1 - (w T)^2 / 24)
///    toward the centre, with no spurious along-track part;
///  - angular rate: the carrier's angular velocity `now`, in the IMU frame `now`.
/// A carrier at rest reads -gravity (+9.81 m/s² up). `before` equal to `now`
/// (no previous state) counts as unaccelerated.
ImuSample ideal_imu_sample(const CarrierMotion& before, const CarrierMotion& now, const Pose& mount, double period_s,
                           const Eigen::Vector3d& gravity_mps2);

/// The peak of a first-order Gauss-Markov process's Allan deviation in units
/// of its stationary standard deviation s: with x = tau / Tc,
///   sigma_A^2(tau) = s^2 (2x - 3 + 4 e^-x - e^-2x) / x^2,
/// which is largest, 0.6174 s, at tau = 1.893 Tc.
inline constexpr double kGaussMarkovAllanPeak = 0.6174;
/// Where that peak lies, in correlation times.
inline constexpr double kGaussMarkovAllanPeakTau = 1.893;

/// The error model of one IMU, advanced once per sample (every `period_s`).
/// Each axis of each instrument (accelerometer, gyroscope) adds
///  - white noise of density N: a fresh N / sqrt(period) stddev draw each
///    sample (Allan deviation N / sqrt(tau));
///  - bias instability B: a first-order Gauss-Markov bias with correlation
///    time Tc (ImuConfig::bias_correlation_time_s) and stationary stddev
///    B / kGaussMarkovAllanPeak, so that its Allan deviation's flat top, the
///    floor a datasheet reads its "bias instability" from, is B (at tau = 1.89 Tc);
///    it starts from a stationary draw (the in-run part of the turn-on bias);
///  - bias random walk K: a bias starting at 0 that takes a step of stddev
///    K sqrt(period) each sample (Allan deviation K sqrt(tau / 3)).
/// Every term draws from its own stream derived from `seed`, so enabling one
/// leaves the others' draws unchanged, and a zero parameter draws nothing: a
/// configuration of zeros returns the ideal sample exactly.
class ImuErrorModel {
 public:
  /// `period_s` > 0; the config's parameters >= 0 and its correlation time > 0
  /// (std::invalid_argument otherwise: the scene loader checks user input first).
  ImuErrorModel(const ImuConfig& config, double period_s, std::uint64_t seed);
  /// `ideal` with this sample's noise and biases added; advances the biases.
  ImuSample corrupt(const ImuSample& ideal);

  /// The bias (instability plus random walk) the next sample carries.
  Eigen::Vector3d accel_bias_mps2() const { return accel_.bias(); }
  Eigen::Vector3d gyro_bias_radps() const { return gyro_.bias(); }

  /// The error processes of one instrument's three axes.
  class Instrument {
   public:
    Instrument(double noise_density, double bias_instability, double random_walk, double correlation_time_s,
               double period_s, std::uint64_t seed);
    /// This sample's error (white noise plus bias); advances the biases.
    Eigen::Vector3d next_error();
    Eigen::Vector3d bias() const { return markov_bias_ + walk_bias_; }

   private:
    double white_stddev_;        // per sample
    double markov_decay_;        // exp(-period / Tc)
    double markov_step_stddev_;  // keeps the stationary stddev: s sqrt(1 - decay^2)
    double walk_step_stddev_;    // per sample
    Rng white_rng_;
    Rng markov_rng_;
    Rng walk_rng_;
    Eigen::Vector3d markov_bias_ = Eigen::Vector3d::Zero();
    Eigen::Vector3d walk_bias_ = Eigen::Vector3d::Zero();
  };

 private:
  Instrument accel_;
  Instrument gyro_;
};

}  // namespace campo
