#include "planners/rrt_star.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "campo/random.hpp"
#include "planners/point_index.hpp"

namespace campo {
namespace {

/// 20 m x 20 m of 0.25 m cells with a wall across y = 10 (x < 14) and a
/// post field, so straight lines from start to goal are blocked.
OccupancyGrid walled_field() {
  OccupancyGrid grid;
  grid.cols = grid.rows = 80;
  grid.resolution_m = 0.25;
  grid.occupied.assign(80 * 80, 0);
  const auto occupy = [&](double x0, double y0, double x1, double y1) {
    for (int row = 0; row < grid.rows; ++row) {
      for (int col = 0; col < grid.cols; ++col) {
        const Eigen::Vector2d c = grid.centre_of(col, row);
        if (c.x() > x0 && c.x() < x1 && c.y() > y0 && c.y() < y1) grid.occupied[static_cast<std::size_t>(row) * 80 + col] = 1;
      }
    }
  };
  occupy(0.0, 9.5, 14.0, 10.5);
  occupy(15.0, 4.0, 16.0, 5.0);
  occupy(5.0, 14.0, 6.0, 17.0);
  return grid;
}

const Eigen::Vector2d kStart(2.0, 2.0);
const Eigen::Vector2d kGoal(3.0, 18.0);

double path_length(const std::vector<Eigen::Vector2d>& path) {
  double length = 0.0;
  for (std::size_t i = 1; i < path.size(); ++i) length += (path[i] - path[i - 1]).norm();
  return length;
}

void expect_valid_solution(const OccupancyGrid& grid, const RrtStarResult& result, const Eigen::Vector2d& start,
                           const Eigen::Vector2d& goal, const RrtStarConfig& config) {
  ASSERT_EQ(result.status, RrtStarStatus::solved);
  ASSERT_GE(result.path_m.size(), 2u);
  EXPECT_EQ(result.path_m.front(), start);
  EXPECT_LE((result.path_m.back() - goal).norm(), config.goal_radius_m);
  for (std::size_t i = 1; i < result.path_m.size(); ++i) {
    EXPECT_TRUE(grid.segment_free(result.path_m[i - 1], result.path_m[i])) << i;
    EXPECT_LE((result.path_m[i] - result.path_m[i - 1]).norm(), std::max(config.step_m, config.rewire_radius_m) + 1e-9);
  }
  EXPECT_NEAR(result.cost_m, path_length(result.path_m), 1e-9);
}

TEST(RrtStar, CostNeverIncreasesAndPathsStayCollisionFreeOverSeeds) {
  const OccupancyGrid grid = walled_field();
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    SCOPED_TRACE(seed);
    RrtStarConfig config;
    config.seed = seed;
    config.max_iterations = 3000;
    const RrtStarResult result = rrt_star(grid, kStart, kGoal, config);
    expect_valid_solution(grid, result, kStart, kGoal, config);
    ASSERT_EQ(result.best_cost_by_iteration.size(), 3000u);
    ASSERT_GT(result.first_solution_iteration, 0);
    for (int i = 0; i < 3000; ++i) {
      const double cost = result.best_cost_by_iteration[static_cast<std::size_t>(i)];
      EXPECT_EQ(std::isinf(cost), i + 1 < result.first_solution_iteration) << i;
      if (i > 0) {
        EXPECT_LE(cost, result.best_cost_by_iteration[static_cast<std::size_t>(i - 1)]) << i;
      }
    }
    EXPECT_EQ(result.best_cost_by_iteration.back(), result.cost_m);
    // Round the wall's east end: the shortest path into the goal region is
    // 14.15 + 1 + 13.31 - 1 = 27.46 m.
    EXPECT_GT(result.cost_m, 27.4);
    EXPECT_LT(result.cost_m, 29.5);
  }
}

TEST(RrtStar, MoreIterationsGiveCheaperPaths) {
  const OccupancyGrid grid = walled_field();
  double first_total = 0.0, final_total = 0.0;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    RrtStarConfig config;
    config.seed = seed;
    config.max_iterations = 4000;
    const RrtStarResult result = rrt_star(grid, kStart, kGoal, config);
    ASSERT_EQ(result.status, RrtStarStatus::solved);
    first_total += result.best_cost_by_iteration[static_cast<std::size_t>(result.first_solution_iteration - 1)];
    final_total += result.cost_m;
  }
  EXPECT_LT(final_total, first_total);
}

