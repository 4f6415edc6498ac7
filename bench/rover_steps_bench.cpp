// The rover's per-step local planners (SPEC §7.3): one pure-pursuit step on a
// 1000-point path and one follow-the-gap step on a planar180 scan (181 beams)
// with obstacles.
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include <Eigen/Core>

#include "campo/random.hpp"
#include "planners/follow_the_gap.hpp"
#include "planners/pure_pursuit.hpp"

namespace campo {
namespace {

constexpr int kPathPoints = 1000;
constexpr int kRobotAt = 500;  ///< the robot stands beside this path point

// A meandering path sampled every 0.1 m in x, like a discretised global path.
std::vector<Eigen::Vector2d> meander() {
  std::vector<Eigen::Vector2d> path;
  path.reserve(kPathPoints);
  for (int i = 0; i < kPathPoints; ++i) path.emplace_back(0.1 * i, 2.0 * std::sin(0.02 * i));
  return path;
}

// lastFoundIndex as the step finds it: just behind the robot while tracking
// (a few segments searched), or 0 (the whole path up to the robot searched,
// the worst case, e.g. the first step from a stale state).
void BM_PurePursuitStep(benchmark::State& state, int last_found_index) {
  const std::vector<Eigen::Vector2d> path = meander();
  const Eigen::Vector2d tangent = (path[kRobotAt + 1] - path[kRobotAt]).normalized();
  const Eigen::Vector2d position = path[kRobotAt] + 0.2 * Eigen::Vector2d(-tangent.y(), tangent.x());
  const double heading = std::atan2(tangent.y(), tangent.x()) + 0.1;
  const PurePursuitConfig config;
  for (auto _ : state) {
    PurePursuitState pp{last_found_index};
    benchmark::DoNotOptimize(pure_pursuit_step(config, pp, position, heading, path));
  }
}

// A wall 3 m ahead with two openings, a post 1.5 m away to the front left, 2 cm range noise.
std::vector<float> cluttered_scan() {
  Rng rng(7);
  std::vector<float> ranges(181, 20.0f);
  for (int i = 0; i < 181; ++i) {
    const double azimuth = (90.0 - i) * M_PI / 180.0;
    const bool open = (i >= 55 && i <= 65) || (i >= 115 && i <= 135);
    const double wall = 3.0 / std::cos(azimuth);
    if (!open && std::abs(azimuth) < M_PI / 2 && wall < 20.0)
      ranges[i] = static_cast<float>(wall + rng.normal(0.0, 0.02));
  }
  for (int i = 75; i <= 80; ++i) ranges[i] = static_cast<float>(1.5 + rng.normal(0.0, 0.02));
  return ranges;
}

void BM_FollowTheGapStep(benchmark::State& state) {
  const std::vector<float> ranges = cluttered_scan();
  const FollowTheGapConfig config;
  for (auto _ : state) {
    FollowTheGapState ftg;
    benchmark::DoNotOptimize(follow_the_gap_step(config, ftg, PlanarScanView{ranges}, 0.1, 0.0));
  }
}

BENCHMARK_CAPTURE(BM_PurePursuitStep, tracking, kRobotAt - 5);
BENCHMARK_CAPTURE(BM_PurePursuitStep, from_start, 0);
BENCHMARK(BM_FollowTheGapStep);

}  // namespace
}  // namespace campo
