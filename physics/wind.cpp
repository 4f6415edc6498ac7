#include "physics/wind.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace campo {

namespace {

// Label of the turbulence stream among a world's random streams ("wind").
constexpr std::uint64_t kTurbulenceStream = 0x77696e64ULL;

// 1 - e^(-x) (1 + x + ... + x^n / n!), the part of e^x's series beyond its
// n-th term weighted by e^(-x): the integrals of s^k e^(-2as) over one step
// are made of these. For small x (a step much shorter than the time
// constant, the usual case) the direct form cancels catastrophically, so it
// is summed from its tail e^(-x) (x^(n+1)/(n+1)! + ...), all terms positive.
double exp_tail(int n, double x) {
  if (x >= 1.0) {
    double term = 1.0;
    double partial = 1.0;
    for (int k = 1; k <= n; ++k) {
      term *= x / k;
      partial += term;
    }
    return 1.0 - std::exp(-x) * partial;
  }
  double term = 1.0;
  for (int k = 1; k <= n + 1; ++k) term *= x / k;
  double sum = 0.0;
  for (int k = n + 2; term > 1e-18 * sum; ++k) {
    sum += term;
    term *= x / k;
  }
  return std::exp(-x) * sum;
}

}  // namespace

double one_minus_cos_shape(double t_s, double start_s, double duration_s) {
  const double phase = (t_s - start_s) / duration_s;
  if (!(phase >= 0.0 && phase <= 1.0)) return 0.0;
  return 0.5 * (1.0 - std::cos(2.0 * std::numbers::pi * phase));
}

Eigen::Vector3d one_minus_cos_gust_mps(const WindConfig& wind, double t_s) {
  if (wind.gust != GustModel::one_minus_cos) return Eigen::Vector3d::Zero();
  return wind.gust_amplitude_mps * one_minus_cos_shape(t_s, wind.gust_start_s, wind.gust_duration_s);
}

double turbulence_reference_speed_mps(const WindConfig& wind) {
  return std::max(wind.steady_velocity_mps().norm(), kMinTurbulenceAdvectionSpeed_mps);
}

std::array<Eigen::Vector3d, 3> turbulence_axes(const WindConfig& wind) {
  const double a = wind.direction_deg * (std::numbers::pi / 180.0);
  const double c = std::cos(a);
  const double s = std::sin(a);
  return {Eigen::Vector3d(c, s, 0.0), Eigen::Vector3d(-s, c, 0.0), Eigen::Vector3d::UnitZ()};
}

std::uint64_t turbulence_seed(std::uint64_t world_seed, std::uint64_t wind_seed) {
  return Rng::derive_seed(Rng::derive_seed(world_seed, kTurbulenceStream), wind_seed);
}

