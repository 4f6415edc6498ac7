#pragma once
/// The grid graph every grid search runs on (SPEC §7.2): a 2D or 3D occupancy
/// grid of free, unknown (assumed free) and blocked cells, with 4/8 (2D) or
/// 6/26 (3D) connectivity, move costs 1, sqrt2, sqrt3 and no corner cutting.
/// Plain data only: the searches never see Bullet.
#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

namespace campo::grid {

/// Index of a cell in the flat per-cell arrays (the grid's own cells plus a
/// border of blocked cells, so neighbour look-ups never need a bounds check).
using CellId = std::int32_t;

/// Path cost in fixed point: kCostScale per cell edge. Integers make sums
/// independent of the order of addition, so equal-cost paths tie exactly
/// (defined tie-breaking) and D* Lite's "rhs came through u" test is exact.
using Cost = std::int64_t;
inline constexpr Cost kCostScale = Cost{1} << 32;
/// Move costs: 1, sqrt2 and sqrt3 cells, rounded to the fixed point.
inline constexpr Cost kStraightCost = kCostScale;
inline constexpr Cost kDiagonalCost = 6074001000;  ///< round(sqrt(2) * 2^32)
inline constexpr Cost kCornerCost = 7439101574;    ///< round(sqrt(3) * 2^32)
/// Unreachable; large enough for any path, small enough that adding a few
/// costs to it cannot overflow.
inline constexpr Cost kInfiniteCost = std::numeric_limits<Cost>::max() / 4;

/// A cost in cell units (1 per straight move), -1 for kInfiniteCost.
double to_cells(Cost cost);

enum class Connectivity : std::uint8_t {
  four,        ///< 2D, straight moves (cost 1)
  eight,       ///< 2D, plus diagonals (sqrt2): MovingAI "octile"
  six,         ///< 3D, straight moves along x, y, z (cost 1)
  twenty_six,  ///< 3D, plus face diagonals (sqrt2) and corner diagonals (sqrt3)
};
std::string_view to_string(Connectivity connectivity);
/// "4", "8", "6", "26"; nullopt for anything else.
std::optional<Connectivity> connectivity_from_string(std::string_view name);
bool is_3d(Connectivity connectivity);

enum class CellState : std::uint8_t {
  unknown,  ///< not observed yet: traversable (unknown cells are assumed free)
  free,     ///< observed free
  blocked,  ///< not traversable
};

/// A cell by its coordinates: x column, y row, z level (0 in 2D).
struct Cell {
  int x = 0;
  int y = 0;
  int z = 0;
  friend bool operator==(const Cell&, const Cell&) = default;
};

struct GridSize {
  int width = 1;   ///< cells along x, 1..kMaxDimension
  int height = 1;  ///< cells along y, 1..kMaxDimension
  int depth = 1;   ///< cells along z (levels), 1..kMaxDimension; 1 for 2D connectivity
};

/// A change of one cell's state, as a map update delivers it.
struct CellChange {
  Cell cell;
  CellState state = CellState::blocked;
};

class GridGraph {
 public:
  static constexpr int kMaxDimension = 32000;           ///< coordinates are stored as int16
  static constexpr std::int64_t kMaxCells = 1 << 28;    ///< cells including the border

  /// All cells start unknown. `level_step_cells` is the length of a vertical
  /// move in horizontal cell sides (a 3D grid's level spacing over its cell
  /// size): moves cost their Euclidean length, so a climb costs what it
  /// measures. Throws std::invalid_argument for a size out of range, a 2D
  /// connectivity with depth > 1, or a level step that is not positive
  /// (or not 1 in 2D).
  GridGraph(GridSize size, Connectivity connectivity, double level_step_cells = 1.0);

  const GridSize& size() const { return size_; }
  Connectivity connectivity() const { return connectivity_; }
  double level_step_cells() const { return level_step_cells_; }
  bool contains(const Cell& cell) const;

  /// Id of a cell inside the grid (contains(cell) must hold).
  CellId id(const Cell& cell) const;
  /// Coordinates of an id returned by id() or by a search.
  Cell cell(CellId id) const;
  /// Size of arrays indexed by CellId (includes the border).
  CellId id_count() const { return static_cast<CellId>(state_.size()); }

