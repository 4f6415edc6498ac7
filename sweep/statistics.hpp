#pragma once
/// Statistics of a sweep's runs (docs/sweeps.md): mean, sample standard
/// deviation and a Student t confidence interval of a metric's values; a rate
/// with its Wilson score interval; quartiles and whiskers for box plots.
#include <cstddef>
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

/// What values a metric can take, which decides its interval's method.
enum class Support {
  real,          ///< any sign: the Student t interval
  non_negative,  ///< >= 0 by definition (lengths, times, counts, ratios): the log-transformed t interval
};

/// The 95 % confidence interval of the mean of `n` >= 2 values with this
/// mean and sample sd; empty for n < 2. Support::real: the Student t
/// interval mean ± t sd / sqrt(n), t = t(0.975, n - 1). Support::non_negative
/// (mean >= 0): the same interval computed for log(mean), whose standard
/// error is by the delta method (sd / sqrt(n)) / mean, and taken back:
/// [mean / f, mean * f] with f = exp(t sd / (sqrt(n) mean)). It is as wide as
/// the t interval in relative terms for small spreads, never below 0, and
/// holds the mean; a mean of 0 (all values 0) gives [0, 0].
std::optional<Interval> mean_interval95(double mean, double sd, int n, Support support);

/// Mean, sd and mean_interval95() of `values` (not empty). Support::non_negative
/// applies when every value is >= 0; a negative value means the metric is
/// signed after all, and the t interval is used.
Summary summarize_values(const std::vector<double>& values, Support support = Support::real);

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

/// Mean and spread of values added one at a time, in constant memory: the
/// mean is their sum in order over n (as summarize_values sums), the sd
/// Welford's (equal to the two-pass sd up to rounding, exactly 0 for equal
/// values). What tables and plots keep per cell instead of the values.
class RunningStats {
 public:
  void add(double value);
  int count() const { return n_; }
  /// summarize_values() of the values added (count() > 0).
  Summary values(Support support = Support::real) const;
  /// summarize_rate() with the values equal to 1 as successes (count() > 0).
  Summary rate() const;

 private:
  int n_ = 0;
  int ones_ = 0;
  bool negative_ = false;  ///< some value < 0
  double sum_ = 0.0;   ///< in order of addition
  double mean_ = 0.0;  ///< Welford's running mean
  double m2_ = 0.0;    ///< sum of squared deviations from it
};

/// Box statistics of values added one at a time, in bounded memory: exact
/// (box_stats) up to kExactValues values; beyond, quantiles from a
/// deterministic compacting sketch (levels of kExactValues sorted values,
/// each level's values standing for twice as many as the level below; the
/// same values in the same order give the same result) whose rank error is
/// at most (1 + log2(n / kExactValues)) * n / kExactValues: 0.22 % of the
/// values for a million. The minimum and maximum stay exact; whiskers and
/// outliers beyond kExactValues come from the values the sketch keeps, the
/// extremes always among them. Memory: at most kExactValues values per level,
/// about log2(n / kExactValues) + 1 levels (96 KiB for a million values).
class QuantileSketch {
 public:
  static constexpr std::size_t kExactValues = 4096;
  /// A value the sketch keeps, standing for `weight` of the values added.
  struct Weighted {
    double value;
    double weight;
  };
  void add(double value);
  std::size_t count() const { return n_; }
  /// Box statistics of the values added (count() > 0).
  BoxStats box() const;
  /// Their median (count() > 0).
  double median() const;

 private:
  std::vector<Weighted> items() const;  ///< ascending
  void compact(std::size_t level);
  std::size_t n_ = 0;
  double min_ = 0.0, max_ = 0.0;
  std::vector<std::vector<double>> levels_;  ///< level i: each value stands for 2^i; level 0 the exact values up to kExactValues
  std::vector<bool> odd_;                    ///< per level: keep the odd positions at its next compaction
};

}  // namespace campo
