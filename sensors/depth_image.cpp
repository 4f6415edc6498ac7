#include "sensors/depth_image.hpp"

#include "core/image_io.hpp"

namespace campo {

cv::Mat depth_to_gray16(const cv::Mat& depth) {
  CV_Assert(depth.type() == CV_32F);
  cv::Mat gray;
  depth.convertTo(gray, CV_16U, 65535.0);  // saturating and rounding
  return gray;
}

void write_depth_png(const cv::Mat& depth, const std::filesystem::path& path) {
  write_png_file(depth_to_gray16(depth), path);
}

}  // namespace campo
