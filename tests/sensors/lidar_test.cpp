#include "sensors/lidar.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "campo/pose.hpp"
#include "campo/random.hpp"
#include "tests/test_units.hpp"

namespace campo {
namespace {

using namespace campo::test_units;

Shape plane_through(const Eigen::Vector3d& point,
                    const Eigen::Vector3d& rpy_deg = Eigen::Vector3d::Zero()) {
  Shape s;
  s.type = ShapeType::plane;
  s.pose = to_isometry(Pose{point, rpy_deg});
  return s;
}

Shape box(const Eigen::Vector3d& center, const Eigen::Vector3d& size) {
  Shape s;
  s.type = ShapeType::cuboid;
  s.pose.translation() = center;
  s.size_m = size;
  return s;
}

// A wall facing the origin: the plane x = distance.
Scene wall_scene(double distance) {
  Scene scene;
  scene.shapes.push_back(plane_through({distance, 0.0, 0.0}, {0.0, 90.0, 0.0}));
  return scene;
}

RangeSensorConfig grid_config(int cols, int rows, double fov_h, double fov_v) {
  RangeSensorConfig c;
  c.cols = cols;
  c.rows = rows;
  c.fov_h_deg = fov_h;
  c.fov_v_deg = fov_v;
  c.max_range_m = 10.0;
  return c;
}

TEST(LidarPresets, NamesTheThreePresetsAndRejectsOthers) {
  const std::vector<std::string_view> expected{"scanner3d", "leddar_vu8", "planar180"};
  EXPECT_EQ(sensor_preset_names(), expected);
  for (const std::string_view name : sensor_preset_names()) {
    const auto config = sensor_preset(name);
    ASSERT_TRUE(config.has_value()) << name;
    EXPECT_EQ(config->preset, name);
    EXPECT_NO_THROW(Lidar(*config, 0)) << name;
  }
  EXPECT_FALSE(sensor_preset("velodyne").has_value());
}

TEST(LidarPresets, Scanner3dIs256By256Over90By90DegreesLookingForward) {
  const RangeSensorConfig c = *sensor_preset("scanner3d");
  EXPECT_EQ(c.beam_count(), 256 * 256);
  EXPECT_DOUBLE_EQ(c.max_range_m, 10.0);
  EXPECT_DOUBLE_EQ(c.min_range_m, 0.05);
  EXPECT_EQ(c.mount.rpy_deg, Eigen::Vector3d::Zero());
  const std::vector<Beam> beams = lidar_beams(c);
  ASSERT_EQ(beams.size(), 256u * 256u);
  const double edge = 45.0 - 0.5 * 90.0 / 256.0;        // centre of the outermost pixel
  EXPECT_DOUBLE_EQ(beams.front().azimuth_deg, edge);    // top-left: left ...
  EXPECT_DOUBLE_EQ(beams.front().elevation_deg, edge);  // ... and up
  EXPECT_DOUBLE_EQ(beams.back().azimuth_deg, -edge);    // bottom-right
  EXPECT_DOUBLE_EQ(beams.back().elevation_deg, -edge);
  EXPECT_DOUBLE_EQ(beams[255].azimuth_deg, -edge);  // end of the first row
  EXPECT_DOUBLE_EQ(beams[255].elevation_deg, edge);
}

TEST(LidarPresets, LeddarVu8FansEightBeamsOver48DegreesPitched45Down) {
  const RangeSensorConfig c = *sensor_preset("leddar_vu8");
  ASSERT_EQ(c.beam_count(), 8);
  const std::vector<Beam> beams = lidar_beams(c);
  const double expected_az[] = {21.0, 15.0, 9.0, 3.0, -3.0, -9.0, -15.0, -21.0};
  for (int i = 0; i < 8; ++i) {
    EXPECT_NEAR(beams[i].azimuth_deg, expected_az[i], 1e-12) << i;
    EXPECT_NEAR(beams[i].elevation_deg, 0.0, 1e-12) << i;
  }
  EXPECT_DOUBLE_EQ(c.fov_v_deg, 0.3);
  // Positive pitch turns the sensor's x axis toward -z: nose down.
  const Eigen::Vector3d forward = to_isometry(c.mount).linear() * Eigen::Vector3d::UnitX();
  EXPECT_NEAR(forward.x(), std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(forward.z(), -std::sqrt(0.5), 1e-12);
}

TEST(LidarPresets, LeddarOnADroneAt30MetresHitsFlatGroundAhead) {
  Scene scene;
  scene.shapes.push_back(plane_through(Eigen::Vector3d::Zero()));
  const RayCaster caster(scene);
  const RangeSensorConfig c = *sensor_preset("leddar_vu8");
  Lidar lidar(c, 0);
  const double h = 30.0;  // 001 flew at 30 m
  const Eigen::Isometry3d body = to_isometry(Pose{{10.0, -4.0, h}, {0.0, 0.0, 30.0}});
  RangeScan scan;
  lidar.scan(caster, body * to_isometry(c.mount), 0.0, scan);
  ASSERT_EQ(scan.rows, 1);
  ASSERT_EQ(scan.cols, 8);
  ASSERT_EQ(scan.points.size(), 8u);
  const std::vector<Beam> beams = lidar_beams(c);
  for (int i = 0; i < 8; ++i) {
    // Sensor-frame beam (cos el cos az, cos el sin az, sin el) pitched down by
    // 45 deg: its downward component is sin45 cos el cos az - cos45 sin el.
    const double az = beams[i].azimuth_deg * kDeg, el = beams[i].elevation_deg * kDeg;
    const double down =
        std::sin(45.0 * kDeg) * std::cos(el) * std::cos(az) - std::cos(45.0 * kDeg) * std::sin(el);
    EXPECT_EQ(scan.hits[i], 1) << i;
    EXPECT_NEAR(scan.ranges_m[i], h / down, kMm) << i;
    EXPECT_NEAR(scan.points[i].z(), 0.0, kMm) << i;
    // Ahead of the drone: positive along its heading.
    const Eigen::Vector3d ahead = body.inverse() * scan.points[i].cast<double>();
    EXPECT_GT(ahead.x(), 0.0) << i;
  }
  // Symmetric fan; the outer beams reach farther.
  EXPECT_GT(scan.ranges_m[0], scan.ranges_m[3]);
  EXPECT_NEAR(scan.ranges_m[0], scan.ranges_m[7], kMm);
}

TEST(LidarPresets, Planar180Has181BeamsOneDegreeApartLeftmostFirst) {
  const RangeSensorConfig c = *sensor_preset("planar180");
  const std::vector<Beam> beams = lidar_beams(c);
  ASSERT_EQ(beams.size(), 181u);
  EXPECT_EQ(c.beam_count(), 181);
  for (std::size_t i = 0; i < beams.size(); ++i) {
    EXPECT_DOUBLE_EQ(beams[i].azimuth_deg, 90.0 - static_cast<double>(i));
    EXPECT_DOUBLE_EQ(beams[i].elevation_deg, 0.0);
  }
  EXPECT_DOUBLE_EQ(c.max_range_m, 20.0);
}

TEST(Lidar, GridBeamsAreRowMajorFromTheTopLeft) {
  const RangeSensorConfig c = grid_config(4, 3, 80.0, 30.0);
  const std::vector<Beam> beams = lidar_beams(c);
  ASSERT_EQ(beams.size(), 12u);
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 4; ++col) {
      const Beam& b = beams[static_cast<std::size_t>(row * 4 + col)];
      EXPECT_DOUBLE_EQ(b.azimuth_deg, 40.0 - (col + 0.5) * 20.0) << col << " " << row;
      EXPECT_DOUBLE_EQ(b.elevation_deg, 15.0 - (row + 0.5) * 10.0) << col << " " << row;
    }
  }
}

TEST(Lidar, BeamDirectionIsXForwardYLeftZUp) {
  EXPECT_TRUE(beam_direction({0.0, 0.0}).isApprox(Eigen::Vector3f::UnitX()));
  EXPECT_TRUE(beam_direction({90.0, 0.0}).isApprox(Eigen::Vector3f::UnitY()));
  EXPECT_TRUE(beam_direction({-90.0, 0.0}).isApprox(-Eigen::Vector3f::UnitY()));
  EXPECT_TRUE(beam_direction({0.0, 90.0}).isApprox(Eigen::Vector3f::UnitZ()));
  const Eigen::Vector3f d = beam_direction({30.0, -20.0});
  EXPECT_NEAR(d.norm(), 1.0f, 1e-6f);
  EXPECT_GT(d.y(), 0.0f);
  EXPECT_NEAR(d.z(), -std::sin(20.0 * kDeg), 1e-6);
}

TEST(Lidar, ExplicitBeamsReplaceTheGrid) {
  RangeSensorConfig c = grid_config(16, 16, 90.0, 90.0);
  c.beams = {{10.0, 0.0}, {0.0, 0.0}, {-10.0, 5.0}};
  ASSERT_EQ(lidar_beams(c).size(), 3u);
  const Scene scene = wall_scene(4.0);
  const RayCaster caster(scene);
  Lidar lidar(c, 0);
  RangeScan scan;
  lidar.scan(caster, Eigen::Isometry3d::Identity(), 0.0, scan);
  EXPECT_EQ(scan.rows, 1);
  EXPECT_EQ(scan.cols, 3);
  ASSERT_EQ(scan.ranges_m.size(), 3u);
  EXPECT_NEAR(scan.ranges_m[0], 4.0 / std::cos(10.0 * kDeg), kMm);
  EXPECT_NEAR(scan.ranges_m[1], 4.0, kMm);
  EXPECT_NEAR(scan.ranges_m[2], 4.0 / (std::cos(10.0 * kDeg) * std::cos(5.0 * kDeg)), kMm);
}

TEST(Lidar, ScanOfAWallFromAMovedSensorMatchesGeometry) {
  const Scene scene = wall_scene(6.0);
  const RayCaster caster(scene);
  const RangeSensorConfig c = grid_config(32, 24, 60.0, 40.0);
  Lidar lidar(c, 0);
  const Eigen::Isometry3d pose = to_isometry(Pose{{1.0, 2.0, 0.5}, {5.0, -8.0, 12.0}});
  RangeScan scan;
  lidar.scan(caster, pose, 1.25, scan);
  EXPECT_EQ(scan.rows, 24);
  EXPECT_EQ(scan.cols, 32);
  EXPECT_DOUBLE_EQ(scan.time_s, 1.25);
  EXPECT_TRUE(scan.sensor_pose.isApprox(pose));
  ASSERT_EQ(scan.points.size(), scan.ranges_m.size());
  for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) {
    const Eigen::Vector3d d = pose.linear() * lidar.directions()[i].cast<double>();
    ASSERT_EQ(scan.hits[i], 1) << i;
    EXPECT_NEAR(scan.ranges_m[i], 5.0 / d.x(), kMm) << i;
    EXPECT_NEAR(scan.points[i].x(), 6.0, kMm) << i;
  }
}

