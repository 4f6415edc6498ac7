#pragma once
/// Scalar PID controller with anti-windup (000 §5.3.1: an accumulator for the
/// integral, clamped against windup, and reset()). Pure: no Bullet, no clock.
#include <limits>
#include <optional>

namespace campo {

/// Gains and limits of one PID loop. Units depend on the loop: the output is
/// in "out" units, the error in "err" units (e.g. err = m, out = m/s).
struct PidConfig {
  double kp = 1.0;  ///< proportional gain, out/err, >= 0
  double ki = 0.0;  ///< integral gain, out/(err s), >= 0
  double kd = 0.0;  ///< derivative gain, out/(err/s), >= 0
  /// Bound on the magnitude of the integral term itself (out units, > 0).
  double integral_limit = std::numeric_limits<double>::infinity();
  /// Bound on the magnitude of the output (out units, > 0).
  double output_limit = std::numeric_limits<double>::infinity();
};

/// u = kp e + I + D, clamped to +-output_limit.
///
/// Integral: I accumulates ki e dt (the term, not the raw error, so its clamp
/// is in output units) and stays within +-integral_limit. Anti-windup: while
/// the output saturates, I is not moved further in the saturating direction.
///
/// Derivative: on the measurement when its rate is given (D = -kd *
/// measurement_rate, which assumes a constant setpoint and so gives no kick
/// when the setpoint jumps); otherwise on the error by backward difference
/// (zero on the first update after construction or reset()).
class Pid {
 public:
  explicit Pid(const PidConfig& config = {});

  /// One update of `dt_s` > 0 seconds; returns the clamped output.
  double update(double error, double dt_s, std::optional<double> measurement_rate = std::nullopt);
  /// Forgets the integral and the previous error.
  void reset();

  double integral() const { return integral_; }
  const PidConfig& config() const { return config_; }

 private:
  PidConfig config_;
  double integral_ = 0.0;
  double previous_error_ = 0.0;
  bool has_previous_ = false;
};

}  // namespace campo
