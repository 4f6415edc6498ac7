#include "planners/depth_reactive_steps.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <tuple>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "core/angles.hpp"
#include "planners/fast_atan.hpp"

#if defined(__x86_64__)
#include <immintrin.h>
#endif

namespace campo {

namespace {

constexpr double kRadToDeg = 180.0 / M_PI;
// Marks "no obstacle of this layer" in a layer image; above every depth value.
constexpr float kEmpty = std::numeric_limits<float>::max();
// Pixels added to a new waypoint's sphere projection when checking it is
// clear, so it stays visible after the vehicle turns to face it (the image
// shifts by a fraction of a pixel and the sensor, ahead of the body centre, moves).
constexpr double kClearMarginPx = 1.5;

// Minimum filter of `image` with a (2 rx + 1) x (2 ry + 1) rectangle, in
// place: erosion, so the nearest value wins; nothing beyond the border.
void erode_square(cv::Mat& image, const cv::Size& r) {
  if (r.width == 0 && r.height == 0) return;
  cv::erode(image, image, cv::getStructuringElement(cv::MORPH_RECT, {2 * r.width + 1, 2 * r.height + 1}),
            cv::Point(-1, -1), 1, cv::BORDER_CONSTANT, cv::Scalar(kEmpty));
}

// Min filter of a layer image with an elliptical disc of semi-axes (rx, ry):
// the disc is the union of horizontal runs of half-width w(dy), so the filter
// is the minimum over dy of row-wise minima of width w(dy), which grow as |dy|
// shrinks. O(rx + ry) passes over the image, where cv::erode with an
// elliptical kernel costs O(rx ry) per pixel (20 ms at r = 49 on 256 x 256).
cv::Mat erode_disc(const cv::Mat& layer, int rx, int ry) {
  const int rows = layer.rows;
  const int cols = layer.cols;
  cv::Mat widened = layer.clone();  // row-wise minimum over [x - w, x + w]
  cv::Mat out(layer.size(), CV_32F, cv::Scalar(kEmpty));
  const double rx2 = static_cast<double>(rx) * rx;
  const double ry2 = static_cast<double>(ry) * ry;
  int width = 0;
  for (int dy = ry; dy >= 0; --dy) {
    // Largest dx with (dx/rx)^2 + (dy/ry)^2 <= 1, in integers where possible.
    const int w = ry == 0 ? rx : static_cast<int>(std::floor(std::sqrt(rx2 * (1.0 - dy * dy / ry2)) + 1e-9));
    for (; width < w; ++width) {
      const int k = width + 1;
      for (int y = 0; y < rows; ++y) {
        const float* src = layer.ptr<float>(y);
        float* dst = widened.ptr<float>(y);
        for (int x = 0; x + k < cols; ++x) dst[x] = std::min(dst[x], src[x + k]);
        for (int x = k; x < cols; ++x) dst[x] = std::min(dst[x], src[x - k]);
      }
    }
    for (const int offset : {dy, -dy}) {
      for (int y = std::max(0, -offset); y < std::min(rows, rows - offset); ++y) {
        const float* src = widened.ptr<float>(y + offset);
        float* dst = out.ptr<float>(y);
        for (int x = 0; x < cols; ++x) dst[x] = std::min(dst[x], src[x]);
      }
      if (dy == 0) break;
    }
  }
  return out;
}

// Smallest value of `image` over the pixels whose footprint (the unit square
// around the pixel's centre) meets the ellipse of semi-axes (rx, ry) around
// `centre`: every direction within the ellipse is read, wherever it falls in
// its pixel. With rx = ry = 0, the pixels whose footprint holds the centre
// (two or four on a border). nullopt when it misses the image.
std::optional<float> min_in_ellipse(const cv::Mat& image, const Eigen::Vector2d& centre, double rx, double ry) {
  float best = std::numeric_limits<float>::infinity();
  bool any = false;
  const int y0 = std::max(0, static_cast<int>(std::ceil(centre.y() - ry - 0.5)));
  const int y1 = std::min(image.rows - 1, static_cast<int>(std::floor(centre.y() + ry + 0.5)));
  for (int y = y0; y <= y1; ++y) {
    // The footprint's nearest point to the centre is dy away in y (0 when the row holds it).
    const double dy = std::max(0.0, std::abs(y - centre.y()) - 0.5);
    double half = rx;
    if (ry > 0.0) {
      const double t = 1.0 - (dy / ry) * (dy / ry);
      if (t < 0.0) continue;
      half = rx * std::sqrt(t);
    } else if (dy > 0.0) {
      continue;
    }
    const int x0 = std::max(0, static_cast<int>(std::ceil(centre.x() - half - 0.5)));
    const int x1 = std::min(image.cols - 1, static_cast<int>(std::floor(centre.x() + half + 0.5)));
    const float* row = image.ptr<float>(y);
    for (int x = x0; x <= x1; ++x) {
      best = std::min(best, row[x]);
      any = true;
    }
  }
  if (any) return best;
  return std::nullopt;
}

// Angular radius of a sphere of `radius_m` seen from `range_m`, in pixels (x, y).
Eigen::Vector2d projected_radius_px(const DepthGrid& grid, double radius_m, double range_m) {
  const double deg = std::asin(std::min(1.0, radius_m / range_m)) * kRadToDeg;
  return {deg / grid.deg_per_col(), deg / grid.deg_per_row()};
}

}  // namespace

DepthGrid DepthGrid::of(const RangeScan& scan, const RangeSensorConfig& config) {
  return {scan.cols, scan.rows, config.fov_h_deg, config.fov_v_deg, config.max_range_m};
}

double DepthGrid::pixel_rad() const { return std::max(deg_per_col(), deg_per_row()) * kDegToRad; }

Eigen::Vector2d DepthGrid::project(const Eigen::Vector3d& d) const {
  const double azimuth_deg = std::atan2(d.y(), d.x()) * kRadToDeg;
  const double elevation_deg = std::atan2(d.z(), d.head<2>().norm()) * kRadToDeg;
  return {(0.5 * fov_h_deg - azimuth_deg) / deg_per_col() - 0.5, (0.5 * fov_v_deg - elevation_deg) / deg_per_row() - 0.5};
}

Eigen::Vector3d DepthGrid::direction(const Eigen::Vector2d& pixel) const {
  const double az = (0.5 * fov_h_deg - (pixel.x() + 0.5) * deg_per_col()) * kDegToRad;
  const double el = (0.5 * fov_v_deg - (pixel.y() + 0.5) * deg_per_row()) * kDegToRad;
  return {std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)};
}