TEST(Lidar, NoReturnReadsMaxRangeAndDepthOne) {
  const Scene empty;
  const RayCaster caster(empty);
  const RangeSensorConfig c = grid_config(8, 6, 90.0, 60.0);
  Lidar lidar(c, 0);
  RangeScan scan;
  lidar.scan(caster, Eigen::Isometry3d::Identity(), 0.0, scan);
  EXPECT_TRUE(std::all_of(scan.hits.begin(), scan.hits.end(), [](auto h) { return h == 0; }));
  EXPECT_TRUE(
      std::all_of(scan.ranges_m.begin(), scan.ranges_m.end(), [](float r) { return r == 10.0f; }));
  EXPECT_TRUE(scan.points.empty());
  const cv::Mat depth = depth_map(scan, c);
  EXPECT_EQ(cv::countNonZero(depth != 1.0f), 0);
}

TEST(Lidar, DepthMapIsRangeOverMaxZeroBelowMinAndOneWithoutReturn) {
  RangeSensorConfig c = grid_config(2, 2, 10.0, 10.0);
  c.min_range_m = 0.05;
  RangeScan scan;
  scan.rows = 2;
  scan.cols = 2;
  scan.ranges_m = {5.0f, 0.01f, 10.0f, 2.5f};
  scan.hits = {1, 1, 0, 1};
  const cv::Mat depth = depth_map(scan, c);
  ASSERT_EQ(depth.type(), CV_32F);
  ASSERT_EQ(depth.rows, 2);
  ASSERT_EQ(depth.cols, 2);
  EXPECT_FLOAT_EQ(depth.at<float>(0, 0), 0.5f);
  EXPECT_FLOAT_EQ(depth.at<float>(0, 1), 0.0f);
  EXPECT_FLOAT_EQ(depth.at<float>(1, 0), 1.0f);
  EXPECT_FLOAT_EQ(depth.at<float>(1, 1), 0.25f);
}