TEST(RrtStar, SameSeedSamePath) {
  const OccupancyGrid grid = walled_field();
  RrtStarConfig config;
  config.seed = 42;
  config.max_iterations = 1500;
  const RrtStarResult a = rrt_star(grid, kStart, kGoal, config);
  const RrtStarResult b = rrt_star(grid, kStart, kGoal, config);
  ASSERT_EQ(a.status, RrtStarStatus::solved);
  EXPECT_EQ(a.path_m, b.path_m);
  EXPECT_EQ(a.cost_m, b.cost_m);
  EXPECT_EQ(a.first_solution_iteration, b.first_solution_iteration);
  EXPECT_EQ(a.nodes, b.nodes);
  config.seed = 43;
  EXPECT_NE(rrt_star(grid, kStart, kGoal, config).path_m, a.path_m);
}

// The progress callback sees the iterations done every kRrtStarProgressEvery; it may stop the search
// (campo plan --time-limit), which then is the same search cut short. Watching changes nothing.
TEST(RrtStar, ProgressSeesEveryThousandIterationsAndMayStopTheSearch) {
  const OccupancyGrid grid = walled_field();
  RrtStarConfig config;
  config.seed = 42;
  config.max_iterations = 5000;
  const RrtStarResult full = rrt_star(grid, kStart, kGoal, config);
  std::vector<int> seen;
  const RrtStarResult watched = rrt_star(grid, kStart, kGoal, config, [&](int done) {
    seen.push_back(done);
    return true;
  });
  EXPECT_EQ(seen, (std::vector<int>{0, 1024, 2048, 3072, 4096}));
  EXPECT_FALSE(watched.stopped);
  EXPECT_EQ(watched.iterations, 5000);
  EXPECT_EQ(watched.path_m, full.path_m);
  EXPECT_EQ(watched.best_cost_by_iteration, full.best_cost_by_iteration);

  const RrtStarResult stopped = rrt_star(grid, kStart, kGoal, config, [](int done) { return done < 2048; });
  EXPECT_TRUE(stopped.stopped);
  EXPECT_EQ(stopped.iterations, 2048);
  ASSERT_EQ(stopped.best_cost_by_iteration.size(), 2048u);
  EXPECT_TRUE(std::equal(stopped.best_cost_by_iteration.begin(), stopped.best_cost_by_iteration.end(),
                         full.best_cost_by_iteration.begin()));
  if (stopped.status == RrtStarStatus::solved) EXPECT_EQ(stopped.cost_m, stopped.best_cost_by_iteration.back());
  // Stopped before the first iteration: no tree beyond the start.
  const RrtStarResult none = rrt_star(grid, kStart, kGoal, config, [](int) { return false; });
  EXPECT_TRUE(none.stopped);
  EXPECT_EQ(none.iterations, 0);
  EXPECT_EQ(none.nodes, 1u);
  EXPECT_EQ(none.status, RrtStarStatus::no_solution);
}

TEST(RrtStar, FixedRewiringRadiusAlsoConverges) {
  const OccupancyGrid grid = walled_field();
  RrtStarConfig config;
  config.rewire_radius_m = 3.0;
  config.max_iterations = 2000;
  const RrtStarResult result = rrt_star(grid, kStart, kGoal, config);
  expect_valid_solution(grid, result, kStart, kGoal, config);
  EXPECT_LT(result.cost_m, 29.5);
}

