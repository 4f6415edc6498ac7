#include "render/figure_canvas.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace campo::figure {

cv::Scalar shade(const cv::Scalar& c, double k) { return {c[0] * k, c[1] * k, c[2] * k}; }

cv::Scalar lighten(const cv::Scalar& c, double t) {
  return {c[0] + (255.0 - c[0]) * t, c[1] + (255.0 - c[1]) * t, c[2] + (255.0 - c[2]) * t};
}

cv::Point fixed(const cv::Point2d& p) {
  constexpr double k = 1 << kShift;
  return {static_cast<int>(std::lround(p.x * k)), static_cast<int>(std::lround(p.y * k))};
}

std::vector<cv::Point> fixed(const std::vector<cv::Point2d>& points) {
  std::vector<cv::Point> out;
  out.reserve(points.size());
  for (const auto& p : points) out.push_back(fixed(p));
  return out;
}

cv::Size text_size(const std::string& text, const Font& font) {
  int baseline = 0;
  return cv::getTextSize(text, font.face, font.scale, font.thickness, &baseline);
}

namespace {

int fixed_radius(double r) { return static_cast<int>(std::lround(r * (1 << kShift))); }

void circle(cv::Mat& image, cv::Point2d c, double r, const cv::Scalar& color, int thickness) {
  cv::circle(image, fixed(c), fixed_radius(r), color, thickness, cv::LINE_AA, kShift);
}

void closed_outline(cv::Mat& image, const std::vector<cv::Point2d>& points, const cv::Scalar& color, int thickness) {
  cv::polylines(image, fixed(points), true, color, thickness, cv::LINE_AA, kShift);
}

void fill(cv::Mat& image, const std::vector<cv::Point2d>& points, const cv::Scalar& color) {
  const std::vector<std::vector<cv::Point>> polygons{fixed(points)};
  cv::fillPoly(image, polygons, color, cv::LINE_AA, kShift);
}

// Multiples of `step` in [lo, hi]; none when there would be more than a
// figure can show (a degenerate or non-finite axis must not allocate without bound).
std::vector<double> ticks_in(double lo, double hi, double step) {
  constexpr double kMaxTicks = 1000.0;
  std::vector<double> ticks;
  const double first = std::ceil(lo / step - 1e-9), last = std::floor(hi / step + 1e-9);
  if (!std::isfinite(first) || !std::isfinite(last) || last - first > kMaxTicks) return ticks;
  for (double k = first; k <= last; k += 1.0) ticks.push_back(k * step);
  return ticks;
}

// `text` cut and ended with "..." so that it is at most `max_width_px` wide.
// The longest prefix that fits is found by bisection: titles come from
// scene names, which may be megabytes long.
std::string fit_text(const std::string& text, const Font& font, int max_width_px) {
  if (text.size() <= 4096 && text_size(text, font).width <= max_width_px) return text;
  std::size_t fits = 0, too_long = std::min<std::size_t>(text.size(), 4096) + 1;
  while (too_long - fits > 1) {
    const std::size_t mid = fits + (too_long - fits) / 2;
    (text_size(text.substr(0, mid) + "...", font).width <= max_width_px ? fits : too_long) = mid;
  }
  return text.substr(0, fits) + "...";
}

}  // namespace

void put_text(cv::Mat& image, const std::string& text, cv::Point2d anchor, const Font& font,
              const cv::Scalar& color, Align align, bool halo) {
  const cv::Size size = text_size(text, font);
  double x = anchor.x;
  if (align == Align::centre) x -= 0.5 * size.width;
  if (align == Align::right) x -= size.width;
  const cv::Point origin(static_cast<int>(std::lround(x)), static_cast<int>(std::lround(anchor.y + 0.5 * size.height)));
  if (halo) cv::putText(image, text, origin, font.face, font.scale, kWhite, font.thickness + 3, cv::LINE_AA);
  cv::putText(image, text, origin, font.face, font.scale, color, font.thickness, cv::LINE_AA);
}

