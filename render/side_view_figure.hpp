#pragma once
/// The side view of a run: altitude profile along the track.
#include <opencv2/core.hpp>

#include "campo/scene.hpp"
#include "render/figure_style.hpp"

namespace campo {

/// Side view: altitude of the vehicle and of the terrain beneath it against
/// the distance travelled along the track, with the vertical extent of the
/// obstacles the track passes over, under or through, and the mission
/// waypoints at the track's closest approach to them. Distances are
/// horizontal, so that slopes show true. Where there is ground beneath the
/// track a second panel shows the height above it (vehicle altitude minus
/// ground height) with the band it stayed in, its minimum and maximum, shaded
/// and labelled (seed 000 Fig. 5.5: the drone follows the terrain).
cv::Mat draw_side_view(const Scene& scene, const RunView& run, const FigureStyle& style = {});
FigureLayout side_view_layout(const Scene& scene, const RunView& run, const FigureStyle& style = {});

}  // namespace campo