TEST(RrtStar, TypedStatusForImpossibleInput) {
  OccupancyGrid grid = walled_field();
  EXPECT_EQ(rrt_star(grid, {5.0, 10.0}, kGoal).status, RrtStarStatus::invalid_start);
  EXPECT_EQ(rrt_star(grid, kStart, {5.0, 15.0}).status, RrtStarStatus::invalid_goal);
  EXPECT_EQ(rrt_star(grid, kStart, {25.0, 5.0}).status, RrtStarStatus::invalid_goal);  // outside
  // Close the gap: the goal side is unreachable.
  for (int row = 0; row < grid.rows; ++row) {
    for (int col = 0; col < grid.cols; ++col) {
      const double y = grid.centre_of(col, row).y();
      if (y > 9.5 && y < 10.5) grid.occupied[static_cast<std::size_t>(row) * grid.cols + col] = 1;
    }
  }
  RrtStarConfig config;
  config.max_iterations = 500;
  const RrtStarResult blocked = rrt_star(grid, kStart, kGoal, config);
  EXPECT_EQ(blocked.status, RrtStarStatus::no_solution);
  EXPECT_TRUE(blocked.path_m.empty());
  EXPECT_EQ(blocked.first_solution_iteration, -1);
  EXPECT_EQ(blocked.iterations, 500);
  // Start already inside the goal region.
  const RrtStarResult there = rrt_star(grid, kStart, kStart + Eigen::Vector2d(0.5, 0.0));
  EXPECT_EQ(there.status, RrtStarStatus::solved);
  EXPECT_EQ(there.first_solution_iteration, 0);
  EXPECT_EQ(there.cost_m, 0.0);
  config.goal_bias = 1.5;
  EXPECT_THROW(rrt_star(grid, kStart, kGoal, config), std::invalid_argument);
  EXPECT_EQ(to_string(RrtStarStatus::no_solution), "no_solution");
}

TEST(RrtStar, MovingAiMapsBecomeOneMetreGrids) {
  const grid::MovingAiMap map =
      grid::read_movingai_map(std::string(CAMPO_SOURCE_DIR) + "/tests/data/movingai/arena.map");
  const OccupancyGrid grid = to_occupancy_grid(map);
  ASSERT_EQ(grid.cols, map.width);
  ASSERT_EQ(grid.rows, map.height);
  EXPECT_EQ(grid.resolution_m, 1.0);
  for (int y = 0; y < map.height; ++y) {
    for (int x = 0; x < map.width; ++x) {
      const Eigen::Vector2d centre = movingai_cell_centre(map, {x, y, 0});
      ASSERT_EQ(grid.is_occupied(centre), !map.is_passable(x, y)) << x << ", " << y;
    }
  }
  // The map's top row is the grid's north edge.
  EXPECT_TRUE(movingai_cell_centre(map, {0, 0, 0}).isApprox(Eigen::Vector2d(0.5, 48.5)));

  // A long arena problem (octile optimum 62.15 cells); any-angle paths may be shorter.
  const Eigen::Vector2d start = movingai_cell_centre(map, {1, 7, 0});
  const Eigen::Vector2d goal = movingai_cell_centre(map, {47, 46, 0});
  RrtStarConfig config;
  config.max_iterations = 4000;
  const RrtStarResult result = rrt_star(grid, start, goal, config);
  expect_valid_solution(grid, result, start, goal, config);
  EXPECT_GT(result.cost_m, (goal - start).norm() - config.goal_radius_m);
  EXPECT_LT(result.cost_m, 62.15 * 1.1);
}

/// A free corridor one cell wide and `length` cells long (1 m cells).
OccupancyGrid corridor(int length) {
  OccupancyGrid grid;
  grid.cols = 1;
  grid.rows = length;
  grid.resolution_m = 1.0;
  grid.occupied.assign(static_cast<std::size_t>(length), 0);
  return grid;
}

