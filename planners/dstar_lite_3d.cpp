#include "planners/dstar_lite_3d.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "campo/json_reader.hpp"
#include "grid/dstar_lite.hpp"
#include "sensors/lidar.hpp"

namespace campo {

namespace {

using Clock = std::chrono::steady_clock;

nlohmann::json position_json(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }
nlohmann::json cell_json(const grid::Cell& c) { return {c.x, c.y, c.z}; }

class DStarLite3dPlanner final : public Planner {
 public:
  explicit DStarLite3dPlanner(const DStarLite3dConfig& config) : config_(config) {}

  PlanResult plan(const Observation& o) override {
    PlanResult result;
    result.command = command::Hold{o.state.position_m, std::nullopt};
    const SensorReading* lidar = o.sensor(config_.sensor);
    if (!lidar) {
      result.status = PlanStatus::invalid_start;
      result.reason = config_.sensor.empty() ? "the vehicle has no sensor to map with"
                                             : "the vehicle has no sensor \"" + config_.sensor + "\"";
      return result;
    }
    if (!map_) {
      // The vehicle starts on the ground: its height is take-off ground level (within a level's rounding).
      map_.emplace(grid_map_config(config_, o.state.position_m.z()));
      if (config_.mapping == Mapping3d::octomap) octomap_.emplace(map_->config(), config_.octomap);
      // A height map only where the map is one (an octree keeps what lies under an overhang).
      if (!octomap_) {
        dstar_lite_3d_record().height_map_grid.set(
            result.decisions.own, HeightMapGrid{.origin_m = config_.origin_m, .cell_size_m = config_.cell_size_m,
                                                .columns = config_.columns, .rows = config_.rows});
      }
      // Moves cost their length: a 7 m climb costs 4.7 cells of 1.5 m, not one,
      // so the drone weaves between buildings at its altitude rather than
      // climbing over every one it has mapped.
      graph_ = std::make_unique<grid::GridGraph>(map_->size(), config_.connectivity, climb_cost_cells(config_));
    }

    // Mission waypoints already reached.
    while (next_ < o.mission.size() && (o.state.position_m - o.mission[next_].position_m).norm() <= config_.tolerance_m) {
      result.decisions.reached_waypoints.push_back(static_cast<int>(next_++));
      leg_started_ = false;
    }
    if (next_ >= o.mission.size()) {
      result.status = PlanStatus::reached;
      result.reason = "all " + std::to_string(o.mission.size()) + " waypoints reached";
      return result;
    }

    const auto started = Clock::now();
    // Map the fresh scan; only cells that changed go to the search.
    std::vector<grid::CellChange> changes;
    if (lidar->fresh && lidar->scan && octomap_) {
      changes = insert_rays(*lidar);
    } else if (lidar->fresh && lidar->scan) {
      for (const Eigen::Vector3f& point : lidar->scan->points) {
        const std::vector<grid::CellChange> marked = map_->mark_hit(point.cast<double>());
        changes.insert(changes.end(), marked.begin(), marked.end());
      }
    }
    const double mapping_ms = std::chrono::duration<double, std::milli>(Clock::now() - started).count();
    if (lidar->fresh && lidar->scan) record_mapping(*lidar->scan, changes, result);

    const std::optional<grid::Cell> start = start_cell(o.state.position_m);
    if (!start) {
      result.status = PlanStatus::aborted;
      result.reason = "the vehicle left the grid or its whole column is blocked at " + position_json(o.state.position_m).dump();
      return result;
    }
    const grid::Cell goal = map_->cell_of(o.mission[next_].position_m);
    if (!map_->contains(goal)) {
      result.status = PlanStatus::no_path;
      result.reason = "mission waypoint " + std::to_string(next_) + " lies outside the grid";
      return result;
    }

    bool replan = !changes.empty();
    if (!leg_started_) {
      // A new start/goal pair: the search starts over on the map known so far.
      for (const grid::CellChange& change : changes) graph_->set_state(change.cell, change.state);
      if (search_) {
        search_->reset(*start, goal);
      } else {
        search_ = std::make_unique<grid::DStarLite>(*graph_, *start, goal);
      }
      leg_started_ = true;
      replan = true;
    } else {
      search_->set_cells(changes);
      if (!(search_->start() == *start)) {
        search_->move_start(*start);
        replan = true;
      }
    }

    if (replan) {
      grid::SearchResult found = search_->plan();
      const double time_ms = std::chrono::duration<double, std::milli>(Clock::now() - started).count();
      ReplanDecision& step = result.decisions.replan.emplace(
          ReplanDecision{.index = replans_++, .sensor = std::string(lidar->alias), .time_ms = time_ms});
      const DStarLite3dRecord& record = dstar_lite_3d_record();
      record.start_cell.set(step.details, cell_json(*start));
      record.goal_cell.set(step.details, cell_json(goal));
      record.changed_cells.set(step.details, static_cast<std::int64_t>(changes.size()));
      record.expansions.set(step.details, found.expansions);
      record.mapping_ms.set(step.details, mapping_ms);
      if (found.status != grid::SearchStatus::found) {
        result.status = PlanStatus::no_path;
        result.reason = "no path from cell " + cell_json(*start).dump() + " to mission waypoint " +
                        std::to_string(next_) + " at cell " + cell_json(goal).dump() + " on the mapped grid";
        return result;
      }
      // A path that only lost the cell just left is the same plan.
      const bool moved_along = path_.size() == found.path.size() + 1 &&
                               std::equal(found.path.begin(), found.path.end(), path_.begin() + 1);
      const bool changed = !moved_along && found.path != path_;
      path_ = std::move(found.path);
      if (changed) record_path(o.mission[next_].position_m, result);
    }

    const Eigen::Vector3d target = next_target(o.mission[next_].position_m);
    if (target != target_m_) {
      target_m_ = target;
      result.decisions.planned_waypoint = target;
    }
    result.command = command::GoTo{target_m_, config_.speed_mps, true};
    return result;
  }