void put_text_vertical(cv::Mat& image, const std::string& text, cv::Point2d centre, const Font& font,
                       const cv::Scalar& color) {
  // Draw the text as coverage into a small mask, rotate it, and blend the colour through it.
  int baseline = 0;
  const cv::Size size = cv::getTextSize(text, font.face, font.scale, font.thickness, &baseline);
  cv::Mat mask = cv::Mat::zeros(size.height + baseline + 4, size.width + 4, CV_8U);
  cv::putText(mask, text, {2, size.height + 2}, font.face, font.scale, cv::Scalar(255), font.thickness, cv::LINE_AA);
  cv::Mat rotated;
  cv::rotate(mask, rotated, cv::ROTATE_90_COUNTERCLOCKWISE);
  const int x0 = static_cast<int>(std::lround(centre.x - 0.5 * rotated.cols));
  const int y0 = static_cast<int>(std::lround(centre.y - 0.5 * rotated.rows));
  for (int r = 0; r < rotated.rows; ++r) {
    const int y = y0 + r;
    if (y < 0 || y >= image.rows) continue;
    for (int c = 0; c < rotated.cols; ++c) {
      const int x = x0 + c;
      if (x < 0 || x >= image.cols) continue;
      const double a = rotated.at<uchar>(r, c) / 255.0;
      auto& px = image.at<cv::Vec3b>(y, x);
      for (int k = 0; k < 3; ++k) px[k] = cv::saturate_cast<uchar>(px[k] * (1.0 - a) + color[k] * a);
    }
  }
}

void put_title(cv::Mat& image, const std::string& title, const cv::Rect& band) {
  Font font = kTitleFont;
  while (font.scale > 0.45 && text_size(title, font).width > band.width - 24) font.scale *= 0.92;
  const std::string text = fit_text(title, font, band.width - 24);
  put_text(image, text, {band.x + 0.5 * band.width, band.y + 0.5 * band.height}, font, kInk, Align::centre);
}

double nice_step(double span, double target_count) {
  const double raw = span / std::max(target_count, 1.0);
  if (!(raw > 0.0) || !std::isfinite(raw)) return 1.0;
  const double decade = std::pow(10.0, std::floor(std::log10(raw)));
  const double m = raw / decade;
  return (m < 1.5 ? 1.0 : m < 3.5 ? 2.0 : m < 7.5 ? 5.0 : 10.0) * decade;
}