// Issue 16: on a 1 x 4096 map the old bucket lattice scanned every bucket
// between a sample and the tree (cubic in the extent). The work of an
// iteration must now be bounded by the tree size and the step alone.
TEST(RrtStar, WorkPerIterationDoesNotGrowWithTheMapsExtent) {
  RrtStarConfig config;
  config.step_m = 5.0;
  config.max_iterations = 4000;
  const auto run = [&](int length) {
    const OccupancyGrid grid = corridor(length);
    return rrt_star(grid, {0.5, 0.5}, {0.5, length - 0.5}, config);
  };
  const RrtStarResult small = run(64);
  const RrtStarResult large = run(4096);
  for (const RrtStarResult* result : {&small, &large}) {
    const RrtStarWork& work = result->work;
    // Rewiring candidates: at most k(n) for the final tree size.
    EXPECT_LE(work.max_neighbours, max_neighbours(result->nodes));
    // One steering check plus one connection and one rewiring check per
    // candidate, each walking at most 2 (|d|_1 + 2) cells of an edge no
    // longer than the step: 2 (5 sqrt(2) + 2) < 19 cells.
    EXPECT_LE(work.max_cells_per_iteration, (2 * max_neighbours(result->nodes) + 1) * 19);
    EXPECT_LE(work.segment_checks, static_cast<std::uint64_t>(config.max_iterations) * (2 * max_neighbours(result->nodes) + 1));
    // Nearest and near queries over nanoflann's k-d trees of at most
    // log2(n) + 1 sizes and a buffer of fewer than PointIndex::kBufferSize
    // (64) points: far fewer distances than nodes (n about 3,900 here).
    // Generous: 10 (log2 n)^2 distances (two coordinates each) per iteration.
    const double log_n = std::log2(static_cast<double>(result->nodes));
    EXPECT_LE(static_cast<double>(work.index_query_reads), 2 * 10.0 * log_n * log_n * config.max_iterations);
    // Rebuilding as nodes arrive: each node lands in about log2 n trees in
    // turn, each build reading it O(log n) times (about 0.9 (log2 n)^2 reads
    // a node here). Generous: 4 (log2 n)^2 per node.
    EXPECT_LE(static_cast<double>(work.index_build_reads), 4.0 * log_n * log_n * result->nodes);
  }
  // 64 times longer, yet not more work per node of the tree than a few times
  // the short corridor's (the old lattice: about 64^3 times more).
  const auto per_node = [](const RrtStarResult& r) {
    return static_cast<double>(r.work.index_query_reads + r.work.index_build_reads) / r.nodes;
  };
  EXPECT_LT(per_node(large), 4.0 * per_node(small) + 100.0);

  // And still right: the only path is the corridor's centre line, 4095 m.
  ASSERT_EQ(large.status, RrtStarStatus::solved);
  EXPECT_GE(large.cost_m, 4095.0 - config.goal_radius_m - 1e-9);
  EXPECT_LT(large.cost_m, 4095.0 * 1.001);
  const OccupancyGrid grid = corridor(4096);
  for (std::size_t i = 1; i < large.path_m.size(); ++i) EXPECT_TRUE(grid.segment_free(large.path_m[i - 1], large.path_m[i]));
}

TEST(RrtStar, NeighbourCapBoundsAFixedRadiusCoveringTheWholeTree) {
  const OccupancyGrid grid = walled_field();
  RrtStarConfig config;
  config.rewire_radius_m = 1000.0;  // every node a neighbour of every other one
  config.max_iterations = 1500;
  const RrtStarResult result = rrt_star(grid, kStart, kGoal, config);
  EXPECT_LE(result.work.max_neighbours, max_neighbours(result.nodes));
  // The cap binds: the tree has far more nodes than k(n).
  EXPECT_GT(result.nodes, 10 * max_neighbours(result.nodes));
  ASSERT_EQ(result.status, RrtStarStatus::solved);
  EXPECT_GT(result.cost_m, 27.4);
  EXPECT_LT(result.cost_m, 29.5);
}

TEST(RrtStar, KOfNFollowsTheFormula) {
  // ceil(3 e ln n): 3 e = 8.1548...
  EXPECT_EQ(max_neighbours(1), 6u);  // n taken as at least 2: 8.15 ln 2 = 5.65
  EXPECT_EQ(max_neighbours(100), 38u);  // 8.1548 x 4.6052 = 37.55
  EXPECT_EQ(max_neighbours(1'000'000), 113u);  // 8.1548 x 13.8155 = 112.66
}