  nlohmann::json parameters() const override { return dstar_lite_3d_config_fields().write(config_); }

 private:
  // Where the search starts: the vehicle's cell once it is near that cell's
  // centre (entering a cell early would let the next move cut the corner past
  // an obstacle), else the cell it last reached. At the start of a leg, the
  // vehicle's cell. On the ground (take-off) the vehicle's cell is blocked once
  // scanned, so the lowest free cell above it.
  std::optional<grid::Cell> start_cell(const Eigen::Vector3d& position_m) const {
    grid::Cell cell = map_->cell_of(position_m);
    cell.z = std::max(cell.z, 0);
    if (!map_->contains(cell)) return std::nullopt;
    const bool reached = (position_m - map_->center(cell)).norm() <= config_.cell_reached_m;
    if (leg_started_ && !reached && !blocked(search_->start())) return search_->start();
    while (blocked(cell)) {
      if (++cell.z >= config_.levels) return std::nullopt;
    }
    return cell;
  }

  bool blocked(const grid::Cell& cell) const {
    return (octomap_ ? octomap_->state(cell) : map_->state(cell)) == grid::CellState::blocked;
  }

  // Casts the scan's rays into the octree: every beam from the sensor to its
  // range, a return or free to the end; without the sensor's beam layout,
  // the hits alone. Returns the planning cells that changed.
  std::vector<grid::CellChange> insert_rays(const SensorReading& lidar) {
    const RangeScan& scan = *lidar.scan;
    const Eigen::Vector3d origin = scan.sensor_pose.translation();
    std::vector<Eigen::Vector3d> ends;
    std::vector<std::uint8_t> returns;
    const std::size_t beams = scan.ranges_m.size();
    if (lidar.config && lidar.config->beam_count() == static_cast<int>(beams) && scan.hits.size() == beams) {
      if (directions_.empty()) {
        for (const Beam& beam : lidar_beams(*lidar.config)) directions_.push_back(beam_direction(beam).cast<double>());
      }
      for (std::size_t i = 0; i < beams; ++i) {
        ends.push_back(origin + scan.sensor_pose.linear() * directions_[i] * static_cast<double>(scan.ranges_m[i]));
        returns.push_back(scan.hits[i]);
      }
    } else {
      for (const Eigen::Vector3f& p : scan.points) ends.push_back(p.cast<double>());
      returns.assign(ends.size(), 1);
    }
    return octomap_->insert_scan(origin, ends, returns);
  }