TEST(Lidar, DepthMapIsItsDefinitionOnEveryBeamOfAnOddSizedScan) {
  // Beams are done several at a time where the CPU allows: every beam of a
  // scan whose size is not a multiple of any vector width, against the
  // definition in double (a hit's range over the maximum, at most 1; 0 below
  // the minimum range; 1 without a return), with ranges at and around both
  // limits, beyond the maximum, zero, and a NaN.
  RangeSensorConfig c = grid_config(37, 11, 90.0, 30.0);
  c.min_range_m = 0.3;
  c.max_range_m = 12.5;
  RangeScan scan;
  scan.rows = 11;
  scan.cols = 37;
  Rng rng(3);
  const float special[] = {0.0f, 0.3f, std::nextafter(0.3f, 0.0f), std::nextafter(0.3f, 1.0f), 12.5f,
                           std::nextafter(12.5f, 0.0f), 13.0f, std::numeric_limits<float>::quiet_NaN()};
  for (int i = 0; i < scan.rows * scan.cols; ++i) {
    scan.ranges_m.push_back(i % 5 == 0 ? special[(i / 5) % 8] : static_cast<float>(rng.uniform(0.0, 14.0)));
    scan.hits.push_back(static_cast<std::uint8_t>(i % 7 == 3 ? 0 : 1 + i % 2));
  }
  const cv::Mat depth = depth_map(scan, c);
  for (int i = 0; i < scan.rows * scan.cols; ++i) {
    const double r = scan.ranges_m[static_cast<std::size_t>(i)];
    const float got = depth.at<float>(i / scan.cols, i % scan.cols);
    if (!scan.hits[static_cast<std::size_t>(i)]) {
      EXPECT_EQ(got, 1.0f) << i;
    } else if (r < c.min_range_m) {
      EXPECT_EQ(got, 0.0f) << i;
    } else if (std::isnan(r)) {
      EXPECT_TRUE(std::isnan(got)) << i;
    } else {
      EXPECT_EQ(got, static_cast<float>(r / c.max_range_m > 1.0 ? 1.0 : r / c.max_range_m)) << i << ": " << r;
    }
  }
}

