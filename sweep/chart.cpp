#include "sweep/chart.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <optional>
#include <stdexcept>


#include "render/figure_canvas.hpp"
#include "render/figures.hpp"
#include "sweep/sweep_spec.hpp"
#include "sweep/table.hpp"

namespace campo {

namespace {

using figure::Align;
using figure::Font;
using figure::PlotFrame;

// Fonts and sizes of one kind of chart; every chart is drawn with the helpers below.
struct ChartStyle {
  Font title, label, tick, legend, note;
  double line_px;       ///< series lines
  double bar_px;        ///< error bars, whiskers, box edges
  double marker_px;     ///< marker radius
  double cap_px;        ///< half width of error bar caps
  double tick_px;       ///< tick mark length
  double dodge_px;      ///< horizontal offset between line series, so error bars do not overlap
  int legend_row_px;
};
// The summary chart of `campo table`: small panels.
// Line widths are those OpenCV's anti-aliased lines of thickness 2 and 1 (3 and 2 for the
// paper) covered, so the charts keep their weight.
const ChartStyle kPanelStyle{figure::kTitleFont, figure::kLabelFont, figure::kTickFont, figure::kLegendFont,
                             figure::kSmallFont, 3.0, 1.5, 4.0, 4.0, 5.0, 5.0, 24};
// `campo plot`: one large plot whose text stays legible scaled down to a column of a paper.
// Its former Hershey fonts drawn 2 px thick are the bold ones.
const ChartStyle kPaperStyle{{1.3, true}, {1.0, true}, {0.85, true}, {0.9, true}, {0.75, false},
                             4.0, 3.0, 7.0, 9.0, 9.0, 9.0, 44};

struct Tick {
  double value;
  std::string label;
};

bool power_of_two(double v) {
  if (!(v >= 1.0) || v > 0x1p60) return false;
  const double e = std::log2(v);
  return e == std::round(e);
}

// Multiples of a nice step within [lo, hi].
std::vector<Tick> linear_ticks(double lo, double hi, double target_count) {
  const double step = figure::nice_step(hi - lo, target_count);
  std::vector<Tick> ticks;
  for (double k = std::ceil(lo / step - 1e-9); k <= std::floor(hi / step + 1e-9); k += 1.0) {
    ticks.push_back({k * step, figure::format_number(k * step, step)});
  }
  return ticks;
}

std::vector<Tick> percent_ticks() {
  std::vector<Tick> ticks;
  for (int v = 0; v <= 100; v += 20) ticks.push_back({double(v), std::to_string(v)});
  return ticks;
}

void put_title(figure::Canvas& canvas, const std::string& title, const cv::Rect& band, Font font) {
  while (font.scale > 0.45 && figure::text_size(title, font).width > band.width - 24) font.scale *= 0.92;
  figure::put_text(canvas, title, {band.x + 0.5 * band.width, band.y + 0.5 * band.height}, font, figure::kInk,
                   Align::centre);
}

void draw_grid(figure::Canvas& canvas, const PlotFrame& frame, const std::vector<Tick>& x_ticks,
               const std::vector<Tick>& y_ticks) {
  const cv::Rect& p = frame.plot_px;
  for (const Tick& t : x_ticks) {
    const double x = frame.to_px(t.value, frame.y0).x;
    canvas.line({x, p.y - 0.5}, {x, p.y + p.height - 0.5}, figure::kGridInk, 1.0);
  }
  for (const Tick& t : y_ticks) {
    const double y = frame.to_px(frame.x0, t.value).y;
    canvas.line({p.x - 0.5, y}, {p.x + p.width - 0.5, y}, figure::kGridInk, 1.0);
  }
}

// Frame, ticks with labels (an x label that would overlap the previous one is left out) and axis titles.
void draw_axes(figure::Canvas& canvas, const PlotFrame& frame, const std::vector<Tick>& x_ticks,
               const std::vector<Tick>& y_ticks, const std::string& x_label, const std::string& y_label,
               const ChartStyle& style) {
  const cv::Rect& p = frame.plot_px;
  canvas.rectangle({p.x - 1, p.y - 1, p.width + 2, p.height + 2}, figure::kInk, 1.0);
  const double bottom = p.y + p.height;
  const double tick_text = figure::text_size("0", style.tick).height;
  const double label_text = figure::text_size("0", style.label).height;
  double free_from = -1e9;  // x where the next tick label may start
  for (const Tick& t : x_ticks) {
    const double x = frame.to_px(t.value, frame.y0).x;
    canvas.line({x, bottom}, {x, bottom + style.tick_px}, figure::kInk, 1.0);
    const double half = 0.5 * figure::text_size(t.label, style.tick).width;
    if (x - half < free_from) continue;
    figure::put_text(canvas, t.label, {x, bottom + style.tick_px + 6.0 + 0.5 * tick_text}, style.tick, figure::kInk,
                     Align::centre);
    free_from = x + half + 8.0;
  }
  int widest = 0;
  for (const Tick& t : y_ticks) {
    const double y = frame.to_px(frame.x0, t.value).y;
    canvas.line({p.x - 1.0 - style.tick_px, y}, {p.x - 1.0, y}, figure::kInk, 1.0);
    figure::put_text(canvas, t.label, {p.x - style.tick_px - 5.0, y}, style.tick, figure::kInk, Align::right);
    widest = std::max(widest, figure::text_size(t.label, style.tick).width);
  }
  figure::put_text(canvas, x_label,
                   {p.x + 0.5 * p.width, bottom + style.tick_px + 6.0 + tick_text + 18.0 + 0.5 * label_text},
                   style.label, figure::kInk, Align::centre);
  figure::put_text_vertical(canvas, y_label,
                            {p.x - style.tick_px - 5.0 - widest - 16.0 - 0.5 * label_text, p.y + 0.5 * p.height},
                            style.label, figure::kInk);
}

// One point of a line series: x in plot units, y and its error bar (none when lo == hi == y).
struct Point {
  double x, y, lo, hi;
};

void draw_cap(figure::Canvas& canvas, cv::Point2d end, const cv::Scalar& color, const ChartStyle& style) {
  canvas.line(end - cv::Point2d(style.cap_px, 0), end + cv::Point2d(style.cap_px, 0), color, style.bar_px);
}

void draw_error_bar(figure::Canvas& canvas, cv::Point2d lo, cv::Point2d hi, const cv::Scalar& color,
                    const ChartStyle& style) {
  canvas.line(lo, hi, color, style.bar_px);
  for (const cv::Point2d& end : {lo, hi}) draw_cap(canvas, end, color, style);
}

void draw_marker(figure::Canvas& canvas, cv::Point2d p, const cv::Scalar& color, const ChartStyle& style) {
  canvas.fill_circle(p, style.marker_px + 2.0, figure::kWhite);
  canvas.fill_circle(p, style.marker_px, color);
}

// A box of a box plot (and its legend symbol): filled with the colour lightened, edged in the colour.
void draw_box(figure::Canvas& canvas, cv::Point2d a, cv::Point2d b, const cv::Scalar& color, const ChartStyle& style) {
  canvas.fill_box(a, b, figure::lighten(color, 0.55));
  canvas.polyline({a, {b.x, a.y}, b, {a.x, b.y}}, color, style.bar_px, true);
}

// An error bar whose end lies beyond the frame: drawn to the frame's edge, ending in an arrowhead
// there instead of a cap, so a very wide interval (n = 2) does not squash the plot yet reads as wider.
void draw_clipped_error_bar(figure::Canvas& canvas, const PlotFrame& frame, double x, double lo, double hi, double dodge_px,
                            const cv::Scalar& color, const ChartStyle& style) {
  const auto px = [&](double y) { return frame.to_px(x, y) + cv::Point2d(dodge_px, 0.0); };
  const bool low_out = lo < frame.y0, high_out = hi > frame.y1;
  if (!low_out && !high_out) return draw_error_bar(canvas, px(lo), px(hi), color, style);
  const cv::Point2d a = px(std::max(lo, frame.y0)), b = px(std::min(hi, frame.y1));
  canvas.line(a, b, color, style.bar_px);
  for (const auto& [end, out, toward] : {std::tuple{a, low_out, 1.0}, std::tuple{b, high_out, -1.0}}) {
    if (!out) {
      draw_cap(canvas, end, color, style);
      continue;
    }
    // The arrowhead points out of the frame (up at the top, where y pixels grow downwards).
    const double depth = 1.6 * style.cap_px;
    const std::vector<cv::Point2d> head{end, end + cv::Point2d(-style.cap_px, -toward * depth),
                                        end + cv::Point2d(style.cap_px, -toward * depth)};
    canvas.fill_polygon(head, color);
  }
}

// Error bars, then the line through the points (unless `connect` is false), then markers on top.
void draw_series(figure::Canvas& canvas, const PlotFrame& frame, const std::vector<Point>& points, double dodge_px,
                 const cv::Scalar& color, const ChartStyle& style, bool connect = true) {
  const auto px = [&](double x, double y) { return frame.to_px(x, y) + cv::Point2d(dodge_px, 0.0); };
  for (const Point& p : points) {
    if (p.hi > p.lo) draw_clipped_error_bar(canvas, frame, p.x, p.lo, p.hi, dodge_px, color, style);
  }
  std::vector<cv::Point2d> line;
  for (const Point& p : points) line.push_back(px(p.x, p.y));
  if (connect) canvas.polyline(line, color, style.line_px);
  for (const cv::Point2d& p : line) draw_marker(canvas, p, color, style);
}

// A legend row: a symbol drawn around a centre, then the text.
struct LegendRow {
  std::function<void(figure::Canvas&, cv::Point2d)> symbol;
  std::string text;
};

// A row's text starts 2.2 rows from the box's left edge and keeps half a row clear of its right one.
constexpr double kLegendTextStartRows = 2.2, kLegendMarginRows = 0.5;

int legend_width(const std::vector<LegendRow>& rows, const std::string& heading, const ChartStyle& style,
                 int min_px, int max_px) {
  const double row_px = style.legend_row_px;
  double width = figure::text_size(heading, style.legend).width + (0.5 + kLegendMarginRows) * row_px;
  for (const LegendRow& row : rows) {
    width = std::max(width, figure::text_size(row.text, style.legend).width +
                                (kLegendTextStartRows + kLegendMarginRows) * row_px);
  }
  return std::clamp(static_cast<int>(std::ceil(width)), min_px, max_px);
}

// `font`, scaled down until `text` is at most `width_px` wide (a legend clamped to its widest).
Font fitted(const std::string& text, Font font, double width_px) {
  while (font.scale > 0.3 && figure::text_size(text, font).width > width_px) font.scale *= 0.95;
  return font;
}

// A white box with a border: an optional heading, then one row per entry.
void draw_legend(figure::Canvas& canvas, cv::Point top_left, int width, const std::vector<LegendRow>& rows,
                 const std::string& heading, const ChartStyle& style) {
  const int pad = style.legend_row_px / 3;
  const int heading_rows = heading.empty() ? 0 : 1;
  const cv::Rect box(top_left.x, top_left.y, width,
                     2 * pad + static_cast<int>(rows.size() + heading_rows) * style.legend_row_px);
  canvas.fill_rectangle(box, figure::kWhite);
  canvas.rectangle(box, figure::kMutedInk, 1.0);
  const double row_px = style.legend_row_px;
  if (heading_rows) {
    figure::put_text(canvas, heading, {box.x + 0.5 * row_px, box.y + pad + 0.5 * row_px},
                     fitted(heading, style.legend, width - (0.5 + kLegendMarginRows) * row_px), figure::kInk);
  }
  const double text_room = width - (kLegendTextStartRows + kLegendMarginRows) * row_px;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const double cy = box.y + pad + row_px * (i + heading_rows + 0.5);
    rows[i].symbol(canvas, {box.x + row_px, cy});
    figure::put_text(canvas, rows[i].text, {box.x + kLegendTextStartRows * row_px, cy},
                     fitted(rows[i].text, style.legend, text_room), figure::kInk);
  }
}

// A line with a marker: the symbol of a line series.
LegendRow line_row(const cv::Scalar& color, const std::string& text, const ChartStyle& style) {
  return {[color, &style](figure::Canvas& m, cv::Point2d c) {
            const double half = 0.6 * style.legend_row_px;
            m.line(c - cv::Point2d(half, 0), c + cv::Point2d(half, 0), color, style.line_px);
            draw_marker(m, c, color, style);
          },
          text};
}

// The symbol of the interval drawn: a grey error bar with its marker.
LegendRow interval_row(const std::string& text, const ChartStyle& style) {
  return {[&style](figure::Canvas& m, cv::Point2d c) {
            const double half = 0.4 * style.legend_row_px;
            draw_error_bar(m, c - cv::Point2d(0, half), c + cv::Point2d(0, half), figure::kMutedInk, style);
            draw_marker(m, c, figure::kMutedInk, style);
          },
          text};
}

// The x axis of numeric values: log2 when all are powers of two; ticked at the values.
struct NumericAxis {
  bool log2 = false;
  std::vector<Tick> ticks;  ///< ascending
  double to_x(double v) const { return log2 ? std::log2(v) : v; }
};

NumericAxis numeric_axis(const std::vector<nlohmann::json>& values) {
  NumericAxis axis;
  axis.log2 = std::all_of(values.begin(), values.end(), [](const nlohmann::json& v) { return power_of_two(v.get<double>()); });
  for (const nlohmann::json& v : values) {
    const double x = axis.to_x(v.get<double>());
    if (std::none_of(axis.ticks.begin(), axis.ticks.end(), [&](const Tick& t) { return t.value == x; })) {
      axis.ticks.push_back({x, value_label(v)});
    }
  }
  std::sort(axis.ticks.begin(), axis.ticks.end(), [](const Tick& a, const Tick& b) { return a.value < b.value; });
  return axis;
}

// Data range [lo, hi] with a margin, so no point sits on the frame.
std::pair<double, double> padded(double lo, double hi, double min_pad) {
  const double pad = std::max(0.08 * (hi - lo), min_pad);
  return {lo - pad, hi + pad};
}

// The y range of means and their intervals: every mean and interval, but an interval reaching
// beyond three times the means' spread (and the means' own size) past them is cut at the frame
// (draw_clipped_error_bar marks it), so one wide interval of two runs does not flatten the rest.
std::pair<double, double> interval_range(double mean_lo, double mean_hi, double lo, double hi) {
  const double reach = 3.0 * std::max({mean_hi - mean_lo, std::abs(mean_hi), std::abs(mean_lo), 1e-9});
  return {std::max(lo, mean_lo - reach), std::min(hi, mean_hi + reach)};
}

// The name of a mean's interval in legends: what statistics.hpp computes for this support.
std::string interval_name(Support support) {
  return support == Support::non_negative ? "mean, 95% CI (log t)" : "mean, 95% CI (t)";
}

// The summary table as series: one per scene, in order of first appearance.
struct Series {
  std::string scene;
  std::vector<Point> path_ratio;  ///< over the runs that reached their goal; rows where some did only
  std::vector<Point> success;
};

}  // namespace

