#include "scene/heightfield_sources.hpp"

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>
#include <stdexcept>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "campo/random.hpp"

namespace campo {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

Eigen::Isometry3d pose_at(double x, double y, double z, double yaw_rad = 0.0) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(x, y, z);
  pose.linear() = Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return pose;
}

// --- expression -------------------------------------------------------------

TEST(HeightfieldSourcesExpression, VerticesAreTheExpressionExactly) {
  // The 001 terrain: 150 m square centred at (75, 75), 2 m below the surface datum.
  const Eigen::Isometry3d pose = pose_at(75.0, 75.0, 2.0);
  const HeightGrid grid = heightgrid_from_expression("sin(x/5)", {150.0, 150.0}, 1.5, pose);
  ASSERT_EQ(grid.cols, 101);
  ASSERT_EQ(grid.rows, 101);
  EXPECT_EQ(grid.spacing_x_m, 1.5);
  EXPECT_EQ(grid.spacing_y_m, 1.5);
  for (int r = 0; r < grid.rows; ++r) {
    for (int c = 0; c < grid.cols; ++c) {
      const double x = (c - 50) * 1.5 + 75.0;
      ASSERT_EQ(grid.at(c, r), std::sin(x / 5.0) - 2.0) << "vertex " << c << ", " << r;
    }
  }
}

TEST(HeightfieldSourcesExpression, InterpolationStaysWithinTheCurvatureBound) {
  const Eigen::Isometry3d pose = pose_at(75.0, 75.0, 2.0);
  const double h = 1.5;
  const HeightGrid grid = heightgrid_from_expression("sin(x/5)", {150.0, 150.0}, h, pose);
  // Linear interpolation of f misses it by at most max|f''| h^2 / 8, here f'' <= 1/25.
  const double bound = (1.0 / 25.0) * h * h / 8.0;
  Rng rng(11);
  double worst = 0.0;
  for (int i = 0; i < 20000; ++i) {
    const double lx = rng.uniform(-75.0, 75.0);
    const double ly = rng.uniform(-75.0, 75.0);
    const auto z = grid.height_at(lx, ly);
    ASSERT_TRUE(z.has_value());
    worst = std::max(worst, std::abs(*z - (std::sin((lx + 75.0) / 5.0) - 2.0)));
  }
  EXPECT_LE(worst, bound + 1e-12);
  EXPECT_GT(worst, 0.5 * bound);  // the bound is nearly reached, so the test is not vacuous
}

TEST(HeightfieldSourcesExpression, UsesWorldCoordinatesOfARotatedGrid) {
  const Eigen::Isometry3d pose = pose_at(10.0, -4.0, 0.5, 0.5);
  const HeightGrid grid = heightgrid_from_expression("0.1*x + 0.01*y^2", {20.0, 10.0}, 0.5, pose);
  ASSERT_EQ(grid.cols, 41);
  ASSERT_EQ(grid.rows, 21);
  for (int r = 0; r < grid.rows; r += 5) {
    for (int c = 0; c < grid.cols; c += 5) {
      const Eigen::Vector3d world = pose * Eigen::Vector3d((c - 20) * 0.5, (r - 10) * 0.5, 0.0);
      EXPECT_NEAR(grid.at(c, r), 0.1 * world.x() + 0.01 * world.y() * world.y() - 0.5, 1e-12);
    }
  }
}