std::string format_number(double value, double step) {
  const int decimals = std::max(0, static_cast<int>(std::ceil(-std::log10(step) - 1e-9)));
  if (std::abs(value) < 1e-6 * step) value = 0.0;
  char text[48];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

cv::Point2d PlotFrame::to_px(double x, double y) const {
  return {plot_px.x - 0.5 + (x - x0) / (x1 - x0) * plot_px.width,
          plot_px.y - 0.5 + plot_px.height - (y - y0) / (y1 - y0) * plot_px.height};
}

namespace {

double x_step(const PlotFrame& f) { return nice_step(f.x1 - f.x0, f.plot_px.width / kTickSpacingPx); }
double y_step(const PlotFrame& f) { return nice_step(f.y1 - f.y0, f.plot_px.height / kTickSpacingPx); }

}  // namespace

void draw_grid(cv::Mat& image, const PlotFrame& frame) {
  const cv::Rect& p = frame.plot_px;
  const double xs = x_step(frame), ys = y_step(frame);
  for (double x : ticks_in(frame.x0, frame.x1, xs)) {
    const double px = frame.to_px(x, frame.y0).x;
    cv::line(image, fixed({px, p.y - 0.5}), fixed({px, p.y + p.height - 0.5}), kGridInk, 1, cv::LINE_AA, kShift);
  }
  for (double y : ticks_in(frame.y0, frame.y1, ys)) {
    const double py = frame.to_px(frame.x0, y).y;
    cv::line(image, fixed({p.x - 0.5, py}), fixed({p.x + p.width - 0.5, py}), kGridInk, 1, cv::LINE_AA, kShift);
  }
}

void draw_axes(cv::Mat& image, const PlotFrame& frame, const std::string& x_label, const std::string& y_label) {
  const cv::Rect& p = frame.plot_px;
  cv::rectangle(image, {p.x - 1, p.y - 1}, {p.x + p.width, p.y + p.height}, kInk, 1, cv::LINE_8);
  const double xs = x_step(frame), ys = y_step(frame);
  const int bottom = p.y + p.height;
  for (double x : ticks_in(frame.x0, frame.x1, xs)) {
    const double px = frame.to_px(x, frame.y0).x;
    cv::line(image, fixed({px, bottom + 0.0}), fixed({px, bottom + 5.0}), kInk, 1, cv::LINE_AA, kShift);
    put_text(image, format_number(x, xs), {px, bottom + 17.0}, kTickFont, kInk, Align::centre);
  }
  int widest = 0;
  for (double y : ticks_in(frame.y0, frame.y1, ys)) {
    const double py = frame.to_px(frame.x0, y).y;
    const std::string label = format_number(y, ys);
    cv::line(image, fixed({p.x - 6.0, py}), fixed({p.x - 1.0, py}), kInk, 1, cv::LINE_AA, kShift);
    put_text(image, label, {p.x - 10.0, py}, kTickFont, kInk, Align::right);
    widest = std::max(widest, text_size(label, kTickFont).width);
  }
  put_text(image, x_label, {p.x + 0.5 * p.width, bottom + 42.0}, kLabelFont, kInk, Align::centre);
  put_text_vertical(image, y_label, {p.x - 10.0 - widest - 16.0, p.y + 0.5 * p.height}, kLabelFont, kInk);
}

void polyline(cv::Mat& image, const std::vector<cv::Point2d>& points, const cv::Scalar& color, int thickness) {
  if (points.size() < 2) return;
  cv::polylines(image, fixed(points), false, color, thickness, cv::LINE_AA, kShift);
}

void dashed_polyline(cv::Mat& image, const std::vector<cv::Point2d>& points, const cv::Scalar& color,
                     int thickness, double dash_px, double gap_px) {
  bool on = true;
  double left = dash_px;  // of the current dash or gap
  for (std::size_t i = 1; i < points.size(); ++i) {
    const cv::Point2d a = points[i - 1], d = points[i] - points[i - 1];
    const double length = std::hypot(d.x, d.y);
    for (double t = 0.0; t < length;) {
      const double step = std::min(left, length - t);
      if (on) cv::line(image, fixed(a + d * (t / length)), fixed(a + d * ((t + step) / length)), color, thickness, cv::LINE_AA, kShift);
      t += step;
      left -= step;
      if (left <= 1e-9) {
        on = !on;
        left = on ? dash_px : gap_px;
      }
    }
  }
}

void start_marker(cv::Mat& image, cv::Point2d p) {
  circle(image, p, 9.5, kWhite, cv::FILLED);
  circle(image, p, 7.5, rgb(44, 160, 44), cv::FILLED);
  circle(image, p, 7.5, rgb(20, 90, 20), 1);
}

void goal_marker(cv::Mat& image, cv::Point2d p, bool filled) {
  std::vector<cv::Point2d> star;
  for (int i = 0; i < 10; ++i) {
    const double a = -CV_PI / 2 + i * CV_PI / 5, r = i % 2 == 0 ? 13.0 : 5.5;
    star.push_back(p + cv::Point2d(r * std::cos(a), r * std::sin(a)));
  }
  const cv::Scalar red = rgb(214, 39, 40);
  closed_outline(image, star, kWhite, 4);
  fill(image, star, filled ? red : kWhite);
  closed_outline(image, star, filled ? shade(red, 0.55) : red, filled ? 1 : 2);
}

void waypoint_marker(cv::Mat& image, cv::Point2d p, int number, bool filled) {
  circle(image, p, 11.5, kWhite, cv::FILLED);
  circle(image, p, 9.5, filled ? kInk : kWhite, cv::FILLED);
  circle(image, p, 9.5, kInk, filled ? 1 : 2);
  if (number <= 0) return;
  const std::string text = std::to_string(number);
  Font font = kSmallFont;
  if (text_size(text, font).width > 15) font.scale = 0.32;
  put_text(image, text, p + cv::Point2d(0.5, 0.0), font, filled ? kWhite : kInk, Align::centre);
}

void diamond_marker(cv::Mat& image, cv::Point2d p, const cv::Scalar& color) {
  const std::vector<cv::Point2d> diamond{p + cv::Point2d(0, -7), p + cv::Point2d(7, 0), p + cv::Point2d(0, 7),
                                         p + cv::Point2d(-7, 0)};
  closed_outline(image, diamond, kWhite, 3);
  fill(image, diamond, color);
  closed_outline(image, diamond, shade(color, 0.55), 1);
}

void cross_marker(cv::Mat& image, cv::Point2d p, const cv::Scalar& color) {
  for (int pass = 0; pass < 2; ++pass) {
    for (const double s : {1.0, -1.0}) {
      cv::line(image, fixed(p + cv::Point2d(-6, -6 * s)), fixed(p + cv::Point2d(6, 6 * s)),
               pass == 0 ? kWhite : color, pass == 0 ? 5 : 2, cv::LINE_AA, kShift);
    }
  }
}

void collision_marker(cv::Mat& image, cv::Point2d p) {
  cv::circle(image, fixed(p), 9 << kShift, kWhite, cv::FILLED, cv::LINE_AA, kShift);
  cv::circle(image, fixed(p), 7 << kShift, kCollision, cv::FILLED, cv::LINE_AA, kShift);
  for (const double s : {1.0, -1.0}) {
    cv::line(image, fixed(p + cv::Point2d(-3.5, -3.5 * s)), fixed(p + cv::Point2d(3.5, 3.5 * s)), kWhite, 2,
             cv::LINE_AA, kShift);
  }
}

namespace {
constexpr int kLegendPadPx = 10;
constexpr int kLegendRowPx = 26;
}  // namespace

int legend_height(std::size_t count) { return 2 * kLegendPadPx + static_cast<int>(count) * kLegendRowPx; }

void draw_legend(cv::Mat& image, const cv::Rect& box, const std::vector<LegendEntry>& entries) {
  cv::rectangle(image, box, kWhite, cv::FILLED);
  cv::rectangle(image, box, kMutedInk, 1, cv::LINE_8);
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const double cy = box.y + kLegendPadPx + kLegendRowPx * (i + 0.5);
    entries[i].symbol(image, {box.x + 28.0, cy});
    put_text(image, fit_text(entries[i].text, kLegendFont, box.width - 62), {box.x + 54.0, cy}, kLegendFont, kInk);
  }
}