TEST(Lidar, DepthMapPixelZeroZeroLooksUpAndLeft) {
  Scene scene;
  scene.shapes.push_back(box({5.0, 3.0, 3.0}, {1.0, 4.0, 4.0}));  // ahead, up and to the left
  const RayCaster caster(scene);
  const RangeSensorConfig c = grid_config(16, 16, 90.0, 90.0);
  Lidar lidar(c, 0);
  RangeScan scan;
  lidar.scan(caster, Eigen::Isometry3d::Identity(), 0.0, scan);
  const cv::Mat depth = depth_map(scan, c);
  EXPECT_LT(depth.at<float>(4, 4), 1.0f);   // row 4 (upper half), column 4 (left half)
  EXPECT_EQ(depth.at<float>(4, 11), 1.0f);  // upper right: nothing
  EXPECT_EQ(depth.at<float>(11, 4), 1.0f);  // lower left: nothing
  EXPECT_NEAR(depth.at<float>(4, 4) * 10.0, scan.ranges_m[4 * 16 + 4], 1e-5);
}

TEST(Lidar, MinRangeLooksPastTheSensorHousing) {
  Scene scene;
  scene.shapes.push_back(box({0.03, 0.0, 0.0}, {0.02, 2.0, 2.0}));  // a window 2 cm ahead
  scene.shapes.push_back(plane_through({3.0, 0.0, 0.0}, {0.0, 90.0, 0.0}));
  const RayCaster caster(scene);
  RangeSensorConfig c = grid_config(4, 4, 20.0, 20.0);
  c.min_range_m = 0.05;
  Lidar lidar(c, 0);
  RangeScan scan;
  lidar.scan(caster, Eigen::Isometry3d::Identity(), 0.0, scan);
  for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) {
    EXPECT_NEAR(scan.ranges_m[i] * lidar.directions()[i].x(), 3.0, kMm) << i;
  }
}

