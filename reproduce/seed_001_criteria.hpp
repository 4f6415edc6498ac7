#pragma once
/// Seed 001's claims judged on the thesis's own criteria: each criterion a
/// pure function of measured data (flown tracks, run outcomes, and the optima
/// of campo's own grid search on the true map of 001's tables), tested
/// directly in tests/reproduce/. A criterion is empty (std::nullopt) when
/// nothing was measured. Where the thesis's words need a bound to be
/// testable, the function's comment names it and why.
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "grid/grid_graph.hpp"

namespace campo {

/// A block of obstacle cells as 001's Tabelle 5.1/5.3/5.5 give it: rows
/// ("Latitudine [celle]") and columns ("Longitudine [celle]"), from 1, and its
/// height above the ground ("ΔAltitudine [m]").
struct GridBlock {
  int row_first = 1, row_last = 1, col_first = 1, col_last = 1;
  double height_m = 0.0;
  friend bool operator==(const GridBlock&, const GridBlock&) = default;
};

/// The block with its rows counted from the other edge of a map of `rows`
/// rows: row r becomes rows + 1 - r (the tables' other reading).
GridBlock mirror_rows(const GridBlock& block, int rows);

/// The smallest block holding all of `blocks` (height: the tallest).
GridBlock bounding_block(const std::vector<GridBlock>& blocks);

/// The true map of a 001 simulation on the thesis's graph (001 §4.2.3-4.2.4):
/// `cols` x `rows` cells of `cell_m`, `levels` levels `level_m` apart, level
/// `ground_level` at the take-off ground. A block of height h blocks its cells
/// on every level up to the thesis's cooz = round(h / level_m) + ground_level,
/// the ground blocks every level up to ground_level (a LIDAR hit blocks its
/// cell and every cell below it).
struct TrueMap {
  int cols = 100, rows = 100, levels = 9;
  double cell_m = 1.5, level_m = 7.0;
  int ground_level = 2;
  std::vector<GridBlock> blocks;
};

/// The thesis's level of a height above the take-off ground: round(h / level_m) + ground_level.
int level_of_height(const TrueMap& map, double height_m);

/// A node of the true map: row and column from 1 (as the tables count), level from 0.
struct MapCell {
  int row = 1, col = 1, level = 0;
};

/// The cheapest route campo's grid search (grid::AStar) finds between two cells.
struct RouteOptimum {
  bool found = false;
  double cost_cells = 0.0;         ///< the search's cost, in horizontal cell moves
  double length_m = 0.0;           ///< the route's length in metres (a climb counts its level_m)
  int links = 0;                   ///< moves along it
  bool leaves_level = false;       ///< it climbs or descends from the start's level on the way
  std::vector<MapCell> path;
};

/// The cheapest route from `from` to `to` on `map` with `connectivity`: four
/// or eight searches the plane of from.level only; six or twenty_six the whole
/// volume, a one-level move costing `climb_cost_cells` horizontal moves (1:
/// 001's equal cost on every link; level_m / cell_m: its length). `closed`
/// blocks are closed on every level as well (e.g. to forbid a region).
RouteOptimum route_optimum(const TrueMap& map, grid::Connectivity connectivity, const MapCell& from,
                           const MapCell& to, double climb_cost_cells, const std::vector<GridBlock>& closed = {});

/// The cheapest route from `from` to `to` that passes through a cell of `area`
/// (on from.level): the better of the routes through each of its cells.
RouteOptimum route_through(const TrueMap& map, grid::Connectivity connectivity, const MapCell& from,
                           const MapCell& to, double climb_cost_cells, const GridBlock& area);

/// The inputs of judge() for a claim: the criterion, departures, cause.
struct Judgement {
  std::optional<bool> holds;
  bool has_departures = false;
  bool cause_known = false;
};

/// A claim measured with the thesis's settings and with the bundled scene's
/// (each empty when not measured): it holds when either run meets the
/// criterion, with departures unless the thesis's settings did; `cause_known`
/// is passed through for a failure. Empty when neither was measured.
Judgement judge_with_thesis_setting(std::optional<bool> thesis_setting, std::optional<bool> bundled,
                                    bool cause_known);

// ---- The slot (001 §5.1, Figura 5.4) ------------------------------------------------------------------------------

/// Under one reading of the table's row order: the cheapest route of the leg
/// against the cheapest through the slot, on the true map.
struct SlotReading {
  std::string reading;          ///< "rows from the south edge", "rows from the north edge"
  RouteOptimum optimum, through_slot;
  /// The slot lies on a shortest route: going through it costs no more.
  bool slot_on_shortest_route() const;
};

/// What the slot claim measured: whether the 28 m lap passed the slot with
/// the thesis's settings and with the bundled scene's (empty when not run),
/// with the other row reading's scene, and the search under both readings.
struct SlotMeasure {
  std::optional<bool> passed_thesis_setting, passed_bundled, passed_other_reading;
  std::vector<SlotReading> readings;  ///< the scenes' reading first
};

/// 001 §5.1: the drone judged it could pass the slot, "hypothesis borne out".
/// Holds when any run passed it; with departures unless the run with the
/// thesis's settings on the scenes' reading did. When none did, the cause is
/// known only when campo's search shows, under every row reading computed,
/// that the slot is not on a shortest route (a shortest-path planner has no
/// reason to take it), and a reading under which it is (not run, or run
/// without passing) leaves the cause unknown. Empty when no run was measured.
Judgement judge_slot(const SlotMeasure& m);

// ---- The weave (001 §5.2, Figura 5.8) -----------------------------------------------------------------------------

/// A rectangle of the ground plane, metres.
struct Rect {
  double x_min = 0.0, x_max = 0.0, y_min = 0.0, y_max = 0.0;
  bool contains(const Eigen::Vector2d& p) const {
    return p.x() >= x_min && p.x() <= x_max && p.y() >= y_min && p.y() <= y_max;
  }
};

/// A block's footprint in metres on a grid whose row 1, column 1 starts at `origin_m`.
Rect footprint(const GridBlock& block, double cell_m, const Eigen::Vector2d& origin_m = Eigen::Vector2d::Zero());

/// Which side of a building the track passed.
enum class Side { none, west, east };
const char* side_name(Side side);

/// For each footprint, the side the track passes it on: from the track's
/// samples within the footprint's y span, west when their mean x is below the
/// footprint's centre, east otherwise; none when no sample lies in the span.
std::vector<Side> passing_sides(const std::vector<Eigen::Vector2d>& track, const std::vector<Rect>& footprints);

/// The lap as flown, for the weave.
struct WeaveMeasure {
  bool climbed = false;    ///< the lap rose above its altitude (route_metrics' climb)
  std::vector<Side> sides;  ///< passing_sides() over the buildings
  double lap_m = 0.0;       ///< its length
};

/// 001 §5.2: the drone "would manage to navigate between the buildings
/// instead of going round them from outside, a less efficient route because
/// longer ... achieved, though with small uncertainties". Holds when the lap
/// stays at its altitude, passes at least one building on the west and one on
/// the east (between them: a route round the outside passes every building on
/// the same side), and is shorter than `outside_optimum_m`, the shortest route
/// round the outside on the thesis's graph. The bound for the "small
/// uncertainties": the lap may exceed the weave's optimum by any amount that
/// still leaves it shorter than going round, since the thesis's point is that
/// the weave is the shorter way. Empty when no building's span was flown or
/// no outside route exists.
std::optional<bool> weave_holds(const WeaveMeasure& m, std::optional<double> outside_optimum_m);

// ---- The wall (001 §5.3, Figura 5.12) -----------------------------------------------------------------------------

/// 001 §5.3: the drone "understands it must move along the Z axis and manages
/// to climb over it, then returns to the original altitude and reaches the
/// goal"; the risk "was to see the drone move parallel to the wall hoping to
/// find a gap". Holds when the leg reached its goal without collision, climbed
/// (`lateral_before_climb_m` set) and moved sideways less than one cell
/// (`cell_m`) before topping the climb: a move along the wall on the
/// thesis's grid is at least one cell. Empty when the run did not complete.
std::optional<bool> wall_holds(std::optional<bool> reached_clean, std::optional<double> lateral_before_climb_m,
                               double cell_m);

// ---- Cost-model sweep ---------------------------------------------------------------------------------------------

/// One setting of the cost-model sweep and the behaviours it showed (empty: its run failed).
struct SettingBehaviours {
  std::string connectivity;
  double climb_cost = 0.0, pitch_deg = 0.0;
  std::optional<bool> slot, weave, wall;
  bool all() const { return slot.value_or(false) && weave.value_or(false) && wall.value_or(false); }
};

/// How many settings showed each behaviour, of how many measured it.
struct BehaviourCounts {
  int settings = 0;
  int slot = 0, slot_n = 0, weave = 0, weave_n = 0, wall = 0, wall_n = 0, all = 0;
};
BehaviourCounts count_behaviours(const std::vector<SettingBehaviours>& settings);

/// The setting with `connectivity`, `climb_cost` and `pitch_deg`, or null.
const SettingBehaviours* find_setting(const std::vector<SettingBehaviours>& settings, const std::string& connectivity,
                                      double climb_cost, double pitch_deg);

/// 001 §4.2.2, §4.2.4 with §5.1-5.3: with its cost model (six-connected,
/// every link the same cost) and the LIDAR at 45° the three behaviours occur.
/// Holds when the thesis's setting shows all three. When it does not, the
/// cause is known when every behaviour it misses has a cause computed on the
/// true map: `slot_cause` (the slot is on no shortest route) for the slot,
/// `weave_cause` (the equal-cost graph's optimum leaves the flight level, so
/// a shortest-path planner climbs) for the weave; a missed wall has none.
/// Empty when the thesis's setting was not measured.
Judgement judge_sweep(const SettingBehaviours* thesis_setting, bool slot_cause, bool weave_cause);

// ---- Other claims -------------------------------------------------------------------------------------------------

/// Largest horizontal distance of `track` from the polyline `nominal`; 0 for an empty track.
double max_offset_m(const std::vector<Eigen::Vector2d>& track, const std::vector<Eigen::Vector2d>& nominal);

/// 001 §5.1-5.3: "the trajectory flown at the higher altitude coincides with
/// the nominal trajectory". Holds when every scene's 42 m lap stays within one
/// cell (`cell_m`) of the straight lines between its waypoints: within a cell
/// it flies the cells of the nominal line, a cell off is another route on the
/// grid. Empty without laps.
std::optional<bool> laps_coincide(const std::vector<double>& max_offsets_m, double cell_m);

/// How the track passed over a block lower than the flight altitude.
struct LowBlockPass {
  int samples_over = 0;      ///< track samples over its footprint on the lap
  int nominal_over = 0;      ///< samples of the nominal route over it (0: the route does not cross it)
  double max_rise_m = 0.0;   ///< highest sample over it above the lap's altitude
};

/// 001 §5.1: obstacles "poco elevati", low enough "that they would not be
/// recognised as obstacles" (the 10 m and 15 m blocks under the 28 m lap).
/// Holds when the track flies over every low block the nominal route crosses
/// (samples over it) without rising `climb_m` above the lap's altitude. Empty
/// when the nominal route crosses none.
std::optional<bool> low_blocks_ignored(const std::vector<LowBlockPass>& passes, double climb_m);

/// A run with an obstacle moving across the route.
struct MoverRun {
  bool hit = false;            ///< collided with the mover
  double max_offset_m = 0.0;   ///< the track's largest distance from the nominal leg
};

/// 001 Ch. 6: "moving obstacles exactly in front of the vehicle ... cannot be
/// foreseen and avoided in real time". Holds when no run turns off its route
/// (every track within one cell, `cell_m`, of the nominal leg) and the mover
/// hits the drone in at least one. Empty without runs.
std::optional<bool> movers_not_avoided(const std::vector<MoverRun>& runs, double cell_m);

/// 001 Ch. 6: with column mapping "a bridge would be reconstructed as a
/// hill; the vehicle could avoid ... by flying over it, but could not
/// consider flying under it". Holds when the drone reached its goal without
/// collision and flew over the deck's span above its top (never under it).
/// Empty when the run did not cross the deck's span (`low_m` > `high_m`).
std::optional<bool> bridge_flown_over(bool reached_clean, double low_m, double high_m, double deck_top_m);

}  // namespace campo
