#include "grid/astar.hpp"

#include <stdexcept>

#include <gtest/gtest.h>

#include "grid_test_support.hpp"

namespace campo::grid {
namespace {

struct RandomCase {
  Connectivity connectivity;
  GridSize size;
  double blocked;
  int maps;
  double level_step = 1.0;  ///< cells; 7 m levels over 1.5 m cells is seed 001's grid
};

// A* finds the cost a plain Dijkstra finds, on many random maps of every connectivity.
TEST(AStar, MatchesDijkstraOnRandomMaps) {
  for (const RandomCase& c : {RandomCase{Connectivity::four, {30, 25, 1}, 0.3, 40},
                              RandomCase{Connectivity::eight, {30, 25, 1}, 0.35, 40},
                              RandomCase{Connectivity::six, {12, 10, 8}, 0.35, 25},
                              RandomCase{Connectivity::twenty_six, {12, 10, 8}, 0.4, 25},
                              RandomCase{Connectivity::six, {12, 10, 8}, 0.35, 25, 7.0 / 1.5},
                              RandomCase{Connectivity::twenty_six, {12, 10, 8}, 0.4, 25, 7.0 / 1.5}}) {
    GridGraph graph(c.size, c.connectivity, c.level_step);
    AStar astar(graph);
    int found = 0;
    for (int map = 0; map < c.maps; ++map) {
      Rng rng(Rng::derive_seed(map, static_cast<std::uint64_t>(c.connectivity)));
      test::fill_random(graph, rng, c.blocked);
      for (int query = 0; query < 5; ++query) {
        const Cell start = test::random_open_cell(graph, rng), goal = test::random_open_cell(graph, rng);
        const SearchResult result = astar.plan(start, goal);
        const double expected = test::dijkstra(graph, start, goal);
        SCOPED_TRACE(std::string(to_string(c.connectivity)) + " level step " + std::to_string(c.level_step) +
                     " map " + std::to_string(map));
        if (expected < 0.0) {
          EXPECT_EQ(result.status, SearchStatus::no_path);
          EXPECT_EQ(to_cells(result.cost), -1.0);
          EXPECT_TRUE(result.path.empty());
          continue;
        }
        ++found;
        EXPECT_NEAR(to_cells(result.cost), expected, 1e-6 * (1.0 + expected));
        test::expect_valid_path(graph, result, start, goal);
        EXPECT_GE(result.expansions, static_cast<std::int64_t>(result.steps()));
      }
    }
    // The maps are dense enough to have blocked queries, sparse enough to have many paths.
    EXPECT_GT(found, c.maps * 2) << to_string(c.connectivity);
  }
}

TEST(AStar, StartAtTheGoal) {
  const GridGraph graph({4, 4, 1}, Connectivity::eight);
  AStar astar(graph);
  const SearchResult result = astar.plan({2, 1, 0}, {2, 1, 0});
  EXPECT_EQ(result.status, SearchStatus::found);
  EXPECT_EQ(result.cost, 0);
  EXPECT_EQ(result.steps(), 0u);
  EXPECT_EQ(result.path, (std::vector<Cell>{{2, 1, 0}}));
}

TEST(AStar, BlockedEndsAndWallsMeanNoPath) {
  GridGraph graph({5, 5, 1}, Connectivity::eight);
  AStar astar(graph);
  graph.set_state({4, 4, 0}, CellState::blocked);
  EXPECT_EQ(astar.plan({0, 0, 0}, {4, 4, 0}).status, SearchStatus::no_path);
  EXPECT_EQ(astar.plan({4, 4, 0}, {4, 4, 0}).status, SearchStatus::no_path);
  // A diagonal wall: without corner cutting nothing slips through.
  graph.set_state({4, 4, 0}, CellState::free);
  for (int i = 0; i < 5; ++i) graph.set_state({i, 4 - i, 0}, CellState::blocked);
  const SearchResult result = astar.plan({0, 0, 0}, {4, 4, 0});
  EXPECT_EQ(result.status, SearchStatus::no_path);
  EXPECT_GT(result.expansions, 0);
  EXPECT_THROW(astar.plan({0, 0, 0}, {5, 0, 0}), std::out_of_range);
}

TEST(AStar, OpenGridExpandsOnlyThePath) {
  // Ties in f go to the node nearest the goal, and fixed-point costs make
  // equal-cost paths tie exactly: on an empty grid A* walks straight there.
  const GridGraph flat({60, 40, 1}, Connectivity::eight);
  AStar a2(flat);
  const SearchResult r2 = a2.plan({3, 5, 0}, {55, 31, 0});
  EXPECT_EQ(r2.expansions, static_cast<std::int64_t>(r2.path.size()));
  const GridGraph cube({30, 30, 9}, Connectivity::twenty_six);
  AStar a3(cube);
  const SearchResult r3 = a3.plan({1, 2, 0}, {28, 17, 8});
  EXPECT_EQ(r3.expansions, static_cast<std::int64_t>(r3.path.size()));
  EXPECT_EQ(r3.cost, 8 * kCornerCost + 7 * kDiagonalCost + 12 * kStraightCost);
}

TEST(AStar, IsDeterministicAcrossReuse) {
  GridGraph graph({40, 40, 1}, Connectivity::eight);
  Rng rng(3);
  test::fill_random(graph, rng, 0.25);
  const Cell start = test::random_open_cell(graph, rng), goal = test::random_open_cell(graph, rng);
  AStar astar(graph);
  const SearchResult first = astar.plan(start, goal);
  for (int i = 0; i < 5; ++i) astar.plan(test::random_open_cell(graph, rng), test::random_open_cell(graph, rng));
  const SearchResult again = astar.plan(start, goal);
  EXPECT_EQ(again.path, first.path);
  EXPECT_EQ(again.expansions, first.expansions);
  AStar fresh(graph);
  EXPECT_EQ(fresh.plan(start, goal).path, first.path);
}

}  // namespace
}  // namespace campo::grid
