// The colour camera against the depth camera at the same pose (where it sees
// the box, the image is the box's colour; where it sees nothing, the sky), the
// box's silhouette against its analytic pinhole projection, the shading
// against the documented Lambert-plus-ambient model, determinism and noise.
#include "sensors/rgb_camera.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "campo/pose.hpp"
#include "campo/scene_loader.hpp"
#include "scene/scene_mesh.hpp"
#include "sensors/depth_camera.hpp"
#include "sensors/lidar.hpp"
#include "tests/test_units.hpp"

namespace campo {
namespace {

using namespace campo::test_units;
constexpr int kCols = 96;
constexpr int kRows = 64;
constexpr double kFov_deg = 60.0;
constexpr double kCameraMaxRange_m = 30.0;
const Color kRed{0.9, 0.1, 0.1};
const Color kGrey{0.5, 0.5, 0.5};
const Color kSky{0.62, 0.75, 0.88};

// The box: front face at x = 5.5 m, y in [-0.25, 1.25] m (off the axis), z in [0, 2] m.
constexpr double kFront_m = 5.5;
constexpr double kLeft_m = 1.25;
constexpr double kRight_m = -0.25;
constexpr double kTop_m = 2.0;
// The camera: at the origin, 1 m up, looking along +x.
constexpr double kEyeHeight_m = 1.0;

Scene red_box_on_grey_ground() {
  Scene scene;
  Shape ground;
  ground.type = ShapeType::plane;
  ground.color = kGrey;
  scene.shapes.push_back(ground);
  Shape box;
  box.type = ShapeType::cuboid;
  box.size_m = Eigen::Vector3d(1.0, kLeft_m - kRight_m, kTop_m);
  box.pose.translation() = Eigen::Vector3d(kFront_m + 0.5, 0.5 * (kLeft_m + kRight_m), 0.5 * kTop_m);
  box.color = kRed;
  scene.shapes.push_back(box);
  return scene;
}

RgbCameraDef camera_def(double noise = 0.0, std::uint64_t seed = 0) {
  RgbCameraDef def;
  def.alias = "eye";
  def.camera.fov_h_deg = kFov_deg;
  def.camera.cols = kCols;
  def.camera.rows = kRows;
  def.camera.max_range_m = kCameraMaxRange_m;
  def.camera.sky = kSky;
  def.camera.noise_stddev = noise;
  def.camera.seed = seed;
  return def;
}

double half_width() { return std::tan(0.5 * kFov_deg * kDeg); }
double half_height() { return half_width() * kRows / kCols; }

Eigen::Isometry3d camera_pose() {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(0.0, 0.0, kEyeHeight_m);
  return pose;
}

// The camera, or nullopt (the test skips) where OSMesa cannot load or make a context.
std::unique_ptr<RgbCamera> make_or_skip(const SceneMesh& mesh, const RgbCameraDef& def, std::uint64_t world_seed = 1) {
  try {
    return make_rgb_camera(mesh, def, world_seed);
  } catch (const std::runtime_error& e) {
    if (std::string(e.what()).find("OSMesa") != std::string::npos) return nullptr;
    throw;
  }
}

#define CAMERA_OR_SKIP(name, ...)                                       \
  const std::unique_ptr<RgbCamera> name = make_or_skip(__VA_ARGS__);  \
  if (!name) GTEST_SKIP() << "OSMesa cannot make a context here"

RgbImage render(RgbCamera& camera, const Scene& scene) {
  RgbImage image;
  camera.render(camera_pose(), 0.0, scripted_poses(scene, 0.0), image);
  return image;
}

struct Pixel {
  int r, g, b;
};

Pixel at(const RgbImage& image, int col, int row) {
  const std::size_t i = 3 * (static_cast<std::size_t>(row) * image.cols + col);
  return {image.rgb[i], image.rgb[i + 1], image.rgb[i + 2]};
}

int byte_of(double v) { return static_cast<int>(std::lround(v * 255.0)); }

// Where a direction of the camera frame (x forward, y left, z up) crosses the
// image, in continuous pixel coordinates (0 at the left and top edges).
Eigen::Vector2d image_point(const Eigen::Vector3d& d) {
  const double x = -d.y() / d.x();  // right on the image plane
  const double y = d.z() / d.x();   // up
  return {0.5 * (x / half_width() + 1.0) * kCols, 0.5 * (1.0 - y / half_height()) * kRows};
}

TEST(RgbCamera, SeesTheBoxWhereTheDepthCameraDoesAndTheSkyWhereItSeesNothing) {
  const Scene scene = red_box_on_grey_ground();
  const SceneMesh mesh = build_scene_mesh(scene);
  CAMERA_OR_SKIP(camera, mesh, camera_def());
  const RgbImage image = render(*camera, scene);
  ASSERT_EQ(image.rows, kRows);
  ASSERT_EQ(image.cols, kCols);
  ASSERT_EQ(image.rgb.size(), static_cast<std::size_t>(kRows * kCols * 3));

  // The depth camera at the same pose over the same fields of view and pixels.
  SensorDef depth;
  depth.alias = "depth";
  depth.range = *sensor_preset("scanner3d");
  depth.range.kind = RangeSensorKind::depth_camera;
  depth.range.cols = kCols;
  depth.range.rows = kRows;
  depth.range.fov_h_deg = kFov_deg;
  depth.range.fov_v_deg = 2.0 * std::atan(half_height()) / kDeg;
  depth.range.max_range_m = kCameraMaxRange_m;
  const auto depth_camera = make_depth_camera(scene, mesh, depth);
  RangeScan scan;
  depth_camera->scan(camera_pose(), 0.0, scripted_poses(scene, 0.0), scan);
  const std::vector<Beam> beams = lidar_beams(depth.range);
  ASSERT_EQ(beams.size(), scan.ranges_m.size());
  const auto hit = [&](int col, int row) {
    return col >= 0 && row >= 0 && col < kCols && row < kRows && scan.hits[static_cast<std::size_t>(row * kCols + col)] != 0;
  };

  // The depth camera's beams are equiangular, the colour camera's pixels a
  // pinhole's: each beam is compared with the pixel its direction falls in.
  const Pixel sky{byte_of(kSky.r), byte_of(kSky.g), byte_of(kSky.b)};
  int box_pixels = 0, sky_pixels = 0;
  for (int row = 0; row < kRows; ++row) {
    for (int col = 0; col < kCols; ++col) {
      const std::size_t i = static_cast<std::size_t>(row * kCols + col);
      const Eigen::Vector3d d = beam_direction(beams[i]).cast<double>();
      const Eigen::Vector2d p = image_point(d);
      const int pc = static_cast<int>(std::floor(p.x())), pr = static_cast<int>(std::floor(p.y()));
      // The grid's corners reach beyond the pinhole's rectangle (elevation there is tan(el) / cos(az) up).
      if (pc < 0 || pr < 0 || pc >= kCols || pr >= kRows) continue;
      const Pixel seen = at(image, pc, pr);
      if (scan.hits[i]) {
        // On the box's front face, away from its edges (half a pixel is 3 cm there).
        const Eigen::Vector3d point = camera_pose() * (scan.ranges_m[i] * d);
        const double margin = 0.08;
        if (std::abs(point.x() - kFront_m) < 0.01 && point.y() < kLeft_m - margin && point.y() > kRight_m + margin &&
            point.z() > margin && point.z() < kTop_m - margin) {
          ++box_pixels;
          EXPECT_GT(seen.r, 2 * seen.g) << "box at pixel " << pc << ", " << pr;
          EXPECT_GT(seen.r, 2 * seen.b) << "box at pixel " << pc << ", " << pr;
        }
      } else {
        // Nothing along this beam nor its neighbours: the pixel it falls in shows the sky.
        bool alone = true;
        for (int dr = -1; dr <= 1; ++dr) {
          for (int dc = -1; dc <= 1; ++dc) alone = alone && !hit(col + dc, row + dr);
        }
        if (!alone) continue;
        ++sky_pixels;
        EXPECT_EQ(seen.r, sky.r) << pc << ", " << pr;
        EXPECT_EQ(seen.g, sky.g) << pc << ", " << pr;
        EXPECT_EQ(seen.b, sky.b) << pc << ", " << pr;
      }
    }
  }
  // The box covers about 25 x 21 pixels, the sky over a third of the image.
  EXPECT_GT(box_pixels, 200);
  EXPECT_GT(sky_pixels, kRows * kCols / 3);
}

TEST(RgbCamera, TheBoxSilhouetteIsItsPinholeProjection) {
  const Scene scene = red_box_on_grey_ground();
  CAMERA_OR_SKIP(camera, build_scene_mesh(scene), camera_def());
  const RgbImage image = render(*camera, scene);
  // The red pixels' bounding rectangle.
  int left = kCols, right = -1, top = kRows, bottom = -1, red = 0;
  for (int row = 0; row < kRows; ++row) {
    for (int col = 0; col < kCols; ++col) {
      const Pixel p = at(image, col, row);
      if (p.r > 2 * p.g && p.r > 2 * p.b) {
        left = std::min(left, col);
        right = std::max(right, col);
        top = std::min(top, row);
        bottom = std::max(bottom, row);
        ++red;
      }
    }
  }
  ASSERT_GT(red, 0);
  // The front face's corners (only it faces the eye: the eye is below the
  // top, between the sides) projected analytically, in pixel edges.
  const Eigen::Vector2d top_left = image_point(Eigen::Vector3d(kFront_m, kLeft_m, kTop_m - kEyeHeight_m));
  const Eigen::Vector2d bottom_right = image_point(Eigen::Vector3d(kFront_m, kRight_m, -kEyeHeight_m));
  EXPECT_NEAR(left, top_left.x(), 1.0);
  EXPECT_NEAR(right + 1, bottom_right.x(), 1.0);
  EXPECT_NEAR(top, top_left.y(), 1.0);
  EXPECT_NEAR(bottom + 1, bottom_right.y(), 1.0);
  // A solid rectangle: every pixel inside it is red.
  EXPECT_EQ(red, (right - left + 1) * (bottom - top + 1));
}

TEST(RgbCamera, ShadingIsLambertUnderTheSunPlusAmbient) {
  const Scene scene = red_box_on_grey_ground();
  CAMERA_OR_SKIP(camera, build_scene_mesh(scene), camera_def());
  const RgbImage image = render(*camera, scene);
  // The documented sun: 60 deg up at azimuth 30 deg; 35% ambient.
  EXPECT_NEAR(kSunDirection.norm(), 1.0, 1e-12);
  EXPECT_NEAR(std::asin(kSunDirection.z()) / kDeg, 60.0, 1e-9);
  EXPECT_NEAR(std::atan2(kSunDirection.y(), kSunDirection.x()) / kDeg, 30.0, 1e-9);
  EXPECT_EQ(kAmbient, 0.35);
  // The box's front face (normal -x) turns away from the sun: ambient only.
  const double away = kAmbient + (1.0 - kAmbient) * std::max(0.0, -kSunDirection.x());
  const Eigen::Vector2d face = image_point(Eigen::Vector3d(kFront_m, 0.5, 0.0));
  const Pixel box = at(image, static_cast<int>(face.x()), static_cast<int>(face.y()));
  EXPECT_NEAR(box.r, kRed.r * away * 255.0, 1.0);
  EXPECT_NEAR(box.g, kRed.g * away * 255.0, 1.0);
  EXPECT_NEAR(box.b, kRed.b * away * 255.0, 1.0);
  // The ground (normal +z) is lit by the sun's height.
  const double lit = kAmbient + (1.0 - kAmbient) * kSunDirection.z();
  const Eigen::Vector2d ground = image_point(Eigen::Vector3d(3.0, -2.0, -kEyeHeight_m));
  const Pixel g = at(image, static_cast<int>(ground.x()), static_cast<int>(ground.y()));
  EXPECT_NEAR(g.r, kGrey.r * lit * 255.0, 1.0);
  EXPECT_EQ(g.r, g.g);
  EXPECT_EQ(g.g, g.b);
}

TEST(RgbCamera, TiltedGroundIsShadedByItsNormal) {
  // A ground plane tilted 30 deg, towards the sun's azimuth or away from it, seen from above:
  // the image centre shows c (ambient + (1 - ambient) max(n . sun, 0)) for the plane's normal n.
  const double azimuth = std::atan2(kSunDirection.y(), kSunDirection.x());
  for (const double toward : {1.0, -1.0}) {
    const Eigen::Vector3d horizontal(std::cos(azimuth), std::sin(azimuth), 0.0);
    const Eigen::Vector3d normal =
        (std::cos(30.0 * kDeg) * Eigen::Vector3d::UnitZ() + toward * std::sin(30.0 * kDeg) * horizontal).normalized();
    Scene scene;
    Shape ground;
    ground.type = ShapeType::plane;
    ground.color = kGrey;
    ground.pose.linear() = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), normal).toRotationMatrix();
    scene.shapes.push_back(ground);
    CAMERA_OR_SKIP(camera, build_scene_mesh(scene), camera_def());
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = Eigen::AngleAxisd(90.0 * kDeg, Eigen::Vector3d::UnitY()).toRotationMatrix();  // looking down
    pose.translation() = Eigen::Vector3d(0.0, 0.0, 5.0);
    RgbImage image;
    camera->render(pose, 0.0, scripted_poses(scene, 0.0), image);
    const double shade = kAmbient + (1.0 - kAmbient) * std::max(0.0, normal.dot(kSunDirection));
    const Pixel p = at(image, kCols / 2, kRows / 2);
    EXPECT_NEAR(p.r, kGrey.r * shade * 255.0, 1.0) << "toward " << toward;
    EXPECT_EQ(p.r, p.g);
    // The level ground's shade lies between the two.
    const double level = kAmbient + (1.0 - kAmbient) * kSunDirection.z();
    EXPECT_EQ(toward > 0 ? p.r > kGrey.r * level * 255.0 + 2 : p.r < kGrey.r * level * 255.0 - 2, true) << p.r;
  }
}

