// D* Lite and LPA* against A* from scratch on the same known map, after
// every batch of map changes (property tests over many seeds).
#include <algorithm>
#include <vector>

#include <gtest/gtest.h>

#include "grid/astar.hpp"
#include "grid/dstar_lite.hpp"
#include "grid/lpa_star.hpp"
#include "grid_test_support.hpp"

namespace campo::grid {
namespace {

struct Setting {
  Connectivity connectivity;
  GridSize size;
  double blocked;  ///< initial density
  double level_step = 1.0;  ///< cells per level (3D)
};

const Setting kFlat{Connectivity::eight, {32, 24, 1}, 0.25};
const Setting kCube{Connectivity::twenty_six, {20, 16, 8}, 0.3};

// A batch like a sensor sweep: cells within `radius` of `near`, mostly found
// blocked, some found free again; never the cell the vehicle is on.
std::vector<CellChange> sweep_changes(const GridGraph& graph, Rng& rng, const Cell& near, int radius, int count) {
  std::vector<CellChange> changes;
  while (static_cast<int>(changes.size()) < count) {
    const Cell c{near.x + static_cast<int>(rng.uniform_int(-radius, radius)),
                 near.y + static_cast<int>(rng.uniform_int(-radius, radius)),
                 near.z + (is_3d(graph.connectivity()) ? static_cast<int>(rng.uniform_int(-radius, radius)) : 0)};
    if (!graph.contains(c) || c == near) continue;
    changes.push_back({c, rng.bernoulli(0.75) ? CellState::blocked : CellState::free});
  }
  return changes;
}

// Moves along the current path a few cells at a time, changing cells near the
// vehicle between moves; D* Lite must match A* from scratch at every replan.
// Returns the number of replans that found a path.
int dstar_episode(const Setting& setting, std::uint64_t seed, int replans) {
  GridGraph graph(setting.size, setting.connectivity, setting.level_step);
  Rng rng(seed);
  test::fill_random(graph, rng, setting.blocked);
  const Cell goal = test::random_open_cell(graph, rng);
  Cell start = test::random_open_cell(graph, rng);
  DStarLite dstar(graph, start, goal);
  AStar astar(graph);
  int found = 0;
  for (int replan = 0; replan < replans; ++replan) {
    const SearchResult d = dstar.plan();
    const SearchResult a = astar.plan(start, goal);
    SCOPED_TRACE("seed " + std::to_string(seed) + " replan " + std::to_string(replan));
    EXPECT_EQ(d.status, a.status);
    if (d.status != a.status) return found;
    if (d.status == SearchStatus::found) {
      ++found;
      EXPECT_EQ(d.cost, a.cost);  // fixed point: equal-cost paths cost exactly the same
      test::expect_valid_path(graph, d, start, goal);
      if (d.steps() == 0) break;
      // The vehicle flies 1-4 cells along the plan, then the sensor sweeps ahead.
      const auto k = static_cast<std::size_t>(rng.uniform_int(1, 4));
      start = d.path[std::min(k, d.steps())];
      dstar.move_start(start);
    }
    const std::vector<CellChange> changes = sweep_changes(graph, rng, start, 3, static_cast<int>(rng.uniform_int(1, 8)));
    dstar.set_cells(changes);
  }
  return found;
}

TEST(DStarLite, MatchesAStarAfterEveryBatchOfChanges2D) {
  int found = 0;
  for (std::uint64_t seed = 0; seed < 60; ++seed) found += dstar_episode(kFlat, seed, 25);
  EXPECT_GT(found, 600);
}

TEST(DStarLite, MatchesAStarAfterEveryBatchOfChanges3D) {
  int found = 0;
  for (std::uint64_t seed = 100; seed < 200; ++seed) found += dstar_episode(kCube, seed, 20);
  EXPECT_GT(found, 400);
}

// Seed 001's grid: a level 7 m high over 1.5 m cells, so climbing costs 4.67 cells.
TEST(DStarLite, MatchesAStarWithTallLevels) {
  int found = 0;
  for (std::uint64_t seed = 300; seed < 360; ++seed) {
    found += dstar_episode({Connectivity::six, {16, 14, 8}, 0.25, 7.0 / 1.5}, seed, 15);
    found += dstar_episode({Connectivity::twenty_six, {16, 14, 8}, 0.3, 7.0 / 1.5}, seed, 15);
  }
  EXPECT_GT(found, 300);
}

TEST(DStarLite, MatchesAStarWithFourAndSixConnectivity) {
  int found = 0;
  for (std::uint64_t seed = 200; seed < 260; ++seed) {
    found += dstar_episode({Connectivity::four, {24, 20, 1}, 0.2}, seed, 15);
    found += dstar_episode({Connectivity::six, {16, 14, 8}, 0.2}, seed, 15);
  }
  EXPECT_GT(found, 300);
}

// The key modifier: the start moves a long way along the path between
// changes, so keys queued earlier were computed from far behind it.
TEST(DStarLite, KeyModifierKeepsReplansExactAfterLongMoves) {
  GridGraph graph({60, 30, 1}, Connectivity::eight);
  // A wall across the middle with two gaps, so blocking one forces a long detour.
  for (int y = 0; y < 30; ++y) {
    if (y != 5 && y != 25) graph.set_state({30, y, 0}, CellState::blocked);
  }
  const Cell goal{58, 15, 0};
  Cell start{1, 15, 0};
  DStarLite dstar(graph, start, goal);
  AStar astar(graph);
  SearchResult d = dstar.plan();
  ASSERT_EQ(d.cost, astar.plan(start, goal).cost);
  const std::int64_t first_expansions = d.expansions;
  for (int leg = 0; leg < 3; ++leg) {
    // Fly 6 cells, then see an obstacle right across the path 3 cells ahead.
    start = d.path[6];
    dstar.move_start(start);
    const Cell ahead = d.path[9];
    std::vector<CellChange> changes;
    for (int dy = -2; dy <= 2; ++dy) {
      const Cell c{ahead.x, ahead.y + dy, 0};
      if (graph.contains(c) && c != start) changes.push_back({c, CellState::blocked});
    }
    dstar.set_cells(changes);
    d = dstar.plan();
    const SearchResult a = astar.plan(start, goal);
    ASSERT_EQ(d.status, SearchStatus::found) << leg;
    EXPECT_EQ(d.cost, a.cost) << leg;
    test::expect_valid_path(graph, d, start, goal);
  }
  // Moving without changes needs no search beyond the start's own key check.
  start = d.path[5];
  dstar.move_start(start);
  const SearchResult rest = dstar.plan();
  EXPECT_EQ(rest.cost, astar.plan(start, goal).cost);
  EXPECT_LT(rest.expansions, first_expansions / 10);
  // Closing the gap in use forces the path through the far one.
  ASSERT_LT(start.x, 30);
  const auto gap = std::find_if(rest.path.begin(), rest.path.end(), [](const Cell& c) { return c.x == 30; });
  ASSERT_NE(gap, rest.path.end());
  dstar.set_cells(std::vector<CellChange>{{*gap, CellState::blocked}});
  const SearchResult detour = dstar.plan();
  EXPECT_EQ(detour.cost, astar.plan(start, goal).cost);
  EXPECT_GT(detour.cost, rest.cost);
  test::expect_valid_path(graph, detour, start, goal);
}

// With no expansion and no change next to the path, the rest of the last
// path is returned as it was (not traced again); a change next to it, even
// one that only forbids a diagonal's corner, forces a fresh trace.
TEST(DStarLite, KeepsThePathWhenNoChangeTouchesIt) {
  GridGraph graph({30, 30, 1}, Connectivity::eight);
  const Cell goal{25, 25, 0};
  Cell start{2, 2, 0};
  DStarLite dstar(graph, start, goal);
  AStar astar(graph);
  const SearchResult first = dstar.plan();  // the diagonal (2,2) -> (25,25)
  start = first.path[3];
  dstar.move_start(start);
  dstar.set_cells(std::vector<CellChange>{{{20, 3, 0}, CellState::blocked}});
  const SearchResult kept = dstar.plan();
  EXPECT_EQ(kept.expansions, 0);
  EXPECT_EQ(kept.path, std::vector<Cell>(first.path.begin() + 3, first.path.end()));
  EXPECT_EQ(kept.cost, astar.plan(start, goal).cost);
  test::expect_valid_path(graph, kept, start, goal);
  // (10, 9) is beside the diagonal: the move (9,9) -> (10,10) would cut its corner.
  dstar.set_cells(std::vector<CellChange>{{{10, 9, 0}, CellState::blocked}});
  const SearchResult moved = dstar.plan();
  EXPECT_EQ(moved.cost, astar.plan(start, goal).cost);
  test::expect_valid_path(graph, moved, start, goal);
  EXPECT_NE(moved.path, kept.path);
}

TEST(DStarLite, GoalCutOffThenReopened) {
  GridGraph graph({10, 10, 1}, Connectivity::eight);
  const Cell start{0, 0, 0}, goal{8, 8, 0};
  DStarLite dstar(graph, start, goal);
  EXPECT_EQ(dstar.plan().status, SearchStatus::found);
  std::vector<CellChange> ring;
  for (int x = 7; x <= 9; ++x)
    for (int y = 7; y <= 9; ++y)
      if (Cell{x, y, 0} != goal) ring.push_back({{x, y, 0}, CellState::blocked});
  dstar.set_cells(ring);
  const SearchResult cut = dstar.plan();
  EXPECT_EQ(cut.status, SearchStatus::no_path);
  EXPECT_EQ(to_cells(cut.cost), -1.0);
  dstar.set_cells(std::vector<CellChange>{{{7, 8, 0}, CellState::free}});
  const SearchResult reopened = dstar.plan();
  EXPECT_EQ(reopened.cost, AStar(graph).plan(start, goal).cost);
  // Unknown <-> free is no change at all.
  dstar.set_cells(std::vector<CellChange>{{{3, 3, 0}, CellState::unknown}});
  EXPECT_EQ(dstar.plan().expansions, 0);
}

TEST(DStarLite, ResetReusesTheSearch) {
  GridGraph graph({20, 20, 1}, Connectivity::eight);
  Rng rng(11);
  test::fill_random(graph, rng, 0.2);
  DStarLite dstar(graph, {0, 0, 0}, {0, 0, 0});
  AStar astar(graph);
  for (int i = 0; i < 10; ++i) {
    const Cell start = test::random_open_cell(graph, rng), goal = test::random_open_cell(graph, rng);
    dstar.reset(start, goal);
    EXPECT_EQ(dstar.plan().cost, astar.plan(start, goal).cost);
  }
}

// LPA*: fixed start and goal, batches of changes anywhere in the map.
TEST(LpaStar, MatchesAStarAfterEveryBatchOfChanges) {
  int found = 0;
  for (const Setting& setting : {kFlat, kCube, Setting{Connectivity::four, {24, 20, 1}, 0.2},
                                 Setting{Connectivity::six, {12, 10, 6}, 0.2}}) {
    for (std::uint64_t seed = 300; seed < 325; ++seed) {
      GridGraph graph(setting.size, setting.connectivity);
      Rng rng(seed);
      test::fill_random(graph, rng, setting.blocked);
      const Cell start = test::random_open_cell(graph, rng), goal = test::random_open_cell(graph, rng);
      LpaStar lpa(graph, start, goal);
      AStar astar(graph);
      for (int replan = 0; replan < 15; ++replan) {
        const SearchResult l = lpa.plan();
        const SearchResult a = astar.plan(start, goal);
        SCOPED_TRACE(std::string(to_string(setting.connectivity)) + " seed " + std::to_string(seed));
        ASSERT_EQ(l.status, a.status);
        if (l.status == SearchStatus::found) {
          ++found;
          EXPECT_EQ(l.cost, a.cost);
          test::expect_valid_path(graph, l, start, goal);
        }
        std::vector<CellChange> changes;
        for (int i = 0; i < 6; ++i) {
          const Cell c = test::random_cell(graph, rng);
          if (c != start && c != goal) changes.push_back({c, rng.bernoulli(0.6) ? CellState::blocked : CellState::free});
        }
        lpa.set_cells(changes);
      }
    }
  }
  EXPECT_GT(found, 800);
}

}  // namespace
}  // namespace campo::grid