std::vector<cv::Size> printed_layer_radii(int layers, double max_radius_x_px, double max_radius_y_px) {
  std::vector<cv::Size> radii;
  for (int s = 1; s <= layers; ++s) {
    const double scale = static_cast<double>(s) / layers;
    radii.emplace_back(static_cast<int>(std::lround(max_radius_x_px * scale)),
                       static_cast<int>(std::lround(max_radius_y_px * scale)));
  }
  return radii;
}

std::vector<cv::Size> margin_layer_radii(int layers, double margin_m, const DepthGrid& grid) {
  std::vector<cv::Size> radii;
  for (int s = 1; s <= layers; ++s) {
    // The layer's nearest depth, where the margin spans the widest angle, and
    // whole pixels rounded up: an obstacle anywhere in the layer is grown by
    // at least margin_m. The edge of an obstacle lies between the last pixel
    // centre that hit it and the next, so a free pixel centre r pixels beyond
    // the dilation is still r pixels (at least the margin) from the obstacle.
    const double near_m = (s - 1.0) / layers * grid.max_range_m;
    const double deg = std::atan2(margin_m, near_m) * kRadToDeg;
    // (No wider than the image: beyond that a larger element changes nothing.)
    const auto pixels = [&](double deg_per_px, int size) {
      return static_cast<int>(std::min(std::ceil(deg / deg_per_px - 1e-9), static_cast<double>(size)));
    };
    radii.emplace_back(pixels(grid.deg_per_col(), grid.cols), pixels(grid.deg_per_row(), grid.rows));
  }
  return radii;
}

int margin_radius_px(double margin_m, double depth_m, double deg_per_px, int size) {
  // asin(margin / d), 90 deg once d <= margin (the sensor itself is within the margin).
  const double deg = depth_m > margin_m ? std::asin(margin_m / depth_m) * kRadToDeg : 90.0;
  return static_cast<int>(std::min(std::ceil(deg / deg_per_px + 0.5 - 1e-9), static_cast<double>(size)));
}

DilationParams margin_layers(double margin_m, const DepthGrid& grid, StructuringShape shape) {
  // margin_radius_px is at most k exactly when asin(margin / d) <= (k - 1/2)
  // deg_per_px, i.e. d >= margin / sin((k - 1/2) deg_per_px). Those depths,
  // both axes, cut [0, d_max] into the layers.
  std::vector<double> cuts;  // normalised depths
  for (const auto& [deg_per_px, size] : {std::pair{grid.deg_per_col(), grid.cols}, std::pair{grid.deg_per_row(), grid.rows}}) {
    for (int k = 1; k <= size && (k - 0.5) * deg_per_px < 90.0; ++k) {
      const double d = margin_m / std::sin((k - 0.5) * deg_per_px * kDegToRad) / grid.max_range_m;
      if (d > 0.0 && d < 1.0) cuts.push_back(d);
    }
  }
  std::sort(cuts.begin(), cuts.end());
  cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
  cuts.push_back(1.0);
  DilationParams p;
  p.shape = shape;
  double lower = 0.0;
  for (const double upper : cuts) {
    // Values in (lower, upper]: the radius only shrinks with depth, so the
    // layer's largest is just above `lower`; at a cut it is the one for d = cut.
    const double near_m = lower * grid.max_range_m;
    const cv::Size r(margin_radius_px(margin_m, near_m, grid.deg_per_col(), grid.cols),
                     margin_radius_px(margin_m, near_m, grid.deg_per_row(), grid.rows));
    if (!p.layer_radius_px.empty() && p.layer_radius_px.back() == r) {
      p.layer_upper.back() = upper;  // same element: one layer
    } else {
      p.layer_radius_px.push_back(r);
      p.layer_upper.push_back(upper);
    }
    lower = upper;
  }
  return p;
}

namespace {

// The layer (1 to n) of a value, 0 for free space (no return, or not a number).
class LayerLookup {
 public:
  explicit LayerLookup(const DilationParams& p) : n_(static_cast<int>(p.layer_radius_px.size())), upper_(p.layer_upper) {
    CV_Assert(n_ >= 1);
    CV_Assert(upper_.empty() || static_cast<int>(upper_.size()) == n_);
    if (upper_.empty()) return;
    // The first layer whose upper bound is at least the value (lower_bound),
    // through a table of kBins bins over [0, 1) (exact in float and double,
    // a power of 2). A bin that holds no bound gives all its values one
    // layer; one that holds one bound, the layer below it or the next, by a
    // comparison with the bound rounded down to a float (v > that float
    // exactly when v > the bound, v being a float); one that holds more,
    // stepped over from the bin's first candidate. So the result is
    // lower_bound's, and almost every value costs a load and a comparison,
    // without a branch that neighbouring pixels could mispredict.
    bins_.resize(kBins);
    int k = 0;  // lower_bound of b / kBins, which only grows with b: one walk over the bounds
    for (int b = 0; b < kBins; ++b) {
      while (k < n_ && upper_[k] < static_cast<double>(b) / kBins) ++k;
      const double bin_end = static_cast<double>(b + 1) / kBins;
      Bin& bin = bins_[b];
      bin.first = k;
      if (k >= n_ - 1 || upper_[k] >= bin_end) {
        bin.layer = std::clamp(k + 1, 1, n_);  // no bound inside, or only the last (beyond it the layer is n too)
      } else if (upper_[k + 1] >= bin_end) {
        float below = static_cast<float>(upper_[k]);
        if (static_cast<double>(below) > upper_[k]) below = std::nextafter(below, -1.0f);
        bin.above = below;
        bin.layer = k + 1;
      } else {
        bin.layer = -1;
      }
    }
  }

  int operator()(float v) const {
    if (!(v < 1.0f)) return 0;
    if (upper_.empty()) return std::clamp(static_cast<int>(std::ceil(v * n_)), 1, n_);
    if (v <= 0.0f) return stepped(0, v);
    const Bin& bin = bins_[static_cast<std::size_t>(v * kBins)];  // v < 1: the bin is below kBins
    return bin.layer >= 0 ? bin.layer + static_cast<int>(v > bin.above) : stepped(bin.first, v);
  }

