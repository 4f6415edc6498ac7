#include "vehicles/pid.hpp"

#include <algorithm>
#include <cassert>

namespace campo {

Pid::Pid(const PidConfig& config) : config_(config) {
  assert(config.kp >= 0.0 && config.ki >= 0.0 && config.kd >= 0.0);
  assert(config.integral_limit > 0.0 && config.output_limit > 0.0);
}

double Pid::update(double error, double dt_s, std::optional<double> measurement_rate) {
  assert(dt_s > 0.0);
  double derivative = 0.0;
  if (measurement_rate) {
    derivative = -config_.kd * *measurement_rate;
  } else if (has_previous_) {
    derivative = config_.kd * (error - previous_error_) / dt_s;
  }
  previous_error_ = error;
  has_previous_ = true;

  const double proportional = config_.kp * error;
  const double candidate = std::clamp(integral_ + config_.ki * error * dt_s, -config_.integral_limit,
                                      config_.integral_limit);
  const double unclamped = proportional + candidate + derivative;
  // Conditional integration: keep the new integral unless the output is
  // saturated and the integral would push it further into saturation.
  const bool saturated = unclamped > config_.output_limit || unclamped < -config_.output_limit;
  const bool deeper = (candidate - integral_) * unclamped > 0.0;
  if (!(saturated && deeper)) integral_ = candidate;

  return std::clamp(proportional + integral_ + derivative, -config_.output_limit, config_.output_limit);
}

void Pid::reset() {
  integral_ = 0.0;
  previous_error_ = 0.0;
  has_previous_ = false;
}

}  // namespace campo
