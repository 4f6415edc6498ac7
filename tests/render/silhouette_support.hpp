#pragma once
// How the replay's silhouette screenshot (Chromium, solid where the page is
// light) is compared with campo's own snapshot of the same view (solid where
// it is not the snapshot's sky colour): replay_test.cpp, mesh_views_test.cpp.
#include <cstdlib>

#include <opencv2/core.hpp>

namespace campo::test {

struct SilhouetteComparison {
  int both = 0;    ///< pixels solid in both
  int either = 0;  ///< pixels solid in either
  int solid = 0;   ///< pixels solid in the page
  double overlap() const { return either > 0 ? static_cast<double>(both) / either : 0.0; }
};

/// `own`: campo's BGR snapshot; `page`: the page's greyscale screenshot, the same size.
inline SilhouetteComparison compare_silhouettes(const cv::Mat& own, const cv::Mat& page) {
  const cv::Vec3b sky(240, 199, 161);
  SilhouetteComparison c;
  for (int row = 0; row < own.rows; ++row) {
    for (int col = 0; col < own.cols; ++col) {
      const cv::Vec3b o = own.at<cv::Vec3b>(row, col);
      const bool ours = std::abs(o[0] - sky[0]) + std::abs(o[1] - sky[1]) + std::abs(o[2] - sky[2]) > 6;
      const bool theirs = page.at<uchar>(row, col) > 127;
      c.both += ours && theirs;
      c.either += ours || theirs;
      c.solid += theirs;
    }
  }
  return c;
}

}  // namespace campo::test
