#pragma once
/// The machinery of the map-like figures (map, overlay, height map and the
/// panels of a sequence): what a map shows (MapPlan, plan_map), where its
/// parts go (layout_map) and drawing it (draw_map_figure). Private to render/.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "campo/scene.hpp"
#include "render/figure_canvas.hpp"
#include "render/figure_parts.hpp"
#include "render/figure_scene.hpp"
#include "render/figure_style.hpp"

namespace campo::figure {

/// Dark outline drawn under tracks, and the track of height maps.
inline const cv::Scalar kTrackHalo = rgb(40, 40, 40);

/// Everything a map shows, decided before the layout because the legend's size depends on it.
struct MapPlan {
  explicit MapPlan(const Scene& scene) : ground(scene) {}
  std::vector<const RunView*> runs;
  bool overlay = false;
  /// The runs are the vehicles of one run (an overlay of them): each in vehicle_color, its own mission and goal,
  /// its start and goal ringed in its colour, its footprint at its track's end (RunView::footprint_m).
  bool fleet = false;
  Eigen::AlignedBox2d bounds;
  Ground ground;
  double contour_interval_m = 0.0;
  std::vector<Footprint> footprints;        // visible solids, lowest top first
  /// Aligned with `footprints`: the solid's bottom lies higher above the ground beneath it than any run flew
  /// above the ground (band_top_agl_m), so no run could touch it: drawn pale with a dashed edge (000's tree
  /// crowns above the flight band read apart from trunks and crowns at flight height).
  std::vector<bool> above_band;
  std::optional<double> band_top_agl_m;     // the highest height above the ground of any track point; none without tracks
  std::vector<std::size_t> movers;          // indices of visible movers
  std::vector<Footprint> mover_footprints;  // at their first point, aligned with `movers`
  bool movers_at_start = true;              // false: their paths alone (a video draws them where they are)
  std::vector<Eigen::Vector3d> starts;      // distinct
  std::vector<Waypoint> mission;            // distinct operator waypoints; the last is the goal
  std::vector<bool> mission_reached;        // single-run and fleet maps only
  std::vector<std::size_t> mission_owner;   // fleet maps: the run (vehicle) of each of `mission`; its last is its goal
  bool colorbar = false;
  TrackColoring coloring = TrackColoring::time;
  double value_lo = 0.0, value_hi = 1.0;    // range of the track colouring
  std::string colorbar_caption;
  std::vector<LegendEntry> legend;
  const HeightMapView* height_map = nullptr;  // a height-map figure: cells coloured, obstacles outlined
};

/// The plan of a map of one run (`overlay` false: the track coloured as
/// style.coloring says, with a colour bar) or of several runs overlaid, one
/// colour each, or (`fleet`) of the vehicles of one run (MapPlan::fleet);
/// std::invalid_argument for a bad style.
MapPlan plan_map(const Scene& scene, std::vector<const RunView*> runs, const FigureStyle& style, bool overlay,
                 bool fleet = false);
/// The colour of run `index` of the plan: vehicle_color on fleet maps, else run_color.
cv::Scalar plan_color(const MapPlan& plan, std::size_t index);
/// Appends to plan.legend an entry for every kind of symbol the plan shows.
void add_symbol_entries(MapPlan& plan, const Scene& scene);
/// Where the parts of the planned map go (FigureLayout, figure_style.hpp).
FigureLayout layout_map(const MapPlan& plan, const FigureStyle& style);
/// Draws the planned map with `layout` under `title` on a canvas of layout.image_px.
Canvas draw_map_figure(const Scene& scene, const MapPlan& plan, const FigureLayout& layout, const std::string& title);
/// Draws it on `canvas` with the figure's top-left corner at the canvas's origin (a sequence's panel
/// draws into a region of one canvas, so that its PDF stays vector).
void draw_map_figure(Canvas& canvas, const Scene& scene, const MapPlan& plan, const FigureLayout& layout,
                     const std::string& title);

/// The highest height above the ground (`ground`, 0 where it has none) of any track point of `runs`; none without
/// track points.
std::optional<double> flight_band_top_agl(const std::vector<const RunView*>& runs, const Ground& ground);
/// Whether a solid's bottom lies above `band_top_agl_m` over the ground beneath its centre; false without a band.
bool above_flight_band(const Footprint& f, const Ground& ground, std::optional<double> band_top_agl_m);

/// A vehicle's footprint (length along its heading, width across) at a
/// track point: its centre, unit heading and left, half extents, and the
/// four corners (front left, rear left, rear right, front right), world x, y.
struct VehicleOutline {
  Eigen::Vector2d centre, ahead, left, half;
  std::vector<Eigen::Vector2d> corners;
};
VehicleOutline vehicle_outline(const TrackPoint& at, const Eigen::Vector2d& footprint_m);

struct PlotMapper;
/// A solid's footprint filled with `fill` and outlined a shade darker.
void draw_footprint(Canvas& plot, const PlotMapper& to, const Footprint& f, const cv::Scalar& fill);
/// A solid above the flight band: its colour mixed with white (kAboveBandLighten) and a dashed edge a shade darker.
void draw_footprint_above_band(Canvas& plot, const PlotMapper& to, const Footprint& f, const cv::Scalar& colour);
/// How much white a solid above the flight band is mixed with.
inline constexpr double kAboveBandLighten = 0.65;
/// What the planned map shows of its runs (plan.runs): avoidance bands, planned paths, tracks,
/// recorded sensor hits, planned and discarded waypoints; draw_map_figure draws them over the
/// scene and under the mission's markers (a video draws them frame by frame).
void draw_run_marks(Canvas& plot, const PlotMapper& to, const MapPlan& plan);
/// A vehicle's footprint (length, width) at `at`'s position and heading, filled pale in `colour` (unless `fill` is
/// false) with an edge and a line to its front in it.
void draw_vehicle_footprint(Canvas& plot, const PlotMapper& to, const TrackPoint& at, const Eigen::Vector2d& footprint_m,
                            const cv::Scalar& colour, bool fill = true);

// Drawing coordinates relative to the plot area: draw in canvas.region(layout.plot_px), which clips what lies outside.
struct PlotMapper {
  const FigureLayout& layout;
  cv::Point2d operator()(const Eigen::Vector2d& p) const {
    return layout.to_px(p) - cv::Point2d(layout.plot_px.x, layout.plot_px.y);
  }
  cv::Point2d operator()(const Eigen::Vector3d& p) const { return (*this)(xy(p)); }
  template <class Points>
  std::vector<cv::Point2d> all(const Points& points) const {
    std::vector<cv::Point2d> out;
    for (const auto& p : points) out.push_back((*this)(p));
    return out;
  }
};

}  // namespace campo::figure
