#include "sensors/imu.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace campo {

ImuSample ideal_imu_sample(const CarrierMotion& before, const CarrierMotion& now, const Pose& mount, double period_s,
                           const Eigen::Vector3d& gravity_mps2) {
  const Eigen::Isometry3d mount_pose = to_isometry(mount);
  // The mount point's world velocity: the body's plus omega x lever arm.
  const auto mount_velocity = [&](const CarrierMotion& s) -> Eigen::Vector3d {
    const Eigen::Vector3d arm = s.orientation * mount_pose.translation();
    return s.linear_velocity_mps + s.angular_velocity_radps.cross(arm);
  };
  const Eigen::Vector3d acceleration =
      period_s > 0.0 ? Eigen::Vector3d((mount_velocity(now) - mount_velocity(before)) / period_s)
                     : Eigen::Vector3d::Zero();
  // The mean acceleration belongs to the whole period: in the frame of its middle. Turned by the frame
  // at its end instead, a turning body's centripetal reading would lean back by half the period's turn.
  const Eigen::Quaterniond middle = before.orientation.slerp(0.5, now.orientation);
  const Eigen::Matrix3d mount_rotation = mount_pose.linear();
  const Eigen::Matrix3d world_to_imu_middle = (middle.toRotationMatrix() * mount_rotation).transpose();
  const Eigen::Matrix3d world_to_imu_now = (now.orientation.toRotationMatrix() * mount_rotation).transpose();
  return {world_to_imu_middle * (acceleration - gravity_mps2), world_to_imu_now * now.angular_velocity_radps};
}

namespace {

// Stream labels of the six error terms (Rng::derive_seed).
enum StreamLabel : std::uint64_t {
  accel_streams = 0x1a'0000,
  gyro_streams = 0x1b'0000,
  white = 1,
  markov = 2,
  walk = 3,
};

void check_parameter(double value, const char* name) {
  if (!(value >= 0.0 && std::isfinite(value))) {
    throw std::invalid_argument(std::string("ImuErrorModel: ") + name + " must be finite and >= 0, got " +
                                std::to_string(value));
  }
}

}  // namespace

ImuErrorModel::Instrument::Instrument(double noise_density, double bias_instability, double random_walk,
                                      double correlation_time_s, double period_s, std::uint64_t seed)
    : white_stddev_(noise_density / std::sqrt(period_s)),
      markov_decay_(std::exp(-period_s / correlation_time_s)),
      markov_step_stddev_(0.0),
      walk_step_stddev_(random_walk * std::sqrt(period_s)),
      white_rng_(Rng::derive_seed(seed, white)),
      markov_rng_(Rng::derive_seed(seed, markov)),
      walk_rng_(Rng::derive_seed(seed, walk)) {
  check_parameter(noise_density, "the noise density");
  check_parameter(bias_instability, "the bias instability");
  check_parameter(random_walk, "the bias random walk");
  if (!(period_s > 0.0 && std::isfinite(period_s))) throw std::invalid_argument("ImuErrorModel: period_s must be > 0");
  if (!(correlation_time_s > 0.0)) throw std::invalid_argument("ImuErrorModel: the correlation time must be > 0");
  if (bias_instability > 0.0) {
    const double stationary_stddev = bias_instability / kGaussMarkovAllanPeak;
    // 1 - decay^2 without the cancellation of a decay near 1 (periods far shorter than Tc).
    markov_step_stddev_ = stationary_stddev * std::sqrt(-std::expm1(-2.0 * period_s / correlation_time_s));
    for (int axis = 0; axis < 3; ++axis) markov_bias_[axis] = markov_rng_.normal(0.0, stationary_stddev);
  }
}

Eigen::Vector3d ImuErrorModel::Instrument::next_error() {
  Eigen::Vector3d error = markov_bias_ + walk_bias_;
  // Zero terms draw nothing, so a zero configuration is the ideal sample exactly.
  if (white_stddev_ > 0.0) {
    for (int axis = 0; axis < 3; ++axis) error[axis] += white_rng_.normal(0.0, white_stddev_);
  }
  if (markov_step_stddev_ > 0.0) {
    for (int axis = 0; axis < 3; ++axis) {
      markov_bias_[axis] = markov_decay_ * markov_bias_[axis] + markov_rng_.normal(0.0, markov_step_stddev_);
    }
  }
  if (walk_step_stddev_ > 0.0) {
    for (int axis = 0; axis < 3; ++axis) walk_bias_[axis] += walk_rng_.normal(0.0, walk_step_stddev_);
  }
  return error;
}

ImuErrorModel::ImuErrorModel(const ImuConfig& config, double period_s, std::uint64_t seed)
    : accel_(config.accel_noise_density_mps2_per_sqrt_hz, config.accel_bias_instability_mps2,
             config.accel_random_walk_mps3_per_sqrt_hz, config.bias_correlation_time_s, period_s,
             Rng::derive_seed(seed, accel_streams)),
      gyro_(config.gyro_noise_density_radps_per_sqrt_hz, config.gyro_bias_instability_radps,
            config.gyro_random_walk_radps2_per_sqrt_hz, config.bias_correlation_time_s, period_s,
            Rng::derive_seed(seed, gyro_streams)) {}

ImuSample ImuErrorModel::corrupt(const ImuSample& ideal) {
  ImuSample measured = ideal;
  measured.specific_force_mps2 += accel_.next_error();
  measured.angular_rate_radps += gyro_.next_error();
  return measured;
}

}  // namespace campo
