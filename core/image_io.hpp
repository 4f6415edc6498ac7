#pragma once
/// PNG files in and out with libpng, without the image library's chatter: the
/// image encoded in memory and written with write_file_atomically (a full
/// disk is one OutputError with the system's reason, not a libpng message),
/// decoded from bytes read with a size limit; libpng's warnings about a
/// damaged file stay off the terminal, the error that follows says what is
/// wrong. (libpng rather than OpenCV's codecs: those load over a hundred
/// libraries, GDAL among them, into every process that writes a figure.)
#include <cstdint>
#include <filesystem>
#include <string>

#include <opencv2/core.hpp>

#include "campo/json_reader.hpp"

namespace campo {

/// Encodes `image` as PNG at zlib level `compression` (0-9) and writes it
/// atomically; OutputError naming the file. Types: CV_8UC1 and CV_16UC1
/// (grey), CV_8UC3 (BGR) and CV_8UC4 (BGRA).
void write_png_file(const cv::Mat& image, const std::filesystem::path& path, int compression = 1);
/// The PNG bytes write_png_file would write; std::invalid_argument for an
/// image of another type, std::runtime_error if libpng fails.
std::string encode_png(const cv::Mat& image, int compression = 1);

/// Reads a PNG file as it is stored: grey as CV_8UC1 or CV_16UC1, colour as
/// CV_8UC3 (BGR) or CV_8UC4 (BGRA) (palettes expanded, 16-bit colour reduced
/// to 8 bits, a grey image's alpha dropped). InputError naming the file when
/// it is missing, larger than `max_bytes`, not a PNG, damaged, or wider or
/// taller than 32768 pixels. The chunks are checked against the file's size
/// before libpng reads them: a chunk longer than the bytes left, or a header
/// declaring more pixels than the file's image data can inflate to (1032
/// times its IDAT bytes, plus 64 KiB), is refused before anything is allocated.
cv::Mat read_png_file(const std::filesystem::path& path, std::uintmax_t max_bytes = 256u << 20);

}  // namespace campo
