// The figures' drawing surface (render/figure_canvas): where primitives put
// ink in drawing coordinates, regions, rasters, and the three formats.
#include "render/figure_canvas.hpp"

#include <stdexcept>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "tests/render/vector_outputs.hpp"

namespace campo::figure {
namespace {

cv::Vec3b pixel(const cv::Mat& image, int x, int y) { return image.at<cv::Vec3b>(y, x); }
const cv::Vec3b kWhitePx(255, 255, 255);

TEST(FigureCanvas, StartsWhiteAtItsSize) {
  const Canvas canvas({37, 21});
  const cv::Mat image = canvas.raster();
  EXPECT_EQ(image.size(), cv::Size(37, 21));
  EXPECT_EQ(image.type(), CV_8UC3);
  EXPECT_EQ(cv::countNonZero(image.reshape(1) != 255), 0);
}

TEST(FigureCanvas, RefusesSizesOutsideTheRange) {
  EXPECT_THROW(Canvas({0, 10}), std::invalid_argument);
  EXPECT_THROW(Canvas({10, 40000}), std::invalid_argument);
}

TEST(FigureCanvas, FilledRectangleCoversExactlyItsPixels) {
  Canvas canvas({20, 20});
  canvas.fill_rectangle({4, 6, 5, 3}, rgb(255, 0, 0));  // pixels x 4..8, y 6..8
  const cv::Mat image = canvas.raster();
  for (int y = 0; y < 20; ++y) {
    for (int x = 0; x < 20; ++x) {
      const bool inside = x >= 4 && x <= 8 && y >= 6 && y <= 8;
      EXPECT_EQ(pixel(image, x, y), inside ? cv::Vec3b(0, 0, 255) : kWhitePx) << x << "," << y;
    }
  }
}

TEST(FigureCanvas, OneWideLineAlongPixelCentresIsOnePixelWide) {
  Canvas canvas({20, 20});
  canvas.line({2, 10}, {17, 10}, rgb(0, 0, 0), 1.0);
  const cv::Mat image = canvas.raster();
  EXPECT_EQ(pixel(image, 10, 10), cv::Vec3b(0, 0, 0));
  EXPECT_EQ(pixel(image, 10, 9), kWhitePx);
  EXPECT_EQ(pixel(image, 10, 11), kWhitePx);
}

TEST(FigureCanvas, RegionMovesTheOriginAndClips) {
  Canvas canvas({30, 30});
  {
    auto clip = canvas.region({10, 10, 5, 5});
    canvas.fill_box({-100, -100}, {100, 100}, rgb(0, 0, 255));  // everything, clipped
    canvas.fill_rectangle({0, 0, 1, 1}, rgb(255, 0, 0));       // the region's top-left pixel
  }
  canvas.fill_rectangle({0, 0, 1, 1}, rgb(0, 255, 0));  // the origin is back
  const cv::Mat image = canvas.raster();
  EXPECT_EQ(pixel(image, 10, 10), cv::Vec3b(0, 0, 255));
  EXPECT_EQ(pixel(image, 14, 14), cv::Vec3b(255, 0, 0));
  EXPECT_EQ(pixel(image, 15, 15), kWhitePx);
  EXPECT_EQ(pixel(image, 9, 12), kWhitePx);
  EXPECT_EQ(pixel(image, 0, 0), cv::Vec3b(0, 255, 0));
}

TEST(FigureCanvas, RasterIsStretchedNearestNeighbourOverItsRectangle) {
  cv::Mat source(2, 2, CV_8UC3);
  source.at<cv::Vec3b>(0, 0) = {255, 0, 0};
  source.at<cv::Vec3b>(0, 1) = {0, 255, 0};
  source.at<cv::Vec3b>(1, 0) = {0, 0, 255};
  source.at<cv::Vec3b>(1, 1) = {0, 0, 0};
  Canvas canvas({20, 20});
  canvas.image(source, {4, 4, 8, 8});  // each source pixel becomes a 4 x 4 block
  const cv::Mat image = canvas.raster();
  EXPECT_EQ(pixel(image, 4, 4), source.at<cv::Vec3b>(0, 0));
  EXPECT_EQ(pixel(image, 7, 7), source.at<cv::Vec3b>(0, 0));
  EXPECT_EQ(pixel(image, 8, 4), source.at<cv::Vec3b>(0, 1));
  EXPECT_EQ(pixel(image, 4, 8), source.at<cv::Vec3b>(1, 0));
  EXPECT_EQ(pixel(image, 11, 11), source.at<cv::Vec3b>(1, 1));
  EXPECT_EQ(pixel(image, 3, 3), kWhitePx);
  EXPECT_EQ(pixel(image, 12, 12), kWhitePx);
}

TEST(FigureCanvas, AlphaRasterBlendsOverTheFigure) {
  cv::Mat half(1, 1, CV_8UC4, cv::Scalar(0, 0, 0, 128));
  Canvas canvas({4, 4});
  canvas.image(half, {0, 0, 4, 4});
  const cv::Vec3b p = pixel(canvas.raster(), 2, 2);
  EXPECT_NEAR(p[0], 127, 1);  // black at half opacity over white
}

TEST(FigureCanvas, TextSizeGrowsWithLengthAndScale) {
  const cv::Size one = text_size("x", kLabelFont), two = text_size("xx", kLabelFont);
  EXPECT_NEAR(two.width, 2 * one.width, 1);
  EXPECT_EQ(text_size("H", Font{1.0}).height, 22);  // scale 1: 22-pixel capitals
  EXPECT_GT(text_size("Height", Font{1.0}).width, text_size("Height", Font{0.5}).width);
}

TEST(FigureCanvas, TextIsInkedWhereItIsPut) {
  Canvas canvas({120, 40});
  put_text(canvas, "HHHH", {10, 20}, Font{0.6}, kInk);
  const cv::Mat image = canvas.raster();
  const cv::Size size = text_size("HHHH", Font{0.6});
  int inked = 0, outside = 0;
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) {
      if (pixel(image, x, y) == kWhitePx) continue;
      const bool in_box = x >= 9 && x <= 11 + size.width && y >= 19 - size.height / 2 - 1 && y <= 21 + size.height / 2;
      (in_box ? inked : outside) += 1;
    }
  }
  EXPECT_GT(inked, 20);
  EXPECT_EQ(outside, 0);
}

