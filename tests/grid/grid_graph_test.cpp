#include "grid/grid_graph.hpp"

#include <cmath>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "grid_test_support.hpp"

namespace campo::grid {
namespace {

struct Neighbour {
  Cell cell;
  Cost cost;
};

std::vector<Neighbour> neighbours(const GridGraph& graph, const Cell& c) {
  std::vector<Neighbour> out;
  graph.for_each_neighbour(graph.id(c), [&](CellId v, Cost cost) { out.push_back({graph.cell(v), cost}); });
  return out;
}

TEST(GridGraph, MoveCostsAreOneSqrt2Sqrt3InFixedPoint) {
  EXPECT_EQ(to_cells(kStraightCost), 1.0);
  EXPECT_NEAR(to_cells(kDiagonalCost), std::sqrt(2.0), 1e-9);
  EXPECT_NEAR(to_cells(kCornerCost), std::sqrt(3.0), 1e-9);
  EXPECT_EQ(to_cells(kInfiniteCost), -1.0);
}

TEST(GridGraph, InteriorCellsHaveAllNeighboursOfTheConnectivity) {
  struct Case {
    Connectivity connectivity;
    GridSize size;
    std::size_t count;
    int straight, diagonal, corner;
  };
  for (const Case& c : {Case{Connectivity::four, {5, 5, 1}, 4, 4, 0, 0}, Case{Connectivity::eight, {5, 5, 1}, 8, 4, 4, 0},
                        Case{Connectivity::six, {5, 5, 5}, 6, 6, 0, 0},
                        Case{Connectivity::twenty_six, {5, 5, 5}, 26, 6, 12, 8}}) {
    const GridGraph graph(c.size, c.connectivity);
    const Cell centre{2, 2, is_3d(c.connectivity) ? 2 : 0};
    const auto n = neighbours(graph, centre);
    ASSERT_EQ(n.size(), c.count) << to_string(c.connectivity);
    int straight = 0, diagonal = 0, corner = 0;
    for (const Neighbour& v : n) {
      EXPECT_EQ(graph.edge_cost(centre, v.cell), v.cost);
      straight += v.cost == kStraightCost;
      diagonal += v.cost == kDiagonalCost;
      corner += v.cost == kCornerCost;
    }
    EXPECT_EQ(straight, c.straight);
    EXPECT_EQ(diagonal, c.diagonal);
    EXPECT_EQ(corner, c.corner);
  }
}

TEST(GridGraph, EdgesOfTheGridAreWalls) {
  const GridGraph flat({4, 3, 1}, Connectivity::eight);
  EXPECT_EQ(neighbours(flat, {0, 0, 0}).size(), 3u);
  EXPECT_EQ(neighbours(flat, {3, 2, 0}).size(), 3u);
  const GridGraph cube({3, 3, 3}, Connectivity::twenty_six);
  EXPECT_EQ(neighbours(cube, {0, 0, 0}).size(), 7u);
  const GridGraph single({1, 1, 1}, Connectivity::six);
  EXPECT_TRUE(neighbours(single, {0, 0, 0}).empty());
}

TEST(GridGraph, UnknownCellsAreTraversableBlockedAreNot) {
  GridGraph graph({3, 1, 1}, Connectivity::four);
  EXPECT_EQ(graph.state({1, 0, 0}), CellState::unknown);
  EXPECT_EQ(graph.edge_cost({0, 0, 0}, {1, 0, 0}), kStraightCost);
  graph.set_state({1, 0, 0}, CellState::blocked);
  EXPECT_EQ(graph.edge_cost({0, 0, 0}, {1, 0, 0}), kInfiniteCost);
  EXPECT_EQ(graph.edge_cost({1, 0, 0}, {0, 0, 0}), kInfiniteCost);
  EXPECT_TRUE(neighbours(graph, {1, 0, 0}).empty());
  EXPECT_EQ(graph.edge_cost({0, 0, 0}, {2, 0, 0}), kInfiniteCost);  // not adjacent
}

TEST(GridGraph, NoCornerCuttingIn2D) {
  // MovingAI: a diagonal needs both orthogonal neighbours free.
  for (const Cell blocker : {Cell{1, 0, 0}, Cell{0, 1, 0}}) {
    GridGraph graph({2, 2, 1}, Connectivity::eight);
    EXPECT_EQ(graph.edge_cost({0, 0, 0}, {1, 1, 0}), kDiagonalCost);
    graph.set_state(blocker, CellState::blocked);
    EXPECT_EQ(graph.edge_cost({0, 0, 0}, {1, 1, 0}), kInfiniteCost);
    EXPECT_EQ(graph.edge_cost({1, 1, 0}, {0, 0, 0}), kInfiniteCost);
  }
}

TEST(GridGraph, NoCornerCuttingIn3D) {
  // A corner move needs all six other cells of its 2 x 2 x 2 box; a face
  // diagonal needs the two cells of its 2 x 2 square.
  const Cell from{0, 0, 0}, corner{1, 1, 1};
  for (int mask = 1; mask < 7; ++mask) {
    GridGraph graph({2, 2, 2}, Connectivity::twenty_six);
    const Cell blocker{mask & 1, (mask >> 1) & 1, (mask >> 2) & 1};
    graph.set_state(blocker, CellState::blocked);
    EXPECT_EQ(graph.edge_cost(from, corner), kInfiniteCost) << mask;
    EXPECT_EQ(graph.edge_cost(corner, from), kInfiniteCost) << mask;
  }
  GridGraph graph({2, 2, 2}, Connectivity::twenty_six);
  EXPECT_EQ(graph.edge_cost(from, corner), kCornerCost);
  graph.set_state({1, 0, 1}, CellState::blocked);
  EXPECT_EQ(graph.edge_cost(from, {1, 1, 0}), kDiagonalCost);  // box {x, y} at z = 0 is clear
  EXPECT_EQ(graph.edge_cost(from, {0, 1, 1}), kDiagonalCost);
  EXPECT_EQ(graph.edge_cost(from, {1, 0, 0}), kStraightCost);
  graph.set_state({0, 1, 0}, CellState::blocked);
  EXPECT_EQ(graph.edge_cost(from, {1, 1, 0}), kInfiniteCost);
  EXPECT_EQ(graph.edge_cost(from, {0, 1, 1}), kInfiniteCost);
}

TEST(GridGraph, IdsRoundTrip) {
  const GridGraph graph({7, 5, 3}, Connectivity::twenty_six);
  for (int z = 0; z < 3; ++z)
    for (int y = 0; y < 5; ++y)
      for (int x = 0; x < 7; ++x) EXPECT_EQ(graph.cell(graph.id({x, y, z})), (Cell{x, y, z}));
  EXPECT_FALSE(graph.contains({7, 0, 0}));
  EXPECT_FALSE(graph.contains({0, -1, 0}));
  EXPECT_FALSE(graph.contains({0, 0, 3}));
}

TEST(GridGraph, HeuristicIsExactOnAnEmptyGridAndConsistentOnRandomMaps) {
  for (const Connectivity connectivity :
       {Connectivity::four, Connectivity::eight, Connectivity::six, Connectivity::twenty_six}) {
    const GridSize size = is_3d(connectivity) ? GridSize{9, 8, 7} : GridSize{23, 17, 1};
    GridGraph graph(size, connectivity);
    Rng rng(7);
    for (int i = 0; i < 20; ++i) {
      const Cell a = test::random_cell(graph, rng), b = test::random_cell(graph, rng);
      EXPECT_NEAR(to_cells(graph.heuristic(graph.id(a), graph.id(b))), test::dijkstra(graph, a, b), 1e-6)
          << to_string(connectivity);
    }
    // Consistency, h(u) <= c(u, v) + h(v), exactly in fixed point.
    test::fill_random(graph, rng, 0.3);
    const CellId goal = graph.id(test::random_cell(graph, rng));
    for (int z = 0; z < size.depth; ++z)
      for (int y = 0; y < size.height; ++y)
        for (int x = 0; x < size.width; ++x) {
          const CellId u = graph.id({x, y, z});
          graph.for_each_neighbour(u, [&](CellId v, Cost c) {
            EXPECT_LE(graph.heuristic(u, goal), c + graph.heuristic(v, goal));
          });
        }
  }
}

// Levels taller than cells: every move costs its Euclidean length in cells,
// and the heuristic stays a consistent lower bound (exact when 6-connected).
TEST(GridGraph, TallLevelsCostTheirHeight) {
  const double step = 7.0 / 1.5;
  for (const Connectivity connectivity : {Connectivity::six, Connectivity::twenty_six}) {
    GridGraph graph({9, 8, 7}, connectivity, step);
    EXPECT_NEAR(to_cells(graph.edge_cost({4, 4, 3}, {4, 4, 4})), step, 1e-9);
    EXPECT_NEAR(to_cells(graph.edge_cost({4, 4, 3}, {5, 4, 3})), 1.0, 1e-9);
    if (connectivity == Connectivity::twenty_six) {
      EXPECT_NEAR(to_cells(graph.edge_cost({4, 4, 3}, {5, 4, 4})), std::sqrt(1.0 + step * step), 1e-9);
      EXPECT_NEAR(to_cells(graph.edge_cost({4, 4, 3}, {5, 5, 2})), std::sqrt(2.0 + step * step), 1e-9);
      EXPECT_NEAR(to_cells(graph.edge_cost({4, 4, 3}, {5, 5, 3})), std::sqrt(2.0), 1e-9);
    }
    Rng rng(11);
    for (int i = 0; i < 30; ++i) {
      const Cell a = test::random_cell(graph, rng), b = test::random_cell(graph, rng);
      const double h = to_cells(graph.heuristic(graph.id(a), graph.id(b)));
      const double shortest = test::dijkstra(graph, a, b);
      if (connectivity == Connectivity::six) {
        // Manhattan with tall levels, by hand: |dx| + |dy| + step |dz|.
        EXPECT_NEAR(h, std::abs(a.x - b.x) + std::abs(a.y - b.y) + step * std::abs(a.z - b.z), 1e-6);
        EXPECT_NEAR(h, shortest, 1e-6);
      } else {
        EXPECT_LE(h, shortest + 1e-9);
      }
    }
    test::fill_random(graph, rng, 0.3);
    const CellId goal = graph.id(test::random_cell(graph, rng));
    for (CellId u = 0; u < graph.id_count(); ++u) {
      graph.for_each_neighbour(u, [&](CellId v, Cost c) { EXPECT_LE(graph.heuristic(u, goal), c + graph.heuristic(v, goal)); });
    }
  }
  EXPECT_THROW(GridGraph({5, 5, 1}, Connectivity::eight, 2.0), std::invalid_argument);
  EXPECT_THROW(GridGraph({5, 5, 5}, Connectivity::six, 0.0), std::invalid_argument);
}

TEST(GridGraph, ConnectivityNamesRoundTrip) {
  for (const Connectivity c : {Connectivity::four, Connectivity::eight, Connectivity::six, Connectivity::twenty_six}) {
    EXPECT_EQ(connectivity_from_string(to_string(c)), c);
  }
  EXPECT_FALSE(connectivity_from_string("12").has_value());
}

TEST(GridGraph, RejectsBadSizes) {
  EXPECT_THROW(GridGraph({0, 5, 1}, Connectivity::eight), std::invalid_argument);
  EXPECT_THROW(GridGraph({5, 5, 2}, Connectivity::eight), std::invalid_argument);
  EXPECT_THROW(GridGraph({5, GridGraph::kMaxDimension + 1, 1}, Connectivity::four), std::invalid_argument);
  EXPECT_THROW(GridGraph({20000, 20000, 1}, Connectivity::four), std::invalid_argument);
}

}  // namespace
}  // namespace campo::grid