 private:
  static constexpr int kBins = 4096;
  struct Bin {
    float above = std::numeric_limits<float>::infinity();  // values above it take the next layer
    int layer = 0;  // of the values up to `above`; -1: several bounds, stepped from `first`
    int first = 0;
  };
  int stepped(int k, float v) const {
    while (k < n_ && upper_[k] < static_cast<double>(v)) ++k;
    return std::clamp(k + 1, 1, n_);
  }
  int n_;
  const std::vector<double>& upper_;
  std::vector<Bin> bins_;
};

// Consecutive pixels of one row in one layer.
struct LayerRun {
  int first;   // index of the first pixel, row-major
  int length;  // pixels
  int row;
  int layer;
};

// out[i] = min(a[i], b[i], c[i]) for i < n (out must not alias the inputs).
// Eight lanes at a time with AVX2 where the CPU has it, four with SSE
// otherwise; a minimum is exact, so both give the same floats.
#if defined(__x86_64__)
__attribute__((target("avx2"))) void min3_avx2(const float* a, const float* b, const float* c, float* out,
                                               std::size_t n) {
  std::size_t i = 0;
  for (; i + 8 <= n; i += 8) {
    const __m256 ab = _mm256_min_ps(_mm256_loadu_ps(a + i), _mm256_loadu_ps(b + i));
    _mm256_storeu_ps(out + i, _mm256_min_ps(ab, _mm256_loadu_ps(c + i)));
  }
  if (i < n && n >= 8) {
    // The last eight again, overlapping: the same minima (out aliases no input).
    const std::size_t k = n - 8;
    const __m256 ab = _mm256_min_ps(_mm256_loadu_ps(a + k), _mm256_loadu_ps(b + k));
    _mm256_storeu_ps(out + k, _mm256_min_ps(ab, _mm256_loadu_ps(c + k)));
    return;
  }
  for (; i < n; ++i) {
    const float ab = a[i] < b[i] ? a[i] : b[i];
    out[i] = ab < c[i] ? ab : c[i];
  }
}
#endif

void min3(const float* a, const float* b, const float* c, float* out, std::size_t n) {
#if defined(__x86_64__)
  static const bool avx2 = __builtin_cpu_supports("avx2");
  if (avx2) {
    min3_avx2(a, b, c, out, n);
    return;
  }
  std::size_t i = 0;
  for (; i + 4 <= n; i += 4) {
    const __m128 ab = _mm_min_ps(_mm_loadu_ps(a + i), _mm_loadu_ps(b + i));
    _mm_storeu_ps(out + i, _mm_min_ps(ab, _mm_loadu_ps(c + i)));
  }
#else
  std::size_t i = 0;
#endif
  for (; i < n; ++i) {
    const float ab = a[i] < b[i] ? a[i] : b[i];
    out[i] = ab < c[i] ? ab : c[i];
  }
}

}  // namespace

cv::Rect erode_rect(std::vector<float>& image, std::vector<float>& scratch, int rows, int cols, cv::Rect box, int rx,
                    int ry) {
  CV_Assert(rows >= 0 && cols >= 0 && rx >= 0 && ry >= 0 && image.size() == static_cast<std::size_t>(rows) * cols &&
            (scratch.empty() || scratch.size() == image.size()));
  box &= cv::Rect(0, 0, cols, rows);
  if (box.empty()) return box;
  // Only the steps of 2 and 3 pixels use the scratch image: the chain's usual
  // step of 1 never fills it.
  const auto ready_scratch = [&] {
    if (scratch.size() != image.size()) scratch.assign(image.size(), kEmpty);
  };
  // A window wider than the line covers all of it whatever its size.
  rx = std::min(rx, cols - 1);
  ry = std::min(ry, rows - 1);
  const std::size_t stride = static_cast<std::size_t>(cols);
  thread_local std::vector<float> prefix, suffix, transposed, empty_row, ring;
  // Radius 1 along the rows of `r`: each pixel and its two neighbours.
  // A box as wide as the image is one run of memory: its inner pixels in
  // one call, each row's two ends (which that call mixed with the next
  // row's) set after it.
  const auto across_by_one = [&](const float* a, float* out, const cv::Rect& r) {
    const std::size_t width = static_cast<std::size_t>(r.width);
    const bool whole_rows = width == stride;
    if (whole_rows) {
      const std::size_t i0 = static_cast<std::size_t>(r.y) * stride;
      const std::size_t n = static_cast<std::size_t>(r.height) * width;
      min3(a + i0, a + i0 + 1, a + i0 + 2, out + i0 + 1, n - 2);
    }
    for (int y = r.y; y < r.y + r.height; ++y) {
      const std::size_t i0 = static_cast<std::size_t>(y) * stride + static_cast<std::size_t>(r.x);
      const std::size_t i1 = i0 + width - 1;  // width >= 2 here
      if (width > 2 && !whole_rows) min3(a + i0, a + i0 + 1, a + i0 + 2, out + i0 + 1, width - 2);
      out[i0] = std::min(a[i0], a[i0 + 1]);
      out[i1] = std::min(a[i1 - 1], a[i1]);
    }
  };
  // Radius 1 down the columns of `r`: each row and the rows above and below it.
  const auto down_by_one = [&](const float* a, float* out, const cv::Rect& r) {
    const std::size_t width = static_cast<std::size_t>(r.width);
    const auto row = [&](int y) { return static_cast<std::size_t>(y) * stride + static_cast<std::size_t>(r.x); };
    const int last = r.y + r.height - 1;  // r.height >= 2 here
    min3(a + row(r.y), a + row(r.y + 1), a + row(r.y + 1), out + row(r.y), width);
    min3(a + row(last - 1), a + row(last), a + row(last), out + row(last), width);
    if (width == stride) {  // the inner rows are one run of memory
      if (last > r.y + 1) min3(a + row(r.y), a + row(r.y + 1), a + row(r.y + 2), out + row(r.y + 1), row(last) - row(r.y + 1));
      return;
    }
    for (int y = r.y + 1; y < last; ++y) min3(a + row(y - 1), a + row(y), a + row(y + 1), out + row(y), width);
  };
  // Radius d down the columns of `r`, in place (van Herk / Gil-Werman): the
  // column padded by d empty pixels at each end is cut into blocks of 2 d + 1;
  // a window of 2 d + 1 meets at most two blocks, so its minimum is the
  // suffix minimum of its first pixel's block and the prefix minimum of its
  // last one's. Three passes whatever d, a row of minima at a time.
  const auto down_by = [&](float* a, std::size_t line_stride, const cv::Rect& r, int d) {
    const std::size_t width = static_cast<std::size_t>(r.width);
    const std::size_t n_rows = static_cast<std::size_t>(r.height);
    const std::size_t pad = static_cast<std::size_t>(d);
    const std::size_t block = 2 * pad + 1;
    const std::size_t padded = n_rows + 2 * pad;
    if (prefix.size() < padded * width) prefix.resize(padded * width);
    if (suffix.size() < padded * width) suffix.resize(padded * width);
    if (empty_row.size() < width) empty_row.resize(width, kEmpty);
    float* const first = a + static_cast<std::size_t>(r.y) * line_stride + static_cast<std::size_t>(r.x);
    const auto row = [&](std::size_t p) -> const float* {
      return p >= pad && p < n_rows + pad ? first + (p - pad) * line_stride : empty_row.data();
    };
    for (std::size_t p = 0; p < padded; ++p) {
      float* g = prefix.data() + p * width;
      if (p % block == 0) {
        std::copy_n(row(p), width, g);
      } else {
        min3(g - width, row(p), row(p), g, width);
      }
    }
    for (std::size_t p = padded; p-- > 0;) {
      float* h = suffix.data() + p * width;
      if (p % block == block - 1 || p == padded - 1) {
        std::copy_n(row(p), width, h);
      } else {
        min3(h + width, row(p), row(p), h, width);
      }
    }
    for (std::size_t y = 0; y < n_rows; ++y) {
      const float* h = suffix.data() + y * width;
      min3(h, prefix.data() + (y + block - 1) * width, h, first + y * line_stride, width);
    }
  };
  // The pixels outside `box` are empty, so the result is too beyond `box`
  // grown by the radii: only that rectangle is computed.
  const cv::Rect image_rect(0, 0, cols, rows);
  if (rx == 1 && ry == 1) {
    // The chain's usual step, a 3 x 3 minimum, in one pass and in place:
    // the minima along each row go through a ring of three rows, a row's
    // taken before the row is overwritten (it is needed by the row above's
    // output and its own). Half the memory traffic of a pass along the rows
    // and one down the columns, and no scratch: the image stays in cache.
    box = cv::Rect(box.x - 1, box.y - 1, box.width + 2, box.height + 2) & image_rect;
    const std::size_t width = static_cast<std::size_t>(box.width);
    if (ring.size() < 3 * width) ring.resize(3 * width);
    float* lines[3] = {ring.data(), ring.data() + width, ring.data() + 2 * width};
    // Row y's minima over x - 1, x, x + 1 for the box's columns (nothing beyond the image's sides).
    const auto row_minima = [&](int y, float* out) {
      const float* a = image.data() + static_cast<std::size_t>(y) * stride;
      const int x0 = box.x;
      const int x1 = box.x + box.width - 1;
      const int inner0 = std::max(x0, 1);
      const int inner1 = std::min(x1, cols - 2);
      if (inner1 >= inner0) {
        min3(a + inner0 - 1, a + inner0, a + inner0 + 1, out + (inner0 - x0), static_cast<std::size_t>(inner1 - inner0 + 1));
      }
      for (const int x : {x0, x1}) {
        if (x >= inner0 && x <= inner1) continue;
        float m = a[x];
        if (x > 0) m = std::min(m, a[x - 1]);
        if (x + 1 < cols) m = std::min(m, a[x + 1]);
        out[x - x0] = m;
      }
    };
    // The rows just outside the box are empty (or beyond the image): they add nothing.
    std::fill_n(lines[0], width, kEmpty);
    row_minima(box.y, lines[1]);
    const int last = box.y + box.height - 1;
    for (int y = box.y; y <= last; ++y) {
      if (y < last) {
        row_minima(y + 1, lines[2]);
      } else {
        std::fill_n(lines[2], width, kEmpty);
      }
      min3(lines[0], lines[1], lines[2], image.data() + static_cast<std::size_t>(y) * stride + box.x, width);
      std::rotate(lines, lines + 1, lines + 3);
    }
    return box;
  }
  constexpr int kStepped = 3;  // small radii as repeated steps of 1 (one pass each), larger in three
  if (rx > 0) {
    box = cv::Rect(box.x - rx, box.y, box.width + 2 * rx, box.height) & image_rect;
    if (rx <= kStepped) {
      ready_scratch();
      for (int k = 0; k < rx; ++k) {
        across_by_one(image.data(), scratch.data(), box);
        image.swap(scratch);  // both stay empty outside the (growing) box
      }
    } else {
      if (transposed.size() < image.size()) transposed.resize(image.size());
      cv::Mat source = cv::Mat(rows, cols, CV_32F, image.data())(box);
      cv::Mat columns(box.width, box.height, CV_32F, transposed.data());
      cv::transpose(source, columns);
      down_by(transposed.data(), static_cast<std::size_t>(box.height), cv::Rect(0, 0, box.height, box.width), rx);
      cv::transpose(columns, source);
    }
  }
  if (ry > 0) {
    box = cv::Rect(box.x, box.y - ry, box.width, box.height + 2 * ry) & image_rect;
    if (ry <= kStepped) {
      ready_scratch();
      for (int k = 0; k < ry; ++k) {
        down_by_one(image.data(), scratch.data(), box);
        image.swap(scratch);
      }
    } else {
      down_by(image.data(), stride, box, ry);
    }
  }
  return box;
}

