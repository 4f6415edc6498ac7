#include "scene/sensor_fields.hpp"

namespace campo {

namespace {

// An IMU's own rate: 0 (the control rate), or within the range sensors' rates.
constexpr double kMinImuRateHz = 0.01;
constexpr double kMaxImuRateHz = 10000.0;

}  // namespace

// The error terms are the usual datasheet figures (IEEE Std 952's names), one per instrument; every
// one 0 by default, so an IMU without them is ideal. The bounds are far beyond any real part's (a
// consumer MEMS gyroscope's noise density is about 1e-4 rad/s/√Hz) while keeping the numbers finite.
const ConfigFields<ImuConfig>& imu_config_fields() {
  using C = ImuConfig;
  static const ConfigFields<C> fields =
      ConfigFields<C>()
          .custom("rate_hz", "Hz", "0, or [0.01, 10000]",
                  "samples per second, dividing the physics rate ([rates](#world)); 0 = `world.control_rate_hz`",
                  [](const JsonNode& n, C& c) {
                    const double rate = n.as_number();
                    if (!(rate == 0.0 || (rate >= kMinImuRateHz && rate <= kMaxImuRateHz))) {
                      n.fail("0 (world.control_rate_hz) or a number in [0.01, 10000]");
                    }
                    c.rate_hz = rate;
                  },
                  [](const C& c, nlohmann::json& j) { j["rate_hz"] = c.rate_hz; })
          .number("accel_noise_density_mps2_per_sqrt_hz", &C::accel_noise_density_mps2_per_sqrt_hz,
                  Range::closed(0.0, 10.0), "m/s²/√Hz",
                  "accelerometer white noise N (velocity random walk): N / √period per sample, Allan deviation N / √τ")
          .number("accel_bias_instability_mps2", &C::accel_bias_instability_mps2, Range::closed(0.0, 10.0), "m/s²",
                  "accelerometer bias instability B: the floor of its Allan deviation (a Gauss-Markov bias of "
                  "stddev B / 0.6174, see below)")
          .number("accel_random_walk_mps3_per_sqrt_hz", &C::accel_random_walk_mps3_per_sqrt_hz,
                  Range::closed(0.0, 10.0), "m/s³/√Hz",
                  "accelerometer bias random walk K: a step of K √period per sample, Allan deviation K √(τ/3)")
          .number("gyro_noise_density_radps_per_sqrt_hz", &C::gyro_noise_density_radps_per_sqrt_hz,
                  Range::closed(0.0, 1.0), "rad/s/√Hz", "gyroscope white noise N (angle random walk)")
          .number("gyro_bias_instability_radps", &C::gyro_bias_instability_radps, Range::closed(0.0, 1.0), "rad/s",
                  "gyroscope bias instability B (the floor of its Allan deviation)")
          .number("gyro_random_walk_radps2_per_sqrt_hz", &C::gyro_random_walk_radps2_per_sqrt_hz,
                  Range::closed(0.0, 1.0), "rad/s²/√Hz", "gyroscope bias random walk K (rate random walk)")
          .number("bias_correlation_time_s", &C::bias_correlation_time_s, {0.0, 1e6, true, false}, "s",
                  "correlation time Tc of both bias-instability processes; their Allan deviation peaks at 1.89 Tc")
          .seed("seed", &C::seed, "noise stream, combined with `world.seed`")
          .nested("mount", &C::mount, mount_fields(), "pose on the vehicle body");
  return fields;
}

}  // namespace campo