// Ranges of a noisy scan minus the noise-free ones, over several scans.
std::vector<double> range_errors(const RangeSensorConfig& noisy, int scans,
                                 std::vector<std::uint8_t>* hits = nullptr) {
  const Scene scene = wall_scene(5.0);
  const RayCaster caster(scene);
  RangeSensorConfig clean = noisy;
  clean.noise_stddev_m = 0.0;
  clean.dropout_probability = 0.0;
  clean.quantization_m = 0.0;
  Lidar truth(clean, 0);
  Lidar lidar(noisy, 0);
  RangeScan expected, scan;
  truth.scan(caster, Eigen::Isometry3d::Identity(), 0.0, expected);
  std::vector<double> errors;
  for (int k = 0; k < scans; ++k) {
    lidar.scan(caster, Eigen::Isometry3d::Identity(), 0.0, scan);
    for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) {
      if (hits) hits->push_back(scan.hits[i]);
      if (scan.hits[i]) errors.push_back(double{scan.ranges_m[i]} - expected.ranges_m[i]);
    }
  }
  return errors;
}

TEST(Lidar, GaussianNoiseHasZeroMeanAndTheConfiguredStddev) {
  RangeSensorConfig c = grid_config(100, 100, 20.0, 20.0);
  c.noise_stddev_m = 0.05;
  const std::vector<double> e = range_errors(c, 5);
  ASSERT_EQ(e.size(), 50000u);
  double mean = 0.0;
  for (double x : e) mean += x;
  mean /= static_cast<double>(e.size());
  double var = 0.0;
  for (double x : e) var += (x - mean) * (x - mean);
  const double stddev = std::sqrt(var / static_cast<double>(e.size() - 1));
  EXPECT_LT(std::abs(mean), 3.0 * 0.05 / std::sqrt(static_cast<double>(e.size())));
  EXPECT_NEAR(stddev, 0.05, 0.05 * 0.05);
}

TEST(Lidar, DropoutLosesTheConfiguredFractionOfBeams) {
  RangeSensorConfig c = grid_config(100, 100, 20.0, 20.0);
  c.dropout_probability = 0.25;
  std::vector<std::uint8_t> hits;
  const std::vector<double> e = range_errors(c, 5, &hits);
  const double n = static_cast<double>(hits.size());
  const double dropped = static_cast<double>(std::count(hits.begin(), hits.end(), 0)) / n;
  EXPECT_NEAR(dropped, 0.25, 4.0 * std::sqrt(0.25 * 0.75 / n));
  // Beams that do return are exact.
  for (double x : e) ASSERT_EQ(x, 0.0);
}

TEST(Lidar, DroppedBeamsReadMaxRangeAndGiveNoPoint) {
  RangeSensorConfig c = grid_config(50, 50, 20.0, 20.0);
  c.dropout_probability = 0.5;
  const Scene scene = wall_scene(5.0);
  const RayCaster caster(scene);
  Lidar lidar(c, 0);
  RangeScan scan;
  lidar.scan(caster, Eigen::Isometry3d::Identity(), 0.0, scan);
  std::size_t returns = 0;
  for (std::size_t i = 0; i < scan.hits.size(); ++i) {
    if (scan.hits[i]) {
      ++returns;
    } else {
      EXPECT_EQ(scan.ranges_m[i], 10.0f);
    }
  }
  EXPECT_EQ(scan.points.size(), returns);
}

