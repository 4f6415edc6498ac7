#include "sensors/lidar.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace campo {

namespace {
constexpr double kDegToRad = std::numbers::pi / 180.0;

void validate(const RangeSensorConfig& c) {
  if (c.beam_count() < 1 || (c.beams.empty() && (c.cols < 1 || c.rows < 1))) {
    throw std::invalid_argument("Lidar: the config has no beams");
  }
  if (!(c.min_range_m >= 0.0 && c.min_range_m < c.max_range_m)) {
    throw std::invalid_argument("Lidar: need 0 <= min_range_m < max_range_m");
  }
  if (!(c.noise_stddev_m >= 0.0 && c.quantization_m >= 0.0)) {
    throw std::invalid_argument("Lidar: noise_stddev_m and quantization_m must be >= 0");
  }
  if (!(c.dropout_probability >= 0.0 && c.dropout_probability <= 1.0)) {
    throw std::invalid_argument("Lidar: dropout_probability must be in [0, 1]");
  }
}
}  // namespace

Eigen::Vector3f beam_direction(const Beam& beam) {
  const double az = beam.azimuth_deg * kDegToRad;
  const double el = beam.elevation_deg * kDegToRad;
  return Eigen::Vector3d(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el))
      .cast<float>();
}

std::vector<Beam> lidar_beams(const RangeSensorConfig& config) {
  if (!config.beams.empty()) return config.beams;
  std::vector<Beam> beams;
  beams.reserve(static_cast<std::size_t>(config.cols) * config.rows);
  const double step_h = config.fov_h_deg / config.cols;
  const double step_v = config.fov_v_deg / config.rows;
  for (int row = 0; row < config.rows; ++row) {
    for (int col = 0; col < config.cols; ++col) {
      beams.push_back({0.5 * config.fov_h_deg - (col + 0.5) * step_h,
                       0.5 * config.fov_v_deg - (row + 0.5) * step_v});
    }
  }
  return beams;
}

namespace {
std::vector<Eigen::Vector3f> beam_directions(const RangeSensorConfig& config) {
  validate(config);
  std::vector<Eigen::Vector3f> directions;
  for (const Beam& beam : lidar_beams(config)) directions.push_back(beam_direction(beam));
  return directions;
}
}  // namespace

Lidar::Lidar(const RangeSensorConfig& config, std::uint64_t world_seed)
    : config_(config),
      rng_(Rng::derive_seed(world_seed, config.seed)),
      directions_sensor_(beam_directions(config)),
      fan_(directions_sensor_),
      hits_(directions_sensor_.size()) {}

void Lidar::scan(const RayCaster& caster, const Eigen::Isometry3d& sensor_pose, double time_s,
                 RangeScan& out) {
  const std::size_t n = directions_sensor_.size();
  const Eigen::Matrix3f rotation = sensor_pose.linear().cast<float>();
  const auto max_range = static_cast<float>(config_.max_range_m);
  caster.cast(sensor_pose, fan_, static_cast<float>(config_.min_range_m), max_range, hits_);

  begin_scan(out, config_, time_s, sensor_pose);
  const bool dropout = config_.dropout_probability > 0.0;
  const bool noise = config_.noise_stddev_m > 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    // Draws are made for every beam, hit or not, so one beam's noise does not
    // depend on what the other beams see.
    const bool dropped = dropout && rng_.bernoulli(config_.dropout_probability);
    const double error = noise ? rng_.normal(0.0, config_.noise_stddev_m) : 0.0;
    if (hits_[i].shape == RayHit::kNoShape || dropped) {
      out.ranges_m[i] = max_range;
      out.hits[i] = 0;
      continue;
    }
    // A noisy range may fall below min_range_m; the depth map then reads 0.
    const float r = reported_range(hits_[i].distance_m + error, config_);
    out.ranges_m[i] = r;
    out.hits[i] = 1;
    const Eigen::Vector3f world_direction = rotation * directions_sensor_[i];
    out.points.push_back((sensor_pose.translation() + r * world_direction.cast<double>()).cast<float>());
  }
}

void begin_scan(RangeScan& out, const RangeSensorConfig& config, double time_s, const Eigen::Isometry3d& sensor_pose) {
  const auto beams = static_cast<std::size_t>(config.beam_count());
  out.rows = config.scan_rows();
  out.cols = config.scan_cols();
  out.time_s = time_s;
  out.sensor_pose = sensor_pose;
  out.ranges_m.resize(beams);
  out.hits.resize(beams);
  out.points.clear();
  out.points.reserve(beams);
}

float reported_range(double range_m, const RangeSensorConfig& config) {
  const double q = config.quantization_m;
  if (q > 0.0) range_m = std::round(range_m / q) * q;
  return static_cast<float>(std::clamp(range_m, 0.0, config.max_range_m));
}

cv::Mat depth_map(const RangeScan& scan, const RangeSensorConfig& config) {
  cv::Mat depth(scan.rows, scan.cols, CV_32F);
  const double min_range = config.min_range_m;
  const double max_range = config.max_range_m;
  for (int row = 0; row < scan.rows; ++row) {
    auto* pixel = depth.ptr<float>(row);
    for (int col = 0; col < scan.cols; ++col) {
      const std::size_t i = static_cast<std::size_t>(row) * scan.cols + col;
      const double range = scan.ranges_m[i];
      if (!scan.hits[i]) {
        pixel[col] = 1.0f;
      } else if (range < min_range) {
        pixel[col] = 0.0f;
      } else {
        pixel[col] = static_cast<float>(std::min(range / max_range, 1.0));
      }
    }
  }
  return depth;
}

}  // namespace campo
