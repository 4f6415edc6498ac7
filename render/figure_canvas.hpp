#pragma once
/// The figures' drawing surface and primitives (render/figures.hpp lists the
/// figures): a Canvas records cairo drawing calls once and writes them as PNG
/// (anti-aliased raster), PDF or SVG (vectors, text as text in PDF), so every
/// format comes from the same drawing code. Text, axes, markers, dashed
/// lines, legends and colour bars are drawn on it. A point is in drawing
/// coordinates, where pixel centres are integers (as in the PNG's pixel
/// indices); one drawing pixel is 0.75 pt (96 per inch) in PDF and SVG.
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

using cairo_t = struct _cairo;
using cairo_surface_t = struct _cairo_surface;

namespace campo::figure {

/// The file formats a figure is written in.
enum class FigureFormat { png, pdf, svg };
/// "png", "pdf", "svg".
const char* extension(FigureFormat format);
/// Formats named in a comma-separated list ("png,pdf"); std::invalid_argument
/// naming the list and the choices for an unknown or repeated name or an empty list.
std::vector<FigureFormat> parse_figure_formats(const std::string& list);

/// The files a figure asked for as `path` is written to, one per format: a
/// path ending in .png, .pdf or .svg (any case) has that extension replaced by
/// each format's ("fig.png" with png,pdf: fig.png and fig.pdf; with pdf alone:
/// fig.pdf); any other path gets the format's extension appended ("fig" and
/// "fig.v2" with pdf: fig.pdf and fig.v2.pdf), so no part of a name is lost.
std::vector<std::filesystem::path> figure_files(const std::filesystem::path& path,
                                                const std::vector<FigureFormat>& formats);

/// A font by size: `scale` 1 is a 22-pixel cap height (the scales of the
/// figures' former Hershey fonts, kept so their layouts hold).
struct Font {
  double scale = 0.5;
  bool bold = false;
};

/// A figure being drawn: cairo calls recorded on an unbounded recording
/// surface, replayed into the size given at construction for each output.
/// Move-only. Not thread-safe (one canvas per thread).
class Canvas {
 public:
  /// A white canvas of `size_px` (each side in [1, 32768]).
  explicit Canvas(cv::Size size_px);
  ~Canvas();
  Canvas(Canvas&& other) noexcept;
  Canvas& operator=(Canvas&& other) noexcept;
  Canvas(const Canvas&) = delete;
  Canvas& operator=(const Canvas&) = delete;

  cv::Size size() const { return size_; }

  /// Drawing clipped to `rect` with the origin moved to its top-left pixel,
  /// until the Region is destroyed (regions nest).
  class Region {
   public:
    ~Region();
    Region(const Region&) = delete;
    Region& operator=(const Region&) = delete;
   private:
    friend class Canvas;
    explicit Region(cairo_t* cr) : cr_(cr) {}
    cairo_t* cr_;
  };
  [[nodiscard]] Region region(const cv::Rect& rect);

  void line(cv::Point2d a, cv::Point2d b, const cv::Scalar& color, double width_px);
  void polyline(const std::vector<cv::Point2d>& points, const cv::Scalar& color, double width_px, bool closed = false);
  /// Dashed polyline; the dash pattern runs on across vertices.
  void dashed_polyline(const std::vector<cv::Point2d>& points, const cv::Scalar& color, double width_px,
                       double dash_px, double gap_px);
  void fill_polygon(const std::vector<cv::Point2d>& points, const cv::Scalar& color);
  void circle(cv::Point2d centre, double radius_px, const cv::Scalar& color, double width_px);
  void fill_circle(cv::Point2d centre, double radius_px, const cv::Scalar& color);
  /// The pixels of `rect` (pixel indices), outlined along their centres or filled whole.
  void rectangle(const cv::Rect& rect, const cv::Scalar& color, double width_px);
  void fill_rectangle(const cv::Rect& rect, const cv::Scalar& color);
  /// Axis-aligned box between two drawing points, filled.
  void fill_box(cv::Point2d a, cv::Point2d b, const cv::Scalar& color);
  /// A line from `tail` to `tip` with an open arrow head `head_fraction` of its length.
  void arrow(cv::Point2d tail, cv::Point2d tip, const cv::Scalar& color, double width_px, double head_fraction);
  /// Text with its baseline's left end at `origin`; `halo` outlines it in
  /// white first. `angle_deg` turns it counter-clockwise about `origin`.
  void text(const std::string& text, cv::Point2d origin, const Font& font, const cv::Scalar& color,
            bool halo = false, double angle_deg = 0.0);
  /// A raster (CV_8UC3 BGR, or CV_8UC4 BGRA with straight alpha) stretched over
  /// the pixels of `where`; `smooth` interpolates, otherwise each source pixel
  /// stays a sharp block.
  void image(const cv::Mat& bgr, const cv::Rect& where, bool smooth = false);