TEST(Lidar, QuantizationRoundsRangesToTheStep) {
  RangeSensorConfig c = grid_config(60, 60, 40.0, 40.0);
  c.quantization_m = 0.1;
  const std::vector<double> e = range_errors(c, 1);
  ASSERT_EQ(e.size(), 3600u);
  for (double x : e) EXPECT_LE(std::abs(x), 0.05 + 1e-5);
  const Scene scene = wall_scene(5.0);
  const RayCaster caster(scene);
  c.noise_stddev_m = 0.03;
  Lidar lidar(c, 0);
  RangeScan scan;
  lidar.scan(caster, Eigen::Isometry3d::Identity(), 0.0, scan);
  for (float r : scan.ranges_m) {
    const double steps = r / 0.1;
    EXPECT_NEAR(steps, std::round(steps), 1e-4) << r;
  }
}

TEST(Lidar, NoiseIsClampedToZeroAndMaxRange) {
  RangeSensorConfig c = grid_config(100, 100, 20.0, 20.0);
  c.noise_stddev_m = 20.0;
  const Scene scene = wall_scene(5.0);
  const RayCaster caster(scene);
  Lidar lidar(c, 0);
  RangeScan scan;
  lidar.scan(caster, Eigen::Isometry3d::Identity(), 0.0, scan);
  int at_zero = 0, at_max = 0;
  for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) {
    ASSERT_EQ(scan.hits[i], 1);
    ASSERT_GE(scan.ranges_m[i], 0.0f);
    ASSERT_LE(scan.ranges_m[i], 10.0f);
    at_zero += scan.ranges_m[i] == 0.0f;
    at_max += scan.ranges_m[i] == 10.0f;
  }
  EXPECT_GT(at_zero, 1000);
  EXPECT_GT(at_max, 1000);
}

TEST(Lidar, SameSeedsGiveIdenticalScansOtherSeedsDiffer) {
  RangeSensorConfig c = grid_config(32, 32, 40.0, 40.0);
  c.noise_stddev_m = 0.02;
  c.dropout_probability = 0.1;
  c.seed = 7;
  const Scene scene = wall_scene(5.0);
  const RayCaster caster(scene);
  const auto first_scan = [&](const RangeSensorConfig& config, std::uint64_t world_seed) {
    Lidar lidar(config, world_seed);
    RangeScan scan;
    lidar.scan(caster, Eigen::Isometry3d::Identity(), 0.0, scan);
    return scan;
  };
  const RangeScan a = first_scan(c, 1);
  const RangeScan b = first_scan(c, 1);
  EXPECT_EQ(a.ranges_m, b.ranges_m);
  EXPECT_EQ(a.hits, b.hits);
  EXPECT_NE(first_scan(c, 2).ranges_m, a.ranges_m);
  RangeSensorConfig other = c;
  other.seed = 8;
  EXPECT_NE(first_scan(other, 1).ranges_m, a.ranges_m);
  // The stream goes on: a second scan from the same pose is not a repeat.
  Lidar lidar(c, 1);
  RangeScan s1, s2;
  lidar.scan(caster, Eigen::Isometry3d::Identity(), 0.0, s1);
  lidar.scan(caster, Eigen::Isometry3d::Identity(), 0.1, s2);
  EXPECT_EQ(s1.ranges_m, a.ranges_m);
  EXPECT_NE(s2.ranges_m, s1.ranges_m);
}

TEST(Lidar, RejectsConfigsWithoutBeamsOrWithBadRanges) {
  RangeSensorConfig c = grid_config(0, 4, 90.0, 90.0);
  EXPECT_THROW(Lidar(c, 0), std::invalid_argument);
  c = grid_config(4, 4, 90.0, 90.0);
  c.min_range_m = 20.0;
  EXPECT_THROW(Lidar(c, 0), std::invalid_argument);
  c = grid_config(4, 4, 90.0, 90.0);
  c.dropout_probability = 1.5;
  EXPECT_THROW(Lidar(c, 0), std::invalid_argument);
  c = grid_config(4, 4, 90.0, 90.0);
  c.noise_stddev_m = -1.0;
  EXPECT_THROW(Lidar(c, 0), std::invalid_argument);
}

}  // namespace
}  // namespace campo
