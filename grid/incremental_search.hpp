#pragma once
/// The engine shared by LPA* and D* Lite (internal to grid/): LPA* in the
/// optimized form of Koenig & Likhachev 2002 (D* Lite, Fig. 4), from a fixed
/// `source` (rhs = 0) towards a `target` that may move, with the key modifier
/// k_m. LPA* is this with source = start, target = goal; D* Lite is this with
/// source = goal, target = the moving start.
///
/// Keys are [min(g, rhs) + h(s, target) + k_m; min(g, rhs)], ties to the
/// smaller CellId. When g(u) drops, each neighbour s only takes
/// rhs(s) = min(rhs(s), c(s, u) + g(u)); rhs(s) is recomputed over all of s's
/// neighbours only when g(u) rises and rhs(s) came through u, or when a map
/// change touches s. The graph is undirected, so predecessors are neighbours.
#include <cstdint>
#include <span>
#include <vector>

#include "grid/grid_graph.hpp"
#include "grid/priority_queue.hpp"
#include "grid/search_result.hpp"

namespace campo::grid {

class IncrementalSearch {
 public:
  /// The graph must outlive this; change it only through set_cells().
  IncrementalSearch(GridGraph& graph, const Cell& source, const Cell& target);

  /// Starts over for a new source and target on the current map (O(cells)).
  void reset(const Cell& source, const Cell& target);

  /// Moves the target; k_m grows by h(previous target, target) at the next compute().
  void set_target(const Cell& target);

  /// Applies map changes to the graph and updates the cells whose moves they
  /// affect (each changed cell and the cells around it).
  void set_cells(std::span<const CellChange> changes);

  /// Brings the search up to date and returns the cheapest path from the
  /// target to the source (target first), with the expansions of this call.
  /// When nothing was expanded, the target lies on the last path and no map
  /// change touched a cell of it, that path's rest is returned without
  /// tracing: no g changed and no move out of a path cell did, so tracing
  /// would step exactly the same way.
  SearchResult compute();

  const GridGraph& graph() const { return graph_; }
  const Cell& source() const { return source_cell_; }
  const Cell& target() const { return target_cell_; }

 private:
  Key key(CellId s) const;
  /// Queues s if it is locally inconsistent (g != rhs), else dequeues it.
  void update_vertex(CellId s);
  /// min over neighbours v of c(s, v) + g(v).
  Cost best_rhs(CellId s) const;
  void expand(CellId u);
  SearchResult trace_path();
  /// The last path from the target on, if still valid (see compute()).
  bool reuse_path(SearchResult& result) const;

  GridGraph& graph_;
  Cell source_cell_;
  Cell target_cell_;
  CellId source_ = 0;
  CellId target_ = 0;
  CellId last_target_ = 0;  ///< target when k_m was last updated
  Cost km_ = 0;
  std::vector<Cost> g_;
  std::vector<Cost> rhs_;
  IndexedHeap open_;
  std::int64_t expansions_ = 0;      ///< in the current compute()
  std::vector<CellId> changed_;          ///< scratch for set_cells()
  std::vector<std::uint32_t> visited_;   ///< stamp: rhs already updated in this set_cells()
  std::uint32_t visit_ = 0;
  // The last traced path (target first, source last) with each of its cells'
  // index in it, valid where on_path_ equals path_stamp_.
  std::vector<CellId> path_;
  std::vector<Cost> path_rest_cost_;  ///< cost from path_[i] to the source
  std::vector<std::uint32_t> on_path_;
  std::vector<std::int32_t> path_index_;
  std::uint32_t path_stamp_ = 0;
  bool path_valid_ = false;  ///< no change touched path_ since it was traced
};

}  // namespace campo::grid