  /// The figure as pixels: CV_8UC3 BGR of size().
  cv::Mat raster() const;
  /// The figure encoded in `format` (PNG bytes, a PDF or an SVG document).
  /// Same drawing => same bytes.
  std::string encode(FigureFormat format) const;
  /// Writes figure_files(path, formats), each atomically; returns the files
  /// written (OutputError naming a file that could not be written).
  std::vector<std::filesystem::path> write(const std::filesystem::path& path,
                                           const std::vector<FigureFormat>& formats) const;

 private:
  cairo_surface_t* recording_ = nullptr;
  cairo_t* cr_ = nullptr;
  cv::Size size_;
};

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

inline const Font kTitleFont{0.8, true};
inline const Font kLabelFont{0.55};
inline const Font kTickFont{0.45};
inline const Font kSmallFont{0.4};
inline const Font kLegendFont{0.5};

enum class Align { left, centre, right };

/// Width and cap height of `text`, pixels.
cv::Size text_size(const std::string& text, const Font& font);
/// Text whose cap height is vertically centred on `anchor.y`; `halo` draws a
/// white outline first so the text reads over lines and shading.
void put_text(Canvas& canvas, const std::string& text, cv::Point2d anchor, const Font& font,
              const cv::Scalar& color, Align align = Align::left, bool halo = false);
/// Text rotated 90 degrees counter-clockwise (reading upwards), centred on `centre`.
void put_text_vertical(Canvas& canvas, const std::string& text, cv::Point2d centre, const Font& font,
                       const cv::Scalar& color);
/// A title centred in `band`, scaled down if it would not fit.
void put_title(Canvas& canvas, const std::string& title, const cv::Rect& band);

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
void draw_grid(Canvas& canvas, const PlotFrame& frame);
/// Frame, outward ticks with labels and axis titles (drawn after the content).
void draw_axes(Canvas& canvas, const PlotFrame& frame, const std::string& x_label, const std::string& y_label);
/// Pixel spacing the axes aim for between ticks.
inline constexpr double kTickSpacingPx = 100.0;


// Map markers, used both on the plots and in the legends.
void start_marker(Canvas& canvas, cv::Point2d p);
void goal_marker(Canvas& canvas, cv::Point2d p, bool filled);
/// Numbered circle; `filled` for a reached waypoint. No number when `number` <= 0.
void waypoint_marker(Canvas& canvas, cv::Point2d p, int number, bool filled);
void diamond_marker(Canvas& canvas, cv::Point2d p, const cv::Scalar& color);
void cross_marker(Canvas& canvas, cv::Point2d p, const cv::Scalar& color);
/// Where the vehicle collided: a red disc with a white cross, haloed in white.
void collision_marker(Canvas& canvas, cv::Point2d p);
/// Its red.
inline const cv::Scalar kCollision = rgb(214, 39, 40);

/// One legend row: a symbol drawn around `centre` and its text.
struct LegendEntry {
  std::function<void(Canvas&, cv::Point2d centre)> symbol;
  std::string text;
};
/// Height of a legend box listing `count` entries, pixels.
int legend_height(std::size_t count);
/// White box with a border and one row per entry; texts are fitted to the box.
void draw_legend(Canvas& canvas, const cv::Rect& box, const std::vector<LegendEntry>& entries);

/// Vertical colour bar over [lo, hi] (bottom to top) with tick labels on its
/// right and `caption` above it; `color_of` maps a fraction in [0, 1] to BGR.
void draw_colorbar(Canvas& canvas, const cv::Rect& bar, double lo, double hi, const std::string& caption,
                   const std::function<cv::Vec3b(double)>& color_of);
/// Room a colour bar's caption needs above the bar, pixels.
inline constexpr int kColorbarCaptionPx = 28;

}  // namespace campo::figure
