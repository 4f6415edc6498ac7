#include "core/image_io.hpp"

#include <cctype>
#include <csetjmp>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>

#include <png.h>

#include "core/output_dir.hpp"

namespace campo {

namespace {

constexpr png_uint_32 kMaxSide = 32768;  // pixels; bounds what a small damaged or hostile file may make us allocate

// The functions below run libpng, which reports errors by longjmp to their
// setjmp: no object with a destructor may live in their frames, so they use
// only plain data and report by return value.

struct ErrorText {
  char text[256] = "";
};

void on_error(png_structp png, png_const_charp message) {
  auto* error = static_cast<ErrorText*>(png_get_error_ptr(png));
  std::snprintf(error->text, sizeof error->text, "%s", message);
  png_longjmp(png, 1);
}

void on_warning(png_structp, png_const_charp) {}  // the error that may follow says what matters

struct ReadCursor {
  const char* data;
  std::size_t size;
  std::size_t at;
};

void read_from_memory(png_structp png, png_bytep out, png_size_t count) {
  auto* cursor = static_cast<ReadCursor*>(png_get_io_ptr(png));
  if (cursor->size - cursor->at < count) png_error(png, "the file ends early");
  std::memcpy(out, cursor->data + cursor->at, count);
  cursor->at += count;
}

void write_to_string(png_structp png, png_bytep data, png_size_t count) {
  static_cast<std::string*>(png_get_io_ptr(png))->append(reinterpret_cast<const char*>(data), count);
}

void flush_nothing(png_structp) {}

bool encode(const cv::Mat& image, int compression, std::string* out, ErrorText* error) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, error, &on_error, &on_warning);
  if (png == nullptr) return false;
  png_infop info = png_create_info_struct(png);
  if (info == nullptr || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_set_write_fn(png, out, &write_to_string, &flush_nothing);
  png_set_compression_level(png, compression);
  const int channels = image.channels();
  const int colour_type = channels == 1 ? PNG_COLOR_TYPE_GRAY : channels == 3 ? PNG_COLOR_TYPE_RGB : PNG_COLOR_TYPE_RGBA;
  const int bit_depth = image.depth() == CV_16U ? 16 : 8;
  png_set_IHDR(png, info, static_cast<png_uint_32>(image.cols), static_cast<png_uint_32>(image.rows), bit_depth,
               colour_type, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  if (bit_depth == 16) png_set_swap(png);  // memory is little-endian, PNG big-endian
  if (channels > 1) png_set_bgr(png);      // OpenCV's channel order
  for (int r = 0; r < image.rows; ++r) png_write_row(png, image.ptr<png_byte>(r));
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return true;
}

std::uint32_t big_endian(const char* p) {
  const auto* b = reinterpret_cast<const unsigned char*>(p);
  return std::uint32_t{b[0]} << 24 | std::uint32_t{b[1]} << 16 | std::uint32_t{b[2]} << 8 | std::uint32_t{b[3]};
}

// Walks the chunks before libpng sees them, so that nothing is allocated for what the file cannot
// hold: every chunk must fit in the bytes left, and the image IHDR declares must fit in what its
// IDAT chunks can inflate to (deflate expands at most 1032 times: kMaxInflation).
bool check_chunks(const char* data, std::size_t size, ErrorText* error) {
  constexpr std::uint64_t kMaxInflation = 1032;
  constexpr std::uint64_t kSlackBytes = 1u << 16;  // zlib and filter bytes of a small image
  std::uint64_t image_bytes = 0, compressed_bytes = 0;
  bool header = false;
  for (std::size_t at = 8; at < size;) {
    if (size - at < 12) {
      std::snprintf(error->text, sizeof error->text, "the file ends inside a chunk header at byte %zu", at);
      return false;
    }
    const std::uint32_t length = big_endian(data + at);
    char type[5] = {};
    for (int i = 0; i < 4; ++i) {
      const unsigned char c = static_cast<unsigned char>(data[at + 4 + i]);
      type[i] = std::isalpha(c) ? static_cast<char>(c) : '?';
    }
    const std::size_t left = size - at - 12;
    if (length > 0x7fffffffu || length > left) {
      std::snprintf(error->text, sizeof error->text,
                    "chunk %s at byte %zu declares %u bytes, more than the %zu bytes left in the file", type, at,
                    length, left);
      return false;
    }
    const char* body = data + at + 8;
    if (!header) {
      if (std::memcmp(type, "IHDR", 4) != 0 || length != 13) {
        std::snprintf(error->text, sizeof error->text, "the first chunk is %s, expected IHDR of 13 bytes", type);
        return false;
      }
      header = true;
      const std::uint64_t width = big_endian(body), height = big_endian(body + 4);
      const unsigned depth = static_cast<unsigned char>(body[8]), colour = static_cast<unsigned char>(body[9]);
      const unsigned channels = colour == 2 ? 3 : colour == 4 ? 2 : colour == 6 ? 4 : 1;
      // Bytes of pixels, without the rows' filter bytes: what inflating the IDAT chunks must produce.
      image_bytes = (width * channels * depth + 7) / 8 * height;
    } else if (std::memcmp(type, "IDAT", 4) == 0) {
      compressed_bytes += length;
    } else if (std::memcmp(type, "IEND", 4) == 0) {
      break;
    }
    at += 12 + static_cast<std::size_t>(length);
  }
  if (image_bytes > kMaxInflation * compressed_bytes + kSlackBytes) {
    std::snprintf(error->text, sizeof error->text,
                  "its header declares %llu bytes of pixels, more than its %llu bytes of image data (IDAT) can hold "
                  "(deflate inflates at most %llu times)",
                  static_cast<unsigned long long>(image_bytes), static_cast<unsigned long long>(compressed_bytes),
                  static_cast<unsigned long long>(kMaxInflation));
    return false;
  }
  return true;
}

bool decode(const char* data, std::size_t size, cv::Mat* out, ErrorText* error) {
  if (size < 8 || png_sig_cmp(reinterpret_cast<png_const_bytep>(data), 0, 8) != 0) {
    std::snprintf(error->text, sizeof error->text, "not a PNG file (no PNG signature)");
    return false;
  }
  if (!check_chunks(data, size, error)) return false;
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, error, &on_error, &on_warning);
  if (png == nullptr) return false;
  png_infop info = png_create_info_struct(png);
  ReadCursor cursor{data, size, 0};
  if (info == nullptr || setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    return false;
  }
  png_set_read_fn(png, &cursor, &read_from_memory);
  png_set_user_limits(png, kMaxSide, kMaxSide);
  png_read_info(png, info);
  const int colour_type = png_get_color_type(png, info);
  const int bit_depth = png_get_bit_depth(png, info);
  if (colour_type == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
  if (colour_type == PNG_COLOR_TYPE_GRAY && bit_depth < 8) png_set_expand_gray_1_2_4_to_8(png);
  const bool grey = (colour_type & PNG_COLOR_MASK_COLOR) == 0;
  if (grey) {
    if (colour_type & PNG_COLOR_MASK_ALPHA) png_set_strip_alpha(png);
  } else {
    if (png_get_valid(png, info, PNG_INFO_tRNS)) png_set_tRNS_to_alpha(png);
    if (bit_depth == 16) png_set_strip_16(png);
    png_set_bgr(png);
  }
  if (grey && bit_depth == 16) png_set_swap(png);
  const int passes = png_set_interlace_handling(png);
  png_read_update_info(png, info);
  const int channels = png_get_channels(png, info);
  const int depth = png_get_bit_depth(png, info) == 16 ? CV_16U : CV_8U;
  out->create(static_cast<int>(png_get_image_height(png, info)), static_cast<int>(png_get_image_width(png, info)),
              CV_MAKETYPE(depth, channels));
  for (int pass = 0; pass < passes; ++pass) {
    for (int r = 0; r < out->rows; ++r) png_read_row(png, out->ptr<png_byte>(r), nullptr);
  }
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  return true;
}

}  // namespace

std::string encode_png(const cv::Mat& image, int compression) {
  const int type = image.type();
  if (image.empty() || (type != CV_8UC1 && type != CV_16UC1 && type != CV_8UC3 && type != CV_8UC4)) {
    throw std::invalid_argument("cannot encode the image as PNG: expected a non-empty 8-bit grey, BGR or BGRA, or "
                                "16-bit grey image");
  }
  const cv::Mat continuous = image.isContinuous() ? image : image.clone();
  std::string bytes;
  ErrorText error;
  if (!encode(continuous, compression, &bytes, &error)) {
    throw std::runtime_error(std::string("cannot encode the image as PNG: ") + error.text);
  }
  return bytes;
}

void write_png_file(const cv::Mat& image, const std::filesystem::path& path, int compression) {
  const int type = image.type();
  if (image.empty() || (type != CV_8UC1 && type != CV_16UC1 && type != CV_8UC3 && type != CV_8UC4)) {
    throw OutputError(path, "cannot encode the image as PNG: expected a non-empty 8-bit grey, BGR or BGRA, or "
                            "16-bit grey image");
  }
  const cv::Mat continuous = image.isContinuous() ? image : image.clone();
  std::string bytes;
  ErrorText error;
  if (!encode(continuous, compression, &bytes, &error)) {
    throw OutputError(path, std::string("cannot encode the image as PNG: ") + error.text);
  }
  write_file_atomically(path, bytes);
}

cv::Mat read_png_file(const std::filesystem::path& path, std::uintmax_t max_bytes) {
  const std::string bytes = read_text_file(path, {.max_file_bytes = max_bytes});
  if (bytes.empty()) throw InputError(path.string(), "", "expected a PNG file, got an empty file");
  cv::Mat image;
  ErrorText error;
  if (!decode(bytes.data(), bytes.size(), &image, &error)) {
    throw InputError(path.string(), "", std::string("expected a PNG file it can decode: ") + error.text);
  }
  return image;
}

}  // namespace campo
