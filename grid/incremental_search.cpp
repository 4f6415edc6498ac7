#include "grid/incremental_search.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace campo::grid {

namespace {

CellId checked_id(const GridGraph& graph, const Cell& cell, const char* what) {
  if (!graph.contains(cell)) throw std::out_of_range(std::string("incremental search: ") + what + " outside the grid");
  return graph.id(cell);
}

}  // namespace

IncrementalSearch::IncrementalSearch(GridGraph& graph, const Cell& source, const Cell& target)
    : graph_(graph), open_(graph.id_count()) {
  reset(source, target);
}

void IncrementalSearch::reset(const Cell& source, const Cell& target) {
  source_ = checked_id(graph_, source, "source");
  target_ = checked_id(graph_, target, "target");
  source_cell_ = source;
  target_cell_ = target;
  last_target_ = target_;
  km_ = 0;
  g_.assign(static_cast<std::size_t>(graph_.id_count()), kInfiniteCost);
  rhs_.assign(static_cast<std::size_t>(graph_.id_count()), kInfiniteCost);
  visited_.assign(static_cast<std::size_t>(graph_.id_count()), 0);
  visit_ = 0;
  on_path_.assign(static_cast<std::size_t>(graph_.id_count()), 0);
  path_index_.assign(static_cast<std::size_t>(graph_.id_count()), 0);
  path_stamp_ = 0;
  path_valid_ = false;
  path_.clear();
  open_.clear();
  rhs_[source_] = 0;
  update_vertex(source_);
}

void IncrementalSearch::set_target(const Cell& target) {
  target_ = checked_id(graph_, target, "target");
  target_cell_ = target;
}

void IncrementalSearch::set_cells(std::span<const CellChange> changes) {
  // Apply every change first, so each recomputed rhs sees the final map.
  changed_.clear();
  bool any_freed = false;
  for (const CellChange& change : changes) {
    const CellId b = checked_id(graph_, change.cell, "changed cell");
    const bool was_traversable = graph_.traversable(b);
    graph_.set_state(change.cell, change.state);
    // unknown <-> free changes no cost.
    if (graph_.traversable(b) == was_traversable) continue;
    changed_.push_back(b);
    any_freed = any_freed || !was_traversable;
  }
  if (changed_.empty()) return;
  // A changed cell alters the moves of the cells around it only (a move's box
  // lies within one step of both ends), so only their rhs can change; each
  // is visited once however many changed cells it touches.
  if (++visit_ == 0) {
    std::fill(visited_.begin(), visited_.end(), 0);
    visit_ = 1;
  }
  for (const CellId b : changed_) {
    for (const CellId offset : graph_.around_offsets()) {
      const CellId s = b + offset;
      if (on_path_[s] == path_stamp_) path_valid_ = false;
      if (s == source_ || visited_[s] == visit_) continue;
      visited_[s] = visit_;
      // When cells were only blocked, costs only rose: an infinite rhs stays infinite.
      if (!any_freed && rhs_[s] >= kInfiniteCost) continue;
      const Cost rhs = best_rhs(s);
      if (rhs == rhs_[s]) continue;
      rhs_[s] = rhs;
      update_vertex(s);
    }
  }
}

SearchResult IncrementalSearch::compute() {
  // Keys queued for the previous target stay lower bounds after adding h(previous, new) to k_m.
  if (target_ != last_target_) {
    km_ += graph_.heuristic(last_target_, target_);
    last_target_ = target_;
  }
  expansions_ = 0;
  // Blocked ends: no path, and no point searching the whole reachable graph to
  // find out. The queue keeps every inconsistent cell for a later call.
  if (!graph_.traversable(target_) || !graph_.traversable(source_)) return {};
  while (!open_.empty() && (open_.top_key() < key(target_) || rhs_[target_] > g_[target_])) {
    const CellId u = open_.top();
    const Key fresh = key(u);
    if (open_.top_key() < fresh) {
      // Queued under an older k_m: requeue with the current key.
      open_.push_or_update(u, fresh);
    } else {
      expand(u);
    }
  }
  SearchResult result;
  if (reuse_path(result)) return result;
  return trace_path();
}