void erode_rect(std::vector<float>& image, int rows, int cols, int rx, int ry) {
  std::vector<float> scratch;  // filled if a step needs it
  erode_rect(image, scratch, rows, cols, cv::Rect(0, 0, cols, rows), rx, ry);
}

cv::Mat dilate_depth_map(const cv::Mat& depth, const DilationParams& p) {
  const int n = static_cast<int>(p.layer_radius_px.size());
  CV_Assert(depth.type() == CV_32F && depth.isContinuous() && n >= 1);
  const int pixels = static_cast<int>(depth.total());
  const float* value = depth.ptr<float>();

  bool nested = p.shape == StructuringShape::square;
  for (int s = 1; s < n; ++s) {
    nested = nested && p.layer_radius_px[s].width <= p.layer_radius_px[s - 1].width &&
             p.layer_radius_px[s].height <= p.layer_radius_px[s - 1].height;
  }
  cv::Mat out(depth.size(), CV_32F);
  // The pixels of each layer as runs along the rows (a layer is a range of
  // depths, so neighbours mostly share one): the runs of each row, then a
  // counting sort of the runs on their layer. Sorting runs rather than
  // pixels is what keeps this cheap: a counter bumped once per pixel waits
  // on its own last store whenever neighbours share a layer.
  // Each pixel's layer is looked up once, as the runs are cut.
  const LayerLookup layer_of(p);
  thread_local std::vector<LayerRun> runs, sorted;
  runs.clear();
  for (int y = 0; y < depth.rows; ++y) {
    const int row_start = y * depth.cols;
    int x = 0;
    int s = depth.cols > 0 ? layer_of(value[row_start]) : 0;
    while (x < depth.cols) {
      int end = x + 1;
      int next = 0;
      while (end < depth.cols && (next = layer_of(value[row_start + end])) == s) ++end;
      if (s > 0) runs.push_back({row_start + x, end - x, y, s});
      x = end;
      s = next;
    }
  }
  std::vector<int> start(n + 2, 0);
  for (const LayerRun& run : runs) ++start[run.layer + 1];
  for (int s = 1; s <= n + 1; ++s) start[s] += start[s - 1];
  sorted.resize(runs.size());
  {
    std::vector<int> next(start.begin(), start.end() - 1);
    for (const LayerRun& run : runs) sorted[static_cast<std::size_t>(next[run.layer]++)] = run;
  }
  const auto layer_runs = [&](int s) {
    return std::span<const LayerRun>(sorted.data() + start[s], sorted.data() + start[s + 1]);
  };
  if (nested) {
    // Square elements that shrink with depth, nearest layer first: the
    // dilation is the minimum over layers s of E(r_s) applied to layer s's
    // pixels alone (E(r): the minimum filter with a (2 rx + 1) x (2 ry + 1)
    // rectangle, nothing beyond the border). Rectangles add: E(a) E(b) =
    // E(a + b), and E distributes over the minimum, so with r_1 >= r_2 >= ...
    // the whole is one chain, Horner's way:
    //   acc = layer 1; acc = min(E(r_1 - r_2) acc, layer 2); ...; E(r_n) acc,
    // which applies to layer s exactly the sum of the steps after it, r_s.
    // Each step is a few passes of vector minima over the image (E with a
    // radius of 1 is one pass, a larger one three), and empty layers take
    // no step of their own (their steps add up into the next).
    // Radii beyond the image change nothing: clipped to its size.
    const auto clip = [](int r, int size) { return std::clamp(r, 0, std::max(size - 1, 0)); };
    // Only the rectangle that holds the obstacles so far, grown by each step,
    // is computed; the rest is still empty.
    thread_local std::vector<float> acc, scratch;
    acc.assign(static_cast<std::size_t>(pixels), kEmpty);
    scratch.clear();  // filled by erode_rect if a step needs it
    cv::Rect box;
    int last_rx = -1;
    int last_ry = -1;
    for (int s = 1; s <= n; ++s) {
      const std::span<const LayerRun> members = layer_runs(s);
      if (members.empty()) continue;
      const int rx = clip(p.layer_radius_px[s - 1].width, depth.cols);
      const int ry = clip(p.layer_radius_px[s - 1].height, depth.rows);
      if (last_rx >= 0) box = erode_rect(acc, scratch, depth.rows, depth.cols, box, last_rx - rx, last_ry - ry);
      int x0 = box.empty() ? depth.cols : box.x;
      int y0 = box.empty() ? depth.rows : box.y;
      int x1 = box.empty() ? -1 : box.x + box.width - 1;
      int y1 = box.empty() ? -1 : box.y + box.height - 1;
      for (const LayerRun& run : members) {
        float* a = acc.data() + run.first;
        const float* v = value + run.first;
        for (int k = 0; k < run.length; ++k) a[k] = std::min(a[k], v[k]);
        const int x = run.first - run.row * depth.cols;
        x0 = std::min(x0, x);
        x1 = std::max(x1, x + run.length - 1);
        y0 = std::min(y0, run.row);
        y1 = std::max(y1, run.row);
      }
      box = cv::Rect(x0, y0, x1 - x0 + 1, y1 - y0 + 1);
      last_rx = rx;
      last_ry = ry;
    }
    if (last_rx >= 0) erode_rect(acc, scratch, depth.rows, depth.cols, box, last_rx, last_ry);
    float* o = out.ptr<float>();
    for (int i = 0; i < pixels; ++i) o[i] = std::min(acc[i], 1.0f);
    return out;
  }

  out.setTo(1.0f);
  const cv::Rect image(0, 0, depth.cols, depth.rows);
  for (int s = 1; s <= n; ++s) {
    const std::span<const LayerRun> members = layer_runs(s);
    if (members.empty()) continue;
    cv::Rect box;
    for (const LayerRun& run : members) box |= cv::Rect(run.first - run.row * depth.cols, run.row, run.length, 1);
    const cv::Size r = p.layer_radius_px[s - 1];
    const cv::Rect roi =
        cv::Rect(box.x - r.width, box.y - r.height, box.width + 2 * r.width, box.height + 2 * r.height) & image;
    cv::Mat dilated(roi.size(), CV_32F, cv::Scalar(kEmpty));
    for (const LayerRun& run : members) {
      for (int i = run.first; i < run.first + run.length; ++i) {
        dilated.at<float>(run.row - roi.y, i - run.row * depth.cols - roi.x) = value[i];
      }
    }
    if (p.shape == StructuringShape::square) {
      erode_square(dilated, r);
    } else {
      dilated = erode_disc(dilated, r.width, r.height);
    }
    // Nearer layers hold smaller values, so "nearer overwrites farther" is the minimum.
    cv::Mat target = out(roi);
    cv::min(target, dilated, target);
  }
  return out;
}