DrydenTurbulence::DrydenTurbulence(double intensity_mps, double length_m, double reference_speed_mps,
                                   double step_s, std::uint64_t seed)
    : rng_(seed) {
  if (!(intensity_mps >= 0.0 && length_m > 0.0 && reference_speed_mps > 0.0 && step_s > 0.0)) {
    throw std::invalid_argument("DrydenTurbulence: expected intensity >= 0 and positive length, speed and step");
  }
  const double sigma = intensity_mps;
  const double a = reference_speed_mps / length_m;
  rate_ = a;
  const double x = 2.0 * a * step_s;  // the decay of a variance over one step

  // Longitudinal, a first-order Gauss-Markov process: u_{k+1} = e^(-a h) u_k
  // + sigma sqrt(1 - e^(-2 a h)) n keeps the variance sigma^2 exactly.
  u_decay_ = std::exp(-a * step_s);
  u_noise_ = sigma * std::sqrt(-std::expm1(-x));

  // Lateral and vertical: x1' = -a x1 + n, x2' = -a x2 + x1 (A = [[-a, 0], [1, -a]], B = [1, 0]).
  // Output y = sigma sqrt(T) (sqrt(3) a x1 + a^2 (1 - sqrt(3)) x2): the transfer function
  // sigma sqrt(T) (1 + sqrt(3) T s) / (1 + T s)^2 in the states, whose stationary
  // covariance P = [[1/(2a), 1/(4a^2)], [1/(4a^2), 1/(4a^3)]] makes y's variance sigma^2.
  const double e = std::exp(-a * step_s);
  transition_ << e, 0.0, step_s * e, e;
  // The noise a step accumulates: Q = integral over [0, h] of e^(As) B B^T e^(A^T s) ds, with
  // e^(As) B = e^(-as) (1, s): entries integral of e^(-2as) (1, s, s^2).
  const double q11 = exp_tail(0, x) / (2.0 * a);
  const double q12 = exp_tail(1, x) / (4.0 * a * a);
  const double q22 = exp_tail(2, x) / (4.0 * a * a * a);
  const double l11 = std::sqrt(q11);
  const double l21 = q12 / l11;
  noise_factor_ << l11, 0.0, l21, std::sqrt(std::max(0.0, q22 - l21 * l21));
  const double sqrt3 = std::numbers::sqrt3;
  output_ << sigma * std::sqrt(1.0 / a) * sqrt3 * a, sigma * std::sqrt(1.0 / a) * a * a * (1.0 - sqrt3);

  // Start stationary: u ~ N(0, sigma^2), each second-order state ~ N(0, P) (P's Cholesky factor).
  u_ = sigma * rng_.normal(0.0, 1.0);
  Eigen::Matrix2d stationary_factor;
  const double p11 = std::sqrt(1.0 / (2.0 * a));
  const double p21 = (1.0 / (4.0 * a * a)) / p11;
  stationary_factor << p11, 0.0, p21, std::sqrt(1.0 / (8.0 * a * a * a));
  for (State2* s : {&lateral_, &vertical_}) {
    const double n1 = rng_.normal(0.0, 1.0);
    const double n2 = rng_.normal(0.0, 1.0);
    *s = stationary_factor * State2(n1, n2);
  }
}

void DrydenTurbulence::advance() {
  u_ = u_decay_ * u_ + u_noise_ * rng_.normal(0.0, 1.0);
  for (State2* s : {&lateral_, &vertical_}) {
    const double n1 = rng_.normal(0.0, 1.0);
    const double n2 = rng_.normal(0.0, 1.0);
    *s = transition_ * *s + noise_factor_ * State2(n1, n2);
  }
}

Eigen::Vector3d DrydenTurbulence::velocity_mps() const {
  return {u_, output_.dot(lateral_), output_.dot(vertical_)};
}

WindField::WindField(const WindConfig& wind, std::uint64_t world_seed, double step_s)
    : config_(wind),
      steady_mps_(wind.steady_velocity_mps()),
      axes_(turbulence_axes(wind)),
      turbulent_(wind.gust == GustModel::dryden && wind.turbulence_intensity_mps > 0.0),
      turbulence_(wind.turbulence_intensity_mps, wind.turbulence_length_m, turbulence_reference_speed_mps(wind),
                  step_s, turbulence_seed(world_seed, wind.seed)) {}

void WindField::advance() {
  if (turbulent_) turbulence_.advance();
}

Eigen::Vector3d WindField::velocity_mps(double t_s) const {
  switch (config_.gust) {
    case GustModel::none:
      return steady_mps_;
    case GustModel::one_minus_cos:
      return steady_mps_ + one_minus_cos_gust_mps(config_, t_s);
    case GustModel::dryden: {
      if (!turbulent_) return steady_mps_;
      const Eigen::Vector3d uvw = turbulence_.velocity_mps();
      return steady_mps_ + uvw.x() * axes_[0] + uvw.y() * axes_[1] + uvw.z() * axes_[2];
    }
  }
  return steady_mps_;
}

}  // namespace campo
