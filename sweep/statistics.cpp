#include "sweep/statistics.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numeric>

namespace campo {

namespace {

// Continued fraction of the regularized incomplete beta function (modified Lentz).
double beta_fraction(double a, double b, double x) {
  constexpr double kTiny = 1e-300;
  double c = 1.0, d = 1.0 - (a + b) * x / (a + 1.0);
  d = 1.0 / (std::abs(d) < kTiny ? kTiny : d);
  double h = d;
  for (int m = 1; m <= 1000; ++m) {
    for (int odd = 0; odd < 2; ++odd) {
      const double numerator = odd == 0 ? m * (b - m) * x / ((a + 2 * m - 1) * (a + 2 * m))
                                        : -(a + m) * (a + b + m) * x / ((a + 2 * m) * (a + 2 * m + 1));
      d = 1.0 + numerator * d;
      d = 1.0 / (std::abs(d) < kTiny ? kTiny : d);
      c = 1.0 + numerator / c;
      if (std::abs(c) < kTiny) c = kTiny;
      h *= c * d;
      if (odd == 1 && std::abs(c * d - 1.0) < 1e-15) return h;
    }
  }
  return h;
}

// I_x(a, b).
double incomplete_beta(double a, double b, double x) {
  if (x <= 0.0) return 0.0;
  if (x >= 1.0) return 1.0;
  const double front =
      std::exp(std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) + a * std::log(x) + b * std::log1p(-x));
  // The fraction converges fast below the mean; use the symmetry above it.
  return x < (a + 1.0) / (a + b + 2.0) ? front * beta_fraction(a, b, x) / a
                                       : 1.0 - front * beta_fraction(b, a, 1.0 - x) / b;
}

// P(T <= t) for t >= 0.
double student_t_cdf(double t, int dof) {
  const double v = dof;
  return 1.0 - 0.5 * incomplete_beta(0.5 * v, 0.5, v / (v + t * t));
}

double quantile_sorted(const std::vector<double>& sorted, double p) {
  const double h = p * static_cast<double>(sorted.size() - 1);
  const auto below = static_cast<std::size_t>(std::floor(h));
  const std::size_t above = std::min(below + 1, sorted.size() - 1);
  return sorted[below] + (h - static_cast<double>(below)) * (sorted[above] - sorted[below]);
}

}  // namespace

