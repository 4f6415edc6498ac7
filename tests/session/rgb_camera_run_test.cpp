// `campo run --record-images N` on a scene with a colour camera: every N-th
// image as an RGB PNG of the camera's size under images/, showing the sky
// and the red box where they are; a video of the run shows them.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "render/video_frame.hpp"
#include "tests/cli_support.hpp"

namespace campo {
namespace {

namespace fs = std::filesystem;

class RecordImages : public testing::CliTest {
 protected:
  // Pixels of the sensor panel of frame `index` of the run's video within 12 levels of `bgr`.
  int panel_pixels_near(const fs::path& run, int index, const cv::Vec3b& bgr) const {
    const fs::path video = dir_ / (run.filename().string() + ".mp4");
    const testing::Result v =
        campo("render " + run.string() + " --kind video --out " + video.string() + " --fps 5 --size 640x360");
    EXPECT_EQ(v.exit_code, 0) << v.err;
    const fs::path png = dir_ / "frame.png";
    const std::string command = "ffmpeg -v error -y -i '" + video.string() + "' -vf 'select=eq(n\\," +
                                std::to_string(index) + ")' -frames:v 1 '" + png.string() + "'";
    EXPECT_EQ(std::system(command.c_str()), 0);
    const cv::Mat panel = cv::imread(png.string(), cv::IMREAD_COLOR)(video_layout({640, 360}).sensor_px);
    int near = 0;
    for (int y = 0; y < panel.rows; ++y) {
      for (int x = 0; x < panel.cols; ++x) {
        const cv::Vec3b p = panel.at<cv::Vec3b>(y, x);
        near += std::abs(p[0] - bgr[0]) <= 12 && std::abs(p[1] - bgr[1]) <= 12 && std::abs(p[2] - bgr[2]) <= 12;
      }
    }
    return near;
  }
};

// Flat grey ground, a red box ahead and to the left, a quadrotor flying
// straight ahead for 2 s with a 64 x 48 colour camera at 10 Hz.
constexpr const char* kCameraRunScene = R"({
  "campo_scene": 1, "name": "camera_run",
  "world": {"physics_step_s": 0.004166666666666667, "control_rate_hz": 60, "sensor_rate_hz": 10,
            "time_limit_s": 2, "seed": 3},
  "objects": [
    {"alias": "ground", "type": "plane", "color": [0.5, 0.5, 0.5]},
    {"alias": "box", "type": "cuboid", "size_m": [1, 2, 2], "pose": {"position_m": [8, 3, 1]},
     "color": [0.9, 0.1, 0.1]},
    {"alias": "drone", "type": "quadrotor", "pose": {"position_m": [0, 0, 1.5]},
     "sensors": [{"alias": "front", "type": "rgb_camera", "fov_deg": 60, "resolution": [64, 48],
                  "range_m": [0.05, 60], "sky": [0.2, 0.4, 0.8]}],
     "planner": {"name": "straight"},
     "mission": {"waypoints": [{"position_m": [20, 0, 1.5]}]}}
  ]
})";

TEST_F(RecordImages, EveryNthImageIsAnRgbPngOfTheCamerasSize) {
  const std::string scene = write("camera_run.json", kCameraRunScene);
  const fs::path out = dir_ / "run";
  const testing::Result r = campo("run " + scene + " --out " + out.string() + " --no-figures --record-images 4");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(out / "images")) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  // Images at 0, 0.1, ... 2 s (21, or 20 if the limit ends the run before the last): 0, 0.4, ... 2.0 kept.
  ASSERT_GE(files.size(), 5u);
  ASSERT_LE(files.size(), 6u);
  EXPECT_EQ(files.front().filename().string(), "front_0000.000.png");
  EXPECT_EQ(files[1].filename().string(), "front_0000.400.png");
  for (const fs::path& file : files) {
    const cv::Mat image = cv::imread(file.string(), cv::IMREAD_UNCHANGED);
    ASSERT_EQ(image.type(), CV_8UC3) << file;  // 8-bit RGB (BGR in OpenCV)
    EXPECT_EQ(image.cols, 64) << file;
    EXPECT_EQ(image.rows, 48) << file;
  }
  // The first image: the sky along the top row, the red box in the left half, the grey ground at the bottom.
  const cv::Mat first = cv::imread(files.front().string(), cv::IMREAD_COLOR);
  const cv::Vec3b sky = first.at<cv::Vec3b>(0, 32);
  EXPECT_EQ(sky, cv::Vec3b(static_cast<unsigned char>(std::lround(0.8 * 255)),
                           static_cast<unsigned char>(std::lround(0.4 * 255)),
                           static_cast<unsigned char>(std::lround(0.2 * 255))));
  int red_left = 0, red_right = 0;
  for (int row = 0; row < first.rows; ++row) {
    for (int col = 0; col < first.cols; ++col) {
      const cv::Vec3b p = first.at<cv::Vec3b>(row, col);
      if (p[2] > 2 * p[1] && p[2] > 2 * p[0]) ++(col < 32 ? red_left : red_right);
    }
  }
  EXPECT_GT(red_left, 20);
  EXPECT_EQ(red_right, 0);
  const cv::Vec3b ground = first.at<cv::Vec3b>(47, 32);
  EXPECT_EQ(ground[0], ground[1]);
  EXPECT_EQ(ground[1], ground[2]);

  // The video's sensor panel shows the recorded images: the sky's blue fills part of it at 0.6 s;
  // without recorded images, none of it.
  const fs::path bare = dir_ / "bare";
  ASSERT_EQ(campo("run " + scene + " --out " + bare.string() + " --no-figures").exit_code, 0);
  const int with_images = panel_pixels_near(out, 3, sky);
  const int without = panel_pixels_near(bare, 3, sky);
  EXPECT_GT(with_images, 2000) << with_images;
  EXPECT_LT(without, 50) << without;
}

TEST_F(RecordImages, WithoutTheFlagNothingIsWritten) {
  const std::string scene = write("camera_run.json", kCameraRunScene);
  const fs::path out = dir_ / "run";
  const testing::Result r = campo("run " + scene + " --out " + out.string() + " --no-figures");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(fs::exists(out / "images"));
  // run.json lists the camera with every field of its block, as the scene gave them.
  const nlohmann::json record = nlohmann::json::parse(testing::slurp(out / "run.json"));
  const nlohmann::json& cameras = record.at("parameters").at("rgb_cameras");
  ASSERT_EQ(cameras.size(), 1u);
  EXPECT_EQ(cameras[0].at("alias"), "front");
  EXPECT_EQ(cameras[0].at("type"), "rgb_camera");
  EXPECT_EQ(cameras[0].at("resolution"), nlohmann::json({64, 48}));
  EXPECT_EQ(cameras[0].at("range_m"), nlohmann::json({0.05, 60.0}));
  EXPECT_EQ(cameras[0].at("sky"), nlohmann::json({0.2, 0.4, 0.8}));
}

}  // namespace
}  // namespace campo