TEST(RgbCamera, ImagesAreBitIdenticalAndTheBufferIsReused) {
  const Scene scene = red_box_on_grey_ground();
  const SceneMesh mesh = build_scene_mesh(scene);
  CAMERA_OR_SKIP(first, mesh, camera_def());
  const auto second = make_rgb_camera(mesh, camera_def(), 1);
  RgbImage a, b;
  first->render(camera_pose(), 0.0, scripted_poses(scene, 0.0), a);
  second->render(camera_pose(), 0.0, scripted_poses(scene, 0.0), b);
  EXPECT_EQ(a.rgb, b.rgb);
  const std::uint8_t* buffer = a.rgb.data();
  const std::vector<std::uint8_t> before = a.rgb;
  first->render(camera_pose(), 0.1, scripted_poses(scene, 0.1), a);
  EXPECT_EQ(a.rgb, before);
  EXPECT_EQ(a.rgb.data(), buffer);  // no new allocation once sized
  EXPECT_DOUBLE_EQ(a.time_s, 0.1);
}

TEST(RgbCamera, NoiseIsSeededAndOfTheConfiguredSpread) {
  const Scene scene = red_box_on_grey_ground();
  const SceneMesh mesh = build_scene_mesh(scene);
  CAMERA_OR_SKIP(clean, mesh, camera_def());
  constexpr double kNoise = 0.04;
  const auto noisy = make_rgb_camera(mesh, camera_def(kNoise, 7), 1);
  const auto same = make_rgb_camera(mesh, camera_def(kNoise, 7), 1);
  const auto other_seed = make_rgb_camera(mesh, camera_def(kNoise, 8), 1);
  const auto other_world = make_rgb_camera(mesh, camera_def(kNoise, 7), 2);
  const RgbImage truth = render(*clean, scene);
  const RgbImage a = render(*noisy, scene);
  EXPECT_EQ(a.rgb, render(*same, scene).rgb);
  EXPECT_NE(a.rgb, render(*other_seed, scene).rgb);
  EXPECT_NE(a.rgb, render(*other_world, scene).rgb);
  EXPECT_NE(a.rgb, render(*noisy, scene).rgb);  // the stream goes on from image to image
  // Away from the ends of the scale (where it is clamped), the error is
  // unbiased with the configured standard deviation.
  double sum = 0.0, sum_sq = 0.0;
  int n = 0;
  for (std::size_t i = 0; i < truth.rgb.size(); ++i) {
    if (truth.rgb[i] < 60 || truth.rgb[i] > 195) continue;
    const double e = static_cast<double>(a.rgb[i]) - truth.rgb[i];
    sum += e;
    sum_sq += e * e;
    ++n;
  }
  ASSERT_GT(n, 5000);
  const double mean = sum / n;
  const double stddev = std::sqrt(sum_sq / n - mean * mean);
  // Rounding adds 1/12 of a level's variance.
  const double expected = std::sqrt(std::pow(kNoise * 255.0, 2) + 1.0 / 12.0);
  EXPECT_NEAR(mean, 0.0, 4.0 * expected / std::sqrt(n));
  EXPECT_NEAR(stddev, expected, 0.05 * expected);
}

