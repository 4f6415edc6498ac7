#include "render/video_frame.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "campo/scene_loader.hpp"
#include "render/figure_canvas.hpp"
#include "render/figure_parts.hpp"
#include "render/scan_view.hpp"
#include "tests/render/figure_test_support.hpp"

namespace campo {
namespace {

using namespace figure::test;

// test_scene() plus a walker crossing the track northward from t = 2 s at 1 m/s.
Scene scene_with_walker() {
  Scene scene = test_scene();
  const char* text = R"j({"objects": [
    {"alias": "walker", "type": "mover", "shape": {"type": "cylinder", "radius_m": 0.4, "height_m": 1.7,
     "color": [0.1, 0.7, 0.1]}, "path_m": [[2, -4, 0.85], [2, 4, 0.85]], "speed_mps": 1, "start_time_s": 2}]})j";
  const Scene movers = parse_scene(nlohmann::json::parse(text), "inline.json", std::filesystem::temp_directory_path());
  scene.movers = movers.movers;
  return scene;
}

RunView until(const RunView& run, double t) {
  RunView v = run;
  v.track.clear();
  for (const TrackPoint& p : run.track) {
    if (p.time_s <= t) v.track.push_back(p);
  }
  return v;
}

cv::Vec3b frame_bgr(const Color& c) {
  return {static_cast<uchar>(std::lround(255 * c.b)), static_cast<uchar>(std::lround(255 * c.g)),
          static_cast<uchar>(std::lround(255 * c.r))};
}

TEST(VideoLayout, PartsTileTheFrame) {
  const VideoLayout l = video_layout({1280, 720});
  EXPECT_EQ(l.map_px.area() + l.sensor_px.area() + l.strip_px.area(), 1280 * 720);
  EXPECT_EQ((l.map_px & l.sensor_px).area(), 0);
  EXPECT_EQ((l.map_px & l.strip_px).area(), 0);
  EXPECT_EQ(l.strip_px.height, kVideoStripPx);
  EXPECT_EQ(l.strip_px.br(), cv::Point(1280, 720));
  EXPECT_THROW(video_layout({1281, 720}), std::invalid_argument);
  EXPECT_THROW(video_layout({400, 300}), std::invalid_argument);
}

TEST(VideoFrames, ObstaclesMoversAndVehicleAreWhereTheWorldPutsThem) {
  const Scene scene = scene_with_walker();
  const RunView run = test_run();
  VideoFrames frames(scene, run, {1.5, 1.0, 0.4}, {1280, 720});
  const cv::Mat sensor(200, 300, CV_8UC3, cv::Scalar(0, 0, 255));
  for (const double t : {1.0, 6.0, 12.0}) {
    const cv::Mat frame = frames.draw(until(run, t), t, sensor, "caption", {t, 16.0, {{"speed", "1.00 m/s"}}, "state"});
    ASSERT_EQ(frame.size(), cv::Size(1280, 720));
    // The box and the post in their scene colours at their centres (drawn by the map figure;
    // located by the frame's own mapping).
    EXPECT_LT(nearest_colour(frame, frames.to_frame_px({0.0, 4.0}), frame_bgr(scene.shapes[1].color)), 30) << t;
    EXPECT_LT(nearest_colour(frame, frames.to_frame_px({-4.0, -2.5}), frame_bgr(scene.shapes[2].color)), 30) << t;
    // The vehicle's white footprint about its track point (x = -8 + t, y = 0, heading east): its rear half.
    EXPECT_LT(nearest_colour(frame, frames.to_frame_px({-8.0 + t - 0.4, 0.0}), cv::Vec3b(250, 250, 250), 1), 10) << t;
    // The walker where it was then: waiting at its first point until 2 s, then 1 m/s north.
    const double walker_y = -4.0 + std::max(0.0, t - 2.0);
    if (walker_y <= 4.0) {
      const cv::Scalar l = figure::lighten(figure::to_bgr(Color{0.1, 0.7, 0.1}), 0.3);
      const cv::Vec3b light(cv::saturate_cast<uchar>(l[0]), cv::saturate_cast<uchar>(l[1]), cv::saturate_cast<uchar>(l[2]));
      EXPECT_LT(nearest_colour(frame, frames.to_frame_px({2.0, walker_y}), light, 1), 20) << t;
    }
    // The sensor panel fitted on the right, aspect kept: its centre is the panel's colour.
    const cv::Rect& s = frames.layout().sensor_px;
    EXPECT_EQ(frame.at<cv::Vec3b>(s.y + s.height / 2, s.x + s.width / 2), cv::Vec3b(0, 0, 255));
  }
  // The track grows: at 12 s the map holds more track than at 6 s, and the frames differ only there.
  const cv::Mat a = frames.draw(until(run, 6.0), 6.0, cv::Mat(), "", {});
  const cv::Mat b = frames.draw(until(run, 6.0), 6.0, cv::Mat(), "", {});
  EXPECT_EQ(cv::norm(a, b, cv::NORM_L1), 0.0);  // same inputs, same pixels
  const cv::Mat c = frames.draw(until(run, 12.0), 12.0, cv::Mat(), "", {});
  EXPECT_GT(cv::norm(a, c, cv::NORM_L1), 0.0);
  // Where the track passes at 9 s, the frame at 6 s shows the ground, the one at 12 s the track.
  const cv::Point2d later = frames.to_frame_px({1.0, 0.0});
  const cv::Point px(static_cast<int>(std::lround(later.x)), static_cast<int>(std::lround(later.y)));
  EXPECT_GT(colour_distance(a.at<cv::Vec3b>(px), c.at<cv::Vec3b>(px)), 60);
}

