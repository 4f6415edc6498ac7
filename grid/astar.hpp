#pragma once
/// A* on a GridGraph: exact (the heuristic is admissible and consistent, so
/// every node is expanded at most once). Ties in f go to the node nearer the
/// goal (smaller h), then to the smaller CellId.
#include <cstdint>
#include <vector>

#include "grid/grid_graph.hpp"
#include "grid/priority_queue.hpp"
#include "grid/search_result.hpp"

namespace campo::grid {

class AStar {
 public:
  /// Searches `graph` as it is at each plan() call; the graph must outlive this.
  explicit AStar(const GridGraph& graph);

  /// A cheapest path from `start` to `goal` (both inside the grid, else
  /// std::out_of_range). Reuses its buffers: no allocation after the first calls.
  SearchResult plan(const Cell& start, const Cell& goal);

 private:
  const GridGraph& graph_;
  IndexedHeap open_;
  // Per-cell data is valid only where its stamp equals the current search's,
  // so a new search needs no O(cells) reset.
  std::uint32_t search_ = 0;
  std::vector<std::uint32_t> reached_;  ///< stamp: g_ and parent_ hold this search's values
  std::vector<std::uint32_t> closed_;   ///< stamp: expanded in this search
  std::vector<Cost> g_;
  std::vector<CellId> parent_;
};

}  // namespace campo::grid
