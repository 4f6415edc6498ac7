#pragma once
/// What the report figures draw and how: the run data they read (RunView),
/// their style (FigureStyle), the bands around a plot and where a figure puts
/// its parts (FigureLayout), and the colours several figures share.
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

/// A planner's reconstructed height map (its PlannerRecord::cells overlay: dstar_lite_3d's
/// height_map_grid, then its height_map_columns as columns rise): the top of what it mapped per cell.
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
  std::vector<Eigen::Vector3d> sensor_hits; ///< range-sensor hits a mapping planner recorded (Decisions::lidar_hits)
  HeightMapView height_map;                 ///< what a mapping planner reconstructed, if any
  /// Time intervals [start, end] of local obstacle avoidance, s
  /// (Decisions::avoiding true, then false; one still open at the end closes
  /// at the last track time), highlighted on the map.
  std::vector<std::pair<double, double>> avoiding_s;
  std::string outcome;                      ///< run outcome, for titles
  /// Each collision recorded (run.json's collision_events): when, s, and the
  /// point of the body touched, world frame; marked on maps, side views and videos.
  std::vector<std::pair<double, Eigen::Vector3d>> collisions;
  /// The vehicle's length and width, m: maps of several vehicles of one run
  /// draw it at the track's end, at its heading (zero: not drawn).
  Eigen::Vector2d footprint_m = Eigen::Vector2d::Zero();
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

/// Colours of run_color before it repeats.
inline constexpr std::size_t kRunColors = 12;
/// Colour of a run in overlays: a fixed qualitative palette of kRunColors, cycled (BGR).
cv::Scalar run_color(std::size_t index);
/// Colours of vehicle_color before it repeats.
inline constexpr std::size_t kVehicleColors = 8;
/// Colour of a vehicle of a run of several (its track, its footprint, its
/// legend entry): Okabe and Ito's colour-blind-safe palette of kVehicleColors,
/// in scene order, cycled (BGR); its green and vermilion last, as start and
/// goal markers are green and red.
cv::Scalar vehicle_color(std::size_t index);
/// Sequential colour map of tracks (time, speed) and depth values (viridis,
/// BGR); `fraction` is clamped to [0, 1]. Tracks map [first time, last time]
/// or [0, top speed] onto it.
cv::Vec3b sequential_color(double fraction);

}  // namespace campo
