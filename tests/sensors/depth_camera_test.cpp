#include "sensors/depth_camera.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "campo/pose.hpp"
#include "campo/scene_loader.hpp"
#include "campo/sensor_factory.hpp"
#include "sensors/lidar.hpp"
#include "sensors/scan_io.hpp"
#include "tests/test_units.hpp"

namespace campo {
namespace {

constexpr double kCm = 0.01;
using namespace campo::test_units;

SensorDef depth_camera_def(int cols, int rows, double fov_h = 90.0, double fov_v = 90.0) {
  SensorDef def;
  def.alias = "camera";
  def.range = *sensor_preset("scanner3d");
  def.range.kind = RangeSensorKind::depth_camera;
  def.range.cols = cols;
  def.range.rows = rows;
  def.range.fov_h_deg = fov_h;
  def.range.fov_v_deg = fov_v;
  return def;
}

SensorDef as_lidar(SensorDef def) {
  def.range.kind = RangeSensorKind::lidar;
  return def;
}

Scene parse(const std::string& text) {
  return parse_scene(nlohmann::json::parse(text), "inline.json", std::filesystem::temp_directory_path());
}

Scene bundled(const std::string& name) {
  return load_scene(std::string(CAMPO_SOURCE_DIR) + "/scenes/" + name + ".json");
}

// A plane through `point` with normal `normal`, as a scene shape.
Shape plane(const Eigen::Vector3d& point, const Eigen::Vector3d& normal) {
  Shape s;
  s.type = ShapeType::plane;
  s.pose.linear() = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), normal).toRotationMatrix();
  s.pose.translation() = point;
  return s;
}

// Every pixel of a camera over a plane, against the range along its ray.
void expect_plane_exact(int n, double tilt_deg, const Eigen::Vector3d& tilt_axis) {
  Scene scene;
  const Eigen::Vector3d normal = Eigen::AngleAxisd(tilt_deg * kDeg, tilt_axis.normalized()) * -Eigen::Vector3d::UnitX();
  const Eigen::Vector3d point(5.0, 0.0, 0.0);
  scene.shapes.push_back(plane(point, normal));
  const SensorDef def = depth_camera_def(n, n);
  const auto camera = make_depth_camera(scene, def);
  // Off the origin and turned, so the test does not rely on symmetry.
  const Eigen::Isometry3d pose = to_isometry(Pose{{0.0, 0.4, -0.3}, {3.0, -4.0, 6.0}});
  RangeScan scan;
  camera->scan(pose, 0.0, scripted_poses(scene, 0.0), scan);
  ASSERT_EQ(scan.rows, n);
  ASSERT_EQ(scan.cols, n);
  const std::vector<Beam> beams = lidar_beams(def.range);
  int checked = 0;
  double worst = 0.0;
  std::size_t point_index = 0;
  for (std::size_t i = 0; i < beams.size(); ++i) {
    const Eigen::Vector3d d = pose.linear() * beam_direction(beams[i]).cast<double>();
    const double t = normal.dot(point - pose.translation()) / normal.dot(d);
    const bool expect_hit = t >= def.range.min_range_m && t <= def.range.max_range_m;
    if (std::abs(t - def.range.max_range_m) < kCm) {  // on the range limit: either
      point_index += scan.hits[i];
      continue;
    }
    ASSERT_EQ(scan.hits[i], expect_hit ? 1 : 0) << "pixel " << i << " expected range " << t;
    if (!expect_hit) {
      EXPECT_FLOAT_EQ(scan.ranges_m[i], static_cast<float>(def.range.max_range_m));
      continue;
    }
    worst = std::max(worst, std::abs(scan.ranges_m[i] - t));
    ASSERT_NEAR(scan.ranges_m[i], t, kCm) << "pixel " << i;
    const Eigen::Vector3d p = scan.points[point_index++].cast<double>();
    EXPECT_NEAR(normal.dot(p - point), 0.0, kCm) << "pixel " << i;
    ++checked;
  }
  EXPECT_EQ(point_index, scan.points.size());
  EXPECT_GT(checked, n * n / 2);
  std::printf("[ plane    ] %dx%d tilt %.0f deg: %d pixels, worst error %.2f mm\n", n, n, tilt_deg, checked,
              worst * 1e3);
}

TEST(DepthCamera, TiltedPlaneRangeAtEveryPixel64) {
  expect_plane_exact(64, 20.0, Eigen::Vector3d::UnitZ());
  expect_plane_exact(64, 40.0, Eigen::Vector3d(0.0, 1.0, 1.0));
}

