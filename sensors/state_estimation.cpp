#include "campo/state_estimation.hpp"

#include <cmath>
#include <numbers>

namespace campo {

StateEstimator::StateEstimator(const StateNoiseConfig& config, std::uint64_t seed) : config_(config), rng_(seed) {}

const StateError& StateEstimator::error_at(double t_s) {
  if (!config_.enabled()) return error_;
  // Period index of t; the small slack keeps t = k / rate in period k despite rounding.
  const std::int64_t period =
      config_.rate_hz > 0.0 ? static_cast<std::int64_t>(std::floor(t_s * config_.rate_hz + 1e-9)) : period_ + 1;
  if (period != period_) {
    draw(period_ < 0 ? 0.0 : t_s - last_draw_s_);
    period_ = period;
    last_draw_s_ = t_s;
  }
  return error_;
}

void StateEstimator::draw(double dt_s) {
  // A random walk: independent steps of variance walk^2 dt.
  const double step = config_.bias_walk_m_per_sqrt_s * std::sqrt(dt_s);
  for (int i = 0; i < 3; ++i) bias_m_[i] += rng_.normal(0.0, step);
  // One draw per statement, altitude first: the order of a call's arguments is the compiler's
  // (GCC, which made the recorded runs, evaluated these right to left; clang goes left to right).
  const double altitude_error_m = rng_.normal(0.0, config_.altitude_stddev_m);
  const double y_error_m = rng_.normal(0.0, config_.position_stddev_m);
  const double x_error_m = rng_.normal(0.0, config_.position_stddev_m);
  error_.position_m = bias_m_ + Eigen::Vector3d(x_error_m, y_error_m, altitude_error_m);
  for (int i = 0; i < 3; ++i) error_.velocity_mps[i] = rng_.normal(0.0, config_.velocity_stddev_mps);
  error_.heading_rad = rng_.normal(0.0, config_.heading_stddev_deg * std::numbers::pi / 180.0);
}

}  // namespace campo
