#pragma once
/// PNG files in and out without the image library's own chatter: encoded in
/// memory and written with write_file_atomically (a full disk is one
/// OutputError with the system's reason, not a libpng message), decoded from
/// bytes read with a size limit, with libpng's and OpenCV's warnings about a
/// damaged file kept off the terminal: the error line that follows says what
/// is wrong.
#include <filesystem>
#include <vector>

#include <opencv2/core.hpp>

#include "campo/json_reader.hpp"

namespace campo {

/// Encodes `image` as PNG with `params` (cv::IMWRITE_*) and writes it atomically; OutputError naming the file.
void write_png_file(const cv::Mat& image, const std::filesystem::path& path, const std::vector<int>& params = {});

/// Reads an image file (cv::IMREAD_* `flags`); InputError naming the file when
/// it is missing, larger than `max_bytes` or not an image.
cv::Mat read_image_file(const std::filesystem::path& path, int flags, std::uintmax_t max_bytes = 256u << 20);

}  // namespace campo
