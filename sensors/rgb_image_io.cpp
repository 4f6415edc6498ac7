#include "sensors/rgb_image_io.hpp"

#include <stdexcept>

#include "core/image_io.hpp"

namespace campo {

cv::Mat to_bgr(const RgbImage& image) {
  if (image.rgb.size() != static_cast<std::size_t>(image.rows) * image.cols * 3) {
    throw std::invalid_argument("colour image: " + std::to_string(image.rgb.size()) + " bytes for " +
                                std::to_string(image.cols) + " x " + std::to_string(image.rows) + " px");
  }
  cv::Mat bgr(image.rows, image.cols, CV_8UC3);
  const std::uint8_t* from = image.rgb.data();
  for (int row = 0; row < image.rows; ++row) {
    auto* to = bgr.ptr<std::uint8_t>(row);
    for (int col = 0; col < image.cols; ++col, from += 3, to += 3) {
      to[0] = from[2];
      to[1] = from[1];
      to[2] = from[0];
    }
  }
  return bgr;
}

void write_rgb_png(const RgbImage& image, const std::filesystem::path& path) { write_png_file(to_bgr(image), path); }

}  // namespace campo