  CellState state(const Cell& cell) const { return state_[id(cell)]; }
  void set_state(const Cell& cell, CellState state) { state_[id(cell)] = state; }
  bool traversable(CellId id) const { return state_[id] != CellState::blocked; }

  /// Cost of the move from `a` to the adjacent `b` (same for `b` to `a`), or
  /// kInfiniteCost when they are not neighbours under the connectivity, either
  /// is blocked, or the move cuts a corner. For checking paths, not for search.
  Cost edge_cost(const Cell& a, const Cell& b) const;

  /// Admissible and consistent lower bound on the path cost from `a` to `b`:
  /// the cost of the cheapest obstacle-free path under the connectivity
  /// (Manhattan, octile, or its 3D form); with 26-connectivity and a level
  /// step other than 1, the larger of the horizontal octile cost and the
  /// vertical moves' cost (each move pays at least its share of both).
  /// Built from the same integer move costs, so it is exactly consistent.
  Cost heuristic(CellId a, CellId b) const {
    const Coord& p = coords_[a];
    const Coord& q = coords_[b];
    int d1 = std::abs(p.x - q.x), d2 = std::abs(p.y - q.y), d3 = std::abs(p.z - q.z);
    switch (connectivity_) {
      case Connectivity::four: return (d1 + d2) * kStraightCost;
      case Connectivity::six: return (d1 + d2) * kStraightCost + d3 * vertical_cost_;
      case Connectivity::eight:
        if (d1 < d2) std::swap(d1, d2);
        return d2 * kDiagonalCost + (d1 - d2) * kStraightCost;
      case Connectivity::twenty_six:
        if (vertical_cost_ != kStraightCost) {
          if (d1 < d2) std::swap(d1, d2);
          return std::max(d2 * kDiagonalCost + (d1 - d2) * kStraightCost, d3 * vertical_cost_);
        }
        // Sorted d1 >= d2 >= d3: d3 corner moves, d2 - d3 face diagonals, the rest straight.
        if (d1 < d2) std::swap(d1, d2);
        if (d2 < d3) std::swap(d2, d3);
        if (d1 < d2) std::swap(d1, d2);
        return d3 * kCornerCost + (d2 - d3) * kDiagonalCost + (d1 - d2) * kStraightCost;
    }
    return 0;
  }

  /// Calls visit(v, cost) for every move out of `u`: none when `u` is blocked;
  /// a move is allowed when every cell of the axis-aligned box spanned by `u`
  /// and `v` is traversable (for 2D diagonals: both orthogonal neighbours).
  /// The graph is undirected, so these are also the predecessors of `u`.
  template <class Visit>
  void for_each_neighbour(CellId u, Visit&& visit) const {
    if (state_[u] == CellState::blocked) return;
    // One look-up per cell around u, then one mask test per move.
    std::uint32_t blocked = 0;
    for (std::size_t i = 0; i < probes_.size(); ++i) {
      blocked |= static_cast<std::uint32_t>(state_[u + probes_[i]] == CellState::blocked) << i;
    }
    for (const Move& move : moves_) {
      if ((blocked & move.box_mask) == 0) visit(u + move.offset, move.cost);
    }
  }

  /// Offsets (CellId deltas) of a cell and every cell around it (3 x 3, or
  /// 3 x 3 x 3 in 3D): the cells whose moves may change when that cell changes.
  std::span<const CellId> around_offsets() const { return around_; }

 private:
  struct Coord {
    std::int16_t x = 0;
    std::int16_t y = 0;
    std::int16_t z = 0;
  };
  struct Move {
    CellId offset = 0;           ///< id delta from u to v
    Cost cost = 0;               ///< kCostScale x the move's length in cells
    std::uint32_t box_mask = 0;  ///< bits of probes_ that must be traversable
  };

  GridSize size_;
  Connectivity connectivity_;
  double level_step_cells_ = 1.0;
  Cost vertical_cost_ = kStraightCost;  ///< cost of a move straight up or down
  std::array<CellId, 3> stride_{};  ///< id delta of +1 in x, y, z
  int border_z_ = 0;                ///< 1 in 3D (a blocked level below and above), 0 in 2D
  std::vector<CellState> state_;
  std::vector<Coord> coords_;
  std::vector<Move> moves_;
  std::vector<CellId> probes_;  ///< offsets of the cells any move's box touches
  std::vector<CellId> around_;
};

}  // namespace campo::grid