TEST(FigureCanvas, FormatListsParseAndRefuseUnknownOrRepeatedNames) {
  EXPECT_EQ(parse_figure_formats("png"), std::vector<FigureFormat>{FigureFormat::png});
  EXPECT_EQ(parse_figure_formats("svg,pdf"), (std::vector<FigureFormat>{FigureFormat::svg, FigureFormat::pdf}));
  EXPECT_THROW(parse_figure_formats("png,jpeg"), std::invalid_argument);
  EXPECT_THROW(parse_figure_formats("pdf,pdf"), std::invalid_argument);
  EXPECT_THROW(parse_figure_formats(""), std::invalid_argument);
  EXPECT_THROW(parse_figure_formats("png,"), std::invalid_argument);
}

TEST(FigureCanvas, PdfAndSvgHoldTheTextAndRenderLikeThePng) {
  Canvas canvas({320, 220});
  PlotFrame frame{{60, 20, 240, 140}, 0.0, 10.0, -1.0, 1.0};
  draw_grid(canvas, frame);
  canvas.polyline({frame.to_px(0, -1), frame.to_px(5, 1), frame.to_px(10, 0)}, rgb(31, 119, 180), 2.0);
  canvas.dashed_polyline({frame.to_px(0, 0), frame.to_px(10, 0.5)}, rgb(214, 39, 40), 2.0, 7.0, 4.0);
  goal_marker(canvas, frame.to_px(5, 1), true);
  draw_axes(canvas, frame, "time (s)", "height (m)");
  put_title(canvas, "Canvas check", {0, 0, 320, 20});
  test::expect_vector_outputs(canvas, {"Canvas check", "time (s)", "height (m)"});
}

TEST(FigureCanvas, SvgIsTheSameWhateverWasDrawnBefore) {
  const auto draw = [] {
    Canvas canvas({60, 40});
    put_text(canvas, "a", {10, 20}, kLabelFont, kInk);
    return canvas;
  };
  const std::string first = draw().encode(FigureFormat::svg);
  for (int i = 0; i < 3; ++i) Canvas({10, 10}).encode(FigureFormat::svg);  // cairo's surface numbers move on
  EXPECT_EQ(draw().encode(FigureFormat::svg), first);
  EXPECT_NE(first.find("id=\"surface1\""), std::string::npos);
}

TEST(FigureCanvas, WritesEachFormatWithItsExtension) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("campo_canvas_write_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const Canvas canvas({50, 40});
  const auto files = canvas.write(dir / "map.png", {FigureFormat::svg, FigureFormat::png});
  ASSERT_EQ(files.size(), 2u);
  EXPECT_EQ(files[0], dir / "map.svg");
  EXPECT_EQ(files[1], dir / "map.png");
  EXPECT_TRUE(fs::exists(dir / "map.svg"));
  EXPECT_TRUE(fs::exists(dir / "map.png"));
  EXPECT_FALSE(fs::exists(dir / "map.pdf"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace campo::figure
