#pragma once
// Test support for the report figures: a small scene and run, and pixel checks.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "campo/scene_loader.hpp"
#include "render/figure_style.hpp"
#include "tests/render/vector_outputs.hpp"

namespace campo::figure::test {

inline const cv::Vec3b kBackground(255, 255, 255);

// Rolling terrain, a rotated red box north of the track and a blue post south of it.
inline Scene test_scene() {
  const char* text = R"j({"objects": [
    {"alias": "hill", "type": "heightfield", "expression": "0.8*sin(x/4) + 0.5*cos(y/5)",
     "size_m": [60, 60], "spacing_m": 0.5, "color": [0.5, 0.6, 0.35]},
    {"alias": "box", "type": "cuboid", "size_m": [2, 1, 3],
     "pose": {"position_m": [0, 4, 1.5], "rpy_deg": [0, 0, 30]}, "color": [0.8, 0.2, 0.2]},
    {"alias": "post", "type": "cylinder", "radius_m": 0.5, "height_m": 4,
     "pose": {"position_m": [-4, -2.5, 2]}, "color": [0.2, 0.3, 0.8]}
  ]})j";
  return parse_scene(nlohmann::json::parse(text), "inline.json", std::filesystem::temp_directory_path());
}

// Flies east along y = 0 from x = -8 to x = 8 at 1 m/s, 3 m above the datum.
inline RunView test_run() {
  RunView run;
  run.label = "run_a";
  run.outcome = "reached";
  for (int i = 0; i <= 160; ++i) {
    TrackPoint p;
    p.time_s = 0.1 * i;
    p.position_m = {-8.0 + 0.1 * i, 0.0, 3.0};
    p.speed_mps = 1.0;
    run.track.push_back(p);
  }
  run.mission = {Waypoint{{-2.0, 0.0, 3.0}, {}}, Waypoint{{4.0, 2.0, 3.0}, {}}, Waypoint{{8.0, 0.0, 3.0}, {}}};
  run.reached = {0, 2};
  run.planned = {{1.0, -1.0, 3.0}};
  run.discarded = {{5.0, -2.0, 3.0}};
  return run;
}

inline FigureStyle small_style() {
  FigureStyle style;
  style.max_size_px = 600;
  style.title = "Test figure";
  return style;
}

inline int colour_distance(const cv::Vec3b& a, const cv::Vec3b& b) {
  return std::abs(a[0] - b[0]) + std::abs(a[1] - b[1]) + std::abs(a[2] - b[2]);
}

// Smallest colour distance to `want` within `radius` pixels of `p`.
inline int nearest_colour(const cv::Mat& image, cv::Point2d p, const cv::Vec3b& want, int radius = 2) {
  int best = 3 * 255;
  const cv::Point c(static_cast<int>(std::lround(p.x)), static_cast<int>(std::lround(p.y)));
  for (int dy = -radius; dy <= radius; ++dy) {
    for (int dx = -radius; dx <= radius; ++dx) {
      best = std::min(best, colour_distance(image.at<cv::Vec3b>(c.y + dy, c.x + dx), want));
    }
  }
  return best;
}

inline int non_background(const cv::Mat& image, const cv::Rect& area) {
  int n = 0;
  const cv::Mat roi = image(area);
  for (auto it = roi.begin<cv::Vec3b>(); it != roi.end<cv::Vec3b>(); ++it) n += *it != kBackground;
  return n;
}

inline std::vector<uchar> png(const cv::Mat& image) {
  std::vector<uchar> bytes;
  EXPECT_TRUE(cv::imencode(".png", image, bytes));
  return bytes;
}

inline cv::Vec3b at(const cv::Mat& image, cv::Point2d p) {
  return image.at<cv::Vec3b>(static_cast<int>(std::lround(p.y)), static_cast<int>(std::lround(p.x)));
}

}  // namespace campo::figure::test
