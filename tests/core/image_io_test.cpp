// PNG coding through libpng, checked against OpenCV's own codec (an independent
// implementation): what one writes the other reads back pixel for pixel.
#include "core/image_io.hpp"

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include <unistd.h>

#include "core/output_dir.hpp"

namespace campo {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("campo_image_io_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir / name;
}

cv::Mat noise(int rows, int cols, int type, unsigned seed) {
  cv::Mat image(rows, cols, type);
  cv::RNG rng(seed);
  rng.fill(image, cv::RNG::UNIFORM, 0, image.depth() == CV_16U ? 65536 : 256);
  return image;
}

bool identical(const cv::Mat& a, const cv::Mat& b) {
  return a.type() == b.type() && a.size() == b.size() && cv::norm(a, b, cv::NORM_INF) == 0.0;
}

TEST(ImageIo, RoundTripsEveryTypeAndAgreesWithOpenCv) {
  int seed = 1;
  for (const int type : {CV_8UC1, CV_16UC1, CV_8UC3, CV_8UC4}) {
    const cv::Mat image = noise(37, 53, type, static_cast<unsigned>(seed++));
    const fs::path ours = scratch("ours_" + std::to_string(type) + ".png");
    write_png_file(image, ours);
    EXPECT_TRUE(identical(read_png_file(ours), image)) << type;
    // OpenCV decodes what libpng wrote here, channel order and byte order included ...
    EXPECT_TRUE(identical(cv::imread(ours.string(), cv::IMREAD_UNCHANGED), image)) << type;
    // ... and what OpenCV writes reads back here.
    const fs::path theirs = scratch("theirs_" + std::to_string(type) + ".png");
    ASSERT_TRUE(cv::imwrite(theirs.string(), image));
    EXPECT_TRUE(identical(read_png_file(theirs), image)) << type;
  }
  // A view into a larger image (not continuous) is written as the view.
  const cv::Mat big = noise(20, 20, CV_8UC3, 9);
  const cv::Mat view = big(cv::Rect(3, 4, 10, 7));
  write_png_file(view, scratch("view.png"), 9);
  EXPECT_TRUE(identical(read_png_file(scratch("view.png")), view.clone()));
}

TEST(ImageIo, DamagedOrHostileFilesAreInputErrorsNamingTheFile) {
  const auto error_of = [](const fs::path& path) -> std::string {
    try {
      read_png_file(path);
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  };
  const fs::path good = scratch("good.png");
  write_png_file(noise(16, 16, CV_8UC1, 3), good);
  std::ifstream in(good, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto write = [](const fs::path& path, const std::string& content) {
    std::ofstream(path, std::ios::binary) << content;
    return path;
  };
  EXPECT_THAT(error_of(write(scratch("cut.png"), bytes.substr(0, bytes.size() / 2))),
              HasSubstr("cut.png: expected a PNG file it can decode"));
  EXPECT_THAT(error_of(write(scratch("text.png"), "width,height\n1,2\n")), HasSubstr("no PNG signature"));
  EXPECT_THAT(error_of(write(scratch("empty.png"), "")), HasSubstr("empty file"));
  EXPECT_THAT(error_of(scratch("missing.png")), HasSubstr("missing.png"));
  // A header claiming 100000 x 100000 pixels is refused before anything is allocated.
  std::string huge = bytes;
  const unsigned char side[4] = {0x00, 0x01, 0x86, 0xA0};  // 100000, big-endian
  huge.replace(16, 4, reinterpret_cast<const char*>(side), 4);
  huge.replace(20, 4, reinterpret_cast<const char*>(side), 4);
  EXPECT_THAT(error_of(write(scratch("huge.png"), huge)), HasSubstr("huge.png: expected a PNG file it can decode"));
  EXPECT_THROW(write_png_file(cv::Mat(4, 4, CV_32FC1), scratch("float.png")), OutputError);
}

}  // namespace
}  // namespace campo