std::string_view to_string(Visibility visibility) {
  static constexpr std::string_view kNames[] = {"visible", "invisible", "unreachable"};
  return kNames[static_cast<int>(visibility)];
}

double nearest_hit_m(const cv::Mat& depth, const DepthGrid& grid, const Eigen::Vector3d& point, double radius_m) {
  const double range = point.norm();
  const double deg = range > radius_m ? std::asin(radius_m / range) * kRadToDeg : 90.0;
  const Eigen::Vector2d centre = grid.project(point);
  const double rx = deg / grid.deg_per_col() + 1.0;
  const double ry = deg / grid.deg_per_row() + 1.0;
  const double half_diagonal = 0.5 * std::sqrt(2.0) * grid.pixel_rad();
  double nearest = std::numeric_limits<double>::infinity();
  const int y0 = std::max(0, static_cast<int>(std::ceil(centre.y() - ry - 0.5)));
  const int y1 = std::min(depth.rows - 1, static_cast<int>(std::floor(centre.y() + ry + 0.5)));
  const int x0 = std::max(0, static_cast<int>(std::ceil(centre.x() - rx - 0.5)));
  const int x1 = std::min(depth.cols - 1, static_cast<int>(std::floor(centre.x() + rx + 0.5)));
  if (y1 < y0 || x1 < x0) return nearest;
  // DepthGrid::direction's angles once per column and row of the window, not
  // per pixel: a point within radius_m of the sensor spans the whole image,
  // and the waypoint search asks for many (the products are direction's own).
  thread_local std::vector<double> cos_az, sin_az;
  cos_az.resize(static_cast<std::size_t>(x1 - x0 + 1));
  sin_az.resize(cos_az.size());
  for (int x = x0; x <= x1; ++x) {
    const double az = (0.5 * grid.fov_h_deg - (x + 0.5) * grid.deg_per_col()) * kDegToRad;
    cos_az[static_cast<std::size_t>(x - x0)] = std::cos(az);
    sin_az[static_cast<std::size_t>(x - x0)] = std::sin(az);
  }
  // Rounding allowance of the bound below, so that no pixel it skips could have lowered the result.
  const double slack = 1e-9 * std::max(1.0, range);
  for (int y = y0; y <= y1; ++y) {
    const float* row = depth.ptr<float>(y);
    const double el = (0.5 * grid.fov_v_deg - (y + 0.5) * grid.deg_per_row()) * kDegToRad;
    const double cos_el = std::cos(el);
    const double sin_el = std::sin(el);
    for (int x = x0; x <= x1; ++x) {
      if (row[x] >= 1.0f) continue;
      const double d = row[x] * grid.max_range_m;
      // A hit at range d is at least |d - range| from the point (triangle inequality).
      if (std::abs(d - range) - half_diagonal * d - slack >= std::min(nearest, radius_m)) continue;
      const std::size_t i = static_cast<std::size_t>(x - x0);
      const Eigen::Vector3d direction(cos_el * cos_az[i], cos_el * sin_az[i], sin_el);
      const double gap = (direction * d - point).norm() - half_diagonal * d;
      if (gap < radius_m) nearest = std::min(nearest, gap);
    }
  }
  return nearest;
}