  // World points of a path, the goal cell replaced by the waypoint itself.
  Eigen::Vector3d point(std::size_t i, const Eigen::Vector3d& waypoint_m) const {
    return i + 1 == path_.size() ? waypoint_m : map_->center(path_[i]);
  }

  // For the figures: the scan's hits (to the centimetre) and the new top of
  // every column whose reconstructed height rose.
  void record_mapping(const RangeScan& scan, const std::vector<grid::CellChange>& changes, PlanResult& result) const {
    const auto cm = [](float v) { return std::round(static_cast<double>(v) * 100.0) / 100.0; };
    std::vector<Eigen::Vector3d>& hits = result.decisions.lidar_hits;
    hits.reserve(scan.points.size());
    for (const Eigen::Vector3f& p : scan.points) hits.emplace_back(cm(p.x()), cm(p.y()), cm(p.z()));
    if (octomap_) {
      // Planning cells an occupied voxel now blocks or no longer blocks: [column, row, level].
      nlohmann::json blocked = nlohmann::json::array(), cleared = nlohmann::json::array();
      for (const grid::CellChange& c : changes) {
        (c.state == grid::CellState::blocked ? blocked : cleared).push_back(cell_json(c.cell));
      }
      const DStarLite3dRecord& record = dstar_lite_3d_record();
      if (!blocked.empty()) record.blocked_cells.set(result.decisions.own, blocked);
      if (!cleared.empty()) record.cleared_cells.set(result.decisions.own, cleared);
      record.occupied_voxels.set(result.decisions.own, static_cast<std::int64_t>(octomap_->occupied_leaf_count()));
      return;
    }
    std::vector<HeightMapColumn> columns;
    for (std::size_t i = 0; i < changes.size(); ++i) {
      const grid::Cell& c = changes[i].cell;
      const bool listed = std::any_of(changes.begin(), changes.begin() + static_cast<std::ptrdiff_t>(i),
                                      [&](const grid::CellChange& e) { return e.cell.x == c.x && e.cell.y == c.y; });
      if (listed) continue;
      const int top = *map_->top_blocked_level(c.x, c.y);
      columns.push_back({c.x, c.y, map_->center({c.x, c.y, top}).z()});
    }
    if (!columns.empty()) dstar_lite_3d_record().height_map_columns.set(result.decisions.own, columns);
  }

  void record_path(const Eigen::Vector3d& waypoint_m, PlanResult& result) const {
    std::vector<Eigen::Vector3d>& points = result.decisions.planned_path.emplace();
    for (std::size_t i = 0; i < path_.size(); ++i) points.push_back(point(i, waypoint_m));
  }

  // The next cell of the path, or a few cells ahead along a straight run of it.
  Eigen::Vector3d next_target(const Eigen::Vector3d& waypoint_m) const {
    if (path_.size() < 2) return waypoint_m;
    const auto step = [&](std::size_t i) {
      return grid::Cell{path_[i + 1].x - path_[i].x, path_[i + 1].y - path_[i].y, path_[i + 1].z - path_[i].z};
    };
    std::size_t ahead = 1;
    while (ahead + 1 < path_.size() && static_cast<int>(ahead) < config_.lookahead_cells && step(ahead) == step(0)) {
      ++ahead;
    }
    return point(ahead, waypoint_m);
  }

