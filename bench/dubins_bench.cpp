// Dubins shortest-path queries per second (all six words solved, the
// shortest kept) over a fixed set of seeded pose pairs: near pairs, where the
// three-arc words are feasible too, and far ones.
#include <benchmark/benchmark.h>

#include <numbers>
#include <vector>

#include "campo/random.hpp"
#include "planners/dubins.hpp"

namespace campo::dubins {
namespace {

constexpr double kRadiusM = 1.5;

struct Query {
  Pose2 from, to;
};

std::vector<Query> queries() {
  Rng rng(7);
  std::vector<Query> out(1024);
  for (Query& q : out) {
    const auto pose = [&] {
      return Pose2{rng.uniform(-20, 20), rng.uniform(-20, 20), rng.uniform(-std::numbers::pi, std::numbers::pi)};
    };
    q = {pose(), pose()};
  }
  return out;
}

void BM_DubinsShortestPath(benchmark::State& state) {
  const std::vector<Query> qs = queries();
  std::size_t i = 0;
  for (auto _ : state) {
    const Query& q = qs[i++ % qs.size()];
    benchmark::DoNotOptimize(shortest_path(q.from, q.to, kRadiusM));
  }
  state.SetItemsProcessed(state.iterations());
}

BENCHMARK(BM_DubinsShortestPath);

}  // namespace
}  // namespace campo::dubins
