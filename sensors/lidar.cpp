#include "sensors/lidar.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numbers>
#include <stdexcept>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include "core/angles.hpp"

namespace campo {

namespace {

void validate_lidar(const RangeSensorConfig& c) {
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
  validate_lidar(config);
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

namespace {

// depth_map's value of one beam: 1 without a return, 0 nearer than the
// minimum range, else the range over the maximum, at most 1.
float normalised_depth(float range_m, std::uint8_t hit, double min_range_m, double max_range_m) {
  const double range = range_m;
  if (!hit) return 1.0f;
  if (range < min_range_m) return 0.0f;
  return static_cast<float>(std::min(range / max_range_m, 1.0));
}

#if defined(__x86_64__)
// normalised_depth four beams at a time, the same operations in the same
// order (a quotient in double, its minimum with 1 as std::min takes it, one
// rounding to float), so the same floats; returns the beams it did.
__attribute__((target("avx2"))) std::size_t normalised_depths_avx2(const float* ranges, const std::uint8_t* hits,
                                                                  float* out, std::size_t n, double min_range_m,
                                                                  double max_range_m) {
  const __m256d min_range = _mm256_set1_pd(min_range_m);
  const __m256d max_range = _mm256_set1_pd(max_range_m);
  const __m256d one = _mm256_set1_pd(1.0);
  const __m128 no_return = _mm_set1_ps(1.0f);
  const __m256i even_lanes = _mm256_setr_epi32(0, 2, 4, 6, 0, 0, 0, 0);
  std::size_t i = 0;
  for (; i + 4 <= n; i += 4) {
    const __m256d range = _mm256_cvtps_pd(_mm_loadu_ps(ranges + i));
    // std::min(q, 1.0) is (1.0 < q ? 1.0 : q): min_pd(one, q) exactly, a NaN quotient included.
    const __m128 quotient = _mm256_cvtpd_ps(_mm256_min_pd(one, _mm256_div_pd(range, max_range)));
    // range < min_range, its four 64-bit masks narrowed to 32-bit lanes: 0 there.
    const __m256d below = _mm256_cmp_pd(range, min_range, _CMP_LT_OQ);
    const __m128 below_lanes = _mm256_castps256_ps128(_mm256_permutevar8x32_ps(_mm256_castpd_ps(below), even_lanes));
    const __m128 hit_value = _mm_andnot_ps(below_lanes, quotient);
    std::int32_t hit_bytes;
    std::memcpy(&hit_bytes, hits + i, sizeof hit_bytes);
    const __m128i no_hit = _mm_cmpeq_epi32(_mm_cvtepu8_epi32(_mm_cvtsi32_si128(hit_bytes)), _mm_setzero_si128());
    _mm_storeu_ps(out + i, _mm_blendv_ps(hit_value, no_return, _mm_castsi128_ps(no_hit)));
  }
  return i;
}
#endif

}  // namespace

cv::Mat depth_map(const RangeScan& scan, const RangeSensorConfig& config) {
  cv::Mat depth(scan.rows, scan.cols, CV_32F);
  const std::size_t beams = static_cast<std::size_t>(scan.rows) * static_cast<std::size_t>(scan.cols);
  CV_Assert(depth.isContinuous() && scan.ranges_m.size() >= beams && scan.hits.size() >= beams);
  float* out = depth.ptr<float>();
  std::size_t i = 0;
#if defined(__x86_64__)
  static const bool avx2 = __builtin_cpu_supports("avx2");
  if (avx2) {
    i = normalised_depths_avx2(scan.ranges_m.data(), scan.hits.data(), out, beams, config.min_range_m,
                               config.max_range_m);
  }
#endif
  for (; i < beams; ++i) out[i] = normalised_depth(scan.ranges_m[i], scan.hits[i], config.min_range_m, config.max_range_m);
  return depth;
}

}  // namespace campo
