#include "render/video_frame.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

#include "render/figure_canvas.hpp"
#include "render/figure_parts.hpp"
#include "render/figure_scene.hpp"

namespace campo {

using figure::PlotMapper;
using figure::xy;

namespace {

const cv::Scalar kStripFill = figure::rgb(244, 244, 244);
const cv::Scalar kClockBar = figure::rgb(31, 119, 180);

// The map is drawn at this plot size and scaled into its panel: large enough that the
// scene's details survive, small enough to draw quickly.
constexpr int kMapPlotPx = 720;

FigureStyle map_style(const RunView& run) {
  FigureStyle style;
  style.max_size_px = kMapPlotPx;
  style.margin_m = 2.0;
  style.title = run.label + (run.outcome.empty() ? "" : " - " + run.outcome);
  return style;
}

// Where an image of `size` lands when fitted into `box` with its aspect kept, centred.
cv::Rect fitted(const cv::Rect& box, cv::Size size) {
  const double k = std::min(static_cast<double>(box.width) / size.width, static_cast<double>(box.height) / size.height);
  const cv::Size scaled(std::max(1, static_cast<int>(std::floor(size.width * k))),
                        std::max(1, static_cast<int>(std::floor(size.height * k))));
  return {box.x + (box.width - scaled.width) / 2, box.y + (box.height - scaled.height) / 2, scaled.width,
          scaled.height};
}

// `image` scaled to `size` (area-averaged when shrinking, so thin lines and text stay smooth).
cv::Mat scaled(const cv::Mat& image, cv::Size size) {
  if (image.size() == size) return image;
  cv::Mat out;
  const bool shrink = size.width < image.cols;
  cv::resize(image, out, size, 0.0, 0.0, shrink ? cv::INTER_AREA : cv::INTER_LINEAR);
  return out;
}

// `image` (BGR) scaled into `at` of the frame: resampled here, embedded pixel for pixel.
void paste(figure::Canvas& frame, const cv::Rect& at, const cv::Mat& image) {
  if (image.empty() || at.width <= 0 || at.height <= 0) return;
  frame.image(scaled(image, at.size()), at);
}

// The layout of the map figure `map` pasted scaled onto `at` of a frame: the same world-to-pixel mapping as the
// pasted pixels (pixel centres to pixel centres, scaling about the corners), with the plot's rectangle rounded to
// whole frame pixels and the rounding taken up by the data origin, so that the run is drawn in frame pixels.
FigureLayout pasted_layout(const FigureLayout& map, const cv::Rect& at) {
  const double kx = static_cast<double>(at.width) / map.image_px.width;
  const double ky = static_cast<double>(at.height) / map.image_px.height;
  const cv::Rect& p = map.plot_px;
  const double left = at.x + p.x * kx, right = at.x + (p.x + p.width) * kx;
  const double top = at.y + p.y * ky, bottom = at.y + (p.y + p.height) * ky;
  FigureLayout out = map;
  out.image_px = at.size();
  const int x0 = static_cast<int>(std::lround(left)), x1 = static_cast<int>(std::lround(right));
  const int y0 = static_cast<int>(std::lround(top)), y1 = static_cast<int>(std::lround(bottom));
  out.plot_px = {x0, y0, x1 - x0, y1 - y0};
  out.px_per_unit = {map.px_per_unit.x() * kx, map.px_per_unit.y() * ky};
  out.min = {map.min.x() + (x0 - left) / out.px_per_unit.x(), map.min.y() + (bottom - y1) / out.px_per_unit.y()};
  return out;
}

// The vehicle's footprint at its heading, with a line to its front and a ring that finds it at any scale.
void draw_vehicle(figure::Canvas& plot, const PlotMapper& to, const TrackPoint& at, const Eigen::Vector2d& footprint_m) {
  const figure::VehicleOutline vehicle = figure::vehicle_outline(at, footprint_m);
  const Eigen::Vector2d& centre = vehicle.centre;
  const std::vector<cv::Point2d> outline = to.all(vehicle.corners);
  plot.circle(to(centre), 14.0, figure::kInk, 2);
  plot.fill_polygon(outline, figure::rgb(250, 250, 250));
  plot.polyline(outline, figure::kInk, 2, true);
  const Eigen::Vector2d nose = centre + std::max(vehicle.half.x(), 0.6) * vehicle.ahead;
  plot.line(to(centre), to(nose), figure::kInk, 2);
}

void draw_strip(figure::Canvas& frame, const cv::Rect& box, const VideoStrip& strip) {
  frame.fill_rectangle(box, kStripFill);
  frame.line(cv::Point2d(box.x, box.y), cv::Point2d(box.br().x - 1, box.y), figure::kGridInk, 1);
  char clock[64];
  std::snprintf(clock, sizeof clock, "%.1f s / %.1f s", strip.time_s, strip.duration_s);
  const int row1 = box.y + 24, row2 = box.y + 52;
  figure::put_text(frame, clock, cv::Point2d(box.x + 16, row1), figure::kTitleFont, figure::kInk);
  // How far through the run: a bar under the clock.
  const cv::Rect bar(box.x + 16, row2 - 5, 220, 10);
  frame.fill_rectangle(bar, figure::kGridInk);
  const double f = strip.duration_s > 0.0 ? std::clamp(strip.time_s / strip.duration_s, 0.0, 1.0) : 1.0;
  frame.fill_box({bar.x - 0.5, bar.y - 0.5}, {bar.x - 0.5 + f * bar.width, bar.y + bar.height - 0.5}, kClockBar);
  // The values in equal columns right of the clock; the state under them.
  const int x0 = box.x + 270;
  const int column = strip.values.empty() ? 0 : std::max(1, (box.br().x - 16 - x0) / static_cast<int>(strip.values.size()));
  for (std::size_t i = 0; i < strip.values.size(); ++i) {
    const auto& [label, value] = strip.values[i];
    const double x = x0 + static_cast<double>(i) * column;
    figure::put_text(frame, label, cv::Point2d(x, row1 - 6), figure::kSmallFont, figure::kMutedInk);
    figure::put_text(frame, value, cv::Point2d(x, row1 + 10), figure::kLabelFont, figure::kInk);
  }
  figure::put_text(frame, strip.state, cv::Point2d(x0, row2 + 2), figure::kLabelFont, figure::kInk);
}

}  // namespace

VideoLayout video_layout(cv::Size frame_px) {
  if (frame_px.width < 480 || frame_px.height < 270 || frame_px.width % 2 || frame_px.height % 2) {
    throw std::invalid_argument("video_layout: frame sides must be even and at least 480 x 270");
  }
  VideoLayout l;
  l.frame_px = frame_px;
  const int top = frame_px.height - kVideoStripPx;
  const int map_w = static_cast<int>(std::lround(0.56 * frame_px.width));
  l.map_px = {0, 0, map_w, top};
  l.sensor_px = {map_w, 0, frame_px.width - map_w, top};
  l.strip_px = {0, top, frame_px.width, kVideoStripPx};
  return l;
}

VideoFrames::VideoFrames(const Scene& scene, const RunView& run, const Eigen::Vector3d& vehicle_size_m,
                         cv::Size frame_px)
    : scene_(scene),
      plan_(figure::plan_map(scene, {&run}, map_style(run), false)),
      vehicle_size_m_(vehicle_size_m),
      layout_(video_layout(frame_px)) {
  if (run.track.empty()) throw std::invalid_argument("VideoFrames: the run has no track");
  RunView bare;
  bare.label = run.label;
  bare.mission = run.mission;
  draw_background({bare}, map_style(run).title, map_style(run));
}

VideoFrames::VideoFrames(const Scene& scene, const std::vector<RunView>& vehicles, cv::Size frame_px,
                         const std::string& title)
    : scene_(scene),
      plan_(scene),
      vehicle_size_m_(Eigen::Vector3d::Zero()),
      layout_(video_layout(frame_px)) {
  std::vector<const RunView*> runs;
  for (const RunView& v : vehicles) {
    if (v.track.empty()) throw std::invalid_argument("VideoFrames: vehicle " + v.label + " has no track");
    runs.push_back(&v);
  }
  FigureStyle style = map_style(RunView{});
  style.title = title.empty() ? std::to_string(vehicles.size()) + " vehicles" : title;
  plan_ = figure::plan_map(scene, runs, style, true, true);
  std::vector<RunView> bare(vehicles.size());
  for (std::size_t i = 0; i < vehicles.size(); ++i) {
    bare[i].label = vehicles[i].label;
    bare[i].mission = vehicles[i].mission;
  }
  draw_background(bare, style.title, style);
}

void VideoFrames::draw_background(const std::vector<RunView>& bare, const std::string& title, const FigureStyle& style) {
  // The whole run fixes the frame, the legend and the time scale; the background shows none of
  // its progress: movers only by their paths, mission waypoints not yet reached.
  plan_.movers_at_start = false;
  plan_.mission_reached.assign(plan_.mission_reached.size(), false);
  map_layout_ = figure::layout_map(plan_, style);
  plan_.runs.clear();
  for (const RunView& v : bare) plan_.runs.push_back(&v);
  const cv::Mat map = figure::draw_map_figure(scene_, plan_, map_layout_, title).raster();
  plan_.runs.clear();
  map_paste_px_ = fitted(layout_.map_px, map.size());
  map_background_ = scaled(map, map_paste_px_.size());
  frame_map_layout_ = pasted_layout(map_layout_, map_paste_px_);
}

cv::Point2d VideoFrames::to_frame_px(const Eigen::Vector2d& world_m) const {
  return frame_map_layout_.to_px(world_m);
}

cv::Mat VideoFrames::draw(const RunView& so_far, double time_s, const cv::Mat& sensor_panel,
                          const std::string& sensor_caption, const VideoStrip& strip) {
  if (so_far.track.empty()) throw std::invalid_argument("VideoFrames::draw: the run has no track");
  return draw_frame({&so_far}, &so_far.track.back(), time_s, sensor_panel, sensor_caption, strip);
}

cv::Mat VideoFrames::draw(const std::vector<RunView>& so_far, double time_s, const cv::Mat& sensor_panel,
                          const std::string& sensor_caption, const VideoStrip& strip) {
  std::vector<const RunView*> runs;
  for (const RunView& v : so_far) {
    if (v.track.empty()) throw std::invalid_argument("VideoFrames::draw: vehicle " + v.label + " has no track");
    runs.push_back(&v);
  }
  // Each vehicle's footprint is one of its marks on a fleet map (draw_run_marks).
  return draw_frame(runs, nullptr, time_s, sensor_panel, sensor_caption, strip);
}

cv::Mat VideoFrames::draw_frame(const std::vector<const RunView*>& so_far, const TrackPoint* vehicle, double time_s,
                                const cv::Mat& sensor_panel, const std::string& sensor_caption, const VideoStrip& strip) {
  figure::Canvas frame(layout_.frame_px);
  frame.image(map_background_, map_paste_px_);
  {
    // The run in frame pixels over the scaled map: lines and markers at their own widths, sharp at any frame size.
    const auto clip = frame.region(frame_map_layout_.plot_px);
    const PlotMapper to{frame_map_layout_};
    plan_.runs = so_far;
    figure::draw_run_marks(frame, to, plan_);
    plan_.runs.clear();
    for (const Mover& m : scene_.movers) {
      Shape then = m.shape;
      then.pose.translation() = m.position_at(time_s);
      figure::draw_footprint(frame, to, figure::footprint(then), figure::lighten(figure::to_bgr(m.shape.color), 0.3));
    }
    if (vehicle) draw_vehicle(frame, to, *vehicle, vehicle_size_m_.head<2>());
  }
  const cv::Rect& s = layout_.sensor_px;
  figure::put_text(frame, sensor_caption, cv::Point2d(s.x + 12, s.y + kVideoCaptionPx / 2 + 4), figure::kLabelFont,
                   figure::kInk);
  if (!sensor_panel.empty()) {
    const cv::Rect box(s.x + 8, s.y + kVideoCaptionPx, s.width - 16, s.height - kVideoCaptionPx - 8);
    paste(frame, fitted(box, sensor_panel.size()), sensor_panel);
  }
  draw_strip(frame, layout_.strip_px, strip);
  return frame.raster();
}

}  // namespace campo
