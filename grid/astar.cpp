#include "grid/astar.hpp"

#include <algorithm>
#include <stdexcept>

namespace campo::grid {

AStar::AStar(const GridGraph& graph)
    : graph_(graph),
      open_(graph.id_count()),
      reached_(static_cast<std::size_t>(graph.id_count()), 0),
      closed_(static_cast<std::size_t>(graph.id_count()), 0),
      g_(static_cast<std::size_t>(graph.id_count()), kInfiniteCost),
      parent_(static_cast<std::size_t>(graph.id_count()), 0) {}

SearchResult AStar::plan(const Cell& start, const Cell& goal) {
  if (!graph_.contains(start) || !graph_.contains(goal)) throw std::out_of_range("A*: start or goal outside the grid");
  if (++search_ == 0) {
    // The stamp wrapped around: forget every old stamp once.
    std::fill(reached_.begin(), reached_.end(), 0);
    std::fill(closed_.begin(), closed_.end(), 0);
    search_ = 1;
  }
  open_.clear();
  SearchResult result;
  const CellId s = graph_.id(start), t = graph_.id(goal);
  if (!graph_.traversable(s) || !graph_.traversable(t)) return result;

  const auto reach = [&](CellId v, Cost g, CellId parent) {
    g_[v] = g;
    parent_[v] = parent;
    const Cost h = graph_.heuristic(v, t);
    open_.push_or_update(v, {g + h, h});
  };
  reached_[s] = search_;
  reach(s, 0, s);
  while (!open_.empty()) {
    const CellId u = open_.pop();
    closed_[u] = search_;
    ++result.expansions;
    if (u == t) break;
    graph_.for_each_neighbour(u, [&](CellId v, Cost c) {
      if (closed_[v] == search_) return;
      const Cost g = g_[u] + c;
      if (reached_[v] != search_ || g < g_[v]) {
        reached_[v] = search_;
        reach(v, g, u);
      }
    });
  }
  if (closed_[t] != search_) return result;

  result.status = SearchStatus::found;
  result.cost = g_[t];
  for (CellId v = t; v != s; v = parent_[v]) result.path.push_back(graph_.cell(v));
  result.path.push_back(start);
  std::reverse(result.path.begin(), result.path.end());
  return result;
}

}  // namespace campo::grid
