#pragma once
/// Colour camera images (RgbImage) as OpenCV matrices and PNG files.
#include <filesystem>

#include <opencv2/core.hpp>

#include "campo/rgb_image.hpp"

namespace campo {

/// The image as an 8-bit BGR matrix (OpenCV's channel order), rows from the top.
cv::Mat to_bgr(const RgbImage& image);

/// Writes the image as an 8-bit RGB PNG (core/image_io.hpp); OutputError naming the file.
void write_rgb_png(const RgbImage& image, const std::filesystem::path& path);

}  // namespace campo