  DStarLite3dConfig config_;
  std::optional<GridMap3d> map_;             ///< created at the first observation (take-off ground level)
  std::optional<OctoMap3d> octomap_;         ///< with mapping "octomap": the occupancy, map_ only the geometry
  std::vector<Eigen::Vector3d> directions_;  ///< the LIDAR's beams in its frame, for casting misses
  std::unique_ptr<grid::GridGraph> graph_;   ///< the map as the search sees it
  std::unique_ptr<grid::DStarLite> search_;  ///< searches graph_, reset for every leg
  std::size_t next_ = 0;                     ///< mission waypoint being flown to
  bool leg_started_ = false;                 ///< search_ is set up for the leg to next_
  std::vector<grid::Cell> path_;             ///< current plan, start cell first
  Eigen::Vector3d target_m_ = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  int replans_ = 0;
};

}  // namespace

double climb_cost_cells(const DStarLite3dConfig& c) {
  return c.climb_cost_cells > 0.0 ? c.climb_cost_cells : c.level_spacing_m / c.cell_size_m;
}

GridMap3dConfig grid_map_config(const DStarLite3dConfig& c, double ground_z_m) {
  return {c.columns, c.rows, c.levels, c.cell_size_m, c.level_spacing_m, c.ground_level, c.origin_m, ground_z_m};
}

namespace {

const ConfigFields<OctoMap3dConfig>& octomap_config_fields() {
  using O = OctoMap3dConfig;
  // The clamping bounds lie either side of the threshold read before them.
  const DependentBound<O, Range> below_threshold{
      [](const O& m) { return Range{0.0, m.occupied_threshold, true, true}; }, "(0, occupied_threshold)"};
  const DependentBound<O, Range> above_threshold{
      [](const O& m) { return Range{m.occupied_threshold, 1.0, true, true}; }, "(occupied_threshold, 1)"};
  static const ConfigFields<O> fields =
      ConfigFields<O>()
          .number("resolution_m", &O::resolution_m, Range::closed(0.05, 10.0), "m",
                  "octree voxel side; half a 1.5 m cell, so voxel faces fall on cell sides (origin at a multiple of "
                  "0.75 m)")
          .number("probability_hit", &O::probability_hit, Range{0.5, 1.0, true, true}, "",
                  "occupancy probability a return gives its voxel (OctoMap's default)")
          .number("probability_miss", &O::probability_miss, Range{0.0, 0.5, true, true}, "",
                  "occupancy probability a crossing ray gives a voxel (OctoMap's default)")
          .number("occupied_threshold", &O::occupied_threshold, Range{0.0, 1.0, true, true}, "",
                  "a voxel is occupied above this probability")
          .number("clamping_min", &O::clamping_min, below_threshold, "",
                  "occupancy probability clamped below here (OctoMap's default)")
          .number("clamping_max", &O::clamping_max, above_threshold, "",
                  "occupancy probability clamped above here (OctoMap's default)")
          .number("vehicle_radius_m", &O::vehicle_radius_m, Range::closed(0.0, 100.0), "m",
                  "planning cells within this distance of an occupied voxel are blocked (the quadrotor's rotors are "
                  "0.225 m from its centre)");
  return fields;
}

}  // namespace

const ConfigFields<DStarLite3dConfig>& dstar_lite_3d_config_fields() {
  using C = DStarLite3dConfig;
  static const ConfigFields<C> fields =
      ConfigFields<C>()
          .text("sensor", &C::sensor, "alias of the LIDAR whose hits map the grid; none: the vehicle's first sensor")
          .omitted_when_default()
          .integer("columns", &C::columns, {1, 4000}, "", "grid cells along x (east)")
          .integer("rows", &C::rows, {1, 4000}, "", "grid cells along y (north)")
          .integer("levels", &C::levels, {1, 1000}, "", "grid levels along z (001: 9, from -14 m to +42 m about "
                   "take-off ground)")
          .number("cell_size_m", &C::cell_size_m, Range::closed(kMinCellSizeM, kMaxCellSizeM), "m",
                  "horizontal cell side (001: 1.5 m)")
          .number("level_spacing_m", &C::level_spacing_m, Range::closed(kMinCellSizeM, kMaxCellSizeM), "m",
                  "vertical distance between levels (001: 7 m)")
          .integer("ground_level", &C::ground_level,
                   DependentBound<C, IntRange>{[](const C& c) { return IntRange{0, c.levels - 1}; }, "[0, levels - 1]"},
                   "", "index of the level at take-off ground height (001: 2)")
          .vector("origin_m", &C::origin_m, Range{}, "m", "world x, y of the grid's south-west corner")
          .choice("connectivity", &C::connectivity,
                  {{"six", grid::Connectivity::six}, {"twenty_six", grid::Connectivity::twenty_six}},
                  "moves between face neighbours only, or to all 26 neighbours")
          .number("climb_cost_cells", &C::climb_cost_cells, Range::closed(0.0, 1000.0), "cell moves",
                  "cost of a move of one level up or down, in horizontal cell moves; 0: its length, "
                  "`level_spacing_m / cell_size_m` (4.67); 001 gave every move cost 1")
          .number("speed_mps", &C::speed_mps, Range::closed(0.01, 20.0), "m/s", "cruise speed (001 flew at 1 m/s)")
          .number("tolerance_m", &C::tolerance_m, Range::positive(), "m",
                  "a mission waypoint is reached within this distance")
          .integer("lookahead_cells", &C::lookahead_cells, {1, 100}, "",
                   "fly up to this many cells ahead along a straight run of the path")
          .number("cell_reached_m", &C::cell_reached_m, Range::positive(), "m",
                  "the search's start moves to the vehicle's cell within this distance of its centre")
          .choice("mapping", &C::mapping, {{"columns", Mapping3d::columns}, {"octomap", Mapping3d::octomap}},
                  "`columns` (001 §4.2.4: a hit blocks its cell and the cells below it) or `octomap` (3D occupancy "
                  "from the rays)")
          .nested("octomap", &C::octomap, octomap_config_fields(),
                  "the octree's settings; only with `mapping` `octomap` (and written only then)")
          .only_when([](const C& c) { return c.mapping == Mapping3d::octomap; },
                     "octomap settings need \"mapping\": \"octomap\"");
  return fields;
}

DStarLite3dConfig parse_dstar_lite_3d_config(const ParamsBlock& params) {
  DStarLite3dConfig c = dstar_lite_3d_config_fields().read(params);
  check_grid_size(c, params);
  return c;
}

void check_grid_size(const DStarLite3dConfig& c, const ParamsBlock& params) {
  const std::int64_t cells = std::int64_t{c.columns} * c.rows * c.levels;
  if (cells > kMaxDStarLite3dCells) {
    throw InputError(params.file, params.pointer,
                     "expected columns x rows x levels <= " + std::to_string(kMaxDStarLite3dCells) + " cells, got " +
                         std::to_string(c.columns) + " x " + std::to_string(c.rows) + " x " + std::to_string(c.levels) +
                         " = " + std::to_string(cells));
  }
  // The search's grid takes a climb of at most 1000 horizontal moves.
  if (c.climb_cost_cells == 0.0 && !(climb_cost_cells(c) <= 1000.0)) {
    throw InputError(params.file, params.pointer,
                     "expected level_spacing_m / cell_size_m <= 1000 (a climb's cost in cell moves) or climb_cost_cells "
                     "given, got " + std::to_string(c.level_spacing_m) + " / " + std::to_string(c.cell_size_m));
  }
}

namespace {

// A cell index of a height-map column: an integer in [0, INT_MAX].
bool is_cell_index(const nlohmann::json& j) {
  constexpr std::int64_t kMax = std::numeric_limits<int>::max();
  if (j.is_number_unsigned()) return j.get<std::uint64_t>() <= static_cast<std::uint64_t>(kMax);
  return j.is_number_integer() && j.get<std::int64_t>() >= 0 && j.get<std::int64_t>() <= kMax;
}

nlohmann::json height_map_grid_json(const HeightMapGrid& grid) {
  return {{"origin_m", {grid.origin_m.x(), grid.origin_m.y()}},
          {"cell_size_m", grid.cell_size_m},
          {"columns", grid.columns},
          {"rows", grid.rows}};
}

HeightMapGrid read_height_map_grid(const JsonNode& node) {
  ObjectReader r(node);
  HeightMapGrid grid;
  grid.origin_m = r.required("origin_m").as_vector2();
  grid.cell_size_m = r.required("cell_size_m").as_number(Range::positive());
  grid.columns = static_cast<int>(r.required("columns").as_int(1, std::numeric_limits<int>::max()));
  grid.rows = static_cast<int>(r.required("rows").as_int(1, std::numeric_limits<int>::max()));
  r.finish();
  return grid;
}

nlohmann::json height_map_columns_json(const std::vector<HeightMapColumn>& columns) {
  nlohmann::json j = nlohmann::json::array();
  for (const HeightMapColumn& c : columns) j.push_back({c.column, c.row, c.top_m});
  return j;
}

std::vector<HeightMapColumn> read_height_map_columns(const JsonNode& node) {
  const nlohmann::json& list = node.value();
  std::vector<HeightMapColumn> columns;
  columns.reserve(list.size());
  for (std::size_t i = 0; i < list.size(); ++i) {
    // Checked here rather than by JsonNode: a scan records thousands, a pointer is made only for the message.
    const nlohmann::json& c = list[i];
    if (!c.is_array() || c.size() != 3 || !is_cell_index(c[0]) || !is_cell_index(c[1]) || !c[2].is_number()) {
      JsonNode(c, node.file(), child_pointer(node.pointer(), i))
          .fail("a height-map column [column, row, top z]: indices from 0, m");
    }
    columns.push_back({c[0].get<int>(), c[1].get<int>(), c[2].get<double>()});
  }
  return columns;
}

// The height map as the figures draw it: the grid's frame, then each column's latest top.
void fold_height_map(const Decisions& decisions, CellsOverlay& cells) {
  const DStarLite3dRecord& record = dstar_lite_3d_record();
  if (const auto grid = record.height_map_grid.get(decisions.own, "", "/decisions")) {
    if (static_cast<std::int64_t>(grid->columns) * grid->rows > (1 << 26)) {
      throw InputError("", "/decisions/height_map_grid", "a height map of at most 2^26 cells");
    }
    cells.origin_m = grid->origin_m;
    cells.cell_size_m = grid->cell_size_m;
    cells.columns = grid->columns;
    cells.rows = grid->rows;
    cells.unit = "m";
    cells.values.assign(static_cast<std::size_t>(grid->columns) * grid->rows,
                        std::numeric_limits<double>::quiet_NaN());
  }
  for (const HeightMapColumn& c : record.height_map_columns.get(decisions.own, "", "/decisions").value_or(
           std::vector<HeightMapColumn>{})) {
    if (c.column >= cells.columns || c.row >= cells.rows) {
      throw InputError("", "/decisions/height_map_columns", "columns inside the height_map_grid recorded before them");
    }
    cells.values[static_cast<std::size_t>(c.row) * cells.columns + c.column] = c.top_m;
  }
}

}  // namespace

DStarLite3dRecord::DStarLite3dRecord()
    : height_map_grid(description.decisions.declare<HeightMapGrid>(
          {"height_map_grid", RecordType::object, "m",
           "the height map's frame {origin_m: [x, y] of cell (0, 0)'s south-west corner, cell_size_m, columns, rows}, "
           "recorded once, before its columns (column mapping)"},
          height_map_grid_json, read_height_map_grid)),
      height_map_columns(description.decisions.declare<std::vector<HeightMapColumn>>(
          {"height_map_columns", RecordType::array, "m",
           "the columns whose reconstructed top rose this call, [column, row, top z] each, listed once"},
          height_map_columns_json, read_height_map_columns)),
      blocked_cells(description.decisions.declare_json(
          {"blocked_cells", RecordType::array, "",
           "planning cells an occupied voxel now blocks, [column, row, level] each (octomap mapping)"})),
      cleared_cells(description.decisions.declare_json(
          {"cleared_cells", RecordType::array, "",
           "planning cells an occupied voxel no longer blocks, [column, row, level] each (octomap mapping)"})),
      occupied_voxels(description.decisions.declare<std::int64_t>(
          "occupied_voxels", "", "occupied leaves of the octree after the scan (octomap mapping)")),
      start_cell(description.replan.declare_json(
          {"start_cell", RecordType::array, "", "the cell the search started from, [column, row, level]"})),
      goal_cell(description.replan.declare_json(
          {"goal_cell", RecordType::array, "", "the cell of the mission waypoint searched for, [column, row, level]"})),
      changed_cells(description.replan.declare<std::int64_t>("changed_cells", "", "cells the scan changed")),
      expansions(description.replan.declare<std::int64_t>("expansions", "", "nodes the search expanded")),
      mapping_ms(description.replan.declare<double>("mapping_ms", "ms", "measured time of the mapping step")) {
  description.cells = fold_height_map;
}

const DStarLite3dRecord& dstar_lite_3d_record() {
  static const DStarLite3dRecord record;
  return record;
}

std::unique_ptr<Planner> make_dstar_lite_3d_planner(const ParamsBlock& params, const PlannerContext& context) {
  return std::make_unique<DStarLite3dPlanner>(parse_dstar_lite_3d_config(params));
}

}  // namespace campo