bool chartable(const SweepTable& table) {
  if (table.axes.size() != 1 || table.rows.empty()) return false;
  return std::all_of(table.rows.begin(), table.rows.end(),
                     [](const TableRow& row) { return row.params.front().is_number(); });
}

figure::Canvas draw_sweep_chart(const SweepTable& table) {
  if (!chartable(table)) throw std::invalid_argument("draw_sweep_chart: expected one numeric axis");
  // Layout, pixels: two plots side by side, the legend to their right.
  constexpr int kHeight = 580, kTitleBandPx = 50;
  constexpr int kPlotTop = 90, kPlotHeight = 410, kPlotWidth = 430;
  constexpr int kLeftPlotX = 95, kRightPlotX = 640, kLegendX = 1100;
  const ChartStyle& style = kPanelStyle;
  const std::string& axis = table.axes.front();
  std::vector<nlohmann::json> values;
  for (const TableRow& row : table.rows) values.push_back(row.params.front());
  const NumericAxis x_axis = numeric_axis(values);

  std::vector<Series> series;
  // The means and their intervals' extent; the ideal ratio 1 is always in view.
  double mean_lo = 1.0, mean_hi = 1.0, ratio_lo = 1.0, ratio_hi = 1.0;
  for (const TableRow& row : table.rows) {
    auto it = std::find_if(series.begin(), series.end(), [&](const Series& s) { return s.scene == row.scene; });
    if (it == series.end()) it = series.insert(series.end(), Series{row.scene, {}, {}});
    const double x = x_axis.to_x(row.params.front().get<double>());
    // Successes only: an aborted run's short path would pull the mean below the ideal 1. The
    // interval is the one campo plot and the tables give (the ratio is >= 0: log scale).
    if (row.path_ratio_reached) {
      const MeanSd& r = *row.path_ratio_reached;
      const Interval ci = r.ci95 && !row.identical ? *r.ci95 : Interval{r.mean, r.mean};
      it->path_ratio.push_back({x, r.mean, ci.low, ci.high});
      mean_lo = std::min(mean_lo, r.mean);
      mean_hi = std::max(mean_hi, r.mean);
      ratio_lo = std::min(ratio_lo, ci.low);
      ratio_hi = std::max(ratio_hi, ci.high);
    }
    const Interval wilson = row.identical ? Interval{row.success_rate, row.success_rate}
                                          : wilson_interval(row.reached, row.runs);
    it->success.push_back({x, 100.0 * row.success_rate, 100.0 * wilson.low, 100.0 * wilson.high});
  }
  std::tie(ratio_lo, ratio_hi) = interval_range(mean_lo, mean_hi, ratio_lo, ratio_hi);
  for (Series& s : series) {
    for (auto* points : {&s.path_ratio, &s.success}) {
      std::sort(points->begin(), points->end(), [](const Point& a, const Point& b) { return a.x < b.x; });
    }
  }

  const double x_min = x_axis.ticks.front().value, x_max = x_axis.ticks.back().value;
  const auto [x0, x1] = x_max > x_min ? padded(x_min, x_max, 0.0) : std::pair{x_min - 1.0, x_max + 1.0};
  const auto [r0, r1] = padded(ratio_lo, ratio_hi, 0.02);
  const PlotFrame ratio_frame{{kLeftPlotX, kPlotTop, kPlotWidth, kPlotHeight}, x0, x1, r0, r1};
  const PlotFrame success_frame{{kRightPlotX, kPlotTop, kPlotWidth, kPlotHeight}, x0, x1, -5.0, 105.0};

  std::vector<LegendRow> legend;
  for (std::size_t i = 0; i < series.size(); ++i) legend.push_back(line_row(run_color(i), series[i].scene, style));
  legend.push_back(interval_row(interval_name(Support::non_negative), style));
  legend.push_back(interval_row("rate, 95% Wilson", style));
  // The legend is as wide as the longest scene name needs (within limits); the image ends after it.
  const int legend_px = legend_width(legend, "", style, 170, 400);
  const int width = kLegendX + legend_px + 15;

  figure::Canvas canvas({width, kHeight});
  put_title(canvas, table.name + ": path length and success rate vs " + quantity_name(axis).words,
            {0, 0, width, kTitleBandPx}, style.title);
  const std::string x_label = field_heading(axis) + (x_axis.log2 ? ", log2 scale" : "");
  const auto ratio_y = linear_ticks(ratio_frame.y0, ratio_frame.y1, kPlotHeight / figure::kTickSpacingPx);
  const auto success_y = percent_ticks();

  const struct {
    const PlotFrame& frame;
    const std::vector<Tick>& y_ticks;
    std::string subtitle, y_label;
    std::vector<Point> Series::*points;
    std::optional<double> reference_y;  ///< a dashed line: the ideal value
  } panels[] = {
      {ratio_frame, ratio_y, "Normalized path length, reached runs", metric_label("path_ratio"),
       &Series::path_ratio, 1.0},
      {success_frame, success_y, "Success rate", metric_label("success"), &Series::success, std::nullopt},
  };
  for (const auto& panel : panels) {
    const cv::Rect& p = panel.frame.plot_px;
    draw_grid(canvas, panel.frame, x_axis.ticks, panel.y_ticks);
    if (panel.reference_y) {
      const double y = panel.frame.to_px(panel.frame.x0, *panel.reference_y).y;
      canvas.dashed_polyline({{p.x - 0.5, y}, {p.x + p.width - 0.5, y}}, figure::kMutedInk, 1.0, 6.0, 4.0);
    }
    figure::put_text(canvas, panel.subtitle, {p.x + 0.5 * p.width, p.y - 18.0}, style.label, figure::kInk,
                     Align::centre);
    for (std::size_t i = 0; i < series.size(); ++i) {
      const double dodge = (static_cast<double>(i) - 0.5 * (series.size() - 1.0)) * style.dodge_px;
      draw_series(canvas, panel.frame, series[i].*panel.points, dodge, run_color(i), style);
    }
    draw_axes(canvas, panel.frame, x_axis.ticks, panel.y_ticks, x_label, panel.y_label, style);
  }
  draw_legend(canvas, {kLegendX, kPlotTop}, legend_px, legend, "", style);
  return canvas;
}

