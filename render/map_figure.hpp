#pragma once
/// The top-down map of one run and several runs overlaid on one map.
#include <vector>

#include <opencv2/core.hpp>

#include "campo/scene.hpp"
#include "render/figure_canvas.hpp"
#include "render/figure_style.hpp"

namespace campo {

/// Top-down map (x east to the right, y north up, equal scales): terrain
/// shading and contour lines, obstacle footprints, movers' paths, planned
/// path, the track coloured by time or speed (with a colour bar) over an
/// amber band where the planner was avoiding an obstacle, numbered
/// mission waypoints (filled when reached), planned and discarded
/// intermediate waypoints, recorded sensor hits, start and goal, axes, scale
/// bar, north arrow and a legend of the symbols present.
figure::Canvas draw_map(const Scene& scene, const RunView& run, const FigureStyle& style = {});
FigureLayout map_layout(const Scene& scene, const RunView& run, const FigureStyle& style = {});

/// Several runs on one map (seed 000 Fig. 5.6), one colour per run (run_color),
/// legend entries "label (outcome)"; shared start and goal markers.
figure::Canvas draw_overlay(const Scene& scene, const std::vector<RunView>& runs, const FigureStyle& style = {});
FigureLayout overlay_layout(const Scene& scene, const std::vector<RunView>& runs, const FigureStyle& style = {});

/// The vehicles of one run on one map, one colour each in scene order
/// (vehicle_color, a colour-blind-safe palette), legend entries "alias
/// (outcome)" from each view's label and outcome; each vehicle's mission with
/// its goal (filled when reached), its start and goal ringed in its colour,
/// its planner's waypoints in its colour, and its footprint
/// (RunView::footprint_m) at its track's end, at its heading.
figure::Canvas draw_fleet_map(const Scene& scene, const std::vector<RunView>& vehicles, const FigureStyle& style = {});
FigureLayout fleet_map_layout(const Scene& scene, const std::vector<RunView>& vehicles, const FigureStyle& style = {});

}  // namespace campo
