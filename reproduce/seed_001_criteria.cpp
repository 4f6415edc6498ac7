#include "reproduce/seed_001_criteria.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "grid/astar.hpp"
#include "reproduce/trajectory_checks.hpp"

namespace campo {

GridBlock mirror_rows(const GridBlock& block, int rows) {
  GridBlock out = block;
  out.row_first = rows + 1 - block.row_last;
  out.row_last = rows + 1 - block.row_first;
  return out;
}

GridBlock bounding_block(const std::vector<GridBlock>& blocks) {
  if (blocks.empty()) return {};
  GridBlock out = blocks.front();
  for (const GridBlock& b : blocks) {
    out.row_first = std::min(out.row_first, b.row_first);
    out.row_last = std::max(out.row_last, b.row_last);
    out.col_first = std::min(out.col_first, b.col_first);
    out.col_last = std::max(out.col_last, b.col_last);
    out.height_m = std::max(out.height_m, b.height_m);
  }
  return out;
}

int level_of_height(const TrueMap& map, double height_m) {
  return static_cast<int>(std::lround(height_m / map.level_m)) + map.ground_level;
}

namespace {

bool planar(grid::Connectivity c) { return !grid::is_3d(c); }

// The true map as campo's grid graph: in the plane of `level` for 4/8 connectivity, else the whole volume.
grid::GridGraph true_map_graph(const TrueMap& map, grid::Connectivity connectivity, int level,
                               double climb_cost_cells, const std::vector<GridBlock>& closed) {
  const bool flat = planar(connectivity);
  grid::GridGraph graph({map.cols, map.rows, flat ? 1 : map.levels}, connectivity, flat ? 1.0 : climb_cost_cells);
  const auto block = [&](const GridBlock& b, int top_level) {
    for (int r = std::max(b.row_first, 1); r <= std::min(b.row_last, map.rows); ++r) {
      for (int c = std::max(b.col_first, 1); c <= std::min(b.col_last, map.cols); ++c) {
        if (flat) {
          if (top_level >= level) graph.set_state({c - 1, r - 1, 0}, grid::CellState::blocked);
          continue;
        }
        for (int z = 0; z <= std::min(top_level, map.levels - 1); ++z) {
          graph.set_state({c - 1, r - 1, z}, grid::CellState::blocked);
        }
      }
    }
  };
  block({1, map.rows, 1, map.cols, 0.0}, map.ground_level);
  for (const GridBlock& b : map.blocks) block(b, level_of_height(map, b.height_m));
  for (const GridBlock& b : closed) block(b, map.levels);
  return graph;
}

grid::Cell to_grid(const MapCell& c, grid::Connectivity connectivity) {
  return {c.col - 1, c.row - 1, planar(connectivity) ? 0 : c.level};
}

RouteOptimum from_search(const TrueMap& map, const grid::SearchResult& result, int plane_level) {
  RouteOptimum out;
  if (result.status != grid::SearchStatus::found) return out;
  out.found = true;
  out.cost_cells = grid::to_cells(result.cost);
  out.links = static_cast<int>(result.steps());
  const bool flat = std::all_of(result.path.begin(), result.path.end(), [](const grid::Cell& c) { return c.z == 0; });
  for (std::size_t i = 0; i < result.path.size(); ++i) {
    const grid::Cell& c = result.path[i];
    out.path.push_back({c.y + 1, c.x + 1, flat && plane_level >= 0 ? plane_level : c.z});
    if (i == 0) continue;
    const grid::Cell& p = result.path[i - 1];
    const double dx = (c.x - p.x) * map.cell_m, dy = (c.y - p.y) * map.cell_m, dz = (c.z - p.z) * map.level_m;
    out.length_m += std::sqrt(dx * dx + dy * dy + dz * dz);
  }
  if (!out.path.empty()) {
    const int level = out.path.front().level;
    out.leaves_level = std::any_of(out.path.begin(), out.path.end(), [&](const MapCell& c) { return c.level != level; });
  }
  return out;
}

}  // namespace

RouteOptimum route_optimum(const TrueMap& map, grid::Connectivity connectivity, const MapCell& from,
                           const MapCell& to, double climb_cost_cells, const std::vector<GridBlock>& closed) {
  const grid::GridGraph graph = true_map_graph(map, connectivity, from.level, climb_cost_cells, closed);
  grid::AStar search(graph);
  return from_search(map, search.plan(to_grid(from, connectivity), to_grid(to, connectivity)),
                     planar(connectivity) ? from.level : -1);
}

RouteOptimum route_through(const TrueMap& map, grid::Connectivity connectivity, const MapCell& from,
                           const MapCell& to, double climb_cost_cells, const GridBlock& area) {
  const grid::GridGraph graph = true_map_graph(map, connectivity, from.level, climb_cost_cells, {});
  grid::AStar search(graph);
  const int plane = planar(connectivity) ? from.level : -1;
  RouteOptimum best;
  for (int r = area.row_first; r <= area.row_last; ++r) {
    for (int c = area.col_first; c <= area.col_last; ++c) {
      const MapCell via{r, c, from.level};
      const grid::SearchResult a = search.plan(to_grid(from, connectivity), to_grid(via, connectivity));
      if (a.status != grid::SearchStatus::found) continue;
      const RouteOptimum first = from_search(map, a, plane);
      const RouteOptimum second =
          from_search(map, search.plan(to_grid(via, connectivity), to_grid(to, connectivity)), plane);
      if (!second.found) continue;
      if (best.found && first.cost_cells + second.cost_cells >= best.cost_cells) continue;
      best = first;
      best.cost_cells += second.cost_cells;
      best.length_m += second.length_m;
      best.links += second.links;
      best.leaves_level = first.leaves_level || second.leaves_level;
      best.path.insert(best.path.end(), second.path.begin() + 1, second.path.end());
    }
  }
  return best;
}

Judgement judge_with_thesis_setting(std::optional<bool> thesis_setting, std::optional<bool> bundled,
                                    bool cause_known) {
  Judgement j;
  if (!thesis_setting && !bundled) return j;
  j.holds = thesis_setting.value_or(false) || bundled.value_or(false);
  j.has_departures = !thesis_setting.value_or(false);
  j.cause_known = !*j.holds && cause_known;
  return j;
}

bool SlotReading::slot_on_shortest_route() const {
  // Costs are sums of the search's fixed-point moves converted to cells: equal routes convert equally.
  return optimum.found && through_slot.found && through_slot.cost_cells <= optimum.cost_cells + 1e-9;
}

Judgement judge_slot(const SlotMeasure& m) {
  Judgement j;
  const std::optional<bool>* runs[] = {&m.passed_thesis_setting, &m.passed_bundled, &m.passed_other_reading};
  bool any_run = false, any_passed = false;
  for (const std::optional<bool>* r : runs) {
    any_run = any_run || r->has_value();
    any_passed = any_passed || r->value_or(false);
  }
  if (!any_run) return j;
  j.holds = any_passed;
  j.has_departures = !m.passed_thesis_setting.value_or(false);
  if (!any_passed) {
    // Settled only when the search shows, under every reading computed, that the slot is no shortest way.
    j.cause_known = !m.readings.empty() &&
                    std::none_of(m.readings.begin(), m.readings.end(),
                                 [](const SlotReading& r) { return !r.optimum.found || r.slot_on_shortest_route(); });
  }
  return j;
}

Rect footprint(const GridBlock& block, double cell_m, const Eigen::Vector2d& origin_m) {
  return {origin_m.x() + (block.col_first - 1) * cell_m, origin_m.x() + block.col_last * cell_m,
          origin_m.y() + (block.row_first - 1) * cell_m, origin_m.y() + block.row_last * cell_m};
}

const char* side_name(Side side) {
  switch (side) {
    case Side::none: return "none";
    case Side::west: return "west";
    case Side::east: return "east";
  }
  return "?";
}

std::vector<Side> passing_sides(const std::vector<Eigen::Vector2d>& track, const std::vector<Rect>& footprints) {
  std::vector<Side> out;
  for (const Rect& f : footprints) {
    double sum = 0.0;
    int n = 0;
    for (const Eigen::Vector2d& p : track) {
      if (p.y() < f.y_min || p.y() > f.y_max) continue;
      sum += p.x();
      ++n;
    }
    out.push_back(n == 0 ? Side::none : sum / n < 0.5 * (f.x_min + f.x_max) ? Side::west : Side::east);
  }
  return out;
}

std::optional<bool> weave_holds(const WeaveMeasure& m, std::optional<double> outside_optimum_m) {
  const bool flown = std::any_of(m.sides.begin(), m.sides.end(), [](Side s) { return s != Side::none; });
  if (!flown || !outside_optimum_m) return std::nullopt;
  const bool west = std::count(m.sides.begin(), m.sides.end(), Side::west) > 0;
  const bool east = std::count(m.sides.begin(), m.sides.end(), Side::east) > 0;
  return !m.climbed && west && east && m.lap_m < *outside_optimum_m;
}

std::optional<bool> wall_holds(std::optional<bool> reached_clean, std::optional<double> lateral_before_climb_m,
                               double cell_m) {
  if (!reached_clean) return std::nullopt;
  return *reached_clean && lateral_before_climb_m.has_value() && *lateral_before_climb_m < cell_m;
}

BehaviourCounts count_behaviours(const std::vector<SettingBehaviours>& settings) {
  BehaviourCounts c;
  for (const SettingBehaviours& s : settings) {
    ++c.settings;
    c.slot_n += s.slot.has_value(), c.slot += s.slot.value_or(false);
    c.weave_n += s.weave.has_value(), c.weave += s.weave.value_or(false);
    c.wall_n += s.wall.has_value(), c.wall += s.wall.value_or(false);
    c.all += s.all();
  }
  return c;
}

const SettingBehaviours* find_setting(const std::vector<SettingBehaviours>& settings, const std::string& connectivity,
                                      double climb_cost, double pitch_deg) {
  for (const SettingBehaviours& s : settings) {
    if (s.connectivity == connectivity && std::abs(s.climb_cost - climb_cost) < 1e-9 &&
        std::abs(s.pitch_deg - pitch_deg) < 1e-9) {
      return &s;
    }
  }
  return nullptr;
}

Judgement judge_sweep(const SettingBehaviours* thesis_setting, bool slot_cause, bool weave_cause) {
  Judgement j;
  if (!thesis_setting || !thesis_setting->slot || !thesis_setting->weave || !thesis_setting->wall) return j;
  j.holds = thesis_setting->all();
  j.has_departures = false;
  if (!*j.holds) {
    j.cause_known = (*thesis_setting->slot || slot_cause) && (*thesis_setting->weave || weave_cause) &&
                    *thesis_setting->wall;
  }
  return j;
}

double max_offset_m(const std::vector<Eigen::Vector2d>& track, const std::vector<Eigen::Vector2d>& nominal) {
  double worst = 0.0;
  for (const Eigen::Vector2d& p : track) worst = std::max(worst, distance_to_polyline(p, nominal));
  return worst;
}

std::optional<bool> laps_coincide(const std::vector<double>& max_offsets_m, double cell_m) {
  if (max_offsets_m.empty()) return std::nullopt;
  return std::all_of(max_offsets_m.begin(), max_offsets_m.end(), [&](double d) { return d < cell_m; });
}

std::optional<bool> low_blocks_ignored(const std::vector<LowBlockPass>& passes, double climb_m) {
  bool any = false, holds = true;
  for (const LowBlockPass& p : passes) {
    if (p.nominal_over == 0) continue;
    any = true;
    holds = holds && p.samples_over > 0 && p.max_rise_m < climb_m;
  }
  if (!any) return std::nullopt;
  return holds;
}

std::optional<bool> movers_not_avoided(const std::vector<MoverRun>& runs, double cell_m) {
  if (runs.empty()) return std::nullopt;
  const bool hit = std::any_of(runs.begin(), runs.end(), [](const MoverRun& r) { return r.hit; });
  const bool kept = std::all_of(runs.begin(), runs.end(), [&](const MoverRun& r) { return r.max_offset_m < cell_m; });
  return hit && kept;
}

std::optional<bool> bridge_flown_over(bool reached_clean, double low_m, double high_m, double deck_top_m) {
  if (!(low_m <= high_m)) return std::nullopt;
  return reached_clean && low_m > deck_top_m;
}

}  // namespace campo