TEST(DepthCamera, TiltedPlaneRangeAtEveryPixel256) {
  expect_plane_exact(256, 20.0, Eigen::Vector3d(0.0, 1.0, 0.0));
  expect_plane_exact(256, 40.0, Eigen::Vector3d::UnitZ());
}

// Agreement statistics of a depth camera scan with a LIDAR scan.
struct Agreement {
  int compared = 0;         // pixels away from edges hit by both
  int within_5cm = 0;
  int hit_mismatches = 0;   // away from edges
  int edge_pixels = 0;
  double median_relative = 0.0;
  double median_abs_m = 0.0;
  double p99_abs_m = 0.0;  // 99th percentile
};

// The q-quantile of `values` (0 if empty).
double quantile(std::vector<double> values, double q) {
  if (values.empty()) return 0.0;
  const auto k = static_cast<std::ptrdiff_t>(q * static_cast<double>(values.size() - 1));
  std::nth_element(values.begin(), values.begin() + k, values.end());
  return values[static_cast<std::size_t>(k)];
}

// A pixel is on an edge when its 3x3 neighbourhood in the LIDAR scan has
// mixed hits or ranges more than 0.3 m apart.
Agreement compare(const RangeScan& lidar, const RangeScan& camera) {
  Agreement a;
  std::vector<double> relative, absolute;
  for (int row = 0; row < lidar.rows; ++row) {
    for (int col = 0; col < lidar.cols; ++col) {
      const std::size_t i = static_cast<std::size_t>(row) * lidar.cols + col;
      bool edge = false;
      for (int dr = -1; dr <= 1; ++dr) {
        for (int dc = -1; dc <= 1; ++dc) {
          const int r = std::clamp(row + dr, 0, lidar.rows - 1);
          const int c = std::clamp(col + dc, 0, lidar.cols - 1);
          const std::size_t j = static_cast<std::size_t>(r) * lidar.cols + c;
          edge = edge || lidar.hits[j] != lidar.hits[i] || std::abs(lidar.ranges_m[j] - lidar.ranges_m[i]) > 0.3f;
        }
      }
      if (edge) {
        ++a.edge_pixels;
        continue;
      }
      if (lidar.hits[i] != camera.hits[i]) {
        ++a.hit_mismatches;
        continue;
      }
      if (!lidar.hits[i]) continue;
      const double error = std::abs(camera.ranges_m[i] - lidar.ranges_m[i]);
      ++a.compared;
      if (error <= 0.05) ++a.within_5cm;
      relative.push_back(error / lidar.ranges_m[i]);
      absolute.push_back(error);
    }
  }
  a.median_relative = quantile(relative, 0.5);
  a.median_abs_m = quantile(absolute, 0.5);
  a.p99_abs_m = quantile(absolute, 0.99);
  return a;
}

void expect_agreement(const std::string& scene_name, int n) {
  const Scene scene = bundled(scene_name);
  const VehicleDef& vehicle = scene.vehicles.front();
  const SensorDef def = depth_camera_def(n, n);
  const auto camera = make_depth_camera(scene, def);
  const auto lidar = make_lidar_sensor(scene, as_lidar(def), 0);
  const Eigen::Isometry3d start = vehicle.pose * to_isometry(def.range.mount);
  const std::vector<Eigen::Isometry3d> poses = {
      start,
      start * to_isometry(Pose{{0.0, 0.0, 0.0}, {0.0, 0.0, 35.0}}),
      start * to_isometry(Pose{{4.0, -1.5, 0.3}, {0.0, 15.0, -50.0}}),
      start * to_isometry(Pose{{7.0, 2.0, 1.0}, {5.0, 30.0, 120.0}}),
  };
  RangeScan expected, actual;
  for (std::size_t k = 0; k < poses.size(); ++k) {
    lidar->scan(poses[k], 0.0, scripted_poses(scene, 0.0), expected);
    camera->scan(poses[k], 0.0, scripted_poses(scene, 0.0), actual);
    const Agreement a = compare(expected, actual);
    const double within = static_cast<double>(a.within_5cm) / std::max(a.compared, 1);
    std::printf("[ agree    ] %s %dx%d pose %zu: %d compared, error median %.3f mm (%.5f %%), 99th percentile "
                "%.2f mm, within 5 cm %.2f %%, hit mismatches %d, edge pixels %d\n",
                scene_name.c_str(), n, n, k, a.compared, 1e3 * a.median_abs_m, 100.0 * a.median_relative,
                1e3 * a.p99_abs_m, 100.0 * within, a.hit_mismatches, a.edge_pixels);
    EXPECT_GT(a.compared, n * n / 4) << "pose " << k;
    EXPECT_LT(a.median_relative, 0.01) << "pose " << k;
    EXPECT_GE(within, 0.98) << "pose " << k;
    EXPECT_EQ(a.hit_mismatches, 0) << "pose " << k;
  }
}