TEST(ScanView, ForwardIsUpAndLeftIsLeft) {
  ScanView view;
  view.range_m = 5.0;
  view.footprint_m = {0.2, 0.2};
  view.points_m = {{3.0, 0.0}, {0.0, 3.0}};
  const int size = 640;
  const figure::Canvas canvas = draw_scan_view(view, size);
  const cv::Mat image = canvas.raster();
  ASSERT_EQ(image.size(), cv::Size(size, size));
  // Returns are red dots: find them and check which side of the centre they lie on.
  const cv::Vec3b red(40, 39, 214);
  cv::Point2d sum_up(0, 0), sum_left(0, 0);
  int up = 0, left = 0;
  const cv::Point2d centre(size / 2.0, (size - 28) / 2.0);
  for (int r = 0; r < image.rows; ++r) {
    for (int c = 0; c < image.cols; ++c) {
      if (colour_distance(image.at<cv::Vec3b>(r, c), red) > 20) continue;
      if (r > size - 40) continue;  // the legend's dot
      if (r < centre.y - 20) {
        sum_up += cv::Point2d(c, r);
        ++up;
      } else if (c < centre.x - 20) {
        sum_left += cv::Point2d(c, r);
        ++left;
      }
    }
  }
  ASSERT_GT(up, 0);
  ASSERT_GT(left, 0);
  // 3 m of the 5 m shown: 0.6 of the plot radius, straight above and straight left of the vehicle.
  const double radius_px = 0.46 * (size - 28);
  EXPECT_NEAR(sum_up.x / up, centre.x, 1.5);
  EXPECT_NEAR(centre.y - sum_up.y / up, 0.6 * radius_px, 1.5);
  EXPECT_NEAR(sum_left.y / left, centre.y, 1.5);
  EXPECT_NEAR(centre.x - sum_left.x / left, 0.6 * radius_px, 1.5);
  view.route_deg = 20.0;
  view.gap_heading_deg = 35.0;
  view.nearest_m = 2.0;
  view.status = "avoiding: gap on the left";
  expect_vector_outputs(draw_scan_view(view, size), {"returns", "gap heading", "avoiding: gap on the left", "2 m"});
  view.range_m = 0.0;
  EXPECT_THROW(draw_scan_view(view), std::invalid_argument);
}

}  // namespace
}  // namespace campo