VisibilityCheck check_visibility(const cv::Mat& dilated, const DepthGrid& grid, const Eigen::Vector3d& w,
                                 double r, double extra_px, double depth_margin_m, const cv::Mat* depth) {
  VisibilityCheck c;
  c.waypoint_range_m = w.norm();
  c.pixel = grid.project(w);
  c.obstacle_range_m = grid.max_range_m;
  if (c.waypoint_range_m <= r) {
    c.visibility = Visibility::visible;  // the sensor is inside the safety sphere
    return c;
  }
  const Eigen::Vector2d radius = (projected_radius_px(grid, r, c.waypoint_range_m).array() + extra_px).cwiseMax(0.0);
  c.radius_x_px = radius.x();
  c.radius_y_px = radius.y();
  const std::optional<float> m = min_in_ellipse(dilated, c.pixel, radius.x(), radius.y());
  if (!m) {
    c.in_view = false;
    c.visibility = Visibility::invisible;
    return c;
  }
  c.obstacle_range_m = std::min(1.0, static_cast<double>(*m)) * grid.max_range_m;
  const double rho = c.waypoint_range_m;
  const double range = c.obstacle_range_m;
  const double keep = r + depth_margin_m;
  if (*m >= 1.0f || range - rho > keep) {
    c.visibility = Visibility::visible;
  } else if (depth_margin_m > 0.0 && depth && range - rho > -r) {
    // Within the margin of W's depth: a dilated obstacle may lie behind W or
    // beside it (the dilation and the neighbourhood together span more than
    // the margin); what the scan hit near W says which.
    c.visibility = nearest_hit_m(*depth, grid, w, keep) >= keep ? Visibility::visible : Visibility::unreachable;
  } else if (depth_margin_m > 0.0 && range - rho > r) {
    c.visibility = Visibility::unreachable;  // beyond W by r, not by r + the margin
  } else if (std::abs(rho - range) < r) {
    c.visibility = Visibility::unreachable;
  } else {
    c.visibility = Visibility::invisible;
  }
  return c;
}

namespace {

// value_at_direction for one grid, its constants worked out once (a segment
// asks it at every step).
class PixelLookup {
 public:
  explicit PixelLookup(const DepthGrid& grid)
      : grid_(grid),
        half_fov_h_rad_(0.5 * grid.fov_h_deg * kDegToRad),
        half_fov_v_rad_(0.5 * grid.fov_v_deg * kDegToRad),
        cols_per_rad_(1.0 / (grid.deg_per_col() * kDegToRad)),
        rows_per_rad_(1.0 / (grid.deg_per_row() * kDegToRad)),
        sure_x_(kSureRad * cols_per_rad_),
        sure_y_(kSureRad * rows_per_rad_) {}

  std::optional<float> operator()(const cv::Mat& image, const Eigen::Vector3d& d) const {
    // DepthGrid::project from floats: fast_atan2 is within 6e-9 rad
    // of the arctangent of its float arguments, and their rounding to float
    // (the horizontal length's too) moves the angle by a few 1e-7 rad at
    // most; so the angles are within 1e-6 rad, and a pixel boundary more than
    // kSureRad from them is on the same side of the exact angle: the pixels
    // read are project's. Nearer a boundary, project decides. (The products
    // with the pitches' reciprocals err by ulps of a pixel, nothing beside
    // that margin.)
    const float xf = static_cast<float>(d.x());
    const float yf = static_cast<float>(d.y());
    const float zf = static_cast<float>(d.z());
    const float horizontal = static_cast<float>(
        std::sqrt(static_cast<double>(xf) * xf + static_cast<double>(yf) * yf));
    // Pixel k spans [k, k + 1) in these (project puts its centre at k).
    const double cx = (half_fov_h_rad_ - fast_atan2(yf, xf)) * cols_per_rad_;
    const double cy = (half_fov_v_rad_ - fast_atan2(zf, horizontal)) * rows_per_rad_;
    const double fx = cx - std::floor(cx);  // boundaries at whole numbers of these
    const double fy = cy - std::floor(cy);
    if (!(fx > sure_x_ && fx < 1.0 - sure_x_ && fy > sure_y_ && fy < 1.0 - sure_y_)) {
      return min_in_ellipse(image, grid_.project(d), 0.0, 0.0);
    }
    const int x = static_cast<int>(std::floor(cx));
    const int y = static_cast<int>(std::floor(cy));
    if (x < 0 || y < 0 || x >= image.cols || y >= image.rows) return std::nullopt;
    return image.at<float>(y, x);
  }

 private:
  static constexpr double kSureRad = 1.0e-5;
  const DepthGrid& grid_;
  double half_fov_h_rad_, half_fov_v_rad_;
  double cols_per_rad_, rows_per_rad_;  // pixels per radian of azimuth, of elevation
  double sure_x_, sure_y_;              // kSureRad in pixels
};

}  // namespace

std::optional<float> value_at_direction(const cv::Mat& image, const DepthGrid& grid, const Eigen::Vector3d& d) {
  return PixelLookup(grid)(image, d);
}

