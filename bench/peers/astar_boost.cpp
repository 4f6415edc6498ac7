// campo's grid A* against Boost Graph's astar_search on MovingAI's maze512-32-9
// (docs/PERFORMANCE.md, "Peers"): every 40th problem of its scenario, octile
// moves without corner cutting as MovingAI defines them. campo plans on its
// GridGraph; Boost searches an adjacency_list of the passable cells with the
// same moves and costs and the octile heuristic, stopped at the goal. Both
// costs are checked against the scenario's optimum. Repetitions interleave in
// one process; the figure is problems per second, median of the repetitions.
//
//   build/campo_peer_astar [--repetitions K]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/astar_search.hpp>

#include "bench/peers/peer_record.hpp"
#include "grid/astar.hpp"
#include "grid/movingai.hpp"

namespace campo {
namespace {

using Clock = std::chrono::steady_clock;
using BoostGraph = boost::adjacency_list<boost::vecS, boost::vecS, boost::directedS, boost::no_property,
                                         boost::property<boost::edge_weight_t, double>>;
using Vertex = BoostGraph::vertex_descriptor;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// The map's octile graph: straight moves cost 1, diagonal ones sqrt(2), a
// diagonal only where both cells beside it are passable (no corner cutting).
BoostGraph octile_graph(const grid::MovingAiMap& map) {
  BoostGraph g(static_cast<std::size_t>(map.width) * map.height);
  const auto free = [&](int x, int y) {
    return x >= 0 && y >= 0 && x < map.width && y < map.height && map.is_passable(x, y);
  };
  for (int y = 0; y < map.height; ++y) {
    for (int x = 0; x < map.width; ++x) {
      if (!free(x, y)) continue;
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          if ((dx == 0 && dy == 0) || !free(x + dx, y + dy)) continue;
          if (dx != 0 && dy != 0 && !(free(x + dx, y) && free(x, y + dy))) continue;
          boost::add_edge(static_cast<Vertex>(y * map.width + x), static_cast<Vertex>((y + dy) * map.width + x + dx),
                          dx != 0 && dy != 0 ? std::sqrt(2.0) : 1.0, g);
        }
      }
    }
  }
  return g;
}

struct FoundGoal {};

class StopAtGoal : public boost::default_astar_visitor {
 public:
  explicit StopAtGoal(Vertex goal) : goal_(goal) {}
  void examine_vertex(Vertex v, const BoostGraph&) const {
    if (v == goal_) throw FoundGoal{};
  }

 private:
  Vertex goal_;
};

class Octile : public boost::astar_heuristic<BoostGraph, double> {
 public:
  Octile(int width, Vertex goal)
      : width_(width), gx_(static_cast<int>(goal) % width), gy_(static_cast<int>(goal) / width) {}
  double operator()(Vertex v) const {
    const double dx = std::abs(static_cast<int>(v) % width_ - gx_), dy = std::abs(static_cast<int>(v) / width_ - gy_);
    return std::max(dx, dy) + (std::sqrt(2.0) - 1.0) * std::min(dx, dy);
  }

 private:
  int width_, gx_, gy_;
};

struct BoostSearch {
  const BoostGraph& graph;
  int width;
  std::vector<Vertex> predecessors;
  std::vector<double> distances;

  double cost(const grid::Cell& start, const grid::Cell& goal) {
    const Vertex s = static_cast<Vertex>(start.y * width + start.x), t = static_cast<Vertex>(goal.y * width + goal.x);
    try {
      boost::astar_search(
          graph, s, Octile(width, t),
          boost::predecessor_map(predecessors.data()).distance_map(distances.data()).visitor(StopAtGoal(t)));
    } catch (const FoundGoal&) {
      return distances[t];
    }
    return -1.0;
  }
};

}  // namespace
}  // namespace campo

int main(int argc, char** argv) {
  int repetitions = 5;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--repetitions") == 0) repetitions = std::stoi(argv[i + 1]);
  }
  try {
    using namespace campo;
    const std::string dir = std::string(CAMPO_SOURCE_DIR) + "/tests/data/movingai/";
    const grid::MovingAiMap map = grid::read_movingai_map(dir + "maze512-32-9.map");
    const auto all = grid::read_movingai_scenario(dir + "maze512-32-9.map.scen");
    std::vector<grid::MovingAiProblem> problems;
    for (std::size_t i = 0; i < all.size(); i += 40) problems.push_back(all[i]);
    const grid::GridGraph graph = grid::to_grid_graph(map);
    grid::AStar astar(graph);
    const BoostGraph boost_graph = octile_graph(map);
    BoostSearch boost_search{boost_graph, map.width, std::vector<Vertex>(boost::num_vertices(boost_graph)),
                             std::vector<double>(boost::num_vertices(boost_graph))};
    std::vector<double> ours, theirs;
    for (int r = 0; r < repetitions; ++r) {
      auto start = Clock::now();
      for (const auto& p : problems) {
        const double cost = grid::to_cells(astar.plan(p.start, p.goal).cost);
        if (r == 0 && !grid::matches_optimal(cost, p.optimal_length)) throw std::runtime_error("campo: not optimal");
      }
      ours.push_back(problems.size() / std::chrono::duration<double>(Clock::now() - start).count());
      start = Clock::now();
      for (const auto& p : problems) {
        const double cost = boost_search.cost(p.start, p.goal);
        if (r == 0 && !grid::matches_optimal(cost, p.optimal_length)) throw std::runtime_error("Boost: not optimal");
      }
      theirs.push_back(problems.size() / std::chrono::duration<double>(Clock::now() - start).count());
    }
    const double a = median(ours), b = median(theirs);
    if (campo::peers::json_requested(argc, argv)) {
      campo::peers::print_json({"astar/maze512-32-9",
                                "A* on maze512-32-9, " + std::to_string(problems.size()) + " problems (every 40th)", a, b,
                                "problems/s",
                                "Boost Graph " + std::to_string(BOOST_VERSION / 100000) + "." +
                                    std::to_string(BOOST_VERSION / 100 % 1000) + " astar_search",
                                "optimal costs checked"});
      return 0;
    }
    std::printf("| A* on maze512-32-9, %zu problems (every 40th) | campo %.1f problems/s | Boost Graph %d.%d "
                "astar_search %.1f problems/s | %.2fx | optimal costs checked |\n",
                problems.size(), a, BOOST_VERSION / 100000, BOOST_VERSION / 100 % 1000, b, a / b);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "campo_peer_astar: %s\n", e.what());
    return 1;
  }
  return 0;
}
