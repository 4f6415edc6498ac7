#include "render/snapshot.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "campo/scene_loader.hpp"
#include "tests/test_units.hpp"

namespace campo {
namespace {

using namespace campo::test_units;

Scene bundled(const std::string& name) {
  return load_scene(std::string(CAMPO_SOURCE_DIR) + "/scenes/" + name + ".json");
}

// A wavy flight from the vehicle's start to the goal, 1.6 m up.
std::vector<Eigen::Vector3d> flight(const Scene& scene) {
  const Eigen::Vector3d start = scene.vehicles.front().pose.translation();
  const Eigen::Vector3d goal = scene.find_frame("goal")->pose.translation();
  std::vector<Eigen::Vector3d> path;
  for (int i = 0; i <= 200; ++i) {
    const double s = i / 200.0;
    path.push_back(start + s * (goal - start) + Eigen::Vector3d(0.0, 2.0 * std::sin(2.0 * std::numbers::pi * s), 0.0));
  }
  return path;
}

// Pixels of `image` (BGR) within `tolerance` of `bgr` in every channel.
int count_near(const cv::Mat& image, const cv::Vec3b& bgr, int tolerance) {
  int count = 0;
  for (int row = 0; row < image.rows; ++row) {
    for (int col = 0; col < image.cols; ++col) {
      const cv::Vec3b& p = image.at<cv::Vec3b>(row, col);
      if (std::abs(p[0] - bgr[0]) <= tolerance && std::abs(p[1] - bgr[1]) <= tolerance &&
          std::abs(p[2] - bgr[2]) <= tolerance) {
        ++count;
      }
    }
  }
  return count;
}

// Pixels where `channel` outweighs both others by `margin`.
int count_dominant(const cv::Mat& image, int channel, int margin) {
  int count = 0;
  for (int row = 0; row < image.rows; ++row) {
    for (int col = 0; col < image.cols; ++col) {
      const cv::Vec3b& p = image.at<cv::Vec3b>(row, col);
      bool dominant = true;
      for (int other = 0; other < 3; ++other) {
        if (other != channel && p[channel] < p[other] + margin) dominant = false;
      }
      count += dominant ? 1 : 0;
    }
  }
  return count;
}

TEST(Snapshot, RendersSkyGroundObjectsTrajectoryAndVehicle) {
  const Scene scene = bundled("trees_rolling_terrain");
  const SceneMesh mesh = build_scene_mesh(scene);
  const std::vector<Eigen::Vector3d> path = flight(scene);
  SnapshotCamera camera = default_snapshot_camera(scene, path);
  camera.width_px = 640;
  camera.height_px = 360;
  const Eigen::Isometry3d vehicle{Eigen::Translation3d(path[10])};
  const cv::Mat image = render_snapshot(scene, mesh, camera, path, vehicle, VehicleType::quadrotor);
  ASSERT_EQ(image.type(), CV_8UC3);
  ASSERT_EQ(image.cols, 640);
  ASSERT_EQ(image.rows, 360);
  const int pixels = image.rows * image.cols;
  // Sky on top (the clear colour), terrain below, red trajectory, blue vehicle.
  const cv::Vec3b sky(240, 199, 161);
  EXPECT_GT(count_near(image.rowRange(0, 20), sky, 3), 20 * 640 / 2);
  EXPECT_EQ(count_near(image.rowRange(340, 360), sky, 3), 0);
  EXPECT_GT(count_dominant(image, 2, 80), pixels / 1000) << "no trajectory";
  EXPECT_GT(count_dominant(image, 0, 60), 5) << "no vehicle";
  std::vector<uchar> png;
  EXPECT_TRUE(cv::imencode(".png", image, png));
  // Without the trajectory there is no red.
  const cv::Mat bare = render_snapshot(scene, mesh, camera, {}, std::nullopt, VehicleType::quadrotor);
  EXPECT_EQ(count_dominant(bare, 2, 80), 0);
}

TEST(Snapshot, SameInputsSameBytes) {
  const Scene scene = bundled("two_barriers");
  const SceneMesh mesh = build_scene_mesh(scene);
  const std::vector<Eigen::Vector3d> path = flight(scene);
  SnapshotCamera camera = default_snapshot_camera(scene, path);
  camera.width_px = 320;
  camera.height_px = 200;
  const Eigen::Isometry3d rover = Eigen::Translation3d(path.back()) * Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ());
  const cv::Mat a = render_snapshot(scene, mesh, camera, path, rover, VehicleType::rover);
  const cv::Mat b = render_snapshot(scene, mesh, camera, path, rover, VehicleType::rover);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0);
  // The barriers' brick colour is lit but still red-brown.
  EXPECT_GT(count_dominant(a, 2, 40), 100);
}

TEST(Snapshot, DefaultCameraLooksAtTheTrajectoryFromBehindAndAbove) {
  const Scene scene = bundled("trees_rolling_terrain");
  const std::vector<Eigen::Vector3d> path = flight(scene);
  const SnapshotCamera camera = default_snapshot_camera(scene, path);
  const Eigen::Vector3d view = camera.target_m - camera.eye_m;
  EXPECT_NEAR(std::asin(-view.z() / view.norm()), 35.0 * kDeg, 1e-9);
  // The flight goes along +x; the camera stands behind the start.
  EXPECT_GT(view.x(), 0.0);
  EXPECT_LT(camera.eye_m.x(), path.front().x());
  EXPECT_NEAR(camera.target_m.x(), 0.5 * (path.front().x() + path.back().x()), 1e-9);
  // The whole path is in front of the camera, within the field of view.
  for (const Eigen::Vector3d& p : path) {
    const Eigen::Vector3d to_p = p - camera.eye_m;
    EXPECT_LT(std::acos(to_p.normalized().dot(view.normalized())), 0.5 * camera.fov_deg * kDeg);
  }
  // Without a trajectory it frames the scene's objects.
  const SnapshotCamera empty = default_snapshot_camera(scene, {});
  EXPECT_GT((empty.target_m - empty.eye_m).norm(), 10.0);
}

TEST(Snapshot, RejectsABadCamera) {
  const Scene scene = bundled("two_barriers");
  const SceneMesh mesh = build_scene_mesh(scene);
  SnapshotCamera camera;
  camera.target_m = camera.eye_m;
  EXPECT_THROW(render_snapshot(scene, mesh, camera, {}, std::nullopt, VehicleType::rover), std::invalid_argument);
  camera = SnapshotCamera{};
  camera.up = (camera.target_m - camera.eye_m).normalized();
  EXPECT_THROW(render_snapshot(scene, mesh, camera, {}, std::nullopt, VehicleType::rover), std::invalid_argument);
  camera = SnapshotCamera{};
  camera.width_px = 0;
  EXPECT_THROW(render_snapshot(scene, mesh, camera, {}, std::nullopt, VehicleType::rover), std::invalid_argument);
}

}  // namespace
}  // namespace campo
