#pragma once
/// Drawing primitives shared by the report figures (render/figures.hpp lists them):
/// text, axes, markers, dashed lines, legends and colour bars. Private to
/// render/. All drawing is anti-aliased with sub-pixel coordinates; a point
/// is in drawing coordinates, where pixel centres are integers.
#include <functional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace campo::figure {

/// BGR scalar from 8-bit RGB components.
inline cv::Scalar rgb(int r, int g, int b) { return {double(b), double(g), double(r)}; }
/// `c` with its components scaled by `k` (k < 1 darkens).
cv::Scalar shade(const cv::Scalar& c, double k);
/// `c` mixed with white: t = 0 gives c, t = 1 white.
cv::Scalar lighten(const cv::Scalar& c, double t);

inline const cv::Scalar kWhite = rgb(255, 255, 255);
inline const cv::Scalar kInk = rgb(34, 34, 34);         ///< text, frames, ticks
inline const cv::Scalar kMutedInk = rgb(110, 110, 110); ///< secondary text, box borders
inline const cv::Scalar kGridInk = rgb(228, 228, 228);  ///< grid lines

struct Font {
  int face = cv::FONT_HERSHEY_SIMPLEX;
  double scale = 0.5;
  int thickness = 1;
};
inline const Font kTitleFont{cv::FONT_HERSHEY_DUPLEX, 0.8, 1};
inline const Font kLabelFont{cv::FONT_HERSHEY_SIMPLEX, 0.55, 1};
inline const Font kTickFont{cv::FONT_HERSHEY_SIMPLEX, 0.45, 1};
inline const Font kSmallFont{cv::FONT_HERSHEY_SIMPLEX, 0.4, 1};
inline const Font kLegendFont{cv::FONT_HERSHEY_SIMPLEX, 0.5, 1};

/// Drawing coordinates -> the fixed-point form the cv:: drawing calls take with kShift.
inline constexpr int kShift = 4;
cv::Point fixed(const cv::Point2d& p);
std::vector<cv::Point> fixed(const std::vector<cv::Point2d>& points);

enum class Align { left, centre, right };

/// Width and cap height of `text`, pixels.
cv::Size text_size(const std::string& text, const Font& font);
/// Text whose cap height is vertically centred on `anchor.y`; `halo` draws a
/// white outline first so the text reads over lines and shading.
void put_text(cv::Mat& image, const std::string& text, cv::Point2d anchor, const Font& font,
              const cv::Scalar& color, Align align = Align::left, bool halo = false);
/// Text rotated 90 degrees counter-clockwise (reading upwards), centred on `centre`.
void put_text_vertical(cv::Mat& image, const std::string& text, cv::Point2d centre, const Font& font,
                       const cv::Scalar& color);
/// A title centred in `band`, scaled down if it would not fit.
void put_title(cv::Mat& image, const std::string& title, const cv::Rect& band);

/// Tick step of 1, 2 or 5 times a power of ten near `span / target_count`.
double nice_step(double span, double target_count);
/// `value` with as many decimals as `step` needs ("-0" printed as "0").
std::string format_number(double value, double step);

/// Linear mapping of a data rectangle onto a plot rectangle (y up).
struct PlotFrame {
  cv::Rect plot_px;
  double x0 = 0.0, x1 = 1.0;  ///< data x at the left and right edges
  double y0 = 0.0, y1 = 1.0;  ///< data y at the bottom and top edges
  cv::Point2d to_px(double x, double y) const;
};

/// Light grid lines at the tick positions (drawn before the content).
void draw_grid(cv::Mat& image, const PlotFrame& frame);
/// Frame, outward ticks with labels and axis titles (drawn after the content).
void draw_axes(cv::Mat& image, const PlotFrame& frame, const std::string& x_label, const std::string& y_label);
/// Pixel spacing the axes aim for between ticks.
inline constexpr double kTickSpacingPx = 100.0;

/// Solid polyline.
void polyline(cv::Mat& image, const std::vector<cv::Point2d>& points, const cv::Scalar& color, int thickness);
/// Dashed polyline; the dash pattern runs on across vertices.
void dashed_polyline(cv::Mat& image, const std::vector<cv::Point2d>& points, const cv::Scalar& color,
                     int thickness, double dash_px, double gap_px);

// Map markers, used both on the plots and in the legends.
void start_marker(cv::Mat& image, cv::Point2d p);
void goal_marker(cv::Mat& image, cv::Point2d p, bool filled);
/// Numbered circle; `filled` for a reached waypoint. No number when `number` <= 0.
void waypoint_marker(cv::Mat& image, cv::Point2d p, int number, bool filled);
void diamond_marker(cv::Mat& image, cv::Point2d p, const cv::Scalar& color);
void cross_marker(cv::Mat& image, cv::Point2d p, const cv::Scalar& color);
/// Where the vehicle collided: a red disc with a white cross, haloed in white.
void collision_marker(cv::Mat& image, cv::Point2d p);
/// Its red.
inline const cv::Scalar kCollision = rgb(214, 39, 40);

/// One legend row: a symbol drawn around `centre` and its text.
struct LegendEntry {
  std::function<void(cv::Mat&, cv::Point2d centre)> symbol;
  std::string text;
};
/// Height of a legend box listing `count` entries, pixels.
int legend_height(std::size_t count);
/// White box with a border and one row per entry; texts are fitted to the box.
void draw_legend(cv::Mat& image, const cv::Rect& box, const std::vector<LegendEntry>& entries);

/// Vertical colour bar over [lo, hi] (bottom to top) with tick labels on its
/// right and `caption` above it; `color_of` maps a fraction in [0, 1] to BGR.
void draw_colorbar(cv::Mat& image, const cv::Rect& bar, double lo, double hi, const std::string& caption,
                   const std::function<cv::Vec3b(double)>& color_of);
/// Room a colour bar's caption needs above the bar, pixels.
inline constexpr int kColorbarCaptionPx = 28;

}  // namespace campo::figure
