#pragma once
/// PNG figures for reports (SPEC §9), drawn with OpenCV from recorded run data
/// alone: top-down map, side view, depth maps with planner overlays, and
/// several runs overlaid. Anti-aliased, with title, axes in metres, scale bar
/// and legend. Same inputs => same pixels.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "campo/scene.hpp"

namespace campo {

/// One recorded sample of a run (a row of trajectory.csv).
struct TrackPoint {
  double time_s = 0.0;
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();
  double speed_mps = 0.0;
  double yaw_deg = 0.0;  ///< heading, counter-clockwise from x (east); 0 when the file has no yaw
};

/// A planner's reconstructed height map (decisions "height_map_grid", then
/// "height_map_columns" as columns rise): the top of what it mapped per cell.
struct HeightMapView {
  Eigen::Vector2d origin_m = Eigen::Vector2d::Zero();  ///< south-west corner of cell (0, 0)
  double cell_size_m = 1.0;
  int columns = 0;
  int rows = 0;
  std::vector<double> top_m;  ///< row-major from the south-west corner; NaN where nothing was mapped
  bool empty() const { return top_m.empty(); }
};

/// What the figures need of one run, read from its files.
struct RunView {
  std::string label;                        ///< legend text (e.g. the run directory name)
  std::vector<TrackPoint> track;            ///< flown/driven path in time order
  std::vector<Waypoint> mission;            ///< operator waypoints (start excluded)
  std::vector<int> reached;                 ///< indices into mission reached
  std::vector<Eigen::Vector3d> planned;     ///< intermediate waypoints a planner set (reached or not)
  std::vector<Eigen::Vector3d> discarded;   ///< intermediate waypoints a planner dropped
  std::vector<Eigen::Vector3d> planned_path;///< a global planner's planned path, if any
  std::vector<Eigen::Vector3d> sensor_hits; ///< range-sensor hits a mapping planner recorded ("lidar_hits")
  HeightMapView height_map;                 ///< what a mapping planner reconstructed, if any
  /// Time intervals [start, end] of local obstacle avoidance, s
  /// (Decisions::avoiding true, then false; one still open at the end closes
  /// at the last track time), highlighted on the map.
  std::vector<std::pair<double, double>> avoiding_s;
  std::string outcome;                      ///< run outcome, for titles
};

enum class TrackColoring { time, speed };

struct FigureStyle {
  int max_size_px = 1200;    ///< longer side of the plot area, in [200, 8000]
  double margin_m = 3.0;     ///< around the runs' paths and waypoints, >= 0
  std::string title;         ///< empty: one made from the run's label and outcome
  TrackColoring coloring = TrackColoring::time;
  /// Maps only: when set, exactly this area (x, y in metres) is drawn, and
  /// margin_m is not added (panels of one sequence share one frame).
  std::optional<Eigen::AlignedBox2d> bounds_m;
};

/// Bands around the plot of map, overlay and side-view figures, pixels: the
/// image is kFigureLeftPx + plot width + kFigurePanelPx wide (the panel on
/// the right holds the legend, the colour bar, the scale bar and the north
/// arrow) and kFigureTitlePx + plot height + kFigureBottomPx high.
inline constexpr int kFigureTitlePx = 56;
inline constexpr int kFigureLeftPx = 84;
inline constexpr int kFigureBottomPx = 64;
inline constexpr int kFigurePanelPx = 320;

/// Where a figure puts its parts and how data maps to pixels, for callers
/// that annotate a figure further and for tests. Maps: the plot's longer
/// side is style.max_size_px and its aspect that of the bounds (the runs'
/// paths, waypoints and planned paths plus margin_m, grown to whole obstacles
/// within the margin), except that a flat plot grows in height to fit the
/// legend column. Side views: the plot is style.max_size_px wide and
/// max(240, 0.35 * style.max_size_px) high, or as high as the legend.
struct FigureLayout {
  cv::Size image_px;
  cv::Rect title_px;             ///< band holding the title
  cv::Rect plot_px;              ///< the map or the profile
  cv::Rect legend_px;            ///< legend box
  cv::Rect colorbar_px;          ///< colour bar; empty when the figure has none
  cv::Rect scalebar_px;          ///< scale bar and north arrow; empty on side views
  /// Side views over ground: the height-above-ground panel under the profile
  /// (same distance axis), kFigureBottomPx below the plot and
  /// max(120, 0.12 * style.max_size_px) high; the image grows by both. Empty otherwise.
  cv::Rect agl_plot_px;
  Eigen::Vector2d min = Eigen::Vector2d::Zero();  ///< data (x, y) at the plot's bottom-left corner, m
  Eigen::Vector2d px_per_unit = Eigen::Vector2d::Ones();  ///< pixels per metre along x and y
  /// Drawing coordinates of a data point: pixel (c, r) is centred on (c, r).
  cv::Point2d to_px(const Eigen::Vector2d& p) const;
};

/// Top-down map (x east to the right, y north up, equal scales): terrain
/// shading and contour lines, obstacle footprints, movers' paths, planned
/// path, the track coloured by time or speed (with a colour bar) over an
/// amber band where the planner was avoiding an obstacle, numbered
/// mission waypoints (filled when reached), planned and discarded
/// intermediate waypoints, recorded sensor hits, start and goal, axes, scale
/// bar, north arrow and a legend of the symbols present.
cv::Mat draw_map(const Scene& scene, const RunView& run, const FigureStyle& style = {});
FigureLayout map_layout(const Scene& scene, const RunView& run, const FigureStyle& style = {});

/// Side view: altitude of the vehicle and of the terrain beneath it against
/// the distance travelled along the track, with the vertical extent of the
/// obstacles the track passes over, under or through, and the mission
/// waypoints at the track's closest approach to them. Distances are
/// horizontal, so that slopes show true. Where there is ground beneath the
/// track a second panel shows the height above it (vehicle altitude minus
/// ground height) with the band it stayed in, its minimum and maximum, shaded
/// and labelled (seed 000 Fig. 5.5: the drone follows the terrain).
/// The run's reconstructed height map (run.height_map must not be empty):
/// mapped cells coloured by height above the take-off ground, with a colour
/// bar, the scene's obstacles as outlines for comparison, the track and the
/// mission, on the same frame as draw_map.
cv::Mat draw_height_map(const Scene& scene, const RunView& run, const FigureStyle& style = {});
FigureLayout height_map_layout(const Scene& scene, const RunView& run, const FigureStyle& style = {});

cv::Mat draw_side_view(const Scene& scene, const RunView& run, const FigureStyle& style = {});
FigureLayout side_view_layout(const Scene& scene, const RunView& run, const FigureStyle& style = {});

/// Several runs on one map (seed 000 Fig. 5.6), one colour per run (run_color),
/// legend entries "label (outcome)"; shared start and goal markers.
cv::Mat draw_overlay(const Scene& scene, const std::vector<RunView>& runs, const FigureStyle& style = {});
FigureLayout overlay_layout(const Scene& scene, const std::vector<RunView>& runs, const FigureStyle& style = {});

/// One panel of a sequence figure: the run as it was at `time_s`.
struct SequencePanel {
  double time_s = 0.0;
  std::string caption;                    ///< the panel's title, e.g. "(a) 6.0 s: gap on the right"
  std::optional<double> heading_deg;      ///< world heading to draw as an arrow from the vehicle (a chosen gap)
};

/// The map of one run at several instants (seed 003 Fig. 46), two panels a
/// row, all on one frame (the track between the first and the last instant,
/// the movers there then, plus style.margin_m): in each, the track up to that
/// instant, every mover where it was then (its path dashed), the vehicle's
/// footprint (`footprint_m`, length x width, about its track point) at its
/// recorded heading and, when given, an arrow along heading_deg.
/// std::invalid_argument when `panels` is empty or the run has no track.
cv::Mat draw_sequence(const Scene& scene, const RunView& run, const std::vector<SequencePanel>& panels,
                      const Eigen::Vector2d& footprint_m, const FigureStyle& style = {});

/// Colour of a run in overlays: a fixed qualitative palette, cycled (BGR).
cv::Scalar run_color(std::size_t index);
/// Sequential colour map of tracks (time, speed) and depth values (viridis,
/// BGR); `fraction` is clamped to [0, 1]. Tracks map [first time, last time]
/// or [0, top speed] onto it.
cv::Vec3b sequential_color(double fraction);

/// Planner overlays on a depth map (seed 000 Fig. 5.2), all optional. Pixel
/// positions are depth-map pixels (column, row); continuous ones have
/// integers at pixel centres.
struct DepthOverlays {
  cv::Mat dilated;                       ///< CV_32F like the depth map
  cv::Mat thresholded;                   ///< CV_8U 0/255
  std::optional<double> threshold;       ///< the threshold t behind `thresholded`, for its caption
  std::optional<cv::Point> chosen_pixel; ///< the pixel a waypoint was chosen at
  std::vector<cv::Point> scan_line;      ///< pixels considered for the choice
  /// W', the projection of the waypoint being checked (continuous; may lie
  /// outside the map, where only the legend gives it).
  std::optional<cv::Point2d> waypoint_projection;
  /// Half-axes, pixels across and down, of W's projected safety sphere
  /// around W' (the neighbourhood ControllaVisibilita reads); 0: not drawn.
  cv::Size2d safety_ellipse_px;
  std::optional<cv::Point> new_waypoint_pixel;  ///< where a new waypoint was placed
};

/// A depth map (CV_32F in [0, 1], SPEC §6) as a report figure: grey or
/// colour-mapped, upscaled with visible pixels, with a value colour bar and
/// the overlays when given (each panel side by side: depth, dilated,
/// thresholded; the markers on every panel: scan line, W' with its safety
/// ellipse, chosen pixel ringed, new waypoint as a diamond). Colour mode: sequential_color, with no return (1) light grey and below
/// min range (0) black. Throws std::invalid_argument for an empty or
/// non-CV_32F depth map or overlays of another size.
cv::Mat draw_depth(const cv::Mat& depth, const DepthOverlays& overlays, bool colour, const std::string& title);

/// Where draw_depth puts its parts: the title band (kFigureTitlePx high),
/// the panels with their captions below, then a legend row (wrapped) of the
/// overlays and, in colour, of the special values. Each panel is the depth
/// map upscaled with nearest neighbours by the smallest integer factor that
/// makes its longer side at least kDepthPanelMinPx. Panels are kDepthGapPx
/// apart and from the left edge; the colour bar starts kDepthGapPx right of
/// the last panel, and with its labels it takes kDepthColorbarPx.
struct DepthFigureLayout {
  cv::Size image_px;
  cv::Rect title_px;
  int scale = 1;                    ///< figure pixels per depth-map pixel
  std::vector<cv::Rect> panels_px;  ///< depth, then dilated and thresholded when given
  cv::Rect colorbar_px;
  cv::Rect legend_px;               ///< legend rows; empty when there is nothing to explain
  /// Drawing coordinates of depth-map position `pixel` (continuous, integers
  /// at pixel centres) in panel `panel`.
  cv::Point2d to_px(std::size_t panel, cv::Point2d pixel) const;
};
inline constexpr int kDepthPanelMinPx = 256;
inline constexpr int kDepthGapPx = 32;
inline constexpr int kDepthColorbarPx = 120;
DepthFigureLayout depth_layout(const cv::Mat& depth, const DepthOverlays& overlays, bool colour);

}  // namespace campo
