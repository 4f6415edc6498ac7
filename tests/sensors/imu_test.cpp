// The IMU: the ideal sample against hand-computed kinematics (rest, a turn, a circle, a lever arm),
// and the error model against the Allan deviation of long stationary sequences, computed here
// with the overlapping estimator (IEEE Std 952 annex C), a method independent of the model's recursion.
#include "sensors/imu.hpp"

#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

namespace campo {
namespace {

const Eigen::Vector3d kGravity(0.0, 0.0, -9.81);

CarrierMotion at_rest() { return CarrierMotion{}; }

Eigen::Quaterniond yaw(double rad) { return Eigen::Quaterniond(Eigen::AngleAxisd(rad, Eigen::Vector3d::UnitZ())); }

TEST(IdealImu, AtRestReadsGravityUp) {
  const ImuSample s = ideal_imu_sample(at_rest(), at_rest(), Pose{}, 0.01, kGravity);
  EXPECT_EQ(s.specific_force_mps2, Eigen::Vector3d(0.0, 0.0, 9.81));
  EXPECT_EQ(s.angular_rate_radps, Eigen::Vector3d::Zero());
  // Rolled 90 degrees on its mount: the IMU's y axis points up (Rx(90) takes y to z).
  Pose rolled;
  rolled.rpy_deg = {90.0, 0.0, 0.0};
  const ImuSample r = ideal_imu_sample(at_rest(), at_rest(), rolled, 0.01, kGravity);
  EXPECT_NEAR(r.specific_force_mps2.x(), 0.0, 1e-12);
  EXPECT_NEAR(r.specific_force_mps2.y(), 9.81, 1e-12);
  EXPECT_NEAR(r.specific_force_mps2.z(), 0.0, 1e-12);
  // Free fall reads nothing.
  CarrierMotion falling = at_rest();
  falling.linear_velocity_mps = kGravity * 0.01;
  const ImuSample f = ideal_imu_sample(at_rest(), falling, Pose{}, 0.01, kGravity);
  EXPECT_NEAR(f.specific_force_mps2.norm(), 0.0, 1e-12);
}

TEST(IdealImu, ConstantYawRateReadsTheTurnRate) {
  const double rate = 0.7, period = 0.02;
  CarrierMotion before, now;
  before.orientation = yaw(0.3);
  now.orientation = yaw(0.3 + rate * period);
  before.angular_velocity_radps = now.angular_velocity_radps = {0.0, 0.0, rate};
  const ImuSample level = ideal_imu_sample(before, now, Pose{}, period, kGravity);
  EXPECT_NEAR((level.angular_rate_radps - Eigen::Vector3d(0.0, 0.0, rate)).norm(), 0.0, 1e-12);
  // Turning in place: no acceleration, gravity only.
  EXPECT_NEAR((level.specific_force_mps2 - Eigen::Vector3d(0.0, 0.0, 9.81)).norm(), 0.0, 1e-12);
  // Pitched 90 degrees on its mount (Ry(90) takes x to -z): the yaw rate shows on -x, gravity on -x too.
  Pose pitched;
  pitched.rpy_deg = {0.0, 90.0, 0.0};
  const ImuSample p = ideal_imu_sample(before, now, pitched, period, kGravity);
  EXPECT_NEAR((p.angular_rate_radps - Eigen::Vector3d(-rate, 0.0, 0.0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((p.specific_force_mps2 - Eigen::Vector3d(-9.81, 0.0, 0.0)).norm(), 0.0, 1e-12);
}

// A body circling counter-clockwise at `speed` on radius `radius` about the origin, nose along its
// velocity (so the centre is on its left, +y), at polar angle `angle`.
CarrierMotion circling(double radius, double speed, double angle) {
  CarrierMotion s;
  s.linear_velocity_mps = {-speed * std::sin(angle), speed * std::cos(angle), 0.0};
  s.orientation = yaw(angle + std::numbers::pi / 2);
  s.angular_velocity_radps = {0.0, 0.0, speed / radius};
  return s;
}

TEST(IdealImu, CirclingBodyReadsTheCentripetalAcceleration) {
  const double radius = 4.0, speed = 3.0, period = 0.02;
  const double rate = speed / radius;
  const ImuSample s =
      ideal_imu_sample(circling(radius, speed, 1.1), circling(radius, speed, 1.1 + rate * period), Pose{}, period,
                       kGravity);
  // The mean acceleration over the period: the chord of the velocity circle, 2 v sin(w T / 2) / T,
  // toward the centre at mid-period: along +y of the body, nothing along its track.
  const double exact = 2.0 * speed * std::sin(rate * period / 2.0) / period;
  EXPECT_NEAR(s.specific_force_mps2.x(), 0.0, 1e-9);
  EXPECT_NEAR(s.specific_force_mps2.y(), exact, 1e-9);
  EXPECT_NEAR(s.specific_force_mps2.z(), 9.81, 1e-9);
  // v^2 / r, to the period's (w T)^2 / 24.
  const double centripetal = speed * speed / radius;
  EXPECT_NEAR(s.specific_force_mps2.y(), centripetal, centripetal * std::pow(rate * period, 2) / 24.0 * 1.01);
  EXPECT_GT(std::abs(s.specific_force_mps2.y() - centripetal), 0.0);  // the finite period shows
  EXPECT_NEAR((s.angular_rate_radps - Eigen::Vector3d(0.0, 0.0, rate)).norm(), 0.0, 1e-12);
}

TEST(IdealImu, LeverArmOnASpinningBodyReadsOmegaSquaredR) {
  const double rate = 2.0, arm = 0.5, period = 0.005;
  CarrierMotion before, now;
  before.orientation = yaw(0.0);
  now.orientation = yaw(rate * period);
  before.angular_velocity_radps = now.angular_velocity_radps = {0.0, 0.0, rate};
  Pose mount;
  mount.position_m = {arm, 0.0, 0.0};
  const ImuSample s = ideal_imu_sample(before, now, mount, period, kGravity);
  // The mount point circles the spin axis: w^2 r toward it, along the IMU's -x (the arm points along +x).
  const double exact = 2.0 * rate * arm * std::sin(rate * period / 2.0) / period;
  EXPECT_NEAR(s.specific_force_mps2.x(), -exact, 1e-9);
  EXPECT_NEAR(s.specific_force_mps2.x(), -rate * rate * arm, rate * rate * arm * 1e-4);
  EXPECT_NEAR(s.specific_force_mps2.y(), 0.0, 1e-9);
  EXPECT_NEAR(s.specific_force_mps2.z(), 9.81, 1e-9);
  // At the centre of the spin: nothing but gravity.
  const ImuSample centre = ideal_imu_sample(before, now, Pose{}, period, kGravity);
  EXPECT_NEAR((centre.specific_force_mps2 - Eigen::Vector3d(0.0, 0.0, 9.81)).norm(), 0.0, 1e-12);
}

TEST(IdealImu, LeverArmOnAnAcceleratingSpinReadsTheTangentialTerm) {
  // Spin-up from w0 at angular acceleration a: the arm's end reads a r along its track (+y) and
  // the mid-period w^2 r inward, to first order in the period.
  const double w0 = 1.0, accel = 3.0, arm = 0.4, period = 1e-4;
  CarrierMotion before, now;
  before.angular_velocity_radps = {0.0, 0.0, w0};
  now.angular_velocity_radps = {0.0, 0.0, w0 + accel * period};
  now.orientation = yaw(w0 * period + accel * period * period / 2.0);
  Pose mount;
  mount.position_m = {arm, 0.0, 0.0};
  const ImuSample s = ideal_imu_sample(before, now, mount, period, kGravity);
  const double w_mid = w0 + accel * period / 2.0;
  EXPECT_NEAR(s.specific_force_mps2.y(), accel * arm, 1e-3);
  EXPECT_NEAR(s.specific_force_mps2.x(), -w_mid * w_mid * arm, 1e-3);
}

// ---------------------------------------------------------------------------------------------
// The error model.

// `samples` of the error at rest on each axis of one instrument: (specific force, angular rate)
// minus the ideal reading, as three sequences per instrument.
struct ErrorSequences {
  std::vector<std::vector<double>> accel{3}, gyro{3};
};

ErrorSequences stationary_errors(const ImuConfig& config, double period, std::size_t samples, std::uint64_t seed) {
  ImuErrorModel model(config, period, seed);
  const ImuSample ideal{{0.0, 0.0, 9.81}, Eigen::Vector3d::Zero()};
  ErrorSequences e;
  for (int a = 0; a < 3; ++a) {
    e.accel[a].reserve(samples);
    e.gyro[a].reserve(samples);
  }
  for (std::size_t k = 0; k < samples; ++k) {
    const ImuSample s = model.corrupt(ideal);
    for (int a = 0; a < 3; ++a) {
      e.accel[a].push_back(s.specific_force_mps2[a] - ideal.specific_force_mps2[a]);
      e.gyro[a].push_back(s.angular_rate_radps[a]);
    }
  }
  return e;
}

// Overlapping Allan deviation of rate samples `y` (spacing `period`) at cluster size `m`, from the
// integral theta_k = period * sum_{i<k} y_i:
//   sigma^2(m T) = sum_k (theta_{k+2m} - 2 theta_{k+m} + theta_k)^2 / (2 (m T)^2 (n - 2m)).
double allan_deviation(const std::vector<double>& y, double period, std::size_t m) {
  const std::size_t n = y.size();
  std::vector<double> theta(n + 1, 0.0);
  for (std::size_t i = 0; i < n; ++i) theta[i + 1] = theta[i] + y[i] * period;
  double sum = 0.0;
  for (std::size_t k = 0; k + 2 * m <= n; ++k) {
    const double d = theta[k + 2 * m] - 2.0 * theta[k + m] + theta[k];
    sum += d * d;
  }
  const double tau = static_cast<double>(m) * period;
  return std::sqrt(sum / (2.0 * tau * tau * static_cast<double>(n + 1 - 2 * m)));
}

// The Allan deviation averaged (in variance) over three independent axes.
double allan_deviation(const std::vector<std::vector<double>>& axes, double period, std::size_t m) {
  double variance = 0.0;
  for (const auto& y : axes) variance += std::pow(allan_deviation(y, period, m), 2);
  return std::sqrt(variance / static_cast<double>(axes.size()));
}

// The slope of log sigma against log tau between cluster sizes m1 and m2.
double allan_slope(const std::vector<std::vector<double>>& axes, double period, std::size_t m1, std::size_t m2) {
  return std::log(allan_deviation(axes, period, m2) / allan_deviation(axes, period, m1)) /
         std::log(static_cast<double>(m2) / static_cast<double>(m1));
}

constexpr double kPeriod = 0.01;           // 100 Hz
constexpr std::size_t kSamples = 1 << 21;  // about 5.8 hours

TEST(ImuErrorModel, ZeroParametersGiveTheIdealSampleExactly) {
  ImuErrorModel model(ImuConfig{}, kPeriod, 99);
  const ImuSample ideal{{0.1, -0.2, 9.7}, {0.01, 0.02, -0.3}};
  for (int k = 0; k < 100; ++k) {
    const ImuSample s = model.corrupt(ideal);
    EXPECT_EQ(s.specific_force_mps2, ideal.specific_force_mps2);
    EXPECT_EQ(s.angular_rate_radps, ideal.angular_rate_radps);
  }
}

TEST(ImuErrorModel, AtRestReadsGravityUpWithinTheNoise) {
  ImuConfig config;
  config.accel_noise_density_mps2_per_sqrt_hz = 0.002;
  config.gyro_noise_density_radps_per_sqrt_hz = 1e-3;
  const std::size_t n = 20000;
  ImuErrorModel model(config, kPeriod, 5);
  const ImuSample ideal = ideal_imu_sample(at_rest(), at_rest(), Pose{}, kPeriod, kGravity);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero(), sum_sq = Eigen::Vector3d::Zero();
  for (std::size_t k = 0; k < n; ++k) {
    const Eigen::Vector3d f = model.corrupt(ideal).specific_force_mps2;
    sum += f;
    sum_sq += f.cwiseProduct(f);
  }
  const Eigen::Vector3d mean = sum / static_cast<double>(n);
  const double sigma = 0.002 / std::sqrt(kPeriod);  // per sample
  const double bound = 3.0 * sigma / std::sqrt(static_cast<double>(n));
  EXPECT_NEAR(mean.x(), 0.0, bound);
  EXPECT_NEAR(mean.y(), 0.0, bound);
  EXPECT_NEAR(mean.z(), 9.81, bound);
  // Each sample's spread is N / sqrt(T) (the stddev's own standard error is sigma / sqrt(2n), 0.5 %).
  for (int a = 0; a < 3; ++a) {
    const double variance = sum_sq[a] / static_cast<double>(n) - mean[a] * mean[a];
    EXPECT_NEAR(std::sqrt(variance), sigma, 0.03 * sigma) << "axis " << a;
  }
}

TEST(ImuErrorModel, WhiteNoiseAllanSlopeIsMinusOneHalfAtTheNoiseDensity) {
  ImuConfig config;
  config.gyro_noise_density_radps_per_sqrt_hz = 2e-3;
  config.accel_noise_density_mps2_per_sqrt_hz = 0.05;
  const ErrorSequences e = stationary_errors(config, kPeriod, kSamples, 11);
  for (const std::size_t m : {1, 10, 100, 1000}) {
    const double tau = static_cast<double>(m) * kPeriod;
    // sigma(tau) = N / sqrt(tau); the estimate's spread at m = 1000 (2000 clusters, 3 axes) is about 2 %.
    EXPECT_NEAR(allan_deviation(e.gyro, kPeriod, m), 2e-3 / std::sqrt(tau), 0.06 * 2e-3 / std::sqrt(tau)) << m;
    EXPECT_NEAR(allan_deviation(e.accel, kPeriod, m), 0.05 / std::sqrt(tau), 0.06 * 0.05 / std::sqrt(tau)) << m;
  }
  EXPECT_NEAR(allan_slope(e.gyro, kPeriod, 1, 100), -0.5, 0.02);
  EXPECT_NEAR(allan_slope(e.accel, kPeriod, 1, 100), -0.5, 0.02);
}

TEST(ImuErrorModel, RandomWalkAllanSlopeIsPlusOneHalfAtTheRandomWalk) {
  ImuConfig config;
  config.gyro_random_walk_radps2_per_sqrt_hz = 1e-4;
  config.accel_random_walk_mps3_per_sqrt_hz = 3e-3;
  const ErrorSequences e = stationary_errors(config, kPeriod, kSamples, 12);
  // sigma(tau) = K sqrt(tau / 3). A random walk's overlapping estimate scatters more than white
  // noise's: at m = 10000 (100 s, 210 clusters per axis) about 10 %; tolerance 20 % there, 10 % below.
  for (const std::size_t m : {100, 1000, 10000}) {
    const double tau = static_cast<double>(m) * kPeriod;
    const double tolerance = m >= 10000 ? 0.2 : 0.1;
    const double gyro = 1e-4 * std::sqrt(tau / 3.0), accel = 3e-3 * std::sqrt(tau / 3.0);
    EXPECT_NEAR(allan_deviation(e.gyro, kPeriod, m), gyro, tolerance * gyro) << m;
    EXPECT_NEAR(allan_deviation(e.accel, kPeriod, m), accel, tolerance * accel) << m;
  }
  EXPECT_NEAR(allan_slope(e.gyro, kPeriod, 100, 1000), 0.5, 0.05);
  EXPECT_NEAR(allan_slope(e.accel, kPeriod, 100, 1000), 0.5, 0.05);
}

TEST(ImuErrorModel, BiasInstabilityIsTheAllanFloor) {
  const double correlation = 2.0;  // s; the peak at 1.89 Tc, 3.8 s: about 2700 clusters per axis
  ImuConfig config;
  config.gyro_bias_instability_radps = 5e-4;
  config.accel_bias_instability_mps2 = 0.02;
  config.bias_correlation_time_s = correlation;
  const ErrorSequences e = stationary_errors(config, kPeriod, kSamples, 13);
  // The largest Allan deviation over tau from 0.1 Tc to 20 Tc is the configured instability, and lies near 1.89 Tc.
  double peak = 0.0, peak_tau = 0.0;
  for (double tau = 0.1 * correlation; tau <= 20.0 * correlation; tau *= 1.1) {
    const auto m = static_cast<std::size_t>(std::lround(tau / kPeriod));
    const double sigma = allan_deviation(e.gyro, kPeriod, m);
    if (sigma > peak) {
      peak = sigma;
      peak_tau = static_cast<double>(m) * kPeriod;
    }
  }
  EXPECT_NEAR(peak, 5e-4, 0.1 * 5e-4);
  EXPECT_GT(peak_tau, 1.0 * correlation);
  EXPECT_LT(peak_tau, 4.0 * correlation);
  // The whole curve is the Gauss-Markov process's, s^2 (2x - 3 + 4 e^-x - e^-2x) / x^2 with
  // s = B / 0.6174: rising like a random walk below Tc, falling like white noise far above it.
  const double s = 0.02 / kGaussMarkovAllanPeak;
  for (const double x : {0.2, 1.0, 1.893, 5.0, 20.0}) {
    const double expected = s * std::sqrt((2 * x - 3 + 4 * std::exp(-x) - std::exp(-2 * x)) / (x * x));
    const auto m = static_cast<std::size_t>(std::lround(x * correlation / kPeriod));
    EXPECT_NEAR(allan_deviation(e.accel, kPeriod, m), expected, 0.12 * expected) << "tau = " << x << " Tc";
  }
  EXPECT_NEAR(allan_slope(e.accel, kPeriod, 20, 40), 0.5, 0.1);        // tau << Tc
  EXPECT_NEAR(allan_slope(e.accel, kPeriod, 8000, 16000), -0.5, 0.15);  // tau >> Tc
}

TEST(ImuErrorModel, DeterministicAndEachTermOnItsOwnStream) {
  ImuConfig config;
  config.accel_noise_density_mps2_per_sqrt_hz = 0.01;
  config.gyro_noise_density_radps_per_sqrt_hz = 1e-3;
  config.gyro_bias_instability_radps = 1e-4;
  const ErrorSequences a = stationary_errors(config, kPeriod, 1000, 21);
  const ErrorSequences b = stationary_errors(config, kPeriod, 1000, 21);
  const ErrorSequences other = stationary_errors(config, kPeriod, 1000, 22);
  EXPECT_EQ(a.accel, b.accel);
  EXPECT_EQ(a.gyro, b.gyro);
  EXPECT_NE(a.accel[0], other.accel[0]);
  // The gyroscope's errors do not move when the accelerometer gains a random walk.
  ImuConfig more = config;
  more.accel_random_walk_mps3_per_sqrt_hz = 1e-3;
  const ErrorSequences c = stationary_errors(more, kPeriod, 1000, 21);
  EXPECT_EQ(c.gyro, a.gyro);
  EXPECT_NE(c.accel, a.accel);
  // Nor the accelerometer's white noise when the gyroscope loses its bias instability.
  ImuConfig less = config;
  less.gyro_bias_instability_radps = 0.0;
  EXPECT_EQ(stationary_errors(less, kPeriod, 1000, 21).accel, a.accel);
}

TEST(ImuErrorModel, RefusesParametersOutOfRange) {
  ImuConfig bad;
  bad.gyro_noise_density_radps_per_sqrt_hz = -1.0;
  EXPECT_THROW(ImuErrorModel(bad, kPeriod, 0), std::invalid_argument);
  EXPECT_THROW(ImuErrorModel(ImuConfig{}, 0.0, 0), std::invalid_argument);
  ImuConfig no_time;
  no_time.bias_correlation_time_s = 0.0;
  EXPECT_THROW(ImuErrorModel(no_time, kPeriod, 0), std::invalid_argument);
}

}  // namespace
}  // namespace campo
