#pragma once
/// Depth-map images for people and for files.
#include <filesystem>

#include <opencv2/core.hpp>

namespace campo {

/// 16-bit grey image of a normalized depth map (CV_32F in [0, 1]):
/// pixel = round(value * 65535).
cv::Mat depth_to_gray16(const cv::Mat& depth);

/// Writes depth_to_gray16(depth) as a PNG; throws std::runtime_error on failure.
void write_depth_png(const cv::Mat& depth, const std::filesystem::path& path);

}  // namespace campo
