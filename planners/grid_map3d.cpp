#include "planners/grid_map3d.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace campo {

GridMap3d::GridMap3d(const GridMap3dConfig& config) : config_(config) {
  const int max = grid::GridGraph::kMaxDimension;
  if (config.columns < 1 || config.columns > max || config.rows < 1 || config.rows > max || config.levels < 1 ||
      config.levels > max) {
    throw std::invalid_argument("GridMap3d: columns, rows and levels must be in 1.." + std::to_string(max));
  }
  if (!(config.cell_size_m > 0.0) || !(config.level_spacing_m > 0.0)) {
    throw std::invalid_argument("GridMap3d: cell size and level spacing must be positive");
  }
  if (config.ground_level < 0 || config.ground_level >= config.levels) {
    throw std::invalid_argument("GridMap3d: ground level must be a level of the grid");
  }
  top_.assign(static_cast<std::size_t>(config.columns) * config.rows, -1);
}

bool GridMap3d::contains(const grid::Cell& c) const {
  return c.x >= 0 && c.x < config_.columns && c.y >= 0 && c.y < config_.rows && c.z >= 0 && c.z < config_.levels;
}

grid::Cell GridMap3d::cell_of(const Eigen::Vector3d& p) const {
  const Eigen::Vector2d offset = (p.head<2>() - config_.origin_m) / config_.cell_size_m;
  return {static_cast<int>(std::floor(offset.x())), static_cast<int>(std::floor(offset.y())),
          static_cast<int>(std::lround((p.z() - config_.ground_z_m) / config_.level_spacing_m)) + config_.ground_level};
}

Eigen::Vector3d GridMap3d::center(const grid::Cell& c) const {
  return {config_.origin_m.x() + (c.x + 0.5) * config_.cell_size_m,
          config_.origin_m.y() + (c.y + 0.5) * config_.cell_size_m,
          config_.ground_z_m + (c.z - config_.ground_level) * config_.level_spacing_m};
}

grid::CellState GridMap3d::state(const grid::Cell& c) const {
  return c.z <= top_[static_cast<std::size_t>(c.y) * config_.columns + c.x] ? grid::CellState::blocked
                                                                             : grid::CellState::unknown;
}

std::vector<grid::CellChange> GridMap3d::mark_hit(const Eigen::Vector3d& point_m) {
  std::vector<grid::CellChange> changes;
  const grid::Cell hit = cell_of(point_m);
  if (hit.x < 0 || hit.x >= config_.columns || hit.y < 0 || hit.y >= config_.rows || hit.z < 0) return changes;
  int& top = top_[static_cast<std::size_t>(hit.y) * config_.columns + hit.x];
  const int new_top = std::min(hit.z, config_.levels - 1);
  for (int z = top + 1; z <= new_top; ++z) changes.push_back({{hit.x, hit.y, z}, grid::CellState::blocked});
  top = std::max(top, new_top);
  return changes;
}

std::optional<int> GridMap3d::top_blocked_level(int column, int row) const {
  const int top = top_.at(static_cast<std::size_t>(row) * config_.columns + column);
  if (top < 0) return std::nullopt;
  return top;
}

std::vector<double> GridMap3d::height_map_m() const {
  std::vector<double> heights(top_.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t i = 0; i < top_.size(); ++i) {
    if (top_[i] >= 0) heights[i] = config_.ground_z_m + (top_[i] - config_.ground_level) * config_.level_spacing_m;
  }
  return heights;
}

}  // namespace campo