TEST(HeightfieldSourcesExpression, ErrorsNameTheExpression) {
  const Eigen::Isometry3d pose = pose_at(3.0, 4.0, 0.0);
  EXPECT_THAT([&] { heightgrid_from_expression("sin(x/", {10.0, 10.0}, 1.0, pose); },
              ThrowsMessage<std::runtime_error>(HasSubstr("expression 'sin(x/': ")));
  EXPECT_THAT([&] { heightgrid_from_expression("z*2", {10.0, 10.0}, 1.0, pose); },
              ThrowsMessage<std::runtime_error>(AllOf(HasSubstr("expression 'z*2': "), HasSubstr("z"))));
  EXPECT_THAT([&] { heightgrid_from_expression("x, y", {10.0, 10.0}, 1.0, pose); },
              ThrowsMessage<std::runtime_error>(HasSubstr("expression 'x, y': must be a single value")));
  // x runs from -2 to 8 and y from -1 to 9; x = 3 divides by zero on the first row.
  EXPECT_THAT([&] { heightgrid_from_expression("1/(x-3)", {10.0, 10.0}, 1.0, pose); },
              ThrowsMessage<std::runtime_error>(
                  HasSubstr("expression '1/(x-3)': not finite (inf) at x = 3, y = -1")));
}

TEST(HeightfieldSourcesExpression, RejectsBadGridsBeforeAllocating) {
  EXPECT_THAT([&] { heightgrid_from_expression("0", {1e5, 1e5}, 1.0, pose_at(0, 0, 0)); },
              ThrowsMessage<std::runtime_error>(HasSubstr("more than 16777216 vertices")));
  EXPECT_THAT([&] { heightgrid_from_expression("0", {10.0, 10.0}, -1.0, pose_at(0, 0, 0)); },
              ThrowsMessage<std::runtime_error>(HasSubstr("spacing must be finite and > 0")));
  EXPECT_THAT([&] { heightgrid_from_expression("0", {10.0, 0.0}, 1.0, pose_at(0, 0, 0)); },
              ThrowsMessage<std::runtime_error>(HasSubstr("size must be finite and > 0")));
}

// --- files ------------------------------------------------------------------

