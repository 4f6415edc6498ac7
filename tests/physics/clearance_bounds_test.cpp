// The bounds the clearance search prunes with leave out nothing it would
// keep: a heightfield cell whose box lies at least the limit from the body's
// box holds no triangle whose own box lies nearer, so the triangles handed
// on are those of the whole walk, in the same order, less only triangles
// the search would have dropped (their box distance reaches the limit).
#include "physics/height_blocks.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace campo {
namespace {

using Triangle = std::array<btVector3, 3>;

struct Record final : btTriangleCallback {
  std::vector<Triangle> seen;
  void processTriangle(btVector3* v, int, int) override { seen.push_back({v[0], v[1], v[2]}); }
};

// The box distance of the clearance search (physics/clearance.cpp), written again.
double box_distance(const Triangle& t, const btVector3& lo, const btVector3& hi) {
  btVector3 a = t[0], b = t[0];
  for (const btVector3& v : t) {
    a.setMin(v);
    b.setMax(v);
  }
  double sum = 0.0;
  for (int i = 0; i < 3; ++i) {
    const double gap = std::max({0.0, static_cast<double>(a[i] - hi[i]), static_cast<double>(lo[i] - b[i])});
    sum += gap * gap;
  }
  return std::sqrt(sum);
}

bool same(const Triangle& a, const Triangle& b) { return a[0] == b[0] && a[1] == b[1] && a[2] == b[2]; }

TEST(ClearanceBounds, CellsLeftOutHoldNoTriangleNearerThanTheLimit) {
  // Rough terrain (0.5 m spacing, heights up to 3 m) and some exactly flat rows: ties of distance.
  HeightGrid grid;
  grid.cols = 41;
  grid.rows = 33;
  grid.spacing_x_m = 0.5;
  grid.spacing_y_m = 0.5;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> height(0.0, 3.0);
  for (int r = 0; r < grid.rows; ++r) {
    for (int c = 0; c < grid.cols; ++c) grid.heights_m.push_back(r < 8 ? 1.0 : height(rng));
  }
  const HeightBlocks blocks(grid);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int left_out = 0, kept = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const btVector3 centre(8.0 * unit(rng), 6.0 * unit(rng), 1.5 + 2.0 * unit(rng));
    const btVector3 half(0.1 + 0.3 * std::abs(unit(rng)), 0.1 + 0.3 * std::abs(unit(rng)), 0.05 + 0.1 * std::abs(unit(rng)));
    const double limit = 0.05 + 3.0 * std::abs(unit(rng));
    const HeightBlocks::Near near{centre - half, centre + half, limit};
    const btVector3 pad(limit, limit, limit);
    Record all, some;
    blocks.triangles_under(near.lo - pad, near.hi + pad, all);
    blocks.triangles_under(near.lo - pad, near.hi + pad, some, &near);
    // `some` is `all` in order, less triangles at the limit or beyond.
    std::size_t j = 0;
    for (const Triangle& t : all.seen) {
      if (j < some.seen.size() && same(some.seen[j], t)) {
        ++j;
        ++kept;
        continue;
      }
      ASSERT_GE(box_distance(t, near.lo, near.hi), limit) << "trial " << trial << ": a triangle nearer than the limit left out";
      ++left_out;
    }
    ASSERT_EQ(j, some.seen.size()) << "trial " << trial << ": triangles handed on that the whole walk does not have";
  }
  // Both happened, many times.
  EXPECT_GT(left_out, 1000);
  EXPECT_GT(kept, 1000);
}

}  // namespace
}  // namespace campo
