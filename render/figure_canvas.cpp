#include "render/figure_canvas.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cctype>
#include <cstring>
#include <string_view>
#include <stdexcept>
#include <utility>

#include "core/image_io.hpp"
#include "core/output_dir.hpp"
#include "render/cairo_api.hpp"

namespace campo::figure {

// ---- formats ---------------------------------------------------------------

const char* extension(FigureFormat format) {
  switch (format) {
    case FigureFormat::png: return "png";
    case FigureFormat::pdf: return "pdf";
    case FigureFormat::svg: return "svg";
  }
  return "png";
}

std::vector<FigureFormat> parse_figure_formats(const std::string& list) {
  std::vector<FigureFormat> formats;
  std::size_t begin = 0;
  while (begin <= list.size()) {
    const std::size_t end = std::min(list.find(',', begin), list.size());
    const std::string name = list.substr(begin, end - begin);
    FigureFormat format;
    if (name == "png") format = FigureFormat::png;
    else if (name == "pdf") format = FigureFormat::pdf;
    else if (name == "svg") format = FigureFormat::svg;
    else throw std::invalid_argument("figure format list '" + list + "': '" + name + "' is not one of png, pdf, svg");
    if (std::find(formats.begin(), formats.end(), format) != formats.end()) {
      throw std::invalid_argument("figure format list '" + list + "' names " + name + " twice");
    }
    formats.push_back(format);
    begin = end + 1;
  }
  return formats;
}

std::vector<std::filesystem::path> figure_files(const std::filesystem::path& path,
                                                const std::vector<FigureFormat>& formats) {
  std::string given = path.extension().string();
  for (char& c : given) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const bool figure_extension = given == ".png" || given == ".pdf" || given == ".svg";
  std::vector<std::filesystem::path> files;
  for (const FigureFormat format : formats) {
    std::filesystem::path file = path;
    if (figure_extension) {
      file.replace_extension(extension(format));
    } else {
      file += std::string(".") + extension(format);
    }
    files.push_back(std::move(file));
  }
  return files;
}

// ---- canvas ----------------------------------------------------------------

namespace {

// The figures' typeface; fonts-dejavu-core is one of campo's dependencies
// (tools/setup.sh), so the same text is laid out alike on every machine that builds it.
constexpr const char* kFontFamily = "DejaVu Sans";
// DejaVu Sans's cap height is 0.729 em: a Font of scale s has caps 22 s pixels tall.
constexpr double kCapHeightEm = 0.729;
constexpr double kCapPxPerScale = 22.0;
// One drawing pixel in PDF and SVG points: 96 pixels per inch.
constexpr double kPointsPerPx = 0.75;

double font_size_px(const Font& font) { return font.scale * kCapPxPerScale / kCapHeightEm; }

void select_font(cairo_t* cr, const Font& font) {
  cairo().select_font_face(cr, kFontFamily, CAIRO_FONT_SLANT_NORMAL,
                         font.bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo().set_font_size(cr, font_size_px(font));
}

void set_color(cairo_t* cr, const cv::Scalar& bgr) {
  cairo().set_source_rgb(cr, bgr[2] / 255.0, bgr[1] / 255.0, bgr[0] / 255.0);
}

void trace(cairo_t* cr, const std::vector<cv::Point2d>& points, bool closed) {
  cairo().new_path(cr);
  for (const auto& p : points) cairo().line_to(cr, p.x, p.y);
  if (closed) cairo().close_path(cr);
}

void stroke(cairo_t* cr, const cv::Scalar& color, double width_px) {
  set_color(cr, color);
  cairo().set_line_width(cr, width_px);
  cairo().stroke(cr);
}

// A context on a 1x1 surface for measuring text (one per thread: cairo
// contexts are not shared between threads).
cairo_t* measuring_context() {
  struct Holder {
    cairo_surface_t* surface = cairo().image_surface_create(CAIRO_FORMAT_RGB24, 1, 1);
    cairo_t* cr = cairo().create(surface);
    ~Holder() {
      cairo().destroy(cr);
      cairo().surface_destroy(surface);
    }
  };
  thread_local Holder holder;
  return holder.cr;
}

// Replays `recording` onto `target`, scaled by `scale`.
void replay(cairo_surface_t* recording, cairo_surface_t* target, double scale) {
  cairo_t* cr = cairo().create(target);
  cairo().scale(cr, scale, scale);
  cairo().set_source_surface(cr, recording, 0.0, 0.0);
  cairo().paint(cr);
  cairo().destroy(cr);
  cairo().surface_flush(target);
}

// cairo names an SVG's groups after its surfaces' process-wide serial numbers
// ("surface86"), which depend on what was drawn before in the process: renumbered
// in order of first appearance, the same figure gives the same bytes.
std::string renumber_svg_surfaces(const std::string& svg) {
  static constexpr std::string_view kPrefix = "surface";
  std::vector<std::pair<std::string, std::string>> renamed;  // cairo's number, ours
  std::string out;
  out.reserve(svg.size());
  std::size_t at = 0;
  for (std::size_t hit = svg.find(kPrefix); hit != std::string::npos; hit = svg.find(kPrefix, at)) {
    std::size_t end = hit + kPrefix.size();
    while (end < svg.size() && std::isdigit(static_cast<unsigned char>(svg[end]))) ++end;
    out.append(svg, at, end - at);
    at = end;
    if (end == hit + kPrefix.size()) continue;  // the word alone
    const std::string number = svg.substr(hit + kPrefix.size(), end - hit - kPrefix.size());
    auto it = std::find_if(renamed.begin(), renamed.end(), [&](const auto& r) { return r.first == number; });
    if (it == renamed.end()) it = renamed.insert(renamed.end(), {number, std::to_string(renamed.size() + 1)});
    out.resize(out.size() - number.size());
    out += it->second;
  }
  out.append(svg, at, std::string::npos);
  return out;
}

cairo_status_t append_to_string(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

}  // namespace

Canvas::Canvas(cv::Size size_px) : size_(size_px) {
  if (size_px.width < 1 || size_px.height < 1 || size_px.width > 32768 || size_px.height > 32768) {
    throw std::invalid_argument("figure size " + std::to_string(size_px.width) + " x " +
                                std::to_string(size_px.height) + " px: each side must be in [1, 32768]");
  }
  const cairo_rectangle_t extents{0.0, 0.0, double(size_px.width), double(size_px.height)};
  recording_ = cairo().recording_surface_create(CAIRO_CONTENT_COLOR, &extents);
  cr_ = cairo().create(recording_);
  cairo().set_source_rgb(cr_, 1.0, 1.0, 1.0);
  cairo().paint(cr_);
  // Pixel centres at integer drawing coordinates, as pixel indices.
  cairo().translate(cr_, 0.5, 0.5);
  cairo().set_line_join(cr_, CAIRO_LINE_JOIN_ROUND);
  cairo().set_line_cap(cr_, CAIRO_LINE_CAP_ROUND);
}

Canvas::~Canvas() {
  if (cr_) cairo().destroy(cr_);
  if (recording_) cairo().surface_destroy(recording_);
}

Canvas::Canvas(Canvas&& other) noexcept
    : recording_(std::exchange(other.recording_, nullptr)), cr_(std::exchange(other.cr_, nullptr)), size_(other.size_) {}

Canvas& Canvas::operator=(Canvas&& other) noexcept {
  if (this != &other) {
    Canvas gone(std::move(*this));
    recording_ = std::exchange(other.recording_, nullptr);
    cr_ = std::exchange(other.cr_, nullptr);
    size_ = other.size_;
  }
  return *this;
}

Canvas::Region::~Region() { cairo().restore(cr_); }

Canvas::Region Canvas::region(const cv::Rect& rect) {
  cairo().save(cr_);
  cairo().rectangle(cr_, rect.x - 0.5, rect.y - 0.5, rect.width, rect.height);
  cairo().clip(cr_);
  cairo().translate(cr_, rect.x, rect.y);
  return Region(cr_);
}

void Canvas::line(cv::Point2d a, cv::Point2d b, const cv::Scalar& color, double width_px) {
  trace(cr_, {a, b}, false);
  stroke(cr_, color, width_px);
}

void Canvas::polyline(const std::vector<cv::Point2d>& points, const cv::Scalar& color, double width_px, bool closed) {
  if (points.size() < 2) return;
  trace(cr_, points, closed);
  stroke(cr_, color, width_px);
}

void Canvas::dashed_polyline(const std::vector<cv::Point2d>& points, const cv::Scalar& color, double width_px,
                             double dash_px, double gap_px) {
  if (points.size() < 2) return;
  cairo().save(cr_);
  // Butt caps: round ones would lengthen each dash by the line's width.
  cairo().set_line_cap(cr_, CAIRO_LINE_CAP_BUTT);
  const double pattern[] = {dash_px, gap_px};
  cairo().set_dash(cr_, pattern, 2, 0.0);
  trace(cr_, points, false);
  stroke(cr_, color, width_px);
  cairo().restore(cr_);
}

void Canvas::fill_polygon(const std::vector<cv::Point2d>& points, const cv::Scalar& color) {
  if (points.size() < 3) return;
  trace(cr_, points, true);
  set_color(cr_, color);
  cairo().fill(cr_);
}

void Canvas::circle(cv::Point2d centre, double radius_px, const cv::Scalar& color, double width_px) {
  cairo().new_path(cr_);
  cairo().arc(cr_, centre.x, centre.y, radius_px, 0.0, 2.0 * CV_PI);
  stroke(cr_, color, width_px);
}

void Canvas::fill_circle(cv::Point2d centre, double radius_px, const cv::Scalar& color) {
  cairo().new_path(cr_);
  cairo().arc(cr_, centre.x, centre.y, radius_px, 0.0, 2.0 * CV_PI);
  set_color(cr_, color);
  cairo().fill(cr_);
}

void Canvas::rectangle(const cv::Rect& rect, const cv::Scalar& color, double width_px) {
  cairo().new_path(cr_);
  cairo().rectangle(cr_, rect.x, rect.y, rect.width - 1, rect.height - 1);
  cairo().save(cr_);
  cairo().set_line_join(cr_, CAIRO_LINE_JOIN_MITER);
  stroke(cr_, color, width_px);
  cairo().restore(cr_);
}

void Canvas::fill_rectangle(const cv::Rect& rect, const cv::Scalar& color) {
  fill_box({rect.x - 0.5, rect.y - 0.5}, {rect.x + rect.width - 0.5, rect.y + rect.height - 0.5}, color);
}

void Canvas::fill_box(cv::Point2d a, cv::Point2d b, const cv::Scalar& color) {
  cairo().new_path(cr_);
  cairo().rectangle(cr_, std::min(a.x, b.x), std::min(a.y, b.y), std::abs(b.x - a.x), std::abs(b.y - a.y));
  set_color(cr_, color);
  cairo().fill(cr_);
}

void Canvas::arrow(cv::Point2d tail, cv::Point2d tip, const cv::Scalar& color, double width_px, double head_fraction) {
  const cv::Point2d d = tip - tail;
  const double head = head_fraction * std::hypot(d.x, d.y), angle = std::atan2(d.y, d.x);
  cairo().new_path(cr_);
  cairo().move_to(cr_, tail.x, tail.y);
  cairo().line_to(cr_, tip.x, tip.y);
  for (const double side : {1.0, -1.0}) {
    const double a = angle + CV_PI + side * CV_PI / 4.0;
    cairo().move_to(cr_, tip.x + head * std::cos(a), tip.y + head * std::sin(a));
    cairo().line_to(cr_, tip.x, tip.y);
  }
  stroke(cr_, color, width_px);
}

void Canvas::text(const std::string& text, cv::Point2d origin, const Font& font, const cv::Scalar& color, bool halo,
                  double angle_deg) {
  if (text.empty()) return;
  cairo().save(cr_);
  select_font(cr_, font);
  cairo().translate(cr_, origin.x, origin.y);
  cairo().rotate(cr_, -angle_deg * CV_PI / 180.0);
  if (halo) {
    cairo().new_path(cr_);
    cairo().move_to(cr_, 0.0, 0.0);
    cairo().text_path(cr_, text.c_str());
    stroke(cr_, kWhite, 3.0);
  }
  cairo().new_path(cr_);
  cairo().move_to(cr_, 0.0, 0.0);
  set_color(cr_, color);
  cairo().show_text(cr_, text.c_str());
  cairo().restore(cr_);
}

void Canvas::image(const cv::Mat& bgr, const cv::Rect& where, bool smooth) {
  if (bgr.empty() || where.width <= 0 || where.height <= 0) return;
  if (bgr.type() != CV_8UC3 && bgr.type() != CV_8UC4) {
    throw std::invalid_argument("Canvas::image: expected an 8-bit BGR or BGRA raster");
  }
  const bool alpha = bgr.channels() == 4;
  cairo_surface_t* surface =
      cairo().image_surface_create(alpha ? CAIRO_FORMAT_ARGB32 : CAIRO_FORMAT_RGB24, bgr.cols, bgr.rows);
  cairo().surface_flush(surface);
  unsigned char* data = cairo().image_surface_get_data(surface);
  const int stride = cairo().image_surface_get_stride(surface);
  for (int r = 0; r < bgr.rows; ++r) {
    auto* out = reinterpret_cast<std::uint32_t*>(data + std::ptrdiff_t(r) * stride);
    const uchar* in = bgr.ptr<uchar>(r);
    for (int c = 0; c < bgr.cols; ++c, in += bgr.channels()) {
      const std::uint32_t a = alpha ? in[3] : 255u;
      // Premultiplied ARGB in native byte order.
      const auto pre = [a](uchar v) { return (std::uint32_t(v) * a + 127u) / 255u; };
      out[c] = (a << 24) | (pre(in[2]) << 16) | (pre(in[1]) << 8) | pre(in[0]);
    }
  }
  cairo().surface_mark_dirty(surface);
  cairo().save(cr_);
  cairo().translate(cr_, where.x - 0.5, where.y - 0.5);
  cairo().scale(cr_, double(where.width) / bgr.cols, double(where.height) / bgr.rows);
  cairo().set_source_surface(cr_, surface, 0.0, 0.0);
  cairo_pattern_t* pattern = cairo().get_source(cr_);
  cairo().pattern_set_filter(pattern, smooth ? CAIRO_FILTER_GOOD : CAIRO_FILTER_NEAREST);
  cairo().pattern_set_extend(pattern, CAIRO_EXTEND_PAD);
  cairo().new_path(cr_);
  cairo().rectangle(cr_, 0.0, 0.0, bgr.cols, bgr.rows);
  cairo().fill(cr_);
  cairo().restore(cr_);
  cairo().surface_destroy(surface);
}

cv::Mat Canvas::raster() const {
  cairo_surface_t* target = cairo().image_surface_create(CAIRO_FORMAT_RGB24, size_.width, size_.height);
  replay(recording_, target, 1.0);
  const unsigned char* data = cairo().image_surface_get_data(target);
  const int stride = cairo().image_surface_get_stride(target);
  cv::Mat out(size_, CV_8UC3);
  for (int r = 0; r < size_.height; ++r) {
    const auto* in = reinterpret_cast<const std::uint32_t*>(data + std::ptrdiff_t(r) * stride);
    auto* px = out.ptr<cv::Vec3b>(r);
    for (int c = 0; c < size_.width; ++c) {
      px[c] = cv::Vec3b(uchar(in[c] & 0xff), uchar((in[c] >> 8) & 0xff), uchar((in[c] >> 16) & 0xff));
    }
  }
  cairo().surface_destroy(target);
  return out;
}

std::string Canvas::encode(FigureFormat format) const {
  if (format == FigureFormat::png) return encode_png(raster(), 6);
  std::string bytes;
  const double w_pt = size_.width * kPointsPerPx, h_pt = size_.height * kPointsPerPx;
  cairo_surface_t* target = nullptr;
  if (format == FigureFormat::pdf) {
    target = cairo().pdf_surface_create_for_stream(append_to_string, &bytes, w_pt, h_pt);
    // A fixed creation date: the same figure gives the same bytes.
    cairo().pdf_surface_set_metadata(target, CAIRO_PDF_METADATA_CREATE_DATE, "2000-01-01T00:00:00Z");
    cairo().pdf_surface_set_metadata(target, CAIRO_PDF_METADATA_CREATOR, "campo");
  } else {
    target = cairo().svg_surface_create_for_stream(append_to_string, &bytes, w_pt, h_pt);
    cairo().svg_surface_restrict_to_version(target, CAIRO_SVG_VERSION_1_1);
  }
  replay(recording_, target, kPointsPerPx);
  cairo().surface_finish(target);
  const cairo_status_t status = cairo().surface_status(target);
  cairo().surface_destroy(target);
  if (status != CAIRO_STATUS_SUCCESS) {
    throw std::runtime_error(std::string("cannot encode the figure as ") + extension(format) + ": " +
                             cairo().status_to_string(status));
  }
  return format == FigureFormat::svg ? renumber_svg_surfaces(bytes) : bytes;
}

std::vector<std::filesystem::path> Canvas::write(const std::filesystem::path& path,
                                                 const std::vector<FigureFormat>& formats) const {
  const std::vector<std::filesystem::path> files = figure_files(path, formats);
  std::vector<std::filesystem::path> written;
  for (std::size_t i = 0; i < files.size(); ++i) {
    const FigureFormat format = formats[i];
    const std::filesystem::path& file = files[i];
    std::string bytes;
    try {
      bytes = encode(format);
    } catch (const std::exception& e) {
      throw OutputError(file, e.what());
    }
    write_file_atomically(file, bytes);
    written.push_back(file);
  }
  return written;
}

// ---- primitives ------------------------------------------------------------

cv::Scalar shade(const cv::Scalar& c, double k) { return {c[0] * k, c[1] * k, c[2] * k}; }

cv::Scalar lighten(const cv::Scalar& c, double t) {
  return {c[0] + (255.0 - c[0]) * t, c[1] + (255.0 - c[1]) * t, c[2] + (255.0 - c[2]) * t};
}

cv::Size text_size(const std::string& text, const Font& font) {
  cairo_t* cr = measuring_context();
  select_font(cr, font);
  cairo_text_extents_t extents;
  cairo().text_extents(cr, text.c_str(), &extents);
  return {static_cast<int>(std::lround(extents.x_advance)),
          static_cast<int>(std::lround(font.scale * kCapPxPerScale))};
}

namespace {

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

void put_text(Canvas& canvas, const std::string& text, cv::Point2d anchor, const Font& font,
              const cv::Scalar& color, Align align, bool halo) {
  const cv::Size size = text_size(text, font);
  double x = anchor.x;
  if (align == Align::centre) x -= 0.5 * size.width;
  if (align == Align::right) x -= size.width;
  canvas.text(text, {x, anchor.y + 0.5 * size.height}, font, color, halo);
}

void put_text_vertical(Canvas& canvas, const std::string& text, cv::Point2d centre, const Font& font,
                       const cv::Scalar& color) {
  const cv::Size size = text_size(text, font);
  canvas.text(text, {centre.x + 0.5 * size.height, centre.y + 0.5 * size.width}, font, color, false, 90.0);
}

void put_title(Canvas& canvas, const std::string& title, const cv::Rect& band) {
  Font font = kTitleFont;
  while (font.scale > 0.45 && text_size(title, font).width > band.width - 24) font.scale *= 0.92;
  const std::string text = fit_text(title, font, band.width - 24);
  put_text(canvas, text, {band.x + 0.5 * band.width, band.y + 0.5 * band.height}, font, kInk, Align::centre);
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

void draw_grid(Canvas& canvas, const PlotFrame& frame) {
  const cv::Rect& p = frame.plot_px;
  const double xs = x_step(frame), ys = y_step(frame);
  for (double x : ticks_in(frame.x0, frame.x1, xs)) {
    const double px = frame.to_px(x, frame.y0).x;
    canvas.line({px, p.y - 0.5}, {px, p.y + p.height - 0.5}, kGridInk, 1.0);
  }
  for (double y : ticks_in(frame.y0, frame.y1, ys)) {
    const double py = frame.to_px(frame.x0, y).y;
    canvas.line({p.x - 0.5, py}, {p.x + p.width - 0.5, py}, kGridInk, 1.0);
  }
}

void draw_axes(Canvas& canvas, const PlotFrame& frame, const std::string& x_label, const std::string& y_label) {
  const cv::Rect& p = frame.plot_px;
  canvas.rectangle({p.x - 1, p.y - 1, p.width + 2, p.height + 2}, kInk, 1.0);
  const double xs = x_step(frame), ys = y_step(frame);
  const int bottom = p.y + p.height;
  for (double x : ticks_in(frame.x0, frame.x1, xs)) {
    const double px = frame.to_px(x, frame.y0).x;
    canvas.line({px, bottom + 0.0}, {px, bottom + 5.0}, kInk, 1.0);
    put_text(canvas, format_number(x, xs), {px, bottom + 17.0}, kTickFont, kInk, Align::centre);
  }
  int widest = 0;
  for (double y : ticks_in(frame.y0, frame.y1, ys)) {
    const double py = frame.to_px(frame.x0, y).y;
    const std::string label = format_number(y, ys);
    canvas.line({p.x - 6.0, py}, {p.x - 1.0, py}, kInk, 1.0);
    put_text(canvas, label, {p.x - 10.0, py}, kTickFont, kInk, Align::right);
    widest = std::max(widest, text_size(label, kTickFont).width);
  }
  put_text(canvas, x_label, {p.x + 0.5 * p.width, bottom + 42.0}, kLabelFont, kInk, Align::centre);
  put_text_vertical(canvas, y_label, {p.x - 10.0 - widest - 16.0, p.y + 0.5 * p.height}, kLabelFont, kInk);
}

void start_marker(Canvas& canvas, cv::Point2d p) {
  canvas.fill_circle(p, 9.5, kWhite);
  canvas.fill_circle(p, 7.5, rgb(44, 160, 44));
  canvas.circle(p, 7.5, rgb(20, 90, 20), 1.0);
}

void goal_marker(Canvas& canvas, cv::Point2d p, bool filled) {
  std::vector<cv::Point2d> star;
  for (int i = 0; i < 10; ++i) {
    const double a = -CV_PI / 2 + i * CV_PI / 5, r = i % 2 == 0 ? 13.0 : 5.5;
    star.push_back(p + cv::Point2d(r * std::cos(a), r * std::sin(a)));
  }
  const cv::Scalar red = rgb(214, 39, 40);
  canvas.polyline(star, kWhite, 4.0, true);
  canvas.fill_polygon(star, filled ? red : kWhite);
  canvas.polyline(star, filled ? shade(red, 0.55) : red, filled ? 1.0 : 2.0, true);
}

void waypoint_marker(Canvas& canvas, cv::Point2d p, int number, bool filled) {
  canvas.fill_circle(p, 11.5, kWhite);
  canvas.fill_circle(p, 9.5, filled ? kInk : kWhite);
  canvas.circle(p, 9.5, kInk, filled ? 1.0 : 2.0);
  if (number <= 0) return;
  const std::string text = std::to_string(number);
  Font font = kSmallFont;
  if (text_size(text, font).width > 15) font.scale = 0.32;
  put_text(canvas, text, p + cv::Point2d(0.5, 0.0), font, filled ? kWhite : kInk, Align::centre);
}

void diamond_marker(Canvas& canvas, cv::Point2d p, const cv::Scalar& color) {
  const std::vector<cv::Point2d> diamond{p + cv::Point2d(0, -7), p + cv::Point2d(7, 0), p + cv::Point2d(0, 7),
                                         p + cv::Point2d(-7, 0)};
  canvas.polyline(diamond, kWhite, 3.0, true);
  canvas.fill_polygon(diamond, color);
  canvas.polyline(diamond, shade(color, 0.55), 1.0, true);
}

void cross_marker(Canvas& canvas, cv::Point2d p, const cv::Scalar& color) {
  for (int pass = 0; pass < 2; ++pass) {
    for (const double s : {1.0, -1.0}) {
      canvas.line(p + cv::Point2d(-6, -6 * s), p + cv::Point2d(6, 6 * s), pass == 0 ? kWhite : color,
                  pass == 0 ? 5.0 : 2.0);
    }
  }
}

void collision_marker(Canvas& canvas, cv::Point2d p) {
  canvas.fill_circle(p, 9.0, kWhite);
  canvas.fill_circle(p, 7.0, kCollision);
  for (const double s : {1.0, -1.0}) {
    canvas.line(p + cv::Point2d(-3.5, -3.5 * s), p + cv::Point2d(3.5, 3.5 * s), kWhite, 2.0);
  }
}

namespace {
constexpr int kLegendPadPx = 10;
constexpr int kLegendRowPx = 26;
}  // namespace

int legend_height(std::size_t count) { return 2 * kLegendPadPx + static_cast<int>(count) * kLegendRowPx; }

void draw_legend(Canvas& canvas, const cv::Rect& box, const std::vector<LegendEntry>& entries) {
  canvas.fill_rectangle(box, kWhite);
  canvas.rectangle(box, kMutedInk, 1.0);
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const double cy = box.y + kLegendPadPx + kLegendRowPx * (i + 0.5);
    entries[i].symbol(canvas, {box.x + 28.0, cy});
    put_text(canvas, fit_text(entries[i].text, kLegendFont, box.width - 62), {box.x + 54.0, cy}, kLegendFont, kInk);
  }
}

void draw_colorbar(Canvas& canvas, const cv::Rect& bar, double lo, double hi, const std::string& caption,
                   const std::function<cv::Vec3b(double)>& color_of) {
  // One pixel row per shade, embedded as a raster (a smooth ramp in every format).
  cv::Mat ramp(bar.height, 1, CV_8UC3);
  for (int r = 0; r < bar.height; ++r) ramp.at<cv::Vec3b>(r, 0) = color_of(1.0 - (r + 0.5) / bar.height);
  canvas.image(ramp, bar);
  canvas.rectangle({bar.x - 1, bar.y - 1, bar.width + 2, bar.height + 2}, kInk, 1.0);
  const double step = nice_step(hi - lo, bar.height / 45.0);
  for (double v : ticks_in(lo, hi, step)) {
    const double y = bar.y - 0.5 + bar.height - (v - lo) / (hi - lo) * bar.height;
    const double right = bar.x + bar.width;
    canvas.line({right, y}, {right + 5.0, y}, kInk, 1.0);
    put_text(canvas, format_number(v, step), {right + 9.0, y}, kTickFont, kInk);
  }
  put_text(canvas, caption, {bar.x - 1.0, bar.y - 18.0}, kLabelFont, kInk);
}

}  // namespace campo::figure