/// A fresh directory under the system temp dir, removed after the test.
class TempDirTest : public testing::Test {
 protected:
  void SetUp() override {
    const auto* info = testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() /
           ("campo_" + std::string(info->test_suite_name()) + "_" + info->name() + "_" +
            std::to_string(std::random_device{}()));
    ASSERT_TRUE(std::filesystem::create_directory(dir_)) << dir_;
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::filesystem::path write(const std::string& name, const std::string& bytes) const {
    const auto path = dir_ / name;
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
  }

  std::filesystem::path dir_;
};

class HeightfieldSourcesCsv : public TempDirTest {};

TEST_F(HeightfieldSourcesCsv, FirstLineIsTheNorthEdge) {
  const HeightGrid grid = heightgrid_from_csv(write("g.csv", "1,2,3\n4,5,6\n"), 0.5);
  ASSERT_EQ(grid.cols, 3);
  ASSERT_EQ(grid.rows, 2);
  EXPECT_EQ(grid.spacing_x_m, 0.5);
  EXPECT_EQ(grid.spacing_y_m, 0.5);
  // Row 1 (north, larger y) is the first line; column 0 is west.
  EXPECT_EQ(grid.at(0, 1), 1.0);
  EXPECT_EQ(grid.at(2, 1), 3.0);
  EXPECT_EQ(grid.at(0, 0), 4.0);
  EXPECT_EQ(grid.at(2, 0), 6.0);
  EXPECT_EQ(grid.height_at(-0.5, 0.25), 1.0);
}

TEST_F(HeightfieldSourcesCsv, AcceptsBlanksCrlfAndNoFinalNewline) {
  const HeightGrid grid = heightgrid_from_csv(write("g.csv", " 1.5, -2e-1 ,3\r\n4,5,6.25\r\n7,8,9\n\n"), 1.0);
  ASSERT_EQ(grid.rows, 3);
  EXPECT_EQ(grid.at(0, 2), 1.5);
  EXPECT_EQ(grid.at(1, 2), -0.2);
  EXPECT_EQ(grid.at(2, 1), 6.25);
  EXPECT_EQ(heightgrid_from_csv(write("h.csv", "1,2\n3,4"), 1.0).at(1, 0), 4.0);
}

TEST_F(HeightfieldSourcesCsv, ErrorsNameLineAndColumn) {
  const auto fails_with = [&](const std::string& text, const std::string& message) {
    EXPECT_THAT([&] { heightgrid_from_csv(write("bad.csv", text), 1.0); },
                ThrowsMessage<std::runtime_error>(HasSubstr(message)))
        << text;
  };
  fails_with("1,2,3\n4,x,6\n", "line 2, column 2: 'x' is not a finite number");
  fails_with("1,2,3\n4,5,nan\n", "line 2, column 3: 'nan' is not a finite number");
  fails_with("1,2,3\n4,5,1e999\n", "line 2, column 3: '1e999' is not a finite number");
  fails_with("1,2 3\n4,5\n", "line 1, column 2: '2 3' is not a finite number");
  fails_with("1,,3\n4,5,6\n", "line 1, column 2: empty field");
  fails_with("1,2,3\n4,5,\n", "line 2, column 3: empty field");
  fails_with("1,2,3\n4,5\n", "line 2 has 2 fields, expected 3 as on the first line");
  fails_with("1,2\n\n3,4\n", "line 2 is empty");
  fails_with("1,2,3\n", "CSV grid is 1 lines x 3 columns; at least 2 x 2 heights are needed");
  fails_with("1\n2\n", "CSV grid is 2 lines x 1 columns");
  fails_with("", "CSV file has no heights");
  fails_with("1," + std::string(70, '1') + "\n", "line 1, column 2: field longer than 64 characters");
}

TEST_F(HeightfieldSourcesCsv, RejectsMissingFileBadSpacingAndTooManyHeights) {
  EXPECT_THAT([&] { heightgrid_from_csv(dir_ / "missing.csv", 1.0); },
              ThrowsMessage<std::runtime_error>(HasSubstr("cannot open CSV file")));
  EXPECT_THAT([&] { heightgrid_from_csv(write("g.csv", "1,2\n3,4\n"), 0.0); },
              ThrowsMessage<std::runtime_error>(HasSubstr("spacing must be finite and > 0, got 0")));
  std::string huge;
  huge.reserve(2 * static_cast<std::size_t>(kMaxHeightfieldVertices) + 8);
  for (long i = 0; i <= kMaxHeightfieldVertices; ++i) huge += "0,";
  huge += "0\n";
  EXPECT_THAT([&] { heightgrid_from_csv(write("huge.csv", huge), 1.0); },
              ThrowsMessage<std::runtime_error>(HasSubstr("line 1: more than 16777216 heights")));
}

class HeightfieldSourcesPng : public TempDirTest {
 protected:
  std::filesystem::path write_png(const std::string& name, const cv::Mat& image) const {
    const auto path = dir_ / name;
    EXPECT_TRUE(cv::imwrite(path.string(), image));
    return path;
  }
  /// A PNG signature and IHDR chunk only: enough for the header checks.
  std::filesystem::path write_png_header(const std::string& name, std::uint32_t width, std::uint32_t height,
                                         int depth, int colour_type) const {
    std::string bytes = "\x89PNG\r\n\x1a\n";
    bytes += std::string("\0\0\0\x0dIHDR", 8);
    for (const std::uint32_t v : {width, height}) {
      for (int shift = 24; shift >= 0; shift -= 8) bytes += static_cast<char>((v >> shift) & 0xff);
    }
    bytes += static_cast<char>(depth);
    bytes += static_cast<char>(colour_type);
    bytes += std::string(7, '\0');  // compression, filter, interlace, CRC
    return write(name, bytes);
  }
};

TEST_F(HeightfieldSourcesPng, TopRowIsTheNorthEdge8Bit) {
  cv::Mat image = (cv::Mat_<std::uint8_t>(2, 3) << 0, 51, 255, 255, 0, 102);
  const HeightGrid grid = heightgrid_from_png(write_png("g.png", image), {4.0, 3.0}, 10.0, -1.0);
  ASSERT_EQ(grid.cols, 3);
  ASSERT_EQ(grid.rows, 2);
  EXPECT_EQ(grid.spacing_x_m, 2.0);
  EXPECT_EQ(grid.spacing_y_m, 3.0);
  EXPECT_DOUBLE_EQ(grid.at(0, 1), -1.0);  // top-left pixel: north-west
  EXPECT_DOUBLE_EQ(grid.at(1, 1), 1.0);
  EXPECT_DOUBLE_EQ(grid.at(2, 1), 9.0);
  EXPECT_DOUBLE_EQ(grid.at(0, 0), 9.0);   // bottom-left pixel: south-west
  EXPECT_DOUBLE_EQ(grid.at(2, 0), 3.0);
}

TEST_F(HeightfieldSourcesPng, SixteenBitUsesTheFullRange) {
  cv::Mat image = (cv::Mat_<std::uint16_t>(2, 2) << 65535, 0, 32768, 1);
  const HeightGrid grid = heightgrid_from_png(write_png("g16.png", image), {1.0, 1.0}, 5.0, 100.0);
  EXPECT_DOUBLE_EQ(grid.at(0, 1), 105.0);
  EXPECT_DOUBLE_EQ(grid.at(1, 1), 100.0);
  EXPECT_DOUBLE_EQ(grid.at(0, 0), 100.0 + 5.0 * 32768.0 / 65535.0);
  EXPECT_DOUBLE_EQ(grid.at(1, 0), 100.0 + 5.0 / 65535.0);
}

TEST_F(HeightfieldSourcesPng, RejectsColourDepthSizeAndNonPng) {
  const cv::Mat colour(4, 4, CV_8UC3, cv::Scalar(10, 20, 30));
  EXPECT_THAT([&] { heightgrid_from_png(write_png("c.png", colour), {1.0, 1.0}, 1.0, 0.0); },
              ThrowsMessage<std::runtime_error>(HasSubstr("must be single-channel greyscale, got colour type 2 (RGB)")));
  EXPECT_THAT([&] { heightgrid_from_png(write_png_header("d.png", 4, 4, 4, 0), {1.0, 1.0}, 1.0, 0.0); },
              ThrowsMessage<std::runtime_error>(HasSubstr("8 or 16 bits per pixel, got 4")));
  const cv::Mat line(1, 5, CV_8UC1, cv::Scalar(7));
  EXPECT_THAT([&] { heightgrid_from_png(write_png("l.png", line), {1.0, 1.0}, 1.0, 0.0); },
              ThrowsMessage<std::runtime_error>(HasSubstr("PNG is 5 x 1 pixels; at least 2 x 2 are needed")));
  // Rejected from the header alone: this file holds no image data at all.
  EXPECT_THAT([&] { heightgrid_from_png(write_png_header("big.png", 5000, 4000, 16, 0), {1.0, 1.0}, 1.0, 0.0); },
              ThrowsMessage<std::runtime_error>(HasSubstr("PNG is 5000 x 4000 pixels, more than the limit")));
  EXPECT_THAT([&] { heightgrid_from_png(write_png_header("trunc.png", 4, 4, 8, 0), {1.0, 1.0}, 1.0, 0.0); },
              ThrowsMessage<std::runtime_error>(HasSubstr("trunc.png: expected a PNG file it can decode")));
  EXPECT_THAT([&] { heightgrid_from_png(write("t.png", "1,2\n3,4\n"), {1.0, 1.0}, 1.0, 0.0); },
              ThrowsMessage<std::runtime_error>(HasSubstr("is not a PNG file")));
  EXPECT_THAT([&] { heightgrid_from_png(dir_ / "missing.png", {1.0, 1.0}, 1.0, 0.0); },
              ThrowsMessage<std::runtime_error>(HasSubstr("cannot open PNG file")));
  const cv::Mat grey(2, 2, CV_8UC1, cv::Scalar(0));
  EXPECT_THAT([&] { heightgrid_from_png(write_png("g.png", grey), {0.0, 1.0}, 1.0, 0.0); },
              ThrowsMessage<std::runtime_error>(HasSubstr("size must be finite and > 0")));
}

}  // namespace
}  // namespace campo
