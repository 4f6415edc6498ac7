#pragma once
/// The velocity of the air (WorldConfig::wind): a steady vector, plus a 1-cos
/// discrete gust or Dryden turbulence. Pure functions and a small seeded
/// filter; World owns one WindField and advances it once per physics step.
///
/// The field is uniform in space: every vehicle sees the same air at a given
/// time (the position argument of World::wind_mps is for a spatial field
/// later). Turbulence is therefore generated in the time domain, as the
/// frozen field of Taylor's hypothesis advected past a point at rest by the
/// mean wind: the Dryden spectra are evaluated with the reference speed
/// turbulence_reference_speed_mps(), not with each vehicle's airspeed.
#include <array>
#include <cstdint>

#include <Eigen/Core>

#include "campo/random.hpp"
#include "campo/scene.hpp"

namespace campo {

/// The 1-cos gust's shape: (1 - cos(2 pi (t - start) / duration)) / 2 for t
/// in [start, start + duration], 0 outside; rises from 0 to 1 at mid-gust and
/// back, with zero slope at both ends. Its integral over the gust is duration / 2.
double one_minus_cos_shape(double t_s, double start_s, double duration_s);

/// The 1-cos gust's velocity at `t_s`: gust_amplitude_mps times the shape,
/// world frame (zero unless wind.gust is one_minus_cos).
Eigen::Vector3d one_minus_cos_gust_mps(const WindConfig& wind, double t_s);

/// Below this mean wind speed the turbulence is advected at this speed: a
/// frozen field needs some speed to pass the vehicle, and Dryden's time
/// constants L / V would grow without bound in still air.
inline constexpr double kMinTurbulenceAdvectionSpeed_mps = 1.0;

/// The speed V at which the Dryden filters see the frozen turbulence go by:
/// the steady wind's magnitude, at least kMinTurbulenceAdvectionSpeed_mps.
double turbulence_reference_speed_mps(const WindConfig& wind);

/// Unit vectors of the turbulence axes, world frame: longitudinal (u, along
/// the steady wind's horizontal direction, direction_deg), lateral (v, 90
/// degrees to its left) and vertical (w, +z).
std::array<Eigen::Vector3d, 3> turbulence_axes(const WindConfig& wind);

/// Dryden turbulence (MIL-F-8785C forms, its convention of one length scale L
/// for the three components, each of standard deviation sigma), sampled
/// every `step_s` at reference speed V; with T = L / V:
///   longitudinal       H_u(s) = sigma sqrt(2T) / (1 + T s)
///   lateral, vertical  H_v(s) = sigma sqrt(T) (1 + sqrt(3) T s) / (1 + T s)^2
/// driven by white noise of unit intensity (E[n(t) n(t')] = delta(t - t');
/// the standard's sqrt(L / (pi V)) factors carry the 1/pi of its one-sided
/// spectra in rad/s instead), so each component's variance is sigma^2 and
/// its autocorrelation sigma^2 exp(-tau/T) (u) or sigma^2 (1 - tau/(2T))
/// exp(-tau/T) (v, w). Discretised exactly: the state moves by e^(A step)
/// and receives Gaussian noise with the covariance the continuous white noise
/// accumulates over a step, so the samples have the continuous process's
/// statistics at any step (no step-size error, no burn-in: the state starts
/// drawn from the stationary distribution).
class DrydenTurbulence {
 public:
  /// sigma >= 0, length_m > 0, reference_speed_mps > 0, step_s > 0.
  DrydenTurbulence(double intensity_mps, double length_m, double reference_speed_mps, double step_s,
                   std::uint64_t seed);

  /// Moves the filters on by one step.
  void advance();
  /// The current (u, v, w) velocity, turbulence axes (turbulence_axes()), m/s.
  Eigen::Vector3d velocity_mps() const;

  /// The time constant T = L / V, s.
  double time_constant_s() const { return 1.0 / rate_; }

 private:
  // A second-order lateral/vertical filter's state: X1 = W / (s + a), X2 = W / (s + a)^2.
  using State2 = Eigen::Vector2d;

  Rng rng_;
  double rate_ = 0.0;  ///< a = 1 / T = V / L, 1/s
  // Longitudinal: u' = a u + b n.
  double u_decay_ = 0.0;
  double u_noise_ = 0.0;
  double u_ = 0.0;
  // Lateral and vertical: x' = Phi x + L n, output c . x.
  Eigen::Matrix2d transition_ = Eigen::Matrix2d::Zero();
  Eigen::Matrix2d noise_factor_ = Eigen::Matrix2d::Zero();  ///< lower Cholesky factor of the step's noise covariance
  Eigen::RowVector2d output_ = Eigen::RowVector2d::Zero();
  State2 lateral_ = State2::Zero();
  State2 vertical_ = State2::Zero();
};

/// The wind of a world: steady + gust + turbulence, advanced once per physics step.
class WindField {
 public:
  /// The turbulence stream derives from `world_seed` and wind.seed; `step_s` is the physics step.
  WindField(const WindConfig& wind, std::uint64_t world_seed, double step_s);

  /// After a physics step: the turbulence moves on by one step.
  void advance();
  /// The air's velocity at time `t_s` (the world's time now), world frame, m/s.
  Eigen::Vector3d velocity_mps(double t_s) const;

 private:
  WindConfig config_;
  Eigen::Vector3d steady_mps_;
  std::array<Eigen::Vector3d, 3> axes_;
  bool turbulent_ = false;
  DrydenTurbulence turbulence_;
};

/// The seed of a world's turbulence stream: world seed and wind.seed under a
/// label of its own, so a LIDAR with the same seed draws another stream.
std::uint64_t turbulence_seed(std::uint64_t world_seed, std::uint64_t wind_seed);

}  // namespace campo
