#include "render/depth_figure.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <stdexcept>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "render/figure_canvas.hpp"
#include "render/figure_style.hpp"
#include "tests/render/figure_test_support.hpp"

namespace campo {
namespace {

using namespace figure::test;

cv::Mat test_depth() {
  cv::Mat depth(16, 16, CV_32F);
  for (int r = 0; r < depth.rows; ++r) {
    for (int c = 0; c < depth.cols; ++c) depth.at<float>(r, c) = 0.05f + 0.05f * c;
  }
  depth.at<float>(0, 0) = 0.0f;    // below min range
  depth.at<float>(0, 15) = 1.0f;   // no return
  return depth;
}

DepthOverlays test_overlays(const cv::Mat& depth) {
  DepthOverlays o;
  cv::erode(depth, o.dilated, cv::Mat::ones(3, 3, CV_8U));
  cv::threshold(o.dilated, o.thresholded, 0.5, 255.0, cv::THRESH_BINARY);
  o.thresholded.convertTo(o.thresholded, CV_8U);
  o.chosen_pixel = cv::Point(5, 9);
  for (int c = 0; c < 16; ++c) o.scan_line.emplace_back(c, 9);
  return o;
}

bool is_ring_red(const cv::Vec3b& v) { return v[2] > 180 && v[1] < 90 && v[0] < 90; }

TEST(FiguresDepth, UpscalesEachPanelByAnIntegerFactor) {
  const cv::Mat depth = test_depth();
  const DepthOverlays overlays = test_overlays(depth);
  const DepthFigureLayout layout = depth_layout(depth, overlays, false);
  const cv::Mat image = draw_depth(depth, overlays, false, "Depth").raster();
  EXPECT_EQ(image.size(), layout.image_px);
  EXPECT_EQ(layout.scale, 16);  // 16 px -> 256 px
  ASSERT_EQ(layout.panels_px.size(), 3u);
  for (const auto& panel : layout.panels_px) EXPECT_EQ(panel.size(), cv::Size(256, 256));
  EXPECT_EQ(image.cols, kDepthGapPx + 3 * 256 + 2 * kDepthGapPx + kDepthGapPx + kDepthColorbarPx);
  // Depth-map pixel (3, 4) is a block of scale x scale figure pixels of its grey.
  const uchar grey = cv::saturate_cast<uchar>(255.0 * depth.at<float>(4, 3));
  const cv::Rect block(layout.panels_px[0].x + 3 * 16, layout.panels_px[0].y + 4 * 16, 16, 16);
  const cv::Mat roi = image(block);
  for (auto it = roi.begin<cv::Vec3b>(); it != roi.end<cv::Vec3b>(); ++it) {
    ASSERT_EQ(*it, cv::Vec3b(grey, grey, grey));
  }
  // Thresholded panel: black or white only.
  const cv::Vec3b t = at(image, layout.to_px(2, {12, 2}));
  EXPECT_EQ(t, cv::Vec3b(255, 255, 255));
  EXPECT_EQ(at(image, layout.to_px(2, {2, 2})), cv::Vec3b(0, 0, 0));
  EXPECT_GT(non_background(image, layout.title_px), 100);
  EXPECT_GT(non_background(image, layout.colorbar_px), 1000);
}

TEST(FiguresDepth, DrawsTheChosenPixelAsARingAtItsScaledPosition) {
  const cv::Mat depth = test_depth();
  const DepthOverlays overlays = test_overlays(depth);
  const DepthFigureLayout layout = depth_layout(depth, overlays, false);
  const cv::Mat image = draw_depth(depth, overlays, false, "Depth").raster();
  for (std::size_t panel = 0; panel < layout.panels_px.size(); ++panel) {
    const cv::Point2d centre = layout.to_px(panel, *overlays.chosen_pixel);
    int ring = 0, inside = 0;
    for (int dy = -40; dy <= 40; ++dy) {
      for (int dx = -40; dx <= 40; ++dx) {
        const double r = std::hypot(dx, dy);
        const bool red = is_ring_red(at(image, centre + cv::Point2d(dx, dy)));
        if (r < 0.5 * layout.scale) inside += red;
        else ring += red;
      }
    }
    EXPECT_GT(ring, 50) << "panel " << panel;   // a ring around the pixel ...
    EXPECT_EQ(inside, 0) << "panel " << panel;  // ... that leaves the pixel itself visible
  }
  // Nothing red far from the chosen pixel.
  EXPECT_FALSE(is_ring_red(at(image, layout.to_px(0, {14, 2}))));
}

TEST(FiguresDepth, DrawsTheProjectedWaypointWithItsSafetyEllipseAndTheNewWaypoint) {
  const cv::Mat depth = test_depth();
  DepthOverlays overlays = test_overlays(depth);
  overlays.waypoint_projection = cv::Point2d(10.5, 4.0);
  overlays.safety_ellipse_px = {3.0, 2.0};
  overlays.new_waypoint_pixel = cv::Point(3, 12);
  const DepthFigureLayout layout = depth_layout(depth, overlays, false);
  const cv::Mat image = draw_depth(depth, overlays, false, "Depth").raster();
  ASSERT_EQ(layout.scale, 16);
  const cv::Vec3b magenta(220, 0, 220), blue(180, 119, 31);  // W' and planned-waypoint colours, BGR
  for (std::size_t panel = 0; panel < layout.panels_px.size(); ++panel) {
    const cv::Point2d w = layout.to_px(panel, *overlays.waypoint_projection);
    EXPECT_LT(nearest_colour(image, w, magenta), 30) << "panel " << panel;  // the plus on W'
    // The ellipse: 3 x 2 depth-map pixels, scaled, around W' and nothing between.
    for (const cv::Point2d d : {cv::Point2d(48, 0), cv::Point2d(-48, 0), cv::Point2d(0, 32), cv::Point2d(0, -32)}) {
      EXPECT_LT(nearest_colour(image, w + d, magenta), 30) << "panel " << panel << " offset " << d;
    }
    EXPECT_GT(nearest_colour(image, w + cv::Point2d(24, 0), magenta), 100) << "panel " << panel;
    EXPECT_LT(colour_distance(at(image, layout.to_px(panel, *overlays.new_waypoint_pixel)), blue), 30) << "panel " << panel;
  }
}

TEST(FiguresDepth, MarksSpecialValuesInColour) {
  const cv::Mat depth = test_depth();
  const DepthFigureLayout layout = depth_layout(depth, {}, true);
  const cv::Mat image = draw_depth(depth, {}, true, "Depth").raster();
  ASSERT_EQ(layout.panels_px.size(), 1u);
  EXPECT_FALSE(layout.legend_px.empty());
  const cv::Vec3b too_near = at(image, layout.to_px(0, {0, 0}));
  const cv::Vec3b no_return = at(image, layout.to_px(0, {15, 0}));
  const cv::Vec3b far = at(image, layout.to_px(0, {15, 1}));  // 0.8
  EXPECT_EQ(far, sequential_color(depth.at<float>(1, 15)));
  EXPECT_GT(colour_distance(no_return, sequential_color(1.0)), 100);
  EXPECT_GT(colour_distance(too_near, sequential_color(0.0)), 100);
  EXPECT_NE(no_return, too_near);
}

TEST(FiguresDepth, IsDeterministic) {
  const cv::Mat depth = test_depth();
  EXPECT_EQ(png(draw_depth(depth, test_overlays(depth), true, "D").raster()),
            png(draw_depth(depth, test_overlays(depth), true, "D").raster()));
}

TEST(FiguresDepth, WritesPdfAndSvgWithThePanelsAsImagesAndTextAsText) {
  const cv::Mat depth = test_depth();
  DepthOverlays overlays = test_overlays(depth);
  overlays.threshold = 0.5;
  overlays.waypoint_projection = cv::Point2d(10.5, 4.0);
  overlays.safety_ellipse_px = {3.0, 2.0};
  const figure::Canvas canvas = draw_depth(depth, overlays, true, "Depth");
  expect_vector_outputs(canvas, {"Depth", "(a) depth map", "(b) dilated", "(c) thresholded at t = 0.500", "scan line"});
  // The panels are embedded as images at the depth map's resolution (16 x 16), not drawn as a rectangle per pixel:
  // poppler's pdfimages lists them.
  const std::filesystem::path pdf = std::filesystem::temp_directory_path() / ("campo_depth_" + std::to_string(::getpid()) + ".pdf");
  canvas.write(pdf, {figure::FigureFormat::pdf});
  const CommandOutput list = run_command("pdfimages -list '" + pdf.string() + "'");
  std::filesystem::remove(pdf);
  ASSERT_EQ(list.status, 0);
  int images_16 = 0;
  std::istringstream lines(list.text);
  for (std::string line; std::getline(lines, line);) {
    std::istringstream fields(line);
    std::string page, num, type;
    int width = 0, height = 0;
    if (fields >> page >> num >> type >> width >> height && type == "image") images_16 += width == 16 && height == 16;
  }
  EXPECT_GE(images_16, 3) << list.text;
}

TEST(FiguresDepth, RejectsMapsOfTheWrongTypeOrSize) {
  const cv::Mat depth = test_depth();
  EXPECT_THROW(draw_depth(cv::Mat(), {}, false, ""), std::invalid_argument);
  EXPECT_THROW(draw_depth(cv::Mat::zeros(4, 4, CV_8U), {}, false, ""), std::invalid_argument);
  DepthOverlays wrong;
  wrong.dilated = cv::Mat::zeros(8, 8, CV_32F);
  EXPECT_THROW(draw_depth(depth, wrong, false, ""), std::invalid_argument);
  wrong = {};
  wrong.thresholded = cv::Mat::zeros(16, 16, CV_32F);
  EXPECT_THROW(draw_depth(depth, wrong, false, ""), std::invalid_argument);
}

}  // namespace
}  // namespace campo