void draw_colorbar(cv::Mat& image, const cv::Rect& bar, double lo, double hi, const std::string& caption,
                   const std::function<cv::Vec3b(double)>& color_of) {
  for (int r = 0; r < bar.height; ++r) {
    const cv::Vec3b c = color_of(1.0 - (r + 0.5) / bar.height);
    cv::line(image, {bar.x, bar.y + r}, {bar.x + bar.width - 1, bar.y + r}, cv::Scalar(c[0], c[1], c[2]), 1, cv::LINE_8);
  }
  cv::rectangle(image, {bar.x - 1, bar.y - 1}, {bar.x + bar.width, bar.y + bar.height}, kInk, 1, cv::LINE_8);
  const double step = nice_step(hi - lo, bar.height / 45.0);
  for (double v : ticks_in(lo, hi, step)) {
    const double y = bar.y - 0.5 + bar.height - (v - lo) / (hi - lo) * bar.height;
    const double right = bar.x + bar.width;
    cv::line(image, fixed({right, y}), fixed({right + 5.0, y}), kInk, 1, cv::LINE_AA, kShift);
    put_text(image, format_number(v, step), {right + 9.0, y}, kTickFont, kInk);
  }
  put_text(image, caption, {bar.x - 1.0, bar.y - 18.0}, kLabelFont, kInk);
}

}  // namespace campo::figure