TEST(RgbCamera, RefusesWhatItCannotRender) {
  const Scene scene = red_box_on_grey_ground();
  const SceneMesh mesh = build_scene_mesh(scene);
  RgbCameraDef wide = camera_def();
  wide.camera.fov_h_deg = 175.0;
  EXPECT_THROW(make_rgb_camera(mesh, wide, 1), std::invalid_argument);
  RgbCameraDef empty = camera_def();
  empty.camera.cols = 0;
  EXPECT_THROW(make_rgb_camera(mesh, empty, 1), std::invalid_argument);
  RgbCameraDef ranges = camera_def();
  ranges.camera.min_range_m = 40.0;
  EXPECT_THROW(make_rgb_camera(mesh, ranges, 1), std::invalid_argument);
}

// A scene whose drone carries one rgb_camera with `fields` (JSON members after its alias and type).
std::string camera_scene(const std::string& fields) {
  return R"({"campo_scene": 1, "world": {"physics_step_s": 0.004166666666666667, "sensor_rate_hz": 10},
    "objects": [{"alias": "drone", "type": "quadrotor", "pose": {"position_m": [0, 0, 1]},
      "sensors": [{"alias": "front", "type": "rgb_camera", )" +
         fields + R"(}],
      "mission": {"waypoints": [{"position_m": [5, 0, 1]}]}}]})";
}

