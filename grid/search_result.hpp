#pragma once
/// What every grid search returns.
#include <cstdint>
#include <string_view>
#include <vector>

#include "grid/grid_graph.hpp"

namespace campo::grid {

enum class SearchStatus {
  found,    ///< path holds a cheapest path
  no_path,  ///< the goal cannot be reached (or the start or goal is blocked)
};
std::string_view to_string(SearchStatus status);

struct SearchResult {
  SearchStatus status = SearchStatus::no_path;
  Cost cost = kInfiniteCost;     ///< fixed point; to_cells(cost) in cell units, -1 when no path
  std::vector<Cell> path;        ///< start to goal inclusive; empty when no path
  std::int64_t expansions = 0;   ///< nodes expanded by this call

  /// Moves along the path (0 when no path or start == goal).
  std::size_t steps() const { return path.empty() ? 0 : path.size() - 1; }
};

}  // namespace campo::grid
