#pragma once
/// Lifelong Planning A* (Koenig, Likhachev & Furcy 2004) between a fixed start
/// and goal: after map changes it repairs the previous search instead of
/// starting over. The same engine as D* Lite, searching forward.
#include <algorithm>
#include <span>

#include "grid/incremental_search.hpp"

namespace campo::grid {

class LpaStar {
 public:
  /// Plans on `graph`, which must outlive this and change only through set_cells().
  LpaStar(GridGraph& graph, const Cell& start, const Cell& goal) : search_(graph, start, goal) {}

  /// Starts over for a new start and goal (O(cells)); reuses the buffers.
  void reset(const Cell& start, const Cell& goal) { search_.reset(start, goal); }
  /// Map changes, applied to the graph.
  void set_cells(std::span<const CellChange> changes) { search_.set_cells(changes); }
  /// A cheapest path from start to goal on the current map.
  SearchResult plan() {
    SearchResult result = search_.compute();  // traced from the goal
    std::reverse(result.path.begin(), result.path.end());
    return result;
  }

  const Cell& start() const { return search_.source(); }
  const Cell& goal() const { return search_.target(); }
  const GridGraph& graph() const { return search_.graph(); }

 private:
  IncrementalSearch search_;  ///< source = start, target = goal
};

}  // namespace campo::grid