// Camera and LIDAR scans from one pose at one time; every pixel away from
// edges agrees on hit or miss and within 5 cm, and half of them within 5 mm.
void expect_matches_lidar(const Scene& scene, const SensorDef& def, const Eigen::Isometry3d& pose, double time_s) {
  const auto camera = make_depth_camera(scene, def);
  const auto lidar = make_lidar_sensor(scene, as_lidar(def), 0);
  RangeScan expected, actual;
  lidar->scan(pose, time_s, scripted_poses(scene, time_s), expected);
  camera->scan(pose, time_s, scripted_poses(scene, time_s), actual);
  EXPECT_EQ(actual.rows, expected.rows);
  EXPECT_EQ(actual.cols, expected.cols);
  EXPECT_EQ(actual.time_s, time_s);
  EXPECT_TRUE(actual.sensor_pose.isApprox(pose));
  const Agreement a = compare(expected, actual);
  EXPECT_EQ(a.hit_mismatches, 0);
  EXPECT_EQ(a.within_5cm, a.compared);
  EXPECT_LT(a.median_abs_m, 0.005);
  EXPECT_GT(a.compared, 0);
}

TEST(DepthCamera, MoversAppearWhereTheyAreAtTheScanTime) {
  const Scene scene = parse(R"j({"objects": [
    {"alias": "crate", "type": "mover", "shape": {"type": "cuboid", "size_m": [1, 1, 2]},
     "path_m": [[5, -3, 0], [5, 3, 0]], "speed_mps": 1.0},
    {"alias": "ball", "type": "mover", "shape": {"type": "sphere", "radius_m": 0.5},
     "path_m": [[3, 2, 0.5], [3, -2, 0.5]], "speed_mps": 2.0, "start_time_s": 1.0}]})j");
  const SensorDef def = depth_camera_def(64, 64);
  const auto camera = make_depth_camera(scene, def);
  RangeScan scan;
  // Pixel (32, 32) looks just right of and below straight ahead.
  const std::size_t centre = 32 * 64 + 32;
  camera->scan(Eigen::Isometry3d::Identity(), 0.0, scripted_poses(scene, 0.0), scan);
  EXPECT_EQ(scan.hits[centre], 0);  // the crate is 3 m to the right, the ball to the left
  camera->scan(Eigen::Isometry3d::Identity(), 3.0, scripted_poses(scene, 3.0), scan);
  EXPECT_EQ(scan.hits[centre], 1);
  EXPECT_NEAR(scan.ranges_m[centre], 4.5 / (std::cos(0.5 * 90.0 / 64 * kDeg) * std::cos(0.5 * 90.0 / 64 * kDeg)), kCm);
  EXPECT_DOUBLE_EQ(scan.time_s, 3.0);
  for (const double t : {0.0, 1.5, 2.0, 3.0, 4.5, 7.0}) {
    SCOPED_TRACE("t = " + std::to_string(t));
    expect_matches_lidar(scene, def, to_isometry(Pose{{0.0, 0.0, 0.3}, {0.0, 5.0, 0.0}}), t);
  }
}

TEST(DepthCamera, TwoCamerasWorkSideBySide) {
  Scene near_wall, far_wall;
  near_wall.shapes.push_back(plane({4.0, 0.0, 0.0}, -Eigen::Vector3d::UnitX()));
  far_wall.shapes.push_back(plane({7.0, 0.0, 0.0}, -Eigen::Vector3d::UnitX()));
  auto first = make_depth_camera(near_wall, depth_camera_def(32, 32));
  auto second = make_depth_camera(far_wall, depth_camera_def(48, 16, 60.0, 20.0));
  RangeScan a, b;
  const auto straight_ahead = [](const RangeScan& scan) {
    // Mean distance along the optical axis of the four pixels around it.
    double sum = 0.0;
    for (const int row : {scan.rows / 2 - 1, scan.rows / 2}) {
      for (const int col : {scan.cols / 2 - 1, scan.cols / 2}) {
        const std::size_t i = static_cast<std::size_t>(row) * scan.cols + col;
        sum += scan.points[i].x();
      }
    }
    return sum / 4.0;
  };
  for (int round = 0; round < 3; ++round) {
    first->scan(Eigen::Isometry3d::Identity(), 0.0, scripted_poses(near_wall, 0.0), a);
    second->scan(Eigen::Isometry3d::Identity(), 0.0, scripted_poses(far_wall, 0.0), b);
    ASSERT_EQ(a.points.size(), 32u * 32u);
    ASSERT_EQ(b.points.size(), 48u * 16u);
    EXPECT_NEAR(straight_ahead(a), 4.0, kCm);
    EXPECT_NEAR(straight_ahead(b), 7.0, kCm);
  }
  first.reset();
  second->scan(to_isometry(Pose{{1.0, 0.0, 0.0}, {0.0, 0.0, 0.0}}), 0.0, scripted_poses(far_wall, 0.0), b);
  EXPECT_NEAR(straight_ahead(b), 7.0, kCm);
}

