#pragma once
/// The side view of a run: altitude profile along the track.
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "campo/scene.hpp"
#include "render/figure_canvas.hpp"
#include "render/figure_style.hpp"

namespace campo {

/// Side view: altitude of the vehicle and of the terrain beneath it against
/// the distance travelled along the track, with the vertical extent of the
/// obstacles the track passes over, under or through, and the mission
/// waypoints at the track's closest approach to them. Distances are
/// horizontal, so that slopes show true. Where there is ground beneath the
/// track a second panel shows the height above it (vehicle altitude minus
/// ground height) with the band it stayed in, its minimum and maximum, shaded
/// and labelled right of the panel (seed 000 Fig. 5.5: the drone follows the
/// terrain); labels of nearly equal values are moved apart
/// (labels_apart_px), and read as one when they print the same.
/// The dashed line of the altitude the mission asks for (the straight legs
/// from the start through each waypoint, seed 001's nominal route) is drawn
/// on it wherever the track passed its waypoints. A goal the run did not
/// reach is drawn beyond the track's end, at goal_distance_m (the distance
/// axis goes on as the straight line from where the track ended to the goal,
/// drawn dashed red), at the goal's altitude.
figure::Canvas draw_side_view(const Scene& scene, const RunView& run, const FigureStyle& style = {});
FigureLayout side_view_layout(const Scene& scene, const RunView& run, const FigureStyle& style = {});

/// The side views of the vehicles of one run on shared axes: each vehicle's
/// altitude along the distance travelled on its own track, in its colour
/// (vehicle_color, the map's), with the obstacles and ground beneath each
/// track, each one's mission altitude dashed in a paler shade, its waypoints,
/// goal, start and collisions; legend entries "alias (outcome)". No
/// height-above-ground panel (one per vehicle would not share the axes).
figure::Canvas draw_fleet_side_view(const Scene& scene, const std::vector<RunView>& vehicles,
                                    const FigureStyle& style = {});

/// The altitude the mission asks for at each distance of `distance_m`:
/// linear between consecutive `knots` (distance along the track, altitude),
/// which are in the order flown (distances not decreasing); NaN before the
/// first knot and after the last. The knots are the start and the track's
/// closest approaches to the waypoints, so a leg between two waypoints at
/// one altitude is flat, and a climb or a descent leg a slope.
std::vector<double> mission_altitude_m(const std::vector<double>& distance_m,
                                       const std::vector<std::pair<double, double>>& knots);

/// Where the side view puts a goal not reached on its distance axis: the
/// track's length plus the horizontal straight-line distance from the track's
/// last point to the goal (the rest of the way, had the vehicle gone straight
/// on to it), metres.
double goal_distance_m(double track_length_m, const Eigen::Vector3d& track_end_m, const Eigen::Vector3d& goal_m);

/// Drawing rows of two labels wanted at `upper_px` <= `lower_px` so that they
/// are at least `min_gap_px` apart: unchanged when they already are, else
/// moved apart symmetrically about their midpoint.
std::pair<double, double> labels_apart_px(double upper_px, double lower_px, double min_gap_px);
/// Rows between the side view's "highest" and "lowest" labels (kLabelFont: a
/// 12-pixel cap height and 3-pixel descenders, so 7 pixels stay clear).
inline constexpr double kAglLabelGapPx = 22.0;

}  // namespace campo
