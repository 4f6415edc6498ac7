// campo's Dubins shortest path against OMPL's DubinsStateSpace (docs/PERFORMANCE.md,
// "Peers"): the same 4,096 seeded pose pairs in +-20 m, turning radius 1.5 m;
// campo solves all six words and keeps the shortest (dubins::shortest_path),
// OMPL computes the same path (DubinsStateSpace::dubins) for the same pair.
// Lengths are checked to agree to 1e-9 m. Repetitions interleave in one
// process; the figure is queries per second, median of the repetitions.
//
//   build/campo_peer_dubins [--repetitions K]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <stdexcept>
#include <vector>

#include <ompl/base/spaces/DubinsStateSpace.h>
#include <ompl/config.h>

#include "bench/peers/peer_record.hpp"
#include "campo/random.hpp"
#include "planners/dubins.hpp"

namespace {

using Clock = std::chrono::steady_clock;
constexpr double kRadius_m = 1.5;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  int repetitions = 7;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--repetitions") == 0) repetitions = std::stoi(argv[i + 1]);
  }
  try {
    campo::Rng rng(7);
    std::vector<campo::dubins::Pose2> from(4096), to(4096);
    for (std::size_t i = 0; i < from.size(); ++i) {
      for (auto* p : {&from[i], &to[i]}) {
        *p = {rng.uniform(-20, 20), rng.uniform(-20, 20), rng.uniform(-std::numbers::pi, std::numbers::pi)};
      }
    }
    ompl::base::DubinsStateSpace space(kRadius_m);
    std::vector<ompl::base::State*> states;
    for (std::size_t i = 0; i < from.size(); ++i) {
      for (const auto& p : {from[i], to[i]}) {
        ompl::base::State* s = space.allocState();
        auto* se2 = s->as<ompl::base::SE2StateSpace::StateType>();
        se2->setXY(p.x_m, p.y_m);
        se2->setYaw(p.heading_rad);
        states.push_back(s);
      }
    }
    std::vector<double> ours, theirs;
    double sink = 0.0;
    for (int r = 0; r < repetitions; ++r) {
      auto start = Clock::now();
      for (std::size_t i = 0; i < from.size(); ++i) {
        sink += campo::dubins::shortest_path(from[i], to[i], kRadius_m).length_m();
      }
      ours.push_back(from.size() / std::chrono::duration<double>(Clock::now() - start).count());
      start = Clock::now();
      for (std::size_t i = 0; i < from.size(); ++i) sink += space.dubins(states[2 * i], states[2 * i + 1]).length();
      theirs.push_back(from.size() / std::chrono::duration<double>(Clock::now() - start).count());
    }
    // The same shortest lengths (OMPL's in units of the radius).
    for (std::size_t i = 0; i < from.size(); ++i) {
      const double ours_m = campo::dubins::shortest_path(from[i], to[i], kRadius_m).length_m();
      const double theirs_m = space.dubins(states[2 * i], states[2 * i + 1]).length() * kRadius_m;
      if (std::abs(ours_m - theirs_m) > 1e-9 * std::max(1.0, ours_m)) {
        throw std::runtime_error("lengths differ at pair " + std::to_string(i) + ": " + std::to_string(ours_m) +
                                 " vs " + std::to_string(theirs_m));
      }
    }
    for (ompl::base::State* s : states) space.freeState(s);
    const double a_rate = median(ours), b_rate = median(theirs);
    if (campo::peers::json_requested(argc, argv)) {
      char note[96];
      std::snprintf(note, sizeof note, "lengths agree to 1e-9 (checksum %.3f)", sink);
      campo::peers::print_json({"dubins/4096_pairs", "Dubins shortest path, 4,096 pose pairs, r = 1.5 m", a_rate, b_rate,
                                "queries/s",
                                "OMPL " + std::to_string(OMPL_MAJOR_VERSION) + "." + std::to_string(OMPL_MINOR_VERSION) +
                                    "." + std::to_string(OMPL_PATCH_VERSION) + " DubinsStateSpace",
                                note});
      return 0;
    }
    std::printf("| Dubins shortest path, 4,096 pose pairs, r = 1.5 m | campo %.2f M queries/s | OMPL DubinsStateSpace "
                "%.2f M queries/s | %.2fx | lengths agree to 1e-9 (checksum %.3f) |\n",
                a_rate / 1e6, b_rate / 1e6, a_rate / b_rate, sink);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "campo_peer_dubins: %s\n", e.what());
    return 1;
  }
  return 0;
}