// Where the LIDAR reports a surface from behind (inside a solid, under the
// ground, past a surface skipped for being too near), the camera does too.
TEST(DepthCamera, SeesBackFacesWhereTheLidarDoes) {
  const Scene scene = parse(R"j({"objects": [
    {"alias": "ground", "type": "plane"},
    {"alias": "hill", "type": "heightfield", "size_m": [20, 20], "spacing_m": 0.5,
     "expression": "1 + 0.3 * sin(x) * cos(y)", "pose": {"position_m": [10, 0, 0]}},
    {"alias": "box", "type": "cuboid", "size_m": [2, 2, 2], "pose": {"position_m": [-5, 0, 3]}},
    {"alias": "sheet", "type": "cuboid", "size_m": [0.1, 4, 4], "pose": {"position_m": [-1.07, 8, 2]}},
    {"alias": "tree", "type": "cylinder", "radius_m": 0.3, "height_m": 4, "pose": {"position_m": [2, 6, 2]}}]})j");
  const SensorDef def = depth_camera_def(96, 96);
  const std::vector<std::pair<std::string, Eigen::Isometry3d>> cases = {
      {"above everything", to_isometry(Pose{{0.0, 0.0, 2.0}, {0.0, 10.0, 0.0}})},
      {"inside the box", to_isometry(Pose{{-5.2, 0.3, 3.1}, {0.0, 0.0, 20.0}})},
      {"under the ground plane", to_isometry(Pose{{0.0, 0.0, -0.5}, {0.0, -30.0, 0.0}})},
      {"under the hill", to_isometry(Pose{{10.0, 1.0, 0.5}, {0.0, -60.0, 0.0}})},
      {"beside the hill, below its top", to_isometry(Pose{{-1.0, 0.0, 0.5}, {0.0, 0.0, 0.0}})},
      {"sheet within the minimum range", to_isometry(Pose{{-1.0, 8.0, 2.0}, {0.0, 0.0, 180.0}})},
      {"inside the tree", to_isometry(Pose{{2.0, 6.1, 1.0}, {0.0, 0.0, -90.0}})},
  };
  for (const auto& [name, pose] : cases) {
    SCOPED_TRACE(name);
    expect_matches_lidar(scene, def, pose, 0.0);
  }
}

TEST(DepthCamera, SingleRowWithoutVerticalFieldOfView) {
  const Scene scene = bundled("trees_rolling_terrain");
  SensorDef def = depth_camera_def(181, 1, 120.0, 0.0);
  def.range.max_range_m = 20.0;
  const Eigen::Isometry3d pose = scene.vehicles.front().pose * to_isometry(Pose{{0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}});
  expect_matches_lidar(scene, def, pose, 0.0);
  def.range.fov_v_deg = 0.3;
  expect_matches_lidar(scene, def, pose, 0.0);
}

