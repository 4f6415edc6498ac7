#include "planners/depth_reactive_steps.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "campo/random.hpp"
#include "campo/scene_loader.hpp"
#include "sensors/lidar.hpp"
#include "sensors/raycaster.hpp"

namespace campo {
namespace {

cv::Mat free_map(int size) { return cv::Mat(size, size, CV_32F, cv::Scalar(1.0f)); }

DepthGrid grid64() { return {64, 64, 90.0, 90.0, 10.0}; }

// Reference DilataMappa straight from the definition: every pixel takes the
// smallest value among the obstacle pixels whose structuring element covers it.
cv::Mat brute_force_dilation(const cv::Mat& depth, const DilationParams& p) {
  cv::Mat out(depth.size(), CV_32F, cv::Scalar(1.0f));
  for (int qy = 0; qy < depth.rows; ++qy) {
    for (int qx = 0; qx < depth.cols; ++qx) {
      const float v = depth.at<float>(qy, qx);
      if (v >= 1.0f) continue;
      const int n = static_cast<int>(p.layer_radius_px.size());
      const int s = std::clamp(static_cast<int>(std::ceil(v * n)), 1, n);
      const cv::Size r = p.layer_radius_px[s - 1];
      for (int dy = -r.height; dy <= r.height; ++dy) {
        for (int dx = -r.width; dx <= r.width; ++dx) {
          if (p.shape == StructuringShape::disc) {
            const double ex = r.width > 0 ? static_cast<double>(dx) / r.width : 0.0;
            const double ey = r.height > 0 ? static_cast<double>(dy) / r.height : 0.0;
            if ((r.width == 0 && dx != 0) || (r.height == 0 && dy != 0) || ex * ex + ey * ey > 1.0 + 1e-12) continue;
          }
          const int x = qx + dx, y = qy + dy;
          if (x < 0 || y < 0 || x >= depth.cols || y >= depth.rows) continue;
          out.at<float>(y, x) = std::min(out.at<float>(y, x), v);
        }
      }
    }
  }
  return out;
}

TEST(DepthGrid, ProjectionInvertsPixelDirectionsAndMatchesTheLidarBeams) {
  RangeSensorConfig config;
  config.cols = 16;
  config.rows = 8;
  config.fov_h_deg = 90.0;
  config.fov_v_deg = 60.0;
  RangeScan scan;
  begin_scan(scan, config, 0.0, Eigen::Isometry3d::Identity());
  const DepthGrid grid = DepthGrid::of(scan, config);
  const std::vector<Beam> beams = lidar_beams(config);
  for (int row = 0; row < config.rows; ++row) {
    for (int col = 0; col < config.cols; ++col) {
      const Eigen::Vector3d d = grid.direction({col, row});
      const Eigen::Vector3f beam = beam_direction(beams[row * config.cols + col]);
      EXPECT_LT((d.cast<float>() - beam).norm(), 1e-6f);
      const Eigen::Vector2d back = grid.project(3.7 * d);
      EXPECT_NEAR(back.x(), col, 1e-9);
      EXPECT_NEAR(back.y(), row, 1e-9);
    }
  }
  // Straight ahead is the centre of the image; left is toward column 0, up toward row 0.
  EXPECT_NEAR(grid.project(Eigen::Vector3d::UnitX()).x(), 7.5, 1e-12);
  EXPECT_NEAR(grid.project(Eigen::Vector3d::UnitX()).y(), 3.5, 1e-12);
  EXPECT_LT(grid.project({1.0, 0.5, 0.0}).x(), 7.5);
  EXPECT_LT(grid.project({1.0, 0.0, 0.5}).y(), 3.5);
}

// Radii r_s = scale * (n + 1 - s): nearer layers larger.
std::vector<cv::Size> descending_radii(int n, int scale) {
  std::vector<cv::Size> radii;
  for (int s = 1; s <= n; ++s) radii.emplace_back(scale * (n + 1 - s), scale * (n + 1 - s));
  return radii;
}

TEST(DilataMappa, LayerRadiiAsPrintedAndForAMargin) {
  // Algorithm 1 as printed: r s / n.
  EXPECT_EQ(printed_layer_radii(4, 8.0, 4.0), (std::vector<cv::Size>{{2, 1}, {4, 2}, {6, 3}, {8, 4}}));
  // A 0.45 m margin over 9 layers of 10 m on a 64 px, 90 deg grid (1.40625 deg/px), seen
  // from each layer's middle: layer 1 from 0.556 m: 39.0 deg = 27.7 px; layer 5 from
  // 5.0 m: 5.14 deg = 3.66 px; layer 9 from 9.44 m: 2.73 deg = 1.94 px.
  // seen from each layer's nearest depth and rounded up: layer 1 from 0 m: 90 deg, the
  // whole 64 px; layer 5 from 4.44 m: 5.78 deg = 4.11 px -> 5; layer 9 from 8.89 m: 2.90 deg = 2.06 px -> 3.
  const std::vector<cv::Size> margin = margin_layer_radii(9, 0.45, grid64());
  ASSERT_EQ(margin.size(), 9u);
  EXPECT_EQ(margin[0], cv::Size(64, 64));
  EXPECT_EQ(margin[4], cv::Size(5, 5));
  EXPECT_EQ(margin[8], cv::Size(3, 3));
  for (std::size_t s = 1; s < margin.size(); ++s) EXPECT_LE(margin[s].width, margin[s - 1].width);
}

TEST(DilataMappa, MarginRadiusCoversTheMarginAndTheErrorsOfACoarsePixel) {
  // 0.5 m at 4 m on 16 px over 90 deg (5.625 deg/px): asin(0.125) = 7.181 deg =
  // 1.277 px, + 1/2 px = 1.777 -> 2 px (atan and no half pixel gave 2 as well);
  // at 8 m: asin(0.0625) = 3.583 deg = 0.637 px + 1/2 -> 2 (atan: 1).
  EXPECT_EQ(margin_radius_px(0.5, 4.0, 5.625, 16), 2);
  EXPECT_EQ(margin_radius_px(0.5, 8.0, 5.625, 16), 2);
  // 10 m: 2.866 deg = 0.509 px + 1/2 = 1.009 -> 2; 11 m: 2.605 deg = 0.463 + 1/2 -> 1.
  EXPECT_EQ(margin_radius_px(0.5, 10.0, 5.625, 16), 2);
  EXPECT_EQ(margin_radius_px(0.5, 11.0, 5.625, 16), 1);
  // Within the margin of the sensor the whole image; never beyond it.
  EXPECT_EQ(margin_radius_px(0.5, 0.4, 5.625, 16), 16);
  EXPECT_EQ(margin_radius_px(0.5, 0.5, 0.35, 256), 256);
  EXPECT_EQ(margin_radius_px(0.5, 0.6, 0.35, 256), 162);  // asin(5 / 6) = 56.44 deg = 161.3 px

  // What the radius guarantees, in one axis: an obstacle hit by the ray of
  // pixel h at depth d has its edge anywhere short of the next pixel's ray
  // (h + 1, which missed); dilating by r leaves pixel h + r + 1 free, and a
  // direction anywhere in its footprint passes at least the margin from the edge.
  for (const int n : {16, 32, 64, 256}) {
    const double deg_per_px = 90.0 / n;
    for (const double d : {0.8, 1.3, 2.0, 3.7, 5.0, 7.9, 9.99}) {
      const int r = margin_radius_px(0.5, d, deg_per_px, n);
      for (double edge = 0.0; edge < 1.0; edge += 0.125) {     // pixels beyond h's centre
        for (double in = -0.5; in <= 0.5; in += 0.125) {        // within the free pixel's footprint
          const double angle = ((r + 1 + in) - edge) * deg_per_px * M_PI / 180.0;
          const double passes = d * std::sin(std::min(angle, M_PI / 2));
          EXPECT_GE(passes, 0.5 - 1e-9) << n << " px, " << d << " m, edge " << edge << ", at " << in;
        }
      }
    }
  }
}

TEST(DilataMappa, MarginLayersCutWhereTheRoundedRadiusSteps) {
  // 0.55 m on a 32 px, 90 deg, 10 m grid (2.8125 deg/px): the radius is
  // ceil(asin(0.55 / d) / 2.8125 deg + 1/2): at most 2 px from d =
  // 0.55 / sin(1.5 px = 4.21875 deg) = 7.477 m, at most 3 px from
  // 0.55 / sin(2.5 px = 7.03125 deg) = 4.493 m.
  const DepthGrid grid{32, 32, 90.0, 90.0, 10.0};
  const DilationParams p = margin_layers(0.55, grid);
  ASSERT_EQ(p.layer_upper.size(), p.layer_radius_px.size());
  ASSERT_GE(p.layer_radius_px.size(), 3u);
  const std::size_t n = p.layer_radius_px.size();
  EXPECT_EQ(p.layer_radius_px[n - 1], cv::Size(2, 2));
  EXPECT_DOUBLE_EQ(p.layer_upper[n - 1], 1.0);
  EXPECT_EQ(p.layer_radius_px[n - 2], cv::Size(3, 3));
  EXPECT_NEAR(p.layer_upper[n - 2], 0.7477, 1e-4);
  EXPECT_NEAR(p.layer_upper[n - 3], 0.4493, 1e-4);
  EXPECT_EQ(p.layer_radius_px.front(), cv::Size(32, 32));  // nearer than any cut: the whole image
}

TEST(DilataMappa, MarginLayersGrowEveryObstaclePixelByTheMarginAtItsOwnDepth) {
  // Reference: every obstacle pixel at depth d covers the square of radius
  // ceil(asin(margin / d) / deg_per_px + 1/2) pixels around it; the nearest value wins.
  const DepthGrid grid{48, 48, 90.0, 90.0, 10.0};
  const double margin = 0.55;
  Rng rng(7);
  cv::Mat depth = free_map(48);
  for (int k = 0; k < 40; ++k) {
    depth.at<float>(static_cast<int>(rng.uniform_int(0, 47)), static_cast<int>(rng.uniform_int(0, 47))) =
        static_cast<float>(rng.uniform(0.03, 0.99));
  }
  cv::Mat expected = free_map(48);
  for (int qy = 0; qy < 48; ++qy) {
    for (int qx = 0; qx < 48; ++qx) {
      const float v = depth.at<float>(qy, qx);
      if (v >= 1.0f) continue;
      const double d = v * grid.max_range_m;
      const double deg = d > margin ? std::asin(margin / d) * 180.0 / M_PI : 90.0;
      const int r = std::min(48, static_cast<int>(std::ceil(deg / grid.deg_per_col() + 0.5 - 1e-9)));
      for (int y = std::max(0, qy - r); y <= std::min(47, qy + r); ++y) {
        for (int x = std::max(0, qx - r); x <= std::min(47, qx + r); ++x) {
          expected.at<float>(y, x) = std::min(expected.at<float>(y, x), v);
        }
      }
    }
  }
  const cv::Mat out = dilate_depth_map(depth, margin_layers(margin, grid));
  EXPECT_EQ(cv::countNonZero(out != expected), 0);
}

TEST(DilataMappa, ASingleObstacleLayerDilatesByExactlyItsRadius) {
  for (const StructuringShape shape : {StructuringShape::square, StructuringShape::disc}) {
    cv::Mat depth = free_map(41);
    depth.at<float>(20, 20) = 0.95f;  // layer 9 of 9
    DilationParams p;
    p.layer_radius_px = std::vector<cv::Size>(9, cv::Size(4, 4));
    p.shape = shape;
    const cv::Mat out = dilate_depth_map(depth, p);
    for (int y = 0; y < 41; ++y) {
      for (int x = 0; x < 41; ++x) {
        const int dx = x - 20, dy = y - 20;
        const bool covered = shape == StructuringShape::square ? std::max(std::abs(dx), std::abs(dy)) <= 4
                                                               : dx * dx + dy * dy <= 16;
        EXPECT_EQ(out.at<float>(y, x), covered ? 0.95f : 1.0f) << "shape " << static_cast<int>(shape) << " at " << x << "," << y;
      }
    }
  }
}

TEST(DilataMappa, NearerLayersOverwriteFartherOnes) {
  cv::Mat depth = free_map(40);
  // A far obstacle (layer 8 of 9) and, beside it, a near one (layer 2).
  depth(cv::Rect(10, 10, 6, 6)).setTo(0.85f);
  depth.at<float>(12, 18) = 0.15f;
  DilationParams p;
  p.layer_radius_px = descending_radii(9, 1);  // layer 2: 8 px, layer 8: 2 px
  const cv::Mat out = dilate_depth_map(depth, p);
  // The near obstacle's element covers part of the far obstacle: nearer wins there.
  EXPECT_EQ(out.at<float>(12, 12), 0.15f);
  EXPECT_EQ(out.at<float>(4, 18), 0.15f);   // 8 px above the near pixel
  EXPECT_EQ(out.at<float>(3, 18), 1.0f);    // 9 px: outside
  // Far pixels outside the near element keep the far value; the far element reaches 2 px.
  EXPECT_EQ(out.at<float>(17, 8), 0.85f);
  EXPECT_EQ(out.at<float>(17, 7), 1.0f);
  EXPECT_EQ(out.at<float>(18, 8), 1.0f);
  // The far layer never overwrites the near obstacle itself.
  EXPECT_EQ(out.at<float>(12, 18), 0.15f);
}

TEST(DilataMappa, InsideALayerTheNearestValueWinsAndZerosAreTheNearestLayer) {
  cv::Mat depth = free_map(21);
  depth.at<float>(10, 8) = 0.95f;
  depth.at<float>(10, 12) = 0.92f;
  depth.at<float>(2, 2) = 0.0f;  // nearer than the sensor's minimum range
  DilationParams p;
  p.layer_radius_px = descending_radii(9, 3);  // layer 9: 3 px; layer 1: 27 px
  const cv::Mat out = dilate_depth_map(depth, p);
  EXPECT_EQ(out.at<float>(20, 20), 0.0f);  // the zero covers everything within 27 px
  cv::Mat far_only = free_map(21);
  far_only.at<float>(10, 8) = 0.95f;
  far_only.at<float>(10, 12) = 0.92f;
  const cv::Mat far = dilate_depth_map(far_only, p);
  EXPECT_EQ(far.at<float>(10, 10), 0.92f);  // covered by both: the nearer value
  EXPECT_EQ(far.at<float>(10, 6), 0.95f);
  EXPECT_EQ(far.at<float>(10, 4), 1.0f);
}

TEST(DilataMappa, MatchesTheDefinitionOnRandomMaps) {
  Rng rng(42);
  for (int trial = 0; trial < 12; ++trial) {
    cv::Mat depth = free_map(48);
    for (int i = 0; i < 40; ++i) {
      const int x = static_cast<int>(rng.uniform(0.0, 48.0));
      const int y = static_cast<int>(rng.uniform(0.0, 48.0));
      depth.at<float>(y, x) = static_cast<float>(rng.uniform(0.0, 0.999));
    }
    DilationParams p;
    for (int s = 0; s <= trial; ++s) {
      p.layer_radius_px.emplace_back(static_cast<int>(rng.uniform_int(0, 9)), static_cast<int>(rng.uniform_int(0, 6)));
    }
    p.shape = trial % 2 ? StructuringShape::disc : StructuringShape::square;
    if (trial % 4 == 0) {
      // Radii shrinking with depth: the square's shared erosion chain.
      std::sort(p.layer_radius_px.begin(), p.layer_radius_px.end(),
                [](const cv::Size& a, const cv::Size& b) { return a.width > b.width; });
      for (std::size_t s = 1; s < p.layer_radius_px.size(); ++s) {
        p.layer_radius_px[s].height = std::min(p.layer_radius_px[s].height, p.layer_radius_px[s - 1].height);
      }
    }
    const cv::Mat fast = dilate_depth_map(depth, p);
    const cv::Mat reference = brute_force_dilation(depth, p);
    EXPECT_EQ(cv::countNonZero(fast != reference), 0) << "trial " << trial;
  }
}

// The layer of a value as DilataMappa defines it: the first whose upper bound
// is at least the value (equal layers s / n when there are no bounds); 0 for
// no return.
int layer_of(float v, const DilationParams& p) {
  const int n = static_cast<int>(p.layer_radius_px.size());
  if (v >= 1.0f) return 0;
  if (p.layer_upper.empty()) return std::clamp(static_cast<int>(std::ceil(v * n)), 1, n);
  const auto it = std::lower_bound(p.layer_upper.begin(), p.layer_upper.end(), static_cast<double>(v));
  return std::clamp(static_cast<int>(it - p.layer_upper.begin()) + 1, 1, n);
}

// Reference DilataMappa one radius at a time: each layer's pixels alone,
// eroded (minimum) with its own rectangle by OpenCV, nothing beyond the
// border; the minimum over the layers (nearer overwrites farther).
cv::Mat per_layer_dilation(const cv::Mat& depth, const DilationParams& p) {
  constexpr float kNone = std::numeric_limits<float>::max();
  const int n = static_cast<int>(p.layer_radius_px.size());
  cv::Mat out(depth.size(), CV_32F, cv::Scalar(kNone));
  for (int s = 1; s <= n; ++s) {
    cv::Mat layer(depth.size(), CV_32F, cv::Scalar(kNone));
    cv::Rect box;  // of the layer's pixels
    for (int y = 0; y < depth.rows; ++y) {
      for (int x = 0; x < depth.cols; ++x) {
        const float v = depth.at<float>(y, x);
        if (layer_of(v, p) != s) continue;
        layer.at<float>(y, x) = v;
        box |= cv::Rect(x, y, 1, 1);
      }
    }
    if (box.empty()) continue;
    // Only where the layer's elements reach (the same erosion, less work).
    const cv::Size r = p.layer_radius_px[s - 1];
    const cv::Rect reach =
        cv::Rect(box.x - r.width, box.y - r.height, box.width + 2 * r.width, box.height + 2 * r.height) &
        cv::Rect(0, 0, depth.cols, depth.rows);
    cv::Mat eroded;
    cv::erode(layer(reach), eroded, cv::getStructuringElement(cv::MORPH_RECT, {2 * r.width + 1, 2 * r.height + 1}),
              cv::Point(-1, -1), 1, cv::BORDER_CONSTANT, cv::Scalar(kNone));
    cv::Mat target = out(reach);
    cv::min(target, eroded, target);
  }
  cv::min(out, 1.0, out);
  return out;
}

// Random depth maps of the kinds a scan gives: ground rising toward the
// horizon, boxes (walls, trunks) at one depth, scattered single pixels, no
// return above, values just either side of the layers' bounds, and zeros
// (nearer than the minimum range).
cv::Mat random_scene_map(Rng& rng, int size, const DilationParams& p) {
  cv::Mat depth = free_map(size);
  const int horizon = static_cast<int>(rng.uniform_int(size / 4, size - 1));
  const double near = rng.uniform(0.02, 0.3);
  for (int y = horizon; y < size; ++y) {
    const double t = static_cast<double>(size - y) / std::max(1, size - horizon);
    for (int x = 0; x < size; ++x) {
      depth.at<float>(y, x) = static_cast<float>(std::min(0.999, near + (1.0 - near) * t * t + rng.uniform(0.0, 0.01)));
    }
  }
  const int boxes = static_cast<int>(rng.uniform_int(0, 12));
  for (int b = 0; b < boxes; ++b) {
    const int w = static_cast<int>(rng.uniform_int(1, size / 3));
    const int h = static_cast<int>(rng.uniform_int(1, size));
    const int x = static_cast<int>(rng.uniform_int(0, size - w));
    const int y = static_cast<int>(rng.uniform_int(0, size - h));
    depth(cv::Rect(x, y, w, h)).setTo(static_cast<float>(rng.uniform(0.05, 0.99)));
  }
  for (int i = 0; i < size; ++i) {
    const int x = static_cast<int>(rng.uniform_int(0, size - 1));
    const int y = static_cast<int>(rng.uniform_int(0, size - 1));
    float v = static_cast<float>(rng.uniform(0.0, 0.999));
    if (!p.layer_upper.empty() && rng.bernoulli(0.5)) {
      const float cut = static_cast<float>(p.layer_upper[static_cast<std::size_t>(
          rng.uniform_int(0, static_cast<std::int64_t>(p.layer_upper.size()) - 1))]);
      v = rng.bernoulli(0.5) ? cut : std::nextafter(cut, rng.bernoulli(0.5) ? 0.0f : 1.0f);
    } else if (rng.bernoulli(0.05)) {
      v = 0.0f;
    }
    if (v < 1.0f) depth.at<float>(y, x) = v;
  }
  return depth;
}

TEST(DilataMappa, MarginLayersEqualOneErosionPerRadiusOnRandomMaps) {
  // The dilation the planner runs (a chain of rectangle erosions, nearest
  // layer first, each layer joining with the steps still to come) against one OpenCV erosion per
  // layer: equal value for value, at the grids the planner flies at, the
  // square default and a wider field across than down (different radii).
  Rng rng(2026);
  for (const DepthGrid& grid : {DepthGrid{64, 64, 90.0, 90.0, 10.0}, DepthGrid{128, 128, 90.0, 90.0, 10.0},
                                DepthGrid{96, 96, 120.0, 60.0, 12.0}}) {
    for (const double margin : {0.5, 0.25, 1.0}) {
      const DilationParams p = margin_layers(margin, grid);
      ASSERT_GT(p.layer_radius_px.size(), 10u);
      for (int trial = 0; trial < 4; ++trial) {
        const cv::Mat depth = random_scene_map(rng, grid.cols, p);
        const cv::Mat fast = dilate_depth_map(depth, p);
        const cv::Mat reference = per_layer_dilation(depth, p);
        EXPECT_EQ(cv::countNonZero(fast != reference), 0)
            << grid.cols << " px, margin " << margin << ", trial " << trial;
      }
    }
  }
}

TEST(DilataMappa, SeparableDilationEqualsTheDefinitionForAnyShrinkingRadii) {
  // Radii that shrink with depth, drawn at random (equal steps, flat runs,
  // different across and down, beyond the image), on small maps of every
  // density: the chain of rectangle erosions against the definition.
  Rng rng(99);
  for (int trial = 0; trial < 200; ++trial) {
    const int size = static_cast<int>(rng.uniform_int(1, 24));
    const int n = static_cast<int>(rng.uniform_int(1, 12));
    DilationParams p;
    std::vector<int> across, down;
    for (int s = 0; s < n; ++s) {
      across.push_back(static_cast<int>(rng.uniform_int(0, 30)));
      down.push_back(static_cast<int>(rng.uniform_int(0, 30)));
    }
    std::sort(across.rbegin(), across.rend());
    std::sort(down.rbegin(), down.rend());
    for (int s = 0; s < n; ++s) p.layer_radius_px.emplace_back(across[s], down[s]);
    if (trial % 2) {
      for (int s = 1; s <= n; ++s) p.layer_upper.push_back(s == n ? 1.0 : std::pow(static_cast<double>(s) / n, 1.7));
    }
    const double density = rng.uniform01();
    cv::Mat depth = free_map(size);
    for (int y = 0; y < size; ++y) {
      for (int x = 0; x < size; ++x) {
        if (rng.bernoulli(density)) depth.at<float>(y, x) = static_cast<float>(rng.uniform(0.0, 0.999));
      }
    }
    const cv::Mat fast = dilate_depth_map(depth, p);
    EXPECT_EQ(cv::countNonZero(fast != per_layer_dilation(depth, p)), 0) << "trial " << trial;
    if (p.layer_upper.empty()) EXPECT_EQ(cv::countNonZero(fast != brute_force_dilation(depth, p)), 0) << "trial " << trial;
  }
}

TEST(DilataMappa, StartViewsOfTheSeed000ScenesEqualOneErosionPerRadius) {
  // The depth maps the planner reads first on the two seed 000 scenes, at
  // 256 x 256 (the benchmark's): the same map as one erosion per layer.
  for (const std::string name : {"two_barriers", "trees_rolling_terrain"}) {
    const Scene scene = load_scene(std::string(CAMPO_SOURCE_DIR) + "/scenes/" + name + ".json");
    const VehicleDef& drone = scene.vehicles.front();
    RangeSensorConfig config = drone.sensors.front().range;
    config.cols = config.rows = 256;
    const RayCaster caster(scene);
    Lidar lidar(config, scene.world.seed);
    RangeScan scan;
    lidar.scan(caster, drone.pose * to_isometry(config.mount), 0.0, scan);
    const DepthGrid grid = DepthGrid::of(scan, config);
    const cv::Mat depth = depth_map(scan, config);
    const DilationParams p = margin_layers(0.5, grid);
    const cv::Mat fast = dilate_depth_map(depth, p);
    EXPECT_EQ(cv::countNonZero(fast != per_layer_dilation(depth, p)), 0) << name;
    EXPECT_LT(cv::countNonZero(fast < 1.0f), static_cast<int>(fast.total())) << name << ": some free space";
  }
}

TEST(DilataMappa, ErodeRectEqualsOpenCvErosion) {
  // erode_rect (vector minima: steps of 1, or blocks of 2 r + 1 for larger
  // radii) against cv::erode with a constant border above every value, on
  // random images of every shape from 1 x 1, radii from 0 to beyond the image,
  // values with many ties and empty pixels.
  Rng rng(7);
  constexpr float kAbove = std::numeric_limits<float>::max();
  for (int trial = 0; trial < 300; ++trial) {
    const bool large = trial < 6;
    const int rows = large ? 256 : static_cast<int>(rng.uniform_int(1, 40));
    const int cols = large ? 256 : static_cast<int>(rng.uniform_int(1, 40));
    const int rx = static_cast<int>(rng.uniform_int(0, large ? 300 : 45));
    const int ry = static_cast<int>(rng.uniform_int(0, large ? 300 : 45));
    cv::Mat image(rows, cols, CV_32F);
    for (int y = 0; y < rows; ++y) {
      for (int x = 0; x < cols; ++x) {
        image.at<float>(y, x) =
            rng.bernoulli(0.3) ? kAbove : static_cast<float>(rng.uniform_int(0, 20)) / 20.0f;
      }
    }
    cv::Mat reference;
    cv::erode(image, reference, cv::getStructuringElement(cv::MORPH_RECT, {2 * rx + 1, 2 * ry + 1}),
              cv::Point(-1, -1), 1, cv::BORDER_CONSTANT, cv::Scalar(kAbove));
    std::vector<float> flat(image.begin<float>(), image.end<float>());
    erode_rect(flat, rows, cols, rx, ry);
    const cv::Mat fast(rows, cols, CV_32F, flat.data());
    EXPECT_EQ(cv::countNonZero(fast != reference), 0) << rows << " x " << cols << ", radii " << rx << ", " << ry;

    // Only a box holds values: the same result, computed in the grown box,
    // with the scratch (garbage inside the box) and the image empty beyond it.
    const int bx = static_cast<int>(rng.uniform_int(0, cols - 1));
    const int by = static_cast<int>(rng.uniform_int(0, rows - 1));
    const cv::Rect box(bx, by, static_cast<int>(rng.uniform_int(1, cols - bx)),
                       static_cast<int>(rng.uniform_int(1, rows - by)));
    cv::Mat boxed(rows, cols, CV_32F, cv::Scalar(kAbove));
    image(box).copyTo(boxed(box));
    cv::erode(boxed, reference, cv::getStructuringElement(cv::MORPH_RECT, {2 * rx + 1, 2 * ry + 1}),
              cv::Point(-1, -1), 1, cv::BORDER_CONSTANT, cv::Scalar(kAbove));
    std::vector<float> in_box(boxed.begin<float>(), boxed.end<float>());
    std::vector<float> scratch(in_box.size(), kAbove);
    for (int y = box.y; y < box.y + box.height; ++y) {
      for (int x = box.x; x < box.x + box.width; ++x) scratch[static_cast<std::size_t>(y) * cols + x] = -1.0f;
    }
    const cv::Rect grown = erode_rect(in_box, scratch, rows, cols, box, rx, ry);
    EXPECT_EQ(cv::countNonZero(cv::Mat(rows, cols, CV_32F, in_box.data()) != reference), 0)
        << rows << " x " << cols << ", box " << box << ", radii " << rx << ", " << ry;
    for (int y = 0; y < rows; ++y) {
      for (int x = 0; x < cols; ++x) {
        if (grown.contains({x, y})) continue;
        ASSERT_EQ(in_box[static_cast<std::size_t>(y) * cols + x], kAbove);
        ASSERT_EQ(scratch[static_cast<std::size_t>(y) * cols + x], kAbove);
      }
    }
  }
}

TEST(DilataMappa, TheThreeByThreeStepInPlaceIsTheErosion) {
  // The chain's usual step (radius 1 both ways) runs in one pass, in place,
  // through a ring of row minima: against cv::erode on random boxes of random
  // images, including one-pixel-wide and one-pixel-high images and boxes at
  // every side.
  Rng rng(11);
  constexpr float kAbove = std::numeric_limits<float>::max();
  for (int trial = 0; trial < 400; ++trial) {
    const int rows = trial < 4 ? 256 : static_cast<int>(rng.uniform_int(1, 30));
    const int cols = trial < 4 ? 256 : static_cast<int>(rng.uniform_int(1, 30));
    const int bx = static_cast<int>(rng.uniform_int(0, cols - 1));
    const int by = static_cast<int>(rng.uniform_int(0, rows - 1));
    const cv::Rect box(bx, by, static_cast<int>(rng.uniform_int(1, cols - bx)),
                       static_cast<int>(rng.uniform_int(1, rows - by)));
    cv::Mat boxed(rows, cols, CV_32F, cv::Scalar(kAbove));
    for (int y = box.y; y < box.y + box.height; ++y) {
      for (int x = box.x; x < box.x + box.width; ++x) {
        boxed.at<float>(y, x) = rng.bernoulli(0.2) ? kAbove : static_cast<float>(rng.uniform_int(0, 30)) / 30.0f;
      }
    }
    cv::Mat reference;
    cv::erode(boxed, reference, cv::getStructuringElement(cv::MORPH_RECT, {3, 3}), cv::Point(-1, -1), 1,
              cv::BORDER_CONSTANT, cv::Scalar(kAbove));
    std::vector<float> image(boxed.begin<float>(), boxed.end<float>());
    std::vector<float> scratch(image.size(), kAbove);
    const cv::Rect grown = erode_rect(image, scratch, rows, cols, box, 1, 1);
    EXPECT_EQ(cv::countNonZero(cv::Mat(rows, cols, CV_32F, image.data()) != reference), 0)
        << rows << " x " << cols << ", box " << box;
    EXPECT_EQ(grown, cv::Rect(box.x - 1, box.y - 1, box.width + 2, box.height + 2) & cv::Rect(0, 0, cols, rows));
    // Twice more, as the chain runs it: each step on the last one's box.
    cv::Rect again = grown;
    for (int k = 0; k < 2; ++k) {
      cv::erode(reference, reference, cv::getStructuringElement(cv::MORPH_RECT, {3, 3}), cv::Point(-1, -1), 1,
                cv::BORDER_CONSTANT, cv::Scalar(kAbove));
      again = erode_rect(image, scratch, rows, cols, again, 1, 1);
    }
    EXPECT_EQ(cv::countNonZero(cv::Mat(rows, cols, CV_32F, image.data()) != reference), 0)
        << rows << " x " << cols << ", box " << box << ", three steps";
  }
}

TEST(DilataMappa, NoReturnIsFreeSpace) {
  const cv::Mat out = dilate_depth_map(free_map(16), DilationParams{StructuringShape::square, descending_radii(9, 2)});
  EXPECT_EQ(cv::countNonZero(out != 1.0f), 0);
}

TEST(ControllaVisibilita, ClassifiesEachOutcome) {
  const DepthGrid grid = grid64();
  const Eigen::Vector3d ahead(5.0, 0.0, 0.0);
  const double r = 0.5;
  const auto classify = [&](const cv::Mat& map, const Eigen::Vector3d& w) { return check_visibility(map, grid, w, r); };

  EXPECT_EQ(classify(free_map(64), ahead).visibility, Visibility::visible);             // m = d_max
  EXPECT_EQ(classify(cv::Mat(64, 64, CV_32F, cv::Scalar(0.8f)), ahead).visibility, Visibility::visible);  // 8 - 5 > r
  const VisibilityCheck blocked = classify(cv::Mat(64, 64, CV_32F, cv::Scalar(0.3f)), ahead);
  EXPECT_EQ(blocked.visibility, Visibility::invisible);                                 // 5 - 3 > r
  EXPECT_NEAR(blocked.obstacle_range_m, 3.0, 1e-6);
  EXPECT_NEAR(blocked.waypoint_range_m, 5.0, 1e-12);
  EXPECT_EQ(classify(cv::Mat(64, 64, CV_32F, cv::Scalar(0.52f)), ahead).visibility, Visibility::unreachable);
  EXPECT_EQ(classify(cv::Mat(64, 64, CV_32F, cv::Scalar(0.46f)), ahead).visibility, Visibility::unreachable);

  // The neighbourhood is the projected safety sphere: asin(0.5 / 5) = 5.74 deg = 4.08 px.
  const VisibilityCheck c = classify(free_map(64), ahead);
  EXPECT_NEAR(c.radius_x_px, std::asin(0.1) * 180.0 / M_PI / (90.0 / 64), 1e-9);
  EXPECT_NEAR(c.pixel.x(), 31.5, 1e-9);
  cv::Mat post = free_map(64);
  post.col(37).setTo(0.2f);  // 5.5 px right of W': outside the neighbourhood
  EXPECT_EQ(classify(post, ahead).visibility, Visibility::visible);
  // Widened by 1.5 px (4.08 + 1.5 = 5.58 px > 5.5 px) the post at column 37 is inside.
  EXPECT_NEAR(check_visibility(post, grid, ahead, r, 1.5).radius_x_px, c.radius_x_px + 1.5, 1e-9);
  EXPECT_EQ(check_visibility(post, grid, ahead, r, 1.5).visibility, Visibility::invisible);
  post.col(35).setTo(0.2f);  // 3.5 px: inside
  EXPECT_EQ(classify(post, ahead).visibility, Visibility::invisible);

  // Behind the sensor: out of view.
  const VisibilityCheck behind = classify(free_map(64), {-5.0, 0.0, 0.0});
  EXPECT_EQ(behind.visibility, Visibility::invisible);
  EXPECT_FALSE(behind.in_view);
  // Within the safety radius: the vehicle is there.
  EXPECT_EQ(classify(cv::Mat(64, 64, CV_32F, cv::Scalar(0.01f)), {0.3, 0.0, 0.0}).visibility, Visibility::visible);
}

TEST(ControllaVisibilita, TheMarginBeyondTheWaypointAndEveryPixelTheNeighbourhoodTouches) {
  const DepthGrid grid = grid64();
  const Eigen::Vector3d ahead(5.0, 0.0, 0.0);
  // A wall 5.6 m away behind a waypoint at 5 m: 0.6 m beyond it, more than
  // r = 0.5 (Algorithm 2: visible), less than r + a 0.5 m margin (unreachable).
  const cv::Mat wall(64, 64, CV_32F, cv::Scalar(0.56f));
  EXPECT_EQ(check_visibility(wall, grid, ahead, 0.5).visibility, Visibility::visible);
  EXPECT_EQ(check_visibility(wall, grid, ahead, 0.5, 0.0, 0.5).visibility, Visibility::unreachable);
  // 1.1 m beyond: visible with the margin too.
  EXPECT_EQ(check_visibility(cv::Mat(64, 64, CV_32F, cv::Scalar(0.61f)), grid, ahead, 0.5, 0.0, 0.5).visibility,
            Visibility::visible);
  // A neighbourhood narrowed to nothing reads the pixels whose footprint
  // holds W': straight ahead is 31.5, the border of columns 31 and 32, so both.
  for (const int col : {31, 32}) {
    cv::Mat post = free_map(64);
    post.col(col).setTo(0.2f);
    EXPECT_EQ(check_visibility(post, grid, ahead, 0.5, -10.0).visibility, Visibility::invisible) << col;
  }
  cv::Mat beside = free_map(64);
  beside.col(33).setTo(0.2f);  // a pixel and a half away: not touched
  EXPECT_EQ(check_visibility(beside, grid, ahead, 0.5, -10.0).visibility, Visibility::visible);
}

TEST(SegmentClear, KeepsTheMarginAcrossAndTowardTheSensor) {
  // 64 px over 90 deg, 10 m. A post 4 m ahead, 1 m to the left, 0.3 m wide
  // (y 0.85..1.15), dilated by 0.5 m at its depth.
  const DepthGrid grid = grid64();
  cv::Mat depth = free_map(64);
  for (int col = 0; col < 64; ++col) {
    const Eigen::Vector3d d = grid.direction({col, 31.5});
    const double y = 4.0 * d.y() / d.x();
    if (y > 0.85 && y < 1.15) depth.col(col).setTo(0.4f);
  }
  const cv::Mat dilated = dilate_depth_map(depth, margin_layers(0.5, grid));
  const double margin = 0.5;
  // Straight ahead to 8 m: 0.85 m from the post, clear.
  EXPECT_TRUE(segment_clear(dilated, grid, {0, 0, 0}, {8, 0, 0}, margin, 0.0));
  // The post's last column hit is 22 (its ray meets x = 4 at y = 0.95; column
  // 23's at 0.847 misses), dilated by ceil(asin(0.5 / 4) / 1.40625 + 1/2) = 6
  // to column 28. Toward (6, 0.4): azimuth 3.81 deg, column 28.79, whose
  // footprint lies in column 29: clear, and truly 4.09 sin(11.99 - 3.81 deg)
  // = 0.58 m from the post's edge. Toward (6, 0.9): column 25.4, blocked,
  // truly 0.25 m from it.
  EXPECT_TRUE(segment_clear(dilated, grid, {0, 0, 0}, {6, 0.4, 0}, margin, 0.0));
  EXPECT_FALSE(segment_clear(dilated, grid, {0, 0, 0}, {6, 0.9, 0}, margin, 0.0));
  // To a point 3.3 m ahead, right in front of the post and 0.7 m from it
  // toward the sensor: clear with a 0.5 m margin, not with 0.8 m.
  const Eigen::Vector3d before(3.3, 1.0 * 3.3 / 4.0, 0.0);
  EXPECT_TRUE(segment_clear(dilated, grid, {0, 0, 0}, before * (3.3 / before.norm()), margin, 0.0));
  EXPECT_FALSE(segment_clear(dilated, grid, {0, 0, 0}, before * (3.3 / before.norm()), 0.8, 0.0));
  // Beyond the post along its line of sight: behind it.
  EXPECT_FALSE(segment_clear(dilated, grid, {0, 0, 0}, {6.0, 1.5, 0.0}, margin, 0.0));
  // The whole segment is judged, not only its ends: both ends clear, the middle through the post.
  EXPECT_FALSE(segment_clear(dilated, grid, {4.0, -0.5, 0.0}, {4.0, 2.5, 0.0}, margin, 0.0));
  // Out of view (behind the sensor) is not clear; nearer than min_range it is not judged.
  EXPECT_FALSE(segment_clear(dilated, grid, {0, 0, 0}, {-2, 0, 0}, margin, 0.0));
  EXPECT_TRUE(segment_clear(dilated, grid, {-0.3, 0, 0}, {2, 0, 0}, margin, 0.5));
}

TEST(SegmentClear, TheBlindStartOfALeg) {
  // 0.5 m, a 90 deg field of view (45 deg either side), the sensor 0.15 m
  // ahead of the centre: 0.15 + 0.5 / sin(45 deg) = 0.857 m.
  EXPECT_NEAR(blind_leg_m(0.5, 45.0, 0.15), 0.15 + 0.5 * std::sqrt(2.0), 1e-12);
  // Brute force: the centre at the origin facing +x, the sensor at x = 0.15.
  // Every point out of view (more than 45 deg off the axis as seen from the
  // sensor) that lies within 0.5 m of the leg does so before 0.857 m along it.
  const double blind = blind_leg_m(0.5, 45.0, 0.15);
  double last = 0.0;
  for (double x = -1.0; x <= 2.0; x += 0.01) {
    for (double y = 0.0; y <= 0.6; y += 0.01) {
      const double off_axis = std::atan2(y, x - 0.15);
      if (off_axis <= M_PI / 4) continue;  // in view
      if (y >= 0.5) continue;              // farther than the margin from the leg (the x axis)
      // Leg points within the margin of (x, y): s in x +- sqrt(0.25 - y^2).
      last = std::max(last, x + std::sqrt(0.25 - y * y));
    }
  }
  EXPECT_LE(last, blind + 1e-9);
  EXPECT_GT(last, blind - 0.02);  // and the bound is tight
}

TEST(TrovaWP, PicksThePixelBesideTheBarrierNearestTheTarget) {
  const DepthGrid grid = grid64();
  // A barrier 4 m ahead over columns 0..40, free to the right of it.
  cv::Mat depth = free_map(64);
  depth(cv::Rect(0, 0, 41, 64)).setTo(0.4f);
  DilationParams dp;
  dp.layer_radius_px = std::vector<cv::Size>(10, cv::Size(7, 7));
  const cv::Mat dilated = dilate_depth_map(depth, dp);
  ASSERT_EQ(dilated.at<float>(31, 47), 0.4f);
  ASSERT_EQ(dilated.at<float>(31, 48), 1.0f);

  FindWaypointParams p;
  const Eigen::Vector2d target(31.5, 31.5);  // 8 m straight ahead
  const WaypointSearch s = find_waypoint(dilated, grid, target, 0.8, 0.4, p);
  EXPECT_NEAR(s.threshold, 0.6, 1e-12);
  EXPECT_EQ(s.candidates, 64);  // column 48, every row
  ASSERT_TRUE(s.found);
  // Rows 31 and 32 cost the same; the upper row comes first.
  EXPECT_EQ(s.found->pixel, Eigen::Vector2i(48, 31));
  EXPECT_EQ(s.found->edge_pixel, Eigen::Vector2i(47, 31));
  EXPECT_NEAR(s.found->edge_range_m, 4.0, 1e-6);
  // Edge + vehicle radius.
  EXPECT_NEAR(s.found->range_m, 4.0 + p.vehicle_radius_m, 1e-6);
  // The sphere of 0.5 m at 4.45 m projects to 4.59 px (+1.5 px margin): the
  // waypoint's pixel moves right from P until the dilated barrier (up to
  // column 47) is outside it: 54 - 47 = 7 > 6.09.
  EXPECT_EQ(s.found->waypoint_pixel, Eigen::Vector2i(54, 31));
  EXPECT_LT((s.found->direction_sensor - grid.direction({54, 31})).norm(), 1e-12);
  // So the new waypoint passes ControllaVisibilita on the same map.
  EXPECT_EQ(check_visibility(dilated, grid, s.found->direction_sensor * s.found->range_m, p.safety_radius_m).visibility,
            Visibility::visible);
  EXPECT_EQ(s.found->tried, 1);
}

TEST(TrovaWP, TheNextLegAndTheCorridorKeepTheMargin) {
  // A barrier 4 m ahead over columns 0..40 of 64 (its right end at y = -0.9),
  // the target 8 m ahead and 3 m to the left, behind it. Beside the barrier's
  // end the new waypoint is 4.45 m away; from there the leg toward the target
  // turns left behind the barrier, into what the sensor cannot see.
  const DepthGrid grid = grid64();
  cv::Mat depth = free_map(64);
  depth(cv::Rect(0, 0, 41, 64)).setTo(0.4f);
  const cv::Mat dilated = dilate_depth_map(depth, margin_layers(0.5, grid));
  const Eigen::Vector3d target(8.0, 3.0, 0.0);
  const Eigen::Vector2d target_pixel = grid.project(target);
  FindWaypointParams p;
  p.safety_radius_m = 0.25;
  p.depth_margin_m = 0.5;
  const auto leg_start_clear = [&](const FoundWaypoint& f, double length) {
    const Eigen::Vector3d w = f.direction_sensor * f.range_m;
    return segment_clear(dilated, grid, w, w + (target - w).normalized() * length, 0.5, 0.5);
  };
  const WaypointSearch plain = find_waypoint(dilated, grid, target_pixel, target.norm() / 10.0, 0.4, p);
  ASSERT_TRUE(plain.found);
  const double blind = blind_leg_m(0.5, 45.0, 0.15);
  EXPECT_FALSE(leg_start_clear(*plain.found, blind)) << plain.found->waypoint_pixel.transpose();
  p.next_leg_check_m = blind;
  const WaypointSearch checked = find_waypoint(dilated, grid, target_pixel, target.norm() / 10.0, 0.4, p);
  ASSERT_TRUE(checked.found);
  EXPECT_TRUE(leg_start_clear(*checked.found, blind));
  // The pixels beside the barrier's end all lead into it: rejected, the
  // waypoint is one of a later candidate (over the barrier's end).
  EXPECT_EQ(plain.found->tried, 1);
  EXPECT_GT(checked.found->tried, 1);
  // Its corridor from the vehicle keeps the margin too.
  EXPECT_TRUE(segment_clear(dilated, grid, {0, 0, 0}, checked.found->direction_sensor * checked.found->range_m, 0.5, 0.5));
}

TEST(TrovaWP, TheAltitudePenaltyTradesClimbingForGoingAround) {
  const DepthGrid grid = grid64();
  // A block 4 m ahead: columns 0..50, rows 25..63. Over it is 7 px up, around it 20 px right.
  cv::Mat depth = free_map(64);
  depth(cv::Rect(0, 25, 51, 39)).setTo(0.4f);
  const Eigen::Vector2d target(31.0, 31.0);
  FindWaypointParams p;
  p.vehicle_radius_m = 0.0;
  p.safety_radius_m = 0.01;
  p.altitude_penalty = 0.0;
  const WaypointSearch over = find_waypoint(depth, grid, target, 0.8, 0.4, p);
  ASSERT_TRUE(over.found);
  EXPECT_EQ(over.found->pixel, Eigen::Vector2i(31, 24));
  p.altitude_penalty = 2.0;  // 7 + 2 * 7 = 21 > 20
  const WaypointSearch around = find_waypoint(depth, grid, target, 0.8, 0.4, p);
  ASSERT_TRUE(around.found);
  EXPECT_EQ(around.found->pixel, Eigen::Vector2i(51, 31));
}

TEST(TrovaWP, FindsNothingWhenTheDilatedMapIsFull) {
  const cv::Mat near(64, 64, CV_32F, cv::Scalar(0.1f));
  const WaypointSearch s = find_waypoint(near, grid64(), {31.5, 31.5}, 0.8, 0.1, FindWaypointParams{});
  EXPECT_EQ(s.candidates, 0);
  EXPECT_FALSE(s.found);
}

TEST(TrovaWP, SkipsWaypointsAlreadyDiscarded) {
  const DepthGrid grid = grid64();
  cv::Mat depth = free_map(64);
  depth(cv::Rect(0, 0, 41, 64)).setTo(0.4f);
  FindWaypointParams p;
  p.vehicle_radius_m = 0.0;
  const WaypointSearch first = find_waypoint(depth, grid, {31.5, 31.5}, 0.8, 0.4, p);
  ASSERT_TRUE(first.found);
  const Eigen::Vector3d discarded = first.found->direction_sensor * first.found->range_m;
  const WaypointSearch second = find_waypoint(depth, grid, {31.5, 31.5}, 0.8, 0.4, p, {&discarded, 1});
  ASSERT_TRUE(second.found);
  EXPECT_GE((second.found->direction_sensor * second.found->range_m - discarded).norm(), p.safety_radius_m);
  EXPECT_GT(second.found->tried, 1);
}

TEST(TrovaWP, ThresholdIsCapped) {
  const WaypointSearch s = find_waypoint(free_map(8), {8, 8, 90.0, 90.0, 10.0}, {3.5, 3.5}, 2.3, 0.5,
                                         FindWaypointParams{});
  EXPECT_NEAR(s.threshold, 0.9, 1e-12);
}

// The candidates of TrovaWP are the pixels at distance 1 of the L1 distance
// transform; obstacle_border finds them without it: same pixels, same order,
// on random maps of every density (obstacles on the image's edges too), a
// map without obstacles and one without free pixels.
TEST(TrovaWP, ObstacleBorderIsDistanceOneOfTheTransform) {
  Rng rng(11);
  std::size_t total = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const int rows = 1 + static_cast<int>(rng.uniform_int(0, 40));
    // Some rows as wide as the planner's images (sixteen pixels at a time there).
    const int cols = trial % 10 == 9 ? 250 + static_cast<int>(rng.uniform_int(0, 20))
                                     : 1 + static_cast<int>(rng.uniform_int(0, 40));
    const double obstacle = trial == 0 ? 0.0 : trial == 1 ? 1.0 : rng.uniform(0.0, 1.0);
    cv::Mat free(rows, cols, CV_8U);
    for (int y = 0; y < rows; ++y) {
      for (int x = 0; x < cols; ++x) free.at<std::uint8_t>(y, x) = rng.uniform(0.0, 1.0) < obstacle ? 0 : 255;
    }
    cv::Mat distance;
    cv::distanceTransform(free, distance, cv::DIST_L1, 3, CV_8U);
    std::vector<Eigen::Vector2i> expected;
    for (int y = 0; y < rows; ++y) {
      for (int x = 0; x < cols; ++x) {
        if (distance.at<std::uint8_t>(y, x) == 1) expected.emplace_back(x, y);
      }
    }
    const std::vector<Eigen::Vector2i> border = obstacle_border(free);
    ASSERT_EQ(border.size(), expected.size()) << "trial " << trial << ", " << rows << " x " << cols;
    for (std::size_t i = 0; i < border.size(); ++i) {
      EXPECT_EQ(border[i], expected[i]) << "trial " << trial << ", pixel " << i;
    }
    total += expected.size();
  }
  EXPECT_GT(total, 1000u);  // the maps do have borders to compare
}

// segment_clear reads the map along its points through value_at_direction;
// it must read what DepthGrid::project says: the pixels whose centres lie
// within half a pixel of the projection (two or four on a boundary), none
// outside the image. Random directions in and around the field of view at
// several resolutions, and directions through pixel boundaries and corners
// (where the float shortcut must defer to project).
TEST(SegmentClear, ValueAtDirectionReadsTheProjectedPixels) {
  Rng rng(5);
  for (const int size : {16, 64, 256, 1024}) {
    DepthGrid grid;
    grid.cols = size;
    grid.rows = size * 3 / 4;
    grid.fov_h_deg = 90.0;
    grid.fov_v_deg = 60.0;
    cv::Mat image(grid.rows, grid.cols, CV_32F);
    for (int y = 0; y < grid.rows; ++y) {
      for (int x = 0; x < grid.cols; ++x) image.at<float>(y, x) = static_cast<float>(rng.uniform(0.0, 1.0));
    }
    const auto expected = [&](const Eigen::Vector3d& d) -> std::optional<float> {
      const Eigen::Vector2d c = grid.project(d);
      std::optional<float> best;
      for (int y = 0; y < grid.rows; ++y) {
        for (int x = 0; x < grid.cols; ++x) {
          if (std::abs(x - c.x()) > 0.5 || std::abs(y - c.y()) > 0.5) continue;
          best = std::min(best.value_or(2.0f), image.at<float>(y, x));
        }
      }
      return best;
    };
    for (int i = 0; i < 400; ++i) {
      Eigen::Vector2d pixel(rng.uniform(-3.0, grid.cols + 2.0), rng.uniform(-3.0, grid.rows + 2.0));
      if (i % 4 == 1) pixel.x() = std::round(pixel.x()) + 0.5;  // on a column boundary
      if (i % 4 == 2) pixel.y() = std::round(pixel.y()) + 0.5;  // on a row boundary
      if (i % 4 == 3) pixel = (pixel.array().round() + 0.5).matrix();  // on a corner
      const Eigen::Vector3d d = grid.direction(pixel) * rng.uniform(0.5, 20.0);
      EXPECT_EQ(value_at_direction(image, grid, d), expected(d)) << size << " px, direction " << d.transpose();
    }
  }
}

TEST(PixelSegment, RunsFromTheStartTowardAPointOutsideTheImage) {
  const auto pixels = pixel_segment({10, 10}, {2, 5}, {1000.0, 5.0});
  ASSERT_EQ(pixels.size(), 8u);
  EXPECT_EQ(pixels.front(), Eigen::Vector2i(2, 5));
  EXPECT_EQ(pixels.back(), Eigen::Vector2i(9, 5));
}

TEST(WallFollowing, FreeFractionOfTheNavigableSector) {
  const DepthGrid grid = grid64();
  const cv::Rect region = navigable_region(grid, 60.0, 10.0);
  // 60 of 90 deg: 42.7 columns around 31.5; +-10 deg: +-7.1 rows.
  EXPECT_EQ(region, cv::Rect(11, 25, 42, 14));
  cv::Mat map = free_map(64);
  EXPECT_DOUBLE_EQ(free_fraction(map, region, 0.5), 1.0);
  map(cv::Rect(0, 0, 32, 64)).setTo(0.2f);  // left half blocked
  EXPECT_DOUBLE_EQ(free_fraction(map, region, 0.5), 21.0 / 42.0);
}

}  // namespace
}  // namespace campo