namespace {

// The request's fields: checked against the axes when they are known.
std::vector<std::string> plot_fields(const PlotRequest& request, const TableLayout& layout, bool check_axes) {
  const std::string cli = "command line";
  if (check_axes) check_field(request.x, layout.axes, cli, "--x");
  std::vector<std::string> fields{request.x};
  if (!request.group.empty()) {
    if (check_axes) check_field(request.group, layout.axes, cli, "--group");
    if (request.group == request.x) throw InputError(cli, "--group", "a field other than --x (\"" + request.x + "\")");
    fields.push_back(request.group);
  }
  return fields;
}

// The runs of one point or box, a run at a time.
struct MarkFold {
  int runs = 0, failed = 0;
  RunningStats stats;     // line plots and rates
  QuantileSketch values;  // box plots of numbers
};

}  // namespace

struct PlotBuilder::Impl {
  const TableLayout& layout;
  PlotRequest request;
  RunGroups groups;
  MetricCatalog catalog;
  std::vector<MarkFold> marks;  // per group
};

PlotBuilder::PlotBuilder(const TableLayout& layout, PlotRequest request)
    : impl_(new Impl{layout, request, RunGroups(layout, plot_fields(request, layout, !layout.axes_from_runs)), {}, {}}) {
  MetricCatalog{}.check(request.y, "command line", "--y");  // the metric's name alone, before any run
}
PlotBuilder::~PlotBuilder() = default;
PlotBuilder::PlotBuilder(PlotBuilder&&) noexcept = default;
PlotBuilder& PlotBuilder::operator=(PlotBuilder&&) noexcept = default;

