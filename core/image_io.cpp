#include "core/image_io.hpp"

#include <cstdio>

#include <fcntl.h>
#include <unistd.h>

#include <opencv2/core/utils/logger.hpp>
#include <opencv2/imgcodecs.hpp>

#include "core/output_dir.hpp"

namespace campo {

namespace {

// libpng prints its warnings straight to stderr ("libpng warning: iCCP: ..."),
// and OpenCV logs its own; while an image is coded, both are silenced. Only
// this thread codes images while it lasts (image I/O is not done concurrently).
class QuietImageLibraries {
 public:
  QuietImageLibraries() : level_(cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_SILENT)) {
    std::fflush(stderr);
    saved_ = ::dup(STDERR_FILENO);
    const int null = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
    if (saved_ >= 0 && null >= 0) ::dup2(null, STDERR_FILENO);
    if (null >= 0) ::close(null);
  }
  ~QuietImageLibraries() {
    std::fflush(stderr);
    if (saved_ >= 0) {
      ::dup2(saved_, STDERR_FILENO);
      ::close(saved_);
    }
    cv::utils::logging::setLogLevel(level_);
  }
  QuietImageLibraries(const QuietImageLibraries&) = delete;
  QuietImageLibraries& operator=(const QuietImageLibraries&) = delete;

 private:
  cv::utils::logging::LogLevel level_;
  int saved_ = -1;
};

}  // namespace

void write_png_file(const cv::Mat& image, const std::filesystem::path& path, const std::vector<int>& params) {
  std::vector<unsigned char> bytes;
  bool encoded = false;
  {
    QuietImageLibraries quiet;
    encoded = cv::imencode(".png", image, bytes, params);
  }
  if (!encoded) throw OutputError(path, "cannot encode the image as PNG");
  write_file_atomically(path, std::string(bytes.begin(), bytes.end()));
}

cv::Mat read_image_file(const std::filesystem::path& path, int flags, std::uintmax_t max_bytes) {
  const std::string bytes = read_text_file(path, {.max_file_bytes = max_bytes});
  if (bytes.empty()) throw InputError(path.string(), "", "expected an image file (PNG), got an empty file");
  cv::Mat image;
  {
    QuietImageLibraries quiet;
    image = cv::imdecode(cv::Mat(1, static_cast<int>(bytes.size()), CV_8U, const_cast<char*>(bytes.data())), flags);
  }
  if (image.empty()) throw InputError(path.string(), "", "expected an image file (PNG), got data it cannot decode");
  return image;
}

}  // namespace campo
