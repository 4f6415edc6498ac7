// PNG coding through libpng, checked against OpenCV's own codec (an independent
// implementation): what one writes the other reads back pixel for pixel.
#include "core/image_io.hpp"

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include "core/output_dir.hpp"
#include "tests/sanitizers.hpp"

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

// A PNG chunk: length, type, data and CRC-32 (of type and data), written out here.
std::string chunk(const std::string& type, const std::string& data, std::uint32_t declared_length) {
  std::uint32_t crc = 0xffffffffu;
  for (unsigned char c : type + data) {
    crc ^= c;
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  crc ^= 0xffffffffu;
  const auto be = [](std::uint32_t v) {
    return std::string{static_cast<char>(v >> 24), static_cast<char>(v >> 16), static_cast<char>(v >> 8),
                       static_cast<char>(v)};
  };
  return be(declared_length) + type + data + be(crc);
}
std::string chunk(const std::string& type, const std::string& data) {
  return chunk(type, data, static_cast<std::uint32_t>(data.size()));
}

// A PNG whose header declares `side` x `side` pixels of 16-bit grey, with a few bytes of image data.
std::string declaring(std::uint32_t side) {
  const std::string signature = "\x89PNG\r\n\x1a\n";
  const std::string s{static_cast<char>(side >> 24), static_cast<char>(side >> 16), static_cast<char>(side >> 8),
                      static_cast<char>(side)};
  const std::string ihdr = s + s + std::string{16, 0, 0, 0, 0};  // depth 16, grey, deflate, filter 0, no interlace
  const std::string idat("\x78\x9c\x63\x60\x60\x00\x00\x00\x03\x00\x01", 11);  // zlib: 3 zero bytes (a 1 x 1 image)
  return signature + chunk("IHDR", ihdr) + chunk("IDAT", idat) + chunk("IEND", "");
}

// What read_png_file says of `path` in a child whose address space is limited to 256 MiB (but
// under AddressSanitizer, which reserves terabytes): an allocation of gigabytes would fail there
// with something other than an InputError.
std::string error_in_small_address_space(const fs::path& path) {
  const fs::path report = fs::path(path).replace_extension(".report");
  const pid_t pid = ::fork();
  if (pid == 0) {
#if !defined(CAMPO_TEST_UNDER_ASAN)
    const rlimit limit{256u << 20, 256u << 20};
    ::setrlimit(RLIMIT_AS, &limit);
#endif
    std::string what = "no error";
    try {
      read_png_file(path);
    } catch (const InputError& e) {
      what = e.what();
    } catch (const std::exception& e) {
      what = std::string("not an InputError: ") + e.what();
    }
    std::ofstream(report) << what;
    ::_exit(0);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  if (!WIFEXITED(status)) return "the child died";
  std::ifstream in(report);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

TEST(ImageIo, ChunksAreCheckedAgainstTheFileSizeBeforeAnythingIsAllocated) {
  const auto write = [](const fs::path& path, const std::string& content) {
    std::ofstream(path, std::ios::binary) << content;
    return path;
  };
  // 32768 x 32768 pixels of 16-bit grey (2 GiB, within libpng's side limit) in 80 bytes.
  const fs::path wide = write(scratch("wide.png"), declaring(32768));
  ASSERT_LT(fs::file_size(wide), 100u);
  EXPECT_THAT(error_in_small_address_space(wide),
              HasSubstr("wide.png: expected a PNG file it can decode: its header declares 2147483648 bytes of pixels, "
                        "more than its 11 bytes of image data (IDAT) can hold"));
  // A 3 KiB file with a chunk that declares 2 GiB.
  const std::string good = declaring(16);
  const std::string text = chunk("zTXt", std::string(3000, 'x'), 0x7fffffffu);
  const fs::path long_chunk = write(scratch("long_chunk.png"), good.substr(0, 33) + text + good.substr(33));
  const std::string left = std::to_string(fs::file_size(long_chunk) - 33 - 12);  // after its length, type and CRC
  EXPECT_THAT(error_in_small_address_space(long_chunk),
              HasSubstr("long_chunk.png: expected a PNG file it can decode: chunk zTXt at byte 33 declares 2147483647 "
                        "bytes, more than the " + left + " bytes left in the file"));
  // The same construction with a plausible size decodes: the checks refuse only what cannot be.
  const cv::Mat small = read_png_file(write(scratch("small.png"), declaring(1)));
  EXPECT_EQ(small.type(), CV_16UC1);
  EXPECT_EQ(small.rows, 1);
}

}  // namespace
}  // namespace campo
