#include "render/height_map_figure.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "render/map_plot.hpp"

namespace campo {

using figure::add_symbol_entries;
using figure::draw_map_figure;
using figure::kTrackHalo;
using figure::layout_map;
using figure::line_entry;
using figure::MapPlan;
using figure::plan_map;
using figure::run_title;

namespace {

MapPlan plan_height_map(const Scene& scene, const RunView& run, const FigureStyle& style) {
  if (run.height_map.empty()) throw std::invalid_argument("the run recorded no height map");
  MapPlan plan = plan_map(scene, {&run}, style, false);
  plan.height_map = &run.height_map;
  plan.value_lo = std::numeric_limits<double>::infinity();
  plan.value_hi = -plan.value_lo;
  for (const double top : run.height_map.top_m) {
    if (std::isnan(top)) continue;
    plan.value_lo = std::min(plan.value_lo, top);
    plan.value_hi = std::max(plan.value_hi, top);
  }
  if (!(plan.value_hi > plan.value_lo)) {
    plan.value_lo = std::isfinite(plan.value_lo) ? plan.value_lo : 0.0;
    plan.value_hi = plan.value_lo + 1.0;
  }
  plan.colorbar = true;
  plan.colorbar_caption = "mapped top, z (m)";
  plan.legend.clear();
  plan.legend.push_back(line_entry(kTrackHalo, 2, "track"));
  add_symbol_entries(plan, scene);
  return plan;
}

}  // namespace

FigureLayout height_map_layout(const Scene& scene, const RunView& run, const FigureStyle& style) {
  return layout_map(plan_height_map(scene, run, style), style);
}

figure::Canvas draw_height_map(const Scene& scene, const RunView& run, const FigureStyle& style) {
  const MapPlan plan = plan_height_map(scene, run, style);
  return draw_map_figure(scene, plan, layout_map(plan, style), run_title(style, run, "reconstructed height map"));
}

}  // namespace campo