double student_t_quantile(double p, int dof) {
  assert(p > 0.0 && p < 1.0 && dof >= 1);
  if (p < 0.5) return -student_t_quantile(1.0 - p, dof);
  if (p == 0.5) return 0.0;
  double lo = 0.0, hi = 1.0;
  while (student_t_cdf(hi, dof) < p) hi *= 2.0;
  // Bisection to the last bit: deterministic and plenty fast for a table.
  for (int i = 0; i < 200 && hi - lo > 1e-13 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (student_t_cdf(mid, dof) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

std::optional<Interval> mean_interval95(double mean, double sd, int n, Support support) {
  if (n < 2) return std::nullopt;
  const double se = sd / std::sqrt(static_cast<double>(n));
  const double t = student_t_quantile(0.975, n - 1);
  if (support == Support::non_negative) {
    assert(mean >= 0.0);
    // Values >= 0 with mean 0 are all 0: no spread to widen.
    if (mean <= 0.0 || se <= 0.0) return Interval{mean, mean};
    // The t interval of log(mean), with the delta method's standard error se / mean, taken back.
    const double factor = std::exp(t * se / mean);
    return Interval{mean / factor, mean * factor};
  }
  return Interval{mean - t * se, mean + t * se};
}

Summary summarize_values(const std::vector<double>& values, Support support) {
  assert(!values.empty());
  Summary s;
  s.n = static_cast<int>(values.size());
  s.mean = std::accumulate(values.begin(), values.end(), 0.0) / s.n;
  if (s.n < 2) return s;
  double squares = 0.0;
  for (double v : values) squares += (v - s.mean) * (v - s.mean);
  s.sd = std::sqrt(squares / (s.n - 1));
  const bool negative = std::any_of(values.begin(), values.end(), [](double v) { return v < 0.0; });
  s.ci95 = mean_interval95(s.mean, s.sd, s.n, negative ? Support::real : support);
  return s;
}

Summary summarize_rate(int successes, int trials) {
  assert(trials > 0 && successes >= 0 && successes <= trials);
  Summary s;
  s.n = trials;
  s.mean = static_cast<double>(successes) / trials;
  // Sample sd of the 0/1 values: sum of squares is n p (1 - p).
  if (trials > 1) s.sd = std::sqrt(trials * s.mean * (1.0 - s.mean) / (trials - 1));
  s.ci95 = wilson_interval(successes, trials);
  return s;
}

Interval wilson_interval(int successes, int trials, double z) {
  const double n = trials, p = successes / n, z2 = z * z;
  const double centre = (p + z2 / (2.0 * n)) / (1.0 + z2 / n);
  const double half = z / (1.0 + z2 / n) * std::sqrt(p * (1.0 - p) / n + z2 / (4.0 * n * n));
  // Exactly 0 and 1 at the ends, whatever the rounding.
  return {successes == 0 ? 0.0 : centre - half, successes == trials ? 1.0 : centre + half};
}

BoxStats box_stats(std::vector<double> values) {
  assert(!values.empty());
  std::sort(values.begin(), values.end());
  BoxStats b;
  b.q1 = quantile_sorted(values, 0.25);
  b.median = quantile_sorted(values, 0.5);
  b.q3 = quantile_sorted(values, 0.75);
  const double reach = 1.5 * (b.q3 - b.q1);
  b.whisker_low = b.q1;
  b.whisker_high = b.q3;
  for (double v : values) {
    if (v < b.q1 - reach || v > b.q3 + reach) {
      b.outliers.push_back(v);
    } else {
      b.whisker_low = std::min(b.whisker_low, v);
      b.whisker_high = std::max(b.whisker_high, v);
    }
  }
  return b;
}

void RunningStats::add(double value) {
  ++n_;
  if (value < 0.0) negative_ = true;
  if (value == 1.0) ++ones_;
  sum_ += value;
  const double delta = value - mean_;
  mean_ += delta / n_;
  m2_ += delta * (value - mean_);
}

Summary RunningStats::values(Support support) const {
  assert(n_ > 0);
  Summary s;
  s.n = n_;
  s.mean = sum_ / n_;
  if (n_ < 2) return s;
  s.sd = std::sqrt(std::max(m2_, 0.0) / (n_ - 1));
  s.ci95 = mean_interval95(s.mean, s.sd, n_, negative_ ? Support::real : support);
  return s;
}

Summary RunningStats::rate() const { return summarize_rate(ones_, n_); }

void QuantileSketch::add(double value) {
  min_ = n_ == 0 ? value : std::min(min_, value);
  max_ = n_ == 0 ? value : std::max(max_, value);
  ++n_;
  if (levels_.empty()) {
    levels_.emplace_back();
    odd_.push_back(false);
  }
  levels_[0].push_back(value);
  // Level 0 holds the values exactly up to kExactValues; one more and it is compacted.
  if (levels_[0].size() > kExactValues) compact(0);
}

// Sorts a full level and moves every other value (the even or the odd positions, in turn) one
// level up, where each stands for twice as many; an odd value out stays. The weights still sum to n.
void QuantileSketch::compact(std::size_t level) {
  if (level + 1 == levels_.size()) {  // before any reference into levels_
    levels_.emplace_back();
    odd_.push_back(false);
  }
  std::vector<double>& values = levels_[level];
  std::sort(values.begin(), values.end());
  const std::size_t pairs = values.size() / 2;
  const std::size_t offset = odd_[level] ? 1 : 0;
  odd_[level] = !odd_[level];
  std::vector<double>& up = levels_[level + 1];
  for (std::size_t i = 0; i < pairs; ++i) up.push_back(values[2 * i + offset]);
  const bool held = values.size() % 2 == 1;
  const double last = values.back();
  values.clear();
  if (held) values.push_back(last);
  if (up.size() >= kExactValues) compact(level + 1);
}

std::vector<QuantileSketch::Weighted> QuantileSketch::items() const {
  std::vector<Weighted> out;
  for (std::size_t level = 0; level < levels_.size(); ++level) {
    for (double v : levels_[level]) out.push_back({v, std::ldexp(1.0, static_cast<int>(level))});
  }
  std::sort(out.begin(), out.end(), [](const Weighted& a, const Weighted& b) { return a.value < b.value; });
  return out;
}

namespace {

// R type 7 quantile of weighted values (ascending, weights summing to n): the values as if each
// were repeated `weight` times.
double weighted_quantile(const std::vector<QuantileSketch::Weighted>& items, double n, double p) {
  const double h = p * (n - 1.0);
  const auto at_rank = [&](double rank) {
    double below = 0.0;
    for (const auto& item : items) {
      below += item.weight;
      if (rank < below) return item.value;
    }
    return items.back().value;
  };
  const double low = std::floor(h);
  const double a = at_rank(low), b = at_rank(std::min(low + 1.0, n - 1.0));
  return a + (h - low) * (b - a);
}

}  // namespace

BoxStats QuantileSketch::box() const {
  assert(n_ > 0);
  if (n_ <= kExactValues) return box_stats(levels_[0]);
  const std::vector<Weighted> sorted = items();
  const double n = static_cast<double>(n_);
  BoxStats b;
  b.q1 = weighted_quantile(sorted, n, 0.25);
  b.median = weighted_quantile(sorted, n, 0.5);
  b.q3 = weighted_quantile(sorted, n, 0.75);
  const double reach = 1.5 * (b.q3 - b.q1);
  b.whisker_low = b.q1;
  b.whisker_high = b.q3;
  // The exact extremes, then the values the sketch keeps.
  std::vector<double> values{min_};
  for (const Weighted& item : sorted) values.push_back(item.value);
  values.push_back(max_);
  for (std::size_t i = 0; i < values.size(); ++i) {
    const double v = values[i];
    if (v < b.q1 - reach || v > b.q3 + reach) {
      if (b.outliers.empty() || b.outliers.back() != v) b.outliers.push_back(v);
    } else {
      b.whisker_low = std::min(b.whisker_low, v);
      b.whisker_high = std::max(b.whisker_high, v);
    }
  }
  return b;
}

double QuantileSketch::median() const {
  assert(n_ > 0);
  if (n_ <= kExactValues) return box_stats(levels_[0]).median;
  return weighted_quantile(items(), static_cast<double>(n_), 0.5);
}

}  // namespace campo