bool segment_clear(const cv::Mat& dilated, const DepthGrid& grid, const Eigen::Vector3d& from,
                   const Eigen::Vector3d& to, double depth_margin_m, double min_range_m, const cv::Mat* depth) {
  const Eigen::Vector3d along = to - from;
  const double length = along.norm();
  // Steps of at most half the finer pitch as seen from the sensor: a point
  // at range d moves across the line of sight by at most the step.
  const double half_px_rad = 0.5 * std::min(grid.deg_per_col(), grid.deg_per_row()) * kDegToRad;
  const PixelLookup value_at(grid);
  constexpr int kMaxSteps = 100000;
  double t = 0.0;  // metres from `from`
  for (int step = 0; step < kMaxSteps; ++step) {
    const Eigen::Vector3d p = length > 0.0 ? from + along * (t / length) : from;
    const double range = p.norm();
    if (range >= min_range_m) {
      const std::optional<float> m = value_at(dilated, p);
      if (!m) return false;  // out of view: nothing vouches for it
      const double obstacle_m = *m * grid.max_range_m;
      if (*m < 1.0f && obstacle_m - range <= depth_margin_m) {
        // Nearer than P along its line of sight (occluded, or passing too
        // near), or within the margin behind it unless the hits there are not.
        if (obstacle_m <= range || !depth || nearest_hit_m(*depth, grid, p, depth_margin_m) < depth_margin_m) return false;
      }
    }
    if (t >= length) return true;
    t = std::min(length, t + std::max(1e-3, half_px_rad * std::max(range, min_range_m)));
  }
  return false;
}

Eigen::Vector3d after_altitude_check(const Eigen::Vector3d& from, const Eigen::Vector3d& to, const Eigen::Vector3d& up,
                                     double max_elevation_deg, double tolerance_m) {
  const Eigen::Vector3d delta = to - from;
  const double dz = delta.dot(up);
  const double allowed = std::tan(max_elevation_deg * kDegToRad) * (delta - dz * up).norm();
  if (std::abs(dz) <= allowed + tolerance_m) return from;
  return from + (dz - std::copysign(allowed, dz)) * up;
}

double blind_leg_m(double margin_m, double half_fov_deg, double mount_ahead_m) {
  // An obstacle O within the margin of the leg point s metres ahead of the
  // centre lies at most margin_m across and s - mount_ahead_m + margin_m
  // along from the sensor (O = P(s) + v, |v| <= margin_m); out of view, its
  // distance along is less than cot(half_fov) times its distance across,
  // which with |v| <= margin_m needs s < mount_ahead_m + margin_m / sin(half_fov).
  return std::max(0.0, mount_ahead_m) + margin_m / std::sin(std::clamp(half_fov_deg, 1.0, 90.0) * kDegToRad);
}

cv::Mat threshold_free(const cv::Mat& dilated, double threshold) {
  cv::Mat binary;
  cv::threshold(dilated, binary, threshold, 255.0, cv::THRESH_BINARY);
  binary.convertTo(binary, CV_8U);
  return binary;
}

std::vector<Eigen::Vector2i> obstacle_border(const cv::Mat& free) {
  CV_Assert(free.type() == CV_8U);
  std::vector<Eigen::Vector2i> border;
  for (int y = 0; y < free.rows; ++y) {
    const std::uint8_t* row = free.ptr<std::uint8_t>(y);
    const std::uint8_t* above = y > 0 ? free.ptr<std::uint8_t>(y - 1) : nullptr;
    const std::uint8_t* below = y + 1 < free.rows ? free.ptr<std::uint8_t>(y + 1) : nullptr;
    // A free pixel with an obstacle beside, above or below it (none beyond the image).
    const auto on_border = [&](int x) {
      return row[x] &&
             ((x > 0 && !row[x - 1]) || (x + 1 < free.cols && !row[x + 1]) || (above && !above[x]) || (below && !below[x]));
    };
    int x = 0;
#if defined(__x86_64__)
    // Sixteen pixels with both side neighbours in the image at a time (SSE2,
    // which every x86-64 has): the same test on bytes, the pixels it marks
    // taken in order from the mask.
    if (free.cols > 0) {
      if (on_border(0)) border.emplace_back(0, y);
      x = 1;
    }
    const __m128i zero = _mm_setzero_si128();
    const auto blocked = [&](const std::uint8_t* p) {
      return _mm_cmpeq_epi8(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p)), zero);
    };
    for (; x + 17 <= free.cols; x += 16) {
      __m128i near = _mm_or_si128(blocked(row + x - 1), blocked(row + x + 1));
      if (above) near = _mm_or_si128(near, blocked(above + x));
      if (below) near = _mm_or_si128(near, blocked(below + x));
      unsigned mask = static_cast<unsigned>(_mm_movemask_epi8(_mm_andnot_si128(blocked(row + x), near)));
      while (mask) {
        border.emplace_back(x + std::countr_zero(mask), y);
        mask &= mask - 1;
      }
    }
#endif
    for (; x < free.cols; ++x) {
      if (on_border(x)) border.emplace_back(x, y);
    }
  }
  return border;
}

std::vector<Eigen::Vector2i> pixel_segment(const cv::Size& size, const Eigen::Vector2i& from,
                                           const Eigen::Vector2d& to) {
  // Far-away ends are pulled in along the segment so the integer end stays representable.
  constexpr double kFar = 1.0e5;
  Eigen::Vector2d end = to;
  const Eigen::Vector2d delta = end - from.cast<double>();
  if (delta.cwiseAbs().maxCoeff() > kFar) end = from.cast<double>() + delta * (kFar / delta.cwiseAbs().maxCoeff());
  cv::LineIterator it(size, cv::Point(from.x(), from.y()),
                      cv::Point(static_cast<int>(std::lround(end.x())), static_cast<int>(std::lround(end.y()))), 8);
  std::vector<Eigen::Vector2i> pixels;
  pixels.reserve(it.count);
  for (int i = 0; i < it.count; ++i, ++it) pixels.emplace_back(it.pos().x, it.pos().y);
  return pixels;
}