TEST(RrtStar, LengthsOutsideTheirLimitsAreRefused) {
  const auto refused = [](auto change, const std::string& what) {
    RrtStarConfig config;
    change(config);
    try {
      validate(config);
      ADD_FAILURE() << "accepted: " << what;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  refused([](RrtStarConfig& c) { c.step_m = 1e-4; }, "step must be in [0.001, 1000000] m");
  refused([](RrtStarConfig& c) { c.step_m = 1e300; }, "step must be in [0.001, 1000000] m");
  refused([](RrtStarConfig& c) { c.step_m = std::nan(""); }, "step must be in");
  refused([](RrtStarConfig& c) { c.rewire_radius_m = 1e300; }, "rewire_radius must be in [0, 1000000] m");
  refused([](RrtStarConfig& c) { c.rewire_gamma_m = 2e6; }, "rewire_gamma must be in [0, 1000000] m");
  RrtStarConfig edge;
  edge.step_m = kMinStepM;
  edge.rewire_radius_m = kMaxLengthM;
  EXPECT_NO_THROW(validate(edge));
}

// A step far beyond the map acts as its diagonal: edges never leave the grid
// and each check walks at most the cells of the map's diagonal.
TEST(RrtStar, HugeStepActsAsTheGridsDiagonal) {
  const OccupancyGrid grid = walled_field();
  RrtStarConfig config;
  config.step_m = kMaxLengthM;
  config.max_iterations = 500;
  const RrtStarResult result = rrt_star(grid, kStart, kGoal, config);
  ASSERT_EQ(result.status, RrtStarStatus::solved);
  // 80 x 80 cells: at most 2 (160 + 2) cells per check.
  EXPECT_LE(result.work.max_cells_per_iteration, (2 * max_neighbours(result.nodes) + 1) * 324);
}

// PointIndex (RRT*'s nearest and near queries) against a brute-force scan of
// every point: the buffer alone (fewer than kBufferSize points), the buffer
// and nanoflann's trees together, right at and past each flush, with the
// k(n) cap binding or not, and many exact ties (points on a lattice, queries
// on lattice points and cell centres), which must go to the lower id.
struct BruteForce {
  const std::vector<Eigen::Vector2d>& points;

  /// (squared distance, id) of every point, nearest first, then lower id.
  std::vector<std::pair<double, int>> ranked(const Eigen::Vector2d& q) const {
    std::vector<std::pair<double, int>> out;
    for (std::size_t i = 0; i < points.size(); ++i) {
      out.emplace_back((q - points[i]).squaredNorm(), static_cast<int>(i));
    }
    std::sort(out.begin(), out.end());
    return out;
  }
  int nearest(const Eigen::Vector2d& q) const { return points.empty() ? -1 : ranked(q).front().second; }
  std::vector<int> nearest_within(const Eigen::Vector2d& q, double radius, std::size_t k) const {
    std::vector<int> ids;
    for (const auto& [d2, id] : ranked(q)) {
      if (ids.size() == k || std::sqrt(d2) > radius) break;
      ids.push_back(id);
    }
    std::sort(ids.begin(), ids.end());
    return ids;
  }
};

void expect_index_matches_brute_force(const std::vector<Eigen::Vector2d>& points, PointIndex& index,
                                      const std::vector<Eigen::Vector2d>& queries) {
  const BruteForce brute{points};
  std::vector<PointIndex::Neighbour> near;
  for (const Eigen::Vector2d& q : queries) {
    SCOPED_TRACE(::testing::Message() << points.size() << " points, query (" << q.x() << ", " << q.y() << ")");
    ASSERT_EQ(index.nearest(q), brute.nearest(q));
    for (const double radius : {0.0, 0.5, 1.0, 2.5, std::numeric_limits<double>::infinity()}) {
      for (const std::size_t k : {std::size_t{0}, std::size_t{1}, std::size_t{3}, std::size_t{40}, points.size() + 1}) {
        index.nearest_within(q, radius, k, near);
        std::vector<int> ids;
        for (const PointIndex::Neighbour& n : near) {
          ids.push_back(n.id);
          ASSERT_DOUBLE_EQ(n.distance_m, (q - points[static_cast<std::size_t>(n.id)]).norm()) << n.id;
        }
        ASSERT_EQ(ids, brute.nearest_within(q, radius, k)) << "radius " << radius << ", k " << k;
      }
    }
  }
}

TEST(RrtStarPointIndex, MatchesABruteForceScanAsRandomPointsArrive) {
  Rng rng(7);
  std::vector<Eigen::Vector2d> points{{5.0, 5.0}};
  PointIndex index(points, 1000);
  std::vector<Eigen::Vector2d> queries;
  for (int i = 0; i < 12; ++i) queries.emplace_back(rng.uniform(-2.0, 12.0), rng.uniform(-2.0, 12.0));
  queries.push_back(points.front());
  // Sizes on both sides of every flush into nanoflann, up to 12 of them.
  const std::size_t buffer = PointIndex::kBufferSize;
  const std::vector<std::size_t> checked{1, 2, buffer - 1, buffer, buffer + 1, 2 * buffer - 1, 2 * buffer,
                                         3 * buffer + 5, 8 * buffer, 12 * buffer + buffer / 2};
  for (std::size_t size = 1; size <= checked.back(); ++size) {
    if (size > 1) {
      points.emplace_back(rng.uniform(0.0, 10.0), rng.uniform(0.0, 10.0));
      index.add(static_cast<int>(points.size()) - 1);
    }
    if (std::find(checked.begin(), checked.end(), size) != checked.end()) {
      expect_index_matches_brute_force(points, index, queries);
    }
  }
  EXPECT_GT(index.build_reads(), 0u);
  EXPECT_GT(index.query_reads(), 0u);
}

TEST(RrtStarPointIndex, TiesGoToTheLowerIdInTheBufferAndTheTrees) {
  // Every point of a 6 x 6 lattice of 1 m, three times over in shuffled
  // orders: each query at a lattice point or a cell centre ties 3 to 12 points.
  Rng rng(11);
  std::vector<Eigen::Vector2d> lattice;
  for (int x = 0; x < 6; ++x) {
    for (int y = 0; y < 6; ++y) lattice.emplace_back(x, y);
  }
  std::vector<Eigen::Vector2d> points;
  for (int copy = 0; copy < 3; ++copy) {
    for (std::size_t i = lattice.size() - 1; i > 0; --i) {
      std::swap(lattice[i], lattice[static_cast<std::size_t>(rng.uniform_int(0, static_cast<std::int64_t>(i)))]);
    }
    points.insert(points.end(), lattice.begin(), lattice.end());
  }
  std::vector<Eigen::Vector2d> queries{{2.0, 3.0}, {2.5, 2.5}, {0.0, 0.0}, {5.5, 0.5}, {-1.0, 2.5}, {2.5, 7.0}};
  std::vector<Eigen::Vector2d> growing;
  growing.reserve(points.size());
  growing.push_back(points.front());
  PointIndex index(growing, points.size());
  for (std::size_t i = 1; i < points.size(); ++i) {
    growing.push_back(points[i]);
    index.add(static_cast<int>(i));
    if (i + 1 == 30 || i + 1 == PointIndex::kBufferSize + 10 || i + 1 == points.size()) {
      expect_index_matches_brute_force(growing, index, queries);
    }
  }
  // Indexing points given up front: the same answers.
  PointIndex at_once(points, points.size());
  expect_index_matches_brute_force(points, at_once, queries);
}

TEST(RrtStarPointIndex, TakesOnlyTheArraysNewestPointUpToItsMaximum) {
  std::vector<Eigen::Vector2d> points{{0.0, 0.0}, {1.0, 0.0}};
  PointIndex index(points, 10);
  points.emplace_back(2.0, 0.0);
  EXPECT_THROW(index.add(1), std::logic_error);
  EXPECT_THROW(index.add(3), std::logic_error);
  index.add(2);
  EXPECT_EQ(index.nearest({1.9, 0.0}), 2);
  // No more points than it was made for.
  PointIndex three(points, 3);
  points.emplace_back(3.0, 0.0);
  EXPECT_THROW(three.add(3), std::logic_error);
  EXPECT_THROW(PointIndex(points, 3), std::logic_error);
  std::vector<Eigen::Vector2d> none;
  PointIndex empty(none, 1);
  EXPECT_EQ(empty.nearest({0.0, 0.0}), -1);
}

}  // namespace
}  // namespace campo