TEST(DepthCamera, FillsTheScanLikeTheLidar) {
  const Scene scene = bundled("two_barriers");
  SensorDef def = depth_camera_def(40, 30, 100.0, 60.0);
  def.range.quantization_m = 0.05;
  const Eigen::Isometry3d pose = to_isometry(Pose{{1.0, 0.5, 1.5}, {0.0, 5.0, 10.0}});
  const auto camera = make_depth_camera(scene, def);
  RangeScan scan;
  scan.points.assign(5000, Eigen::Vector3f::Zero());  // stale content is replaced
  camera->scan(pose, 2.5, scripted_poses(scene, 2.5), scan);
  EXPECT_EQ(scan.rows, 30);
  EXPECT_EQ(scan.cols, 40);
  EXPECT_EQ(scan.time_s, 2.5);
  ASSERT_EQ(scan.ranges_m.size(), 1200u);
  ASSERT_EQ(scan.hits.size(), 1200u);
  std::size_t hits = 0;
  const std::vector<Beam> beams = lidar_beams(def.range);
  for (std::size_t i = 0; i < beams.size(); ++i) {
    if (!scan.hits[i]) {
      EXPECT_EQ(scan.ranges_m[i], static_cast<float>(def.range.max_range_m));
      continue;
    }
    // Quantized, and the point lies along the beam at that range.
    EXPECT_NEAR(scan.ranges_m[i] / 0.05, std::round(scan.ranges_m[i] / 0.05), 1e-3);
    const Eigen::Vector3d expected =
        pose.translation() + scan.ranges_m[i] * (pose.linear() * beam_direction(beams[i]).cast<double>());
    ASSERT_LT(hits, scan.points.size());
    EXPECT_LT((scan.points[hits].cast<double>() - expected).norm(), 1e-4);
    ++hits;
  }
  EXPECT_EQ(hits, scan.points.size());
  EXPECT_GT(hits, 300u);
  // The depth map reads it as it reads a LIDAR scan.
  const cv::Mat depth = depth_map(scan, def.range);
  EXPECT_EQ(depth.rows, 30);
  EXPECT_EQ(depth.cols, 40);
}

TEST(DepthCamera, RejectsWhatItCannotRender) {
  const Scene scene;
  SensorDef def = depth_camera_def(16, 16);
  def.range.noise_stddev_m = 0.01;
  EXPECT_THROW(make_depth_camera(scene, def), std::invalid_argument);
  def = depth_camera_def(16, 16);
  def.range.dropout_probability = 0.1;
  EXPECT_THROW(make_depth_camera(scene, def), std::invalid_argument);
  def = depth_camera_def(16, 16);
  def.range.beams = {{0.0, 0.0}};
  EXPECT_THROW(make_depth_camera(scene, def), std::invalid_argument);
  def = depth_camera_def(16, 16, 170.0, 90.0);
  EXPECT_THROW(make_depth_camera(scene, def), std::invalid_argument);
  EXPECT_THROW(make_depth_camera(scene, as_lidar(depth_camera_def(16, 16))), std::invalid_argument);
  // An empty scene renders: every pixel a miss.
  RangeScan scan;
  make_depth_camera(scene, depth_camera_def(16, 16))->scan(Eigen::Isometry3d::Identity(), 0.0, scripted_poses(scene, 0.0), scan);
  EXPECT_EQ(std::count(scan.hits.begin(), scan.hits.end(), 0), 256);
}

// The kind travels with the configuration: written as the block's "type" (run.json, campo scan) and read
// back into the same configuration; make_range_sensor builds what the kind says.
TEST(DepthCamera, TheKindIsTheConfigurations) {
  SensorDef def = depth_camera_def(24, 12, 60.0, 30.0);
  def.range.mount.rpy_deg = {0.0, 10.0, 0.0};
  const nlohmann::json block = sensor_json(def);
  EXPECT_EQ(block.at("type"), "depth_camera");
  EXPECT_EQ(block.at("alias"), "camera");
  const SensorDef back = parse_sensor(JsonNode(block, "block", ""));
  EXPECT_EQ(back.range.kind, RangeSensorKind::depth_camera);
  EXPECT_EQ(sensor_json(back), block);
  EXPECT_EQ(sensor_json(as_lidar(def)).at("type"), "lidar");
  EXPECT_EQ(parse_sensor(JsonNode(sensor_json(as_lidar(def)), "block", "")).range.kind, RangeSensorKind::lidar);

  // Each maker refuses the other kind, so the factory gave each to its own.
  const Scene scene;
  EXPECT_THROW(make_lidar_sensor(scene, def, 0), std::invalid_argument);
  EXPECT_THROW(make_depth_camera(scene, as_lidar(def)), std::invalid_argument);
  EXPECT_NE(make_range_sensor(scene, def, 0), nullptr);
  EXPECT_NE(make_range_sensor(scene, as_lidar(def), 0), nullptr);
}

TEST(DepthCamera, AgreesWithLidarOnTreesRollingTerrain256) { expect_agreement("trees_rolling_terrain", 256); }
TEST(DepthCamera, AgreesWithLidarOnTreesRollingTerrain128) { expect_agreement("trees_rolling_terrain", 128); }
TEST(DepthCamera, AgreesWithLidarOnTwoBarriers256) { expect_agreement("two_barriers", 256); }
TEST(DepthCamera, AgreesWithLidarOnTwoBarriers128) { expect_agreement("two_barriers", 128); }

}  // namespace
}  // namespace campo