TEST(RgbCamera, SceneBlocksAreReadWithEveryField) {
  const Scene scene = parse_scene(nlohmann::json::parse(camera_scene(R"(
      "fov_deg": 75, "resolution": [160, 90], "range_m": [0.2, 80], "sky": [0.1, 0.2, 0.3],
      "noise_stddev": 0.01, "seed": 5, "rate_hz": 20, "mount": {"position_m": [0.1, 0, 0], "rpy_deg": [0, 10, 0]})")),
                                  "inline.json", std::filesystem::temp_directory_path());
  ASSERT_EQ(scene.vehicles.size(), 1u);
  ASSERT_EQ(scene.vehicles[0].rgb_cameras.size(), 1u);
  const RgbCameraConfig& c = scene.vehicles[0].rgb_cameras[0].camera;
  EXPECT_EQ(c.fov_h_deg, 75.0);
  EXPECT_EQ(c.cols, 160);
  EXPECT_EQ(c.rows, 90);
  EXPECT_EQ(c.min_range_m, 0.2);
  EXPECT_EQ(c.max_range_m, 80.0);
  EXPECT_EQ(c.sky.b, 0.3);
  EXPECT_EQ(c.noise_stddev, 0.01);
  EXPECT_EQ(c.seed, 5u);
  EXPECT_EQ(c.rate_hz, 20.0);
  EXPECT_EQ(c.mount.rpy_deg.y(), 10.0);
}

TEST(RgbCamera, BadBlocksAreInputErrorsNamingTheField) {
  const auto error_of = [](const std::string& fields) -> std::string {
    try {
      parse_scene(nlohmann::json::parse(camera_scene(fields)), "inline.json", std::filesystem::temp_directory_path());
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_NE(error_of(R"("fov_deg": 175)").find("/objects/0/sensors/0/fov_deg"), std::string::npos)
      << error_of(R"("fov_deg": 175)");
  EXPECT_NE(error_of(R"("resolution": [0, 10])").find("/objects/0/sensors/0/resolution"), std::string::npos);
  EXPECT_NE(error_of(R"("range_m": [5, 1])").find("/objects/0/sensors/0/range_m"), std::string::npos);
  EXPECT_NE(error_of(R"("sky": [1, 2, 0])").find("/objects/0/sensors/0/sky"), std::string::npos);
  EXPECT_NE(error_of(R"("noise_stddev": -1)").find("/objects/0/sensors/0/noise_stddev"), std::string::npos);
  EXPECT_NE(error_of(R"("rate_hz": 0.001)").find("rate_hz"), std::string::npos);
  EXPECT_NE(error_of(R"("fov": 60)").find("/objects/0/sensors/0/fov"), std::string::npos);
}

}  // namespace
}  // namespace campo
