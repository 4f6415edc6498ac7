#pragma once
/// The side view of a run: altitude profile along the track.
#include <utility>
#include <vector>

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
/// The dashed line of the altitude the mission asks for (the straight legs
/// from the start through each waypoint, seed 001's nominal route) is drawn
/// on it wherever the track passed its waypoints.
cv::Mat draw_side_view(const Scene& scene, const RunView& run, const FigureStyle& style = {});
FigureLayout side_view_layout(const Scene& scene, const RunView& run, const FigureStyle& style = {});

/// The altitude the mission asks for at each distance of `distance_m`:
/// linear between consecutive `knots` (distance along the track, altitude),
/// which are in the order flown (distances not decreasing); NaN before the
/// first knot and after the last. The knots are the start and the track's
/// closest approaches to the waypoints, so a leg between two waypoints at
/// one altitude is flat, and a climb or a descent leg a slope.
std::vector<double> mission_altitude_m(const std::vector<double>& distance_m,
                                       const std::vector<std::pair<double, double>>& knots);

}  // namespace campo