void PlotBuilder::add(const RunResult& run, std::size_t index) {
  Impl& d = *impl_;
  d.catalog.add(run);
  const std::size_t g = d.groups.add(run, index);
  if (g == d.marks.size()) d.marks.emplace_back();
  MarkFold& mark = d.marks[g];
  ++mark.runs;
  if (!run.completed) ++mark.failed;
  if (const auto v = metric_value(run, d.request.y)) {
    mark.stats.add(*v);
    mark.values.add(*v);
  }
}

figure::Canvas draw_sweep_plot(const std::vector<RunResult>& runs, const TableLayout& layout, const PlotRequest& request,
                        const PlotConfig& config) {
  PlotBuilder builder(layout, request);
  for (std::size_t i = 0; i < runs.size(); ++i) builder.add(runs[i], i);
  return builder.draw(config);
}

figure::Canvas PlotBuilder::draw(const PlotConfig& config) const {
  const Impl& d = *impl_;
  const PlotRequest& request = d.request;
  const TableLayout& layout = d.layout;
  const std::string cli = "command line";
  plot_fields(request, layout, true);
  const MetricKind kind = d.catalog.check(request.y, cli, "--y");
  if (config.width_px < 800 || config.height_px < 500) {
    throw std::invalid_argument("draw_sweep_plot: expected at least 800 x 500 pixels");
  }
  if (d.groups.size() == 0) throw InputError(cli, "DIR", "results with at least one run to plot");
  struct Group {
    const std::vector<nlohmann::json>& key;
    const MarkFold& fold;
  };
  std::vector<Group> groups;
  for (std::size_t g : d.groups.order()) groups.push_back({d.groups.key(g), d.marks[g]});

  // X values and series (group values) in the sweep's expansion order.
  std::vector<nlohmann::json> xs, series;
  for (const Group& g : groups) {
    index_in_order(xs, g.key[0]);
    index_in_order(series, g.key.size() > 1 ? g.key[1] : nlohmann::json());
  }
  const bool numeric_x = std::all_of(xs.begin(), xs.end(), [](const nlohmann::json& v) { return v.is_number(); });
  if (request.kind == PlotKind::line && !numeric_x) {
    throw InputError(cli, "--kind", "line needs numeric values of --x \"" + request.x + "\"; use --kind box");
  }
  const bool line = request.kind == PlotKind::line || (request.kind == PlotKind::automatic && numeric_x);
  // Box plots list numeric categories in ascending order too.
  if (numeric_x) {
    std::stable_sort(xs.begin(), xs.end(), [](const auto& a, const auto& b) { return a.template get<double>() < b.template get<double>(); });
  }
  const bool rate = kind == MetricKind::rate;
  const double scale = rate ? 100.0 : 1.0;  // rates in percent
  const NumericAxis x_axis = line ? numeric_axis(xs) : NumericAxis{};
  const auto x_of = [&](const nlohmann::json& v) {
    return line ? x_axis.to_x(v.get<double>()) : static_cast<double>(index_in_order(xs, v));
  };

  // Statistics per group, and the data range.
  struct Mark {
    std::size_t series;
    double x;
    std::optional<Summary> summary;  ///< line plots and rates
    std::optional<BoxStats> box;     ///< box plots of numbers
  };
  std::vector<Mark> marks;
  const Support support = metric_support(request.y);
  double y_lo = HUGE_VAL, y_hi = -HUGE_VAL;
  double mean_lo = HUGE_VAL, mean_hi = -HUGE_VAL;  // line plots: the means alone
  int run_count = 0, failed = 0;
  for (const Group& g : groups) {
    run_count += g.fold.runs;
    failed += g.fold.failed;
    const std::size_t series_index = index_in_order(series, g.key.size() > 1 ? g.key[1] : nlohmann::json());
    Mark mark{series_index, x_of(g.key[0]), std::nullopt, std::nullopt};
    if (line || rate) {
      if (g.fold.stats.count() == 0) continue;
      mark.summary = kind == MetricKind::number ? g.fold.stats.values(support) : g.fold.stats.rate();
      const Summary& s = *mark.summary;
      mean_lo = std::min(mean_lo, scale * s.mean);
      mean_hi = std::max(mean_hi, scale * s.mean);
      y_lo = std::min({y_lo, scale * s.mean, s.ci95 ? scale * s.ci95->low : HUGE_VAL});
      y_hi = std::max({y_hi, scale * s.mean, s.ci95 ? scale * s.ci95->high : -HUGE_VAL});
    } else {
      if (g.fold.values.count() == 0) continue;
      mark.box = g.fold.values.box();
      y_lo = std::min({y_lo, mark.box->whisker_low, mark.box->outliers.empty() ? HUGE_VAL : mark.box->outliers.front()});
      y_hi = std::max({y_hi, mark.box->whisker_high, mark.box->outliers.empty() ? -HUGE_VAL : mark.box->outliers.back()});
    }
    marks.push_back(std::move(mark));
  }
  if (marks.empty()) throw InputError(cli, "--y", "a metric with values: no run has \"" + request.y + "\"");
  if (line && !rate) std::tie(y_lo, y_hi) = interval_range(mean_lo, mean_hi, y_lo, y_hi);

  // Layout: title and note on top, the legend right of the plot.
  const ChartStyle& style = kPaperStyle;
  const std::string series_label = request.group.empty() ? metric_heading(request.y) : "";
  std::vector<LegendRow> legend;
  for (std::size_t i = 0; i < series.size(); ++i) {
    const cv::Scalar color = run_color(i);
    const std::string text = request.group.empty() ? series_label : (series[i].is_null() ? "-" : value_label(series[i]));
    if (line || rate) {
      legend.push_back(line_row(color, text, style));
    } else {
      legend.push_back({[color, &box_style = style](figure::Canvas& m, cv::Point2d c) {
                          const cv::Point2d half(0.5 * box_style.legend_row_px, 0.3 * box_style.legend_row_px);
                          draw_box(m, c - half, c + half, color, box_style);
                        },
                        text});
    }
  }
  // What the error bars are, named in the legend.
  if (rate) {
    legend.push_back(interval_row("rate, 95% Wilson", style));
  } else if (line) {
    legend.push_back(interval_row(interval_name(support), style));
  }
  const std::string legend_heading = request.group.empty() ? "" : field_heading(request.group);
  // At most 30 % of the width (the legend's interval name fits at 1600 px); longer texts are scaled down.
  const int legend_px = legend_width(legend, legend_heading, style, 220, config.width_px * 3 / 10);
  const int left = 170, top = 150, bottom_margin = 130;
  const cv::Rect plot_px(left, top, config.width_px - left - legend_px - 70, config.height_px - top - bottom_margin);

  double x0 = -0.5, x1 = xs.size() - 0.5;
  if (line) {
    const double x_min = x_axis.ticks.front().value, x_max = x_axis.ticks.back().value;
    std::tie(x0, x1) = x_max > x_min ? padded(x_min, x_max, 0.0) : std::pair{x_min - 1.0, x_max + 1.0};
  }
  const auto [y0, y1] = rate ? std::pair{-5.0, 105.0} : padded(y_lo, y_hi, y_hi > y_lo ? 0.0 : std::max(std::abs(y_hi) * 0.1, 0.5));
  const PlotFrame frame{plot_px, x0, x1, y0, y1};
  const std::vector<Tick> y_ticks = rate ? percent_ticks() : linear_ticks(y0, y1, plot_px.height / figure::kTickSpacingPx);
  std::vector<Tick> x_ticks = x_axis.ticks;
  if (!line) {
    for (std::size_t i = 0; i < xs.size(); ++i) x_ticks.push_back({double(i), xs[i].is_null() ? "-" : value_label(xs[i])});
  }

  figure::Canvas canvas({config.width_px, config.height_px});
  const std::string y_label = request.y_label.empty() ? metric_heading(request.y) : request.y_label;
  const std::string title = !request.title.empty() ? request.title
                                                   : layout.name + ": " + metric_heading(request.y) + " vs " +
                                                         quantity_name(request.x).words;
  put_title(canvas, title, {0, 10, config.width_px, 60}, style.title);
  const std::string spread = rate   ? "rate with 95% Wilson interval"
                             : line ? (support == Support::non_negative
                                           ? "mean and 95% confidence interval (t on the log scale: the metric is >= 0)"
                                           : "mean and 95% confidence interval (Student t)")
                                    : "median, quartiles, whiskers at 1.5 IQR, outliers";
  const std::string note = spread + "; " + std::to_string(run_count) + " runs" +
                           (failed > 0 ? ", " + std::to_string(failed) + " failed" : "");
  figure::put_text(canvas, note, {config.width_px * 0.5, 95.0}, style.note, figure::kMutedInk, Align::centre);

  draw_grid(canvas, frame, line ? x_ticks : std::vector<Tick>{}, y_ticks);
  // Series side by side within a category (box) or slightly apart (line).
  const double slot_px = line ? style.dodge_px : 0.8 * plot_px.width / xs.size() / series.size();
  for (std::size_t i = 0; i < series.size(); ++i) {
    const cv::Scalar color = run_color(i);
    const double dodge = (static_cast<double>(i) - 0.5 * (series.size() - 1.0)) * slot_px;
    std::vector<Point> points;
    for (const Mark& m : marks) {
      if (m.series != i) continue;
      if (m.summary) {
        const Summary& s = *m.summary;
        points.push_back({m.x, scale * s.mean, s.ci95 ? scale * s.ci95->low : scale * s.mean,
                          s.ci95 ? scale * s.ci95->high : scale * s.mean});
        continue;
      }
      // A box: whiskers, the box from Q1 to Q3, the median, outliers.
      const BoxStats& b = *m.box;
      const double cx = frame.to_px(m.x, 0.0).x + dodge;
      const double half = std::min(0.4 * slot_px, 45.0);
      const auto y_px = [&](double v) { return frame.to_px(m.x, v).y; };
      draw_error_bar(canvas, {cx, y_px(b.whisker_low)}, {cx, y_px(b.q1)}, color, style);
      draw_error_bar(canvas, {cx, y_px(b.q3)}, {cx, y_px(b.whisker_high)}, color, style);
      draw_box(canvas, {cx - half, y_px(b.q3)}, {cx + half, y_px(b.q1)}, color, style);
      canvas.line({cx - half, y_px(b.median)}, {cx + half, y_px(b.median)}, figure::shade(color, 0.55),
                  style.line_px + 1.0);
      for (double v : b.outliers) canvas.circle({cx, y_px(v)}, style.marker_px, color, style.bar_px);
    }
    std::sort(points.begin(), points.end(), [](const Point& a, const Point& b) { return a.x < b.x; });
    draw_series(canvas, frame, points, dodge, color, style, line);
  }
  const std::string x_label =
      !request.x_label.empty() ? request.x_label : field_heading(request.x) + (x_axis.log2 ? ", log2 scale" : "");
  draw_axes(canvas, frame, x_ticks, y_ticks, x_label, y_label, style);
  draw_legend(canvas, {plot_px.x + plot_px.width + 40, plot_px.y}, legend_px, legend, legend_heading, style);
  return canvas;
}

}  // namespace campo
