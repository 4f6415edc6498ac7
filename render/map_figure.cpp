#include "render/map_figure.hpp"

#include <string>

#include "render/map_plot.hpp"

namespace campo {

using figure::draw_map_figure;
using figure::layout_map;
using figure::MapPlan;
using figure::plan_map;
using figure::run_title;

namespace {

std::vector<const RunView*> pointers(const std::vector<RunView>& runs) {
  std::vector<const RunView*> out;
  for (const auto& r : runs) out.push_back(&r);
  return out;
}

}  // namespace

FigureLayout map_layout(const Scene& scene, const RunView& run, const FigureStyle& style) {
  return layout_map(plan_map(scene, {&run}, style, false), style);
}

figure::Canvas draw_map(const Scene& scene, const RunView& run, const FigureStyle& style) {
  const MapPlan plan = plan_map(scene, {&run}, style, false);
  return draw_map_figure(scene, plan, layout_map(plan, style), run_title(style, run, "map"));
}

FigureLayout overlay_layout(const Scene& scene, const std::vector<RunView>& runs, const FigureStyle& style) {
  return layout_map(plan_map(scene, pointers(runs), style, true), style);
}

figure::Canvas draw_overlay(const Scene& scene, const std::vector<RunView>& runs, const FigureStyle& style) {
  const MapPlan plan = plan_map(scene, pointers(runs), style, true);
  const std::string title = !style.title.empty() ? style.title
                            : runs.size() == 1   ? "1 run"
                                                 : std::to_string(runs.size()) + " runs";
  return draw_map_figure(scene, plan, layout_map(plan, style), title);
}

FigureLayout fleet_map_layout(const Scene& scene, const std::vector<RunView>& vehicles, const FigureStyle& style) {
  return layout_map(plan_map(scene, pointers(vehicles), style, true, true), style);
}

figure::Canvas draw_fleet_map(const Scene& scene, const std::vector<RunView>& vehicles, const FigureStyle& style) {
  const MapPlan plan = plan_map(scene, pointers(vehicles), style, true, true);
  const std::string title = !style.title.empty() ? style.title : std::to_string(vehicles.size()) + " vehicles";
  return draw_map_figure(scene, plan, layout_map(plan, style), title);
}

}  // namespace campo
