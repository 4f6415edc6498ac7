#pragma once
/// A mapping planner's reconstructed height map drawn as a map.
#include <opencv2/core.hpp>

#include "campo/scene.hpp"
#include "render/figure_canvas.hpp"
#include "render/figure_style.hpp"

namespace campo {

/// The run's reconstructed height map (run.height_map must not be empty):
/// mapped cells coloured by height above the take-off ground, with a colour
/// bar, the scene's obstacles as outlines for comparison, the track and the
/// mission, on the same frame as draw_map.
figure::Canvas draw_height_map(const Scene& scene, const RunView& run, const FigureStyle& style = {});
FigureLayout height_map_layout(const Scene& scene, const RunView& run, const FigureStyle& style = {});

}  // namespace campo