bool IncrementalSearch::reuse_path(SearchResult& result) const {
  if (expansions_ != 0 || !path_valid_ || on_path_[target_] != path_stamp_) return false;
  result.expansions = 0;
  result.status = SearchStatus::found;
  const auto first = static_cast<std::size_t>(path_index_[target_]);
  result.cost = path_rest_cost_[first];
  for (std::size_t i = first; i < path_.size(); ++i) {
    result.path.push_back(graph_.cell(path_[i]));
  }
  return true;
}

Key IncrementalSearch::key(CellId s) const {
  const Cost m = std::min(g_[s], rhs_[s]);
  if (m >= kInfiniteCost) return {kInfiniteCost, kInfiniteCost};
  return {m + graph_.heuristic(s, target_) + km_, m};
}

void IncrementalSearch::update_vertex(CellId s) {
  if (g_[s] != rhs_[s]) {
    open_.push_or_update(s, key(s));
  } else {
    open_.remove(s);
  }
}

Cost IncrementalSearch::best_rhs(CellId s) const {
  // c + kInfiniteCost stays above kInfiniteCost without overflow, so no test is needed.
  Cost best = kInfiniteCost;
  graph_.for_each_neighbour(s, [&](CellId v, Cost c) { best = std::min(best, c + g_[v]); });
  return best;
}

void IncrementalSearch::expand(CellId u) {
  ++expansions_;
  if (g_[u] > rhs_[u]) {
    // Overconsistent: g(u) drops to rhs(u); neighbours may now do better through u.
    // (The source never improves: its rhs is 0.)
    g_[u] = rhs_[u];
    open_.remove(u);
    const Cost gu = g_[u];
    graph_.for_each_neighbour(u, [&](CellId s, Cost c) {
      if (c + gu < rhs_[s]) {
        rhs_[s] = c + gu;
        update_vertex(s);
      }
    });
  } else {
    // Underconsistent: g(u) rises to infinity; only neighbours whose rhs came
    // through u need their rhs recomputed.
    const Cost g_old = g_[u];
    g_[u] = kInfiniteCost;
    graph_.for_each_neighbour(u, [&](CellId s, Cost c) {
      if (s != source_ && rhs_[s] == c + g_old) {
        rhs_[s] = best_rhs(s);
        update_vertex(s);
      }
    });
    update_vertex(u);
  }
}

SearchResult IncrementalSearch::trace_path() {
  SearchResult result;
  result.expansions = expansions_;
  // A new stamp forgets the previous path's cells.
  if (++path_stamp_ == 0) {
    std::fill(on_path_.begin(), on_path_.end(), 0);
    path_stamp_ = 1;
  }
  path_.clear();
  path_rest_cost_.clear();
  path_valid_ = false;
  if (rhs_[target_] >= kInfiniteCost) return result;

  // From the target, always step to the neighbour v minimizing c + g(v)
  // (first in move order on ties); this reaches the source along a cheapest path.
  result.status = SearchStatus::found;
  result.cost = 0;
  result.path.push_back(target_cell_);
  for (CellId s = target_; s != source_;) {
    CellId next = -1;
    Cost best = kInfiniteCost, step = 0;
    graph_.for_each_neighbour(s, [&](CellId v, Cost c) {
      if (c + g_[v] < best) {
        best = c + g_[v];
        next = v;
        step = c;
      }
    });
    if (next < 0 || result.path.size() > static_cast<std::size_t>(graph_.id_count())) {
      throw std::logic_error("incremental search: no consistent path to trace");
    }
    result.cost += step;
    path_rest_cost_.push_back(step);  // the step costs, summed from the end below
    result.path.push_back(graph_.cell(next));
    s = next;
  }
  path_rest_cost_.push_back(0);
  for (std::size_t i = path_rest_cost_.size() - 1; i-- > 0;) path_rest_cost_[i] += path_rest_cost_[i + 1];
  for (const Cell& c : result.path) {
    const CellId id = graph_.id(c);
    on_path_[id] = path_stamp_;
    path_index_[id] = static_cast<std::int32_t>(path_.size());
    path_.push_back(id);
  }
  path_valid_ = true;
  return result;
}

}  // namespace campo::grid
