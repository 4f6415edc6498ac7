#pragma once
// Test support for grid/: random maps, a plain Dijkstra written independently
// of GridGraph (its own moves, costs and corner rule, in double), and a path check.
#include <cmath>
#include <cstdint>
#include <functional>
#include <queue>
#include <vector>

#include <gtest/gtest.h>

#include "campo/random.hpp"
#include "grid/grid_graph.hpp"
#include "grid/search_result.hpp"

namespace campo::grid::test {

/// Blocks each cell with probability `blocked`; of the rest, half stay unknown.
inline void fill_random(GridGraph& graph, Rng& rng, double blocked) {
  const GridSize& n = graph.size();
  for (int z = 0; z < n.depth; ++z) {
    for (int y = 0; y < n.height; ++y) {
      for (int x = 0; x < n.width; ++x) {
        const CellState state =
            rng.bernoulli(blocked) ? CellState::blocked : (rng.bernoulli(0.5) ? CellState::free : CellState::unknown);
        graph.set_state({x, y, z}, state);
      }
    }
  }
}

inline Cell random_cell(const GridGraph& graph, Rng& rng) {
  const GridSize& n = graph.size();
  return {static_cast<int>(rng.uniform_int(0, n.width - 1)), static_cast<int>(rng.uniform_int(0, n.height - 1)),
          static_cast<int>(rng.uniform_int(0, n.depth - 1))};
}

/// A random traversable cell (the grid must have one).
inline Cell random_open_cell(const GridGraph& graph, Rng& rng) {
  while (true) {
    const Cell c = random_cell(graph, rng);
    if (graph.state(c) != CellState::blocked) return c;
  }
}

/// Cheapest path cost in cells by Dijkstra, -1 when unreachable. A move costs
/// its Euclidean length (sqrt(k) for k unit components when levels are one
/// cell high) and needs every cell of the box between its ends unblocked.
inline double dijkstra(const GridGraph& graph, const Cell& start, const Cell& goal) {
  const GridSize& n = graph.size();
  const int max_nonzero = graph.connectivity() == Connectivity::four || graph.connectivity() == Connectivity::six ? 1
                          : graph.connectivity() == Connectivity::eight                                          ? 2
                                                                                                                 : 3;
  const int zr = is_3d(graph.connectivity()) ? 1 : 0;
  const auto open = [&](int x, int y, int z) {
    return graph.contains({x, y, z}) && graph.state({x, y, z}) != CellState::blocked;
  };
  const auto index = [&](const Cell& c) { return (static_cast<std::size_t>(c.z) * n.height + c.y) * n.width + c.x; };
  std::vector<double> dist(static_cast<std::size_t>(n.width) * n.height * n.depth, INFINITY);
  using Item = std::pair<double, std::size_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  std::vector<Cell> cells(dist.size());
  for (int z = 0; z < n.depth; ++z)
    for (int y = 0; y < n.height; ++y)
      for (int x = 0; x < n.width; ++x) cells[index({x, y, z})] = {x, y, z};
  if (!open(start.x, start.y, start.z) || !open(goal.x, goal.y, goal.z)) return -1.0;
  dist[index(start)] = 0.0;
  queue.push({0.0, index(start)});
  while (!queue.empty()) {
    const auto [d, i] = queue.top();
    queue.pop();
    if (d > dist[i]) continue;
    const Cell u = cells[i];
    if (u == goal) return d;
    for (int dz = -zr; dz <= zr; ++dz) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const int k = (dx != 0) + (dy != 0) + (dz != 0);
          if (k == 0 || k > max_nonzero) continue;
          bool clear = true;
          for (int bx = std::min(0, dx); bx <= std::max(0, dx); ++bx)
            for (int by = std::min(0, dy); by <= std::max(0, dy); ++by)
              for (int bz = std::min(0, dz); bz <= std::max(0, dz); ++bz)
                clear = clear && open(u.x + bx, u.y + by, u.z + bz);
          if (!clear) continue;
          const Cell v{u.x + dx, u.y + dy, u.z + dz};
          // Euclidean move length, a level being level_step_cells() cells high.
          const double rise = dz * graph.level_step_cells();
          const double nd = d + std::sqrt(static_cast<double>(dx * dx + dy * dy) + rise * rise);
          if (nd < dist[index(v)]) {
            dist[index(v)] = nd;
            queue.push({nd, index(v)});
          }
        }
      }
    }
  }
  return -1.0;
}

/// The path runs from start to goal by allowed moves whose costs sum to result.cost.
inline void expect_valid_path(const GridGraph& graph, const SearchResult& result, const Cell& start, const Cell& goal) {
  ASSERT_EQ(result.status, SearchStatus::found);
  ASSERT_FALSE(result.path.empty());
  EXPECT_EQ(result.path.front(), start);
  EXPECT_EQ(result.path.back(), goal);
  Cost sum = 0;
  for (std::size_t i = 1; i < result.path.size(); ++i) {
    const Cost c = graph.edge_cost(result.path[i - 1], result.path[i]);
    ASSERT_LT(c, kInfiniteCost) << "step " << i << " is not an allowed move";
    sum += c;
  }
  EXPECT_EQ(sum, result.cost);
}

}  // namespace campo::grid::test
