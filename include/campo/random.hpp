#pragma once
/// Seeded random numbers with distributions written out here, so a seed gives
/// the same numbers with any compiler and standard library (the standard fixes
/// mt19937_64's output but not the output of its distributions).
#include <cstdint>
#include <random>

namespace campo {

class Rng {
 public:
  explicit Rng(std::uint64_t seed) : engine_(seed) {}

  /// Uniform in [0, 1) with 53 random bits.
  double uniform01() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  /// Uniform in [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform01(); }
  /// Uniform integer in [lo, hi] (hi >= lo).
  std::int64_t uniform_int(std::int64_t lo, std::int64_t hi) {
    const auto span = static_cast<std::uint64_t>(hi - lo) + 1;
    return lo + static_cast<std::int64_t>(span == 0 ? engine_() : engine_() % span);
  }
  /// Standard normal (Marsaglia polar method), then scaled.
  double normal(double mean, double stddev);
  /// True with probability p.
  bool bernoulli(double p) { return uniform01() < p; }
  /// An independent stream derived from this one's seed and a label (for
  /// sub-generators that must not shift when another consumer changes).
  static std::uint64_t derive_seed(std::uint64_t seed, std::uint64_t label);

 private:
  std::mt19937_64 engine_;
  double spare_normal_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace campo
