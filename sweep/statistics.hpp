#pragma once
/// Statistics of a sweep's runs (docs/sweeps.md): mean, sample standard
/// deviation and a Student t confidence interval of a metric's values; a rate
/// with its Wilson score interval; quartiles and whiskers for box plots.
#include <optional>
#include <vector>

namespace campo {

/// Quantile of Student's t distribution with `dof` >= 1 degrees of freedom:
/// the t with P(T <= t) = p, for p in (0, 1). Accurate to ~1e-10 (the
/// regularized incomplete beta function, inverted by bisection).
double student_t_quantile(double p, int dof);

/// Two-sided quantile of the standard normal distribution for 95 % intervals.
inline constexpr double kNormal975 = 1.959963984540054;

struct Interval {
  double low = 0.0;
  double high = 0.0;
};

/// A metric over some runs.
struct Summary {
  int n = 0;                     ///< values summarized
  double mean = 0.0;             ///< for a rate: the fraction of successes
  double sd = 0.0;               ///< sample standard deviation (n - 1); 0 for one value
  std::optional<Interval> ci95;  ///< 95 % interval of the mean; empty for n < 2 (numbers) or n = 0 (rates)
};

/// Mean, sd and the t interval mean ± t(0.975, n - 1) sd / sqrt(n) of `values` (not empty).
Summary summarize_values(const std::vector<double>& values);

/// `successes` of `trials` (> 0) as a rate: mean = fraction, sd of the 0/1
/// values, ci95 the Wilson score interval (sensible at 0 % and 100 %).
Summary summarize_rate(int successes, int trials);

/// Wilson score interval of a proportion at normal quantile `z`.
Interval wilson_interval(int successes, int trials, double z = kNormal975);

/// A box plot's statistics: quartiles by linear interpolation between order
/// statistics (R type 7), whiskers at the furthest values within 1.5 IQR of
/// the box, the values beyond them.
struct BoxStats {
  double q1 = 0.0, median = 0.0, q3 = 0.0;
  double whisker_low = 0.0, whisker_high = 0.0;
  std::vector<double> outliers;  ///< ascending
};
/// Box statistics of `values` (not empty).
BoxStats box_stats(std::vector<double> values);

}  // namespace campo