WaypointSearch find_waypoint(const cv::Mat& dilated, const DepthGrid& grid,
                             const Eigen::Vector2d& target_pixel, double target_range_norm,
                             double obstacle_range_norm, const FindWaypointParams& p,
                             std::span<const Eigen::Vector3d> avoid_sensor, const Eigen::Vector3d& origin_sensor,
                             const Eigen::Vector3d& up_sensor, const cv::Mat* depth) {
  WaypointSearch search;
  const Eigen::Vector3d target_sensor = grid.direction(target_pixel) * (target_range_norm * grid.max_range_m);
  // A waypoint the vehicle may fly to and turn at: its corridor from the
  // vehicle, and the start of the next leg that it will not see once turned
  // toward the target, keep the margin on this map.
  const auto clear = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return segment_clear(dilated, grid, a, b, p.depth_margin_m, p.depth_margin_m, depth);
  };
  // Where ControllaAltitudine takes the vehicle at `from` before it turns toward `to`.
  const auto climb = [&](const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
    return p.max_elevation_deg > 0.0
               ? after_altitude_check(from, to, up_sensor, p.max_elevation_deg, p.altitude_tolerance_m)
               : from;
  };
  const auto safe_to_use = [&](const Eigen::Vector3d& w) {
    if (p.depth_margin_m <= 0.0) return true;
    const Eigen::Vector3d start = climb(origin_sensor, w);
    if (!clear(origin_sensor, start) || !clear(start, w)) return false;
    if (p.next_leg_check_m <= 0.0) return true;
    const Eigen::Vector3d turn = climb(w, target_sensor);
    if (!clear(w, turn)) return false;
    const Eigen::Vector3d leg = target_sensor - turn;
    const double length = std::min(p.next_leg_check_m, leg.norm());
    return length <= 0.0 || clear(turn, turn + leg.normalized() * length);
  };
  search.threshold = std::min(0.5 * (target_range_norm + obstacle_range_norm), p.threshold_cap);
  // Candidates: free pixels next to the obstacle, cheapest first (ties by row, then column).
  std::vector<std::tuple<double, int, int>> candidates;
  for (const Eigen::Vector2i& q : obstacle_border(threshold_free(dilated, search.threshold))) {
    const int x = q.x();
    const int y = q.y();
    const double cost = (target_pixel - Eigen::Vector2d(x, y)).norm() + p.altitude_penalty * std::abs(target_pixel.y() - y);
    candidates.emplace_back(cost, y, x);
  }
  search.candidates = static_cast<int>(candidates.size());
  const std::size_t tries = std::min<std::size_t>(candidates.size(), static_cast<std::size_t>(p.max_candidates));
  std::partial_sort(candidates.begin(), candidates.begin() + static_cast<std::ptrdiff_t>(tries), candidates.end());

  for (std::size_t i = 0; i < tries; ++i) {
    const Eigen::Vector2i pixel(std::get<2>(candidates[i]), std::get<1>(candidates[i]));
    FoundWaypoint f;
    f.pixel = pixel;
    f.edge_pixel = pixel;
    f.edge_range_m = obstacle_range_norm * grid.max_range_m;
    for (const Eigen::Vector2i& q : pixel_segment(dilated.size(), pixel, target_pixel)) {
      const float v = dilated.at<float>(q.y(), q.x());
      if (v <= search.threshold) {
        f.edge_pixel = q;
        f.edge_range_m = v * grid.max_range_m;
        break;
      }
    }
    f.range_m = f.edge_range_m + p.vehicle_radius_m;
    // P touches the dilated obstacle, so the safety sphere of a waypoint on
    // P's ray would overlap it and ControllaVisibilita would reject it. Step
    // away from the edge until the sphere's projection is clear at the full
    // distance; failing that, take the step that allows the farthest waypoint.
    // Either way the new waypoint passes the check the planner applies next.
    const double full_range = f.range_m;
    const Eigen::Vector2d radius = projected_radius_px(grid, p.safety_radius_m, full_range);
    Eigen::Vector2d away = (pixel - f.edge_pixel).cast<double>();
    if (away.norm() < 0.5) away = pixel.cast<double>() - target_pixel;
    away /= std::max(away.norm(), 1e-9);
    const int max_steps = static_cast<int>(std::ceil(2.0 * radius.maxCoeff())) + 2;
    std::optional<std::pair<Eigen::Vector2i, double>> best;
    for (int k = 0; k <= max_steps; ++k) {
      const Eigen::Vector2d q = pixel.cast<double>() + k * away;
      const Eigen::Vector2i qi(static_cast<int>(std::lround(q.x())), static_cast<int>(std::lround(q.y())));
      if (qi.x() < 0 || qi.y() < 0 || qi.x() >= dilated.cols || qi.y() >= dilated.rows) break;
      std::optional<double> range = clear_range(dilated, grid, qi.cast<double>(), full_range, p.safety_radius_m,
                                                p.min_distance_m, kClearMarginPx, p.depth_margin_m, depth);
      if (range && !safe_to_use(grid.direction(qi.cast<double>()) * *range)) range.reset();
      if (range && (!best || *range > best->second)) best = {qi, *range};
      if (range && *range >= full_range) break;
    }
    if (!best) continue;
    f.waypoint_pixel = best->first;
    f.range_m = best->second;
    f.direction_sensor = grid.direction(best->first.cast<double>());
    const Eigen::Vector3d point = f.direction_sensor * f.range_m;
    if (std::any_of(avoid_sensor.begin(), avoid_sensor.end(),
                    [&](const Eigen::Vector3d& a) { return (a - point).norm() < p.safety_radius_m; })) {
      continue;
    }
    f.tried = static_cast<int>(i) + 1;
    search.found = f;
    break;
  }
  return search;
}

std::optional<double> clear_range(const cv::Mat& dilated, const DepthGrid& grid, const Eigen::Vector2d& pixel,
                                  double max_range_m, double safety_radius_m, double min_range_m, double extra_px,
                                  double depth_margin_m, const cv::Mat* depth) {
  // The projection grows as the range shrinks, so m only decreases: a few rounds settle it.
  double range = max_range_m;
  for (int round = 0; round < 16 && range >= min_range_m; ++round) {
    const Eigen::Vector2d radius = projected_radius_px(grid, safety_radius_m, range).array() + extra_px;
    const std::optional<float> m = min_in_ellipse(dilated, pixel, radius.x(), radius.y());
    if (!m) return std::nullopt;
    const double obstacle_m = *m * grid.max_range_m;
    const double keep = safety_radius_m + depth_margin_m;
    if (*m >= 1.0f || obstacle_m - range > keep) return range;
    if (obstacle_m - range > safety_radius_m && depth &&
        nearest_hit_m(*depth, grid, grid.direction(pixel) * range, keep) >= keep) {
      return range;
    }
    range = obstacle_m - keep - 1e-3;
  }
  return std::nullopt;
}

double free_fraction(const cv::Mat& dilated, const cv::Rect& region, double free_value) {
  const cv::Rect r = region & cv::Rect(0, 0, dilated.cols, dilated.rows);
  if (r.empty()) return 0.0;
  const cv::Mat free = dilated(r) > free_value;
  return static_cast<double>(cv::countNonZero(free)) / r.area();
}

cv::Rect navigable_region(const DepthGrid& grid, double sector_deg, double band_deg) {
  const Eigen::Vector2d centre = grid.project(Eigen::Vector3d::UnitX());
  const double half_cols = 0.5 * sector_deg / grid.deg_per_col();
  const double half_rows = band_deg / grid.deg_per_row();
  const int x0 = static_cast<int>(std::ceil(centre.x() - half_cols));
  const int x1 = static_cast<int>(std::floor(centre.x() + half_cols));
  const int y0 = static_cast<int>(std::ceil(centre.y() - half_rows));
  const int y1 = static_cast<int>(std::floor(centre.y() + half_rows));
  return cv::Rect(x0, y0, std::max(1, x1 - x0 + 1), std::max(1, y1 - y0 + 1)) &
         cv::Rect(0, 0, grid.cols, grid.rows);
}

}  // namespace campo
