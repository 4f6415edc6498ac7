#pragma once
/// The frames of a run's video (`campo render --kind video`): the top-down
/// map with the track growing, a sensor panel of that moment and a clock and
/// metrics strip, side by side on one frame. Drawn from recorded data alone:
/// the same run gives the same pixels.
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "campo/scene.hpp"
#include "render/figure_style.hpp"
#include "render/map_plot.hpp"

namespace campo {

/// The strip under a frame: the clock over the run's duration, measured
/// values of that moment and the planner's state.
struct VideoStrip {
  double time_s = 0.0;
  double duration_s = 0.0;
  std::vector<std::pair<std::string, std::string>> values;  ///< label, value with unit: {"speed", "1.20 m/s"}
  std::string state;                                        ///< e.g. "avoiding: gap on the left"
};

/// Where a frame puts its parts: the map on the left, the sensor panel on the
/// right (its caption in the top kVideoCaptionPx), the strip along the bottom
/// (kVideoStripPx high).
struct VideoLayout {
  cv::Size frame_px;
  cv::Rect map_px;
  cv::Rect sensor_px;
  cv::Rect strip_px;
};
inline constexpr int kVideoStripPx = 72;
inline constexpr int kVideoCaptionPx = 32;
/// The layout of a frame of `frame_px` (even sides, at least 480 x 270).
VideoLayout video_layout(cv::Size frame_px);

/// Draws the frames of one run. The scene's map (terrain, obstacles, mission,
/// axes, legend, time colour bar over the whole run) is drawn once; each
/// frame adds the run as it was then (RunView at that time: the track so far
/// coloured by time, avoidance bands, planner waypoints), the movers where
/// they were and the vehicle's footprint at its heading.
class VideoFrames {
 public:
  /// `run` is the whole run (its track fixes the map's frame and time scale);
  /// `vehicle_size_m` is the vehicle's length, width and height.
  VideoFrames(const Scene& scene, const RunView& run, const Eigen::Vector3d& vehicle_size_m, cv::Size frame_px);
  /// The frames of the vehicles of one run (a fleet map, draw_fleet_map): `vehicles` whole, in scene order, each
  /// with its footprint (RunView::footprint_m), drawn each frame where it is, in its colour; the map titled
  /// `title` (empty: "N vehicles").
  VideoFrames(const Scene& scene, const std::vector<RunView>& vehicles, cv::Size frame_px, const std::string& title = "");

  const VideoLayout& layout() const { return layout_; }
  /// Where world point (x, y) is drawn on a frame, pixels (centres at integers).
  cv::Point2d to_frame_px(const Eigen::Vector2d& world_m) const;

  /// The frame at `time_s`: `so_far` is the run up to then (run_view_at),
  /// `sensor_panel` any BGR image (fitted into the panel, aspect kept; empty:
  /// the caption alone), `strip` the strip's content. Drawn on a canvas of
  /// the frame's size (the map's background a raster, the run and the strip
  /// vectors) and returned as its BGR raster, for the encoder.
  cv::Mat draw(const RunView& so_far, double time_s, const cv::Mat& sensor_panel, const std::string& sensor_caption,
               const VideoStrip& strip);
  /// The same for the vehicles of one run (the second constructor): `so_far` one view per vehicle, in its order.
  cv::Mat draw(const std::vector<RunView>& so_far, double time_s, const cv::Mat& sensor_panel,
               const std::string& sensor_caption, const VideoStrip& strip);

 private:
  // The map's background and the layouts, from plan_ (its runs the whole runs), titled `title`.
  void draw_background(const std::vector<RunView>& whole, const std::string& title, const FigureStyle& style);
  // The frame: the runs (plan_.runs) over the background, then the vehicle, the sensor panel and the strip.
  cv::Mat draw_frame(const std::vector<const RunView*>& so_far, const TrackPoint* vehicle, double time_s,
                     const cv::Mat& sensor_panel, const std::string& sensor_caption, const VideoStrip& strip);

  const Scene& scene_;
  figure::MapPlan plan_;
  FigureLayout map_layout_;
  cv::Mat map_background_;         // the map figure without the run and the movers, scaled to map_paste_px_
  cv::Rect map_paste_px_;          // where the map figure lands on a frame
  FigureLayout frame_map_layout_;  // the map's layout in frame pixels
  Eigen::Vector3d vehicle_size_m_;
  VideoLayout layout_;
};

}  // namespace campo
