#pragma once
/// D* Lite (Koenig & Likhachev 2002, optimized version with the key modifier
/// k_m): searches from the goal to the start, so when the start moves along
/// the path and a few cells change near it, replanning only repairs the part
/// of the search the changes touch.
#include <span>

#include "grid/incremental_search.hpp"

namespace campo::grid {

class DStarLite {
 public:
  /// Plans on `graph`, which must outlive this and change only through set_cells().
  DStarLite(GridGraph& graph, const Cell& start, const Cell& goal) : search_(graph, goal, start) {}

  /// Starts over for a new start and goal (O(cells)); reuses the buffers.
  void reset(const Cell& start, const Cell& goal) { search_.reset(goal, start); }
  /// The vehicle moved: plan from here next time.
  void move_start(const Cell& start) { search_.set_target(start); }
  /// Map changes (e.g. cells a LIDAR sweep found blocked), applied to the graph.
  void set_cells(std::span<const CellChange> changes) { search_.set_cells(changes); }
  /// A cheapest path from the current start to the goal on the current map.
  SearchResult plan() { return search_.compute(); }

  const Cell& start() const { return search_.target(); }
  const Cell& goal() const { return search_.source(); }
  const GridGraph& graph() const { return search_.graph(); }

 private:
  IncrementalSearch search_;  ///< source = goal, target = start
};

}  // namespace campo::grid
