#include "grid/grid_graph.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace campo::grid {

namespace {

// One table serves both directions (names for parsing and printing).
struct ConnectivityName {
  Connectivity connectivity;
  std::string_view name;
};
constexpr std::array<ConnectivityName, 4> kConnectivityNames{{
    {Connectivity::four, "4"},
    {Connectivity::eight, "8"},
    {Connectivity::six, "6"},
    {Connectivity::twenty_six, "26"},
}};

// Nonzero components a move may have under the connectivity.
int max_nonzero(Connectivity connectivity) {
  switch (connectivity) {
    case Connectivity::four:
    case Connectivity::six: return 1;
    case Connectivity::eight: return 2;
    case Connectivity::twenty_six: return 3;
  }
  return 0;
}

// Fixed-point cost of a move by (dx, dy, dz) cells, a level `level_step` cells
// high. The unit-step costs are the shared constants, so 2D costs and the
// unit-step 3D heuristic stay exactly the same integers.
Cost move_cost(int dx, int dy, int dz, double level_step) {
  const int horizontal = dx * dx + dy * dy;
  if (dz == 0 || level_step == 1.0) {
    const int nonzero = (dx != 0) + (dy != 0) + (dz != 0);
    return nonzero == 1 ? kStraightCost : nonzero == 2 ? kDiagonalCost : kCornerCost;
  }
  return std::llround(std::sqrt(horizontal + level_step * level_step) * static_cast<double>(kCostScale));
}

}  // namespace

double to_cells(Cost cost) {
  return cost >= kInfiniteCost ? -1.0 : static_cast<double>(cost) / static_cast<double>(kCostScale);
}

std::string_view to_string(Connectivity connectivity) {
  for (const auto& entry : kConnectivityNames) {
    if (entry.connectivity == connectivity) return entry.name;
  }
  return "?";
}

std::optional<Connectivity> connectivity_from_string(std::string_view name) {
  for (const auto& entry : kConnectivityNames) {
    if (entry.name == name) return entry.connectivity;
  }
  return std::nullopt;
}

bool is_3d(Connectivity connectivity) {
  return connectivity == Connectivity::six || connectivity == Connectivity::twenty_six;
}

GridGraph::GridGraph(GridSize size, Connectivity connectivity, double level_step_cells)
    : size_(size), connectivity_(connectivity), level_step_cells_(level_step_cells) {
  for (const int n : {size.width, size.height, size.depth}) {
    if (n < 1 || n > kMaxDimension) {
      throw std::invalid_argument("grid dimensions must be in 1.." + std::to_string(kMaxDimension));
    }
  }
  const bool three_d = is_3d(connectivity);
  if (!three_d && size.depth != 1) {
    throw std::invalid_argument("connectivity " + std::string(to_string(connectivity)) + " is 2D: depth must be 1");
  }
  if (!(level_step_cells > 0.0 && level_step_cells <= 1000.0) || (!three_d && level_step_cells != 1.0)) {
    throw std::invalid_argument("the level step must be in (0, 1000] cells, and 1 in 2D");
  }
  vertical_cost_ = move_cost(0, 0, 1, level_step_cells);
  border_z_ = three_d ? 1 : 0;
  const std::int64_t nx = size.width + 2, ny = size.height + 2, nz = size.depth + 2 * border_z_;
  if (nx * ny * nz > kMaxCells) throw std::invalid_argument("grid too large: at most 2^28 cells");
  stride_ = {1, static_cast<CellId>(nx), static_cast<CellId>(nx * ny)};

  // Border cells are blocked; the grid's own cells start unknown.
  state_.assign(static_cast<std::size_t>(nx * ny * nz), CellState::blocked);
  coords_.resize(state_.size());
  for (std::int64_t z = 0; z < nz; ++z) {
    for (std::int64_t y = 0; y < ny; ++y) {
      for (std::int64_t x = 0; x < nx; ++x) {
        const std::size_t i = static_cast<std::size_t>(x + nx * (y + ny * z));
        coords_[i] = {static_cast<std::int16_t>(x), static_cast<std::int16_t>(y), static_cast<std::int16_t>(z)};
        const bool inside = x >= 1 && x <= size.width && y >= 1 && y <= size.height && z >= border_z_ &&
                            z < border_z_ + size.depth;
        if (inside) state_[i] = CellState::unknown;
      }
    }
  }

  // Cells around a cell, and the moves with the box each must keep clear.
  const int zr = three_d ? 1 : 0;
  const auto offset = [&](int dx, int dy, int dz) { return dx * stride_[0] + dy * stride_[1] + dz * stride_[2]; };
  for (int dz = -zr; dz <= zr; ++dz) {
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) around_.push_back(offset(dx, dy, dz));
    }
  }
  for (int dz = -zr; dz <= zr; ++dz) {
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        const int nonzero = (dx != 0) + (dy != 0) + (dz != 0);
        if (nonzero == 0 || nonzero > max_nonzero(connectivity)) continue;
        Move move;
        move.offset = offset(dx, dy, dz);
        move.cost = move_cost(dx, dy, dz, level_step_cells);
        // Every cell of the box but u itself: (a, b, c) with a in {0, dx}, b in {0, dy}, c in {0, dz}.
        for (const int bx : {0, dx}) {
          for (const int by : {0, dy}) {
            for (const int bz : {0, dz}) {
              if (bx == 0 && by == 0 && bz == 0) continue;
              const CellId probe = offset(bx, by, bz);
              auto it = std::find(probes_.begin(), probes_.end(), probe);
              if (it == probes_.end()) it = probes_.insert(probes_.end(), probe);
              move.box_mask |= 1u << (it - probes_.begin());
            }
          }
        }
        moves_.push_back(move);
      }
    }
  }
}

bool GridGraph::contains(const Cell& c) const {
  return c.x >= 0 && c.x < size_.width && c.y >= 0 && c.y < size_.height && c.z >= 0 && c.z < size_.depth;
}

CellId GridGraph::id(const Cell& c) const {
  return (c.x + 1) * stride_[0] + (c.y + 1) * stride_[1] + (c.z + border_z_) * stride_[2];
}

Cell GridGraph::cell(CellId id) const {
  const Coord& p = coords_[id];
  return {p.x - 1, p.y - 1, p.z - border_z_};
}

Cost GridGraph::edge_cost(const Cell& a, const Cell& b) const {
  if (!contains(a) || !contains(b) || a == b) return kInfiniteCost;
  if (std::abs(b.x - a.x) > 1 || std::abs(b.y - a.y) > 1 || std::abs(b.z - a.z) > 1) return kInfiniteCost;
  Cost cost = kInfiniteCost;
  const CellId target = id(b);
  for_each_neighbour(id(a), [&](CellId v, Cost c) {
    if (v == target) cost = c;
  });
  return cost;
}

}  // namespace campo::grid
