#include "sweep/chart.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>

#include "render/figure_canvas.hpp"
#include "render/figures.hpp"
#include "sim/output_dir.hpp"
#include "sweep/sweep_spec.hpp"

namespace campo {

namespace {

using figure::Align;
using figure::PlotFrame;

// Layout, pixels: two plots side by side, the legend to their right.
constexpr int kHeight = 580;
constexpr int kTitleBandPx = 50;
constexpr int kPlotTop = 90, kPlotHeight = 410, kPlotWidth = 430;
constexpr int kLeftPlotX = 95, kRightPlotX = 640;
constexpr int kLegendX = 1100, kMinLegendWidth = 170, kMaxLegendWidth = 400;
constexpr double kDodgePx = 5.0;  ///< horizontal offset between series, so error bars do not overlap

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

void draw_grid(cv::Mat& image, const PlotFrame& frame, const std::vector<Tick>& x_ticks,
               const std::vector<Tick>& y_ticks) {
  const cv::Rect& p = frame.plot_px;
  for (const Tick& t : x_ticks) {
    const double x = frame.to_px(t.value, frame.y0).x;
    cv::line(image, figure::fixed({x, p.y - 0.5}), figure::fixed({x, p.y + p.height - 0.5}), figure::kGridInk, 1,
             cv::LINE_AA, figure::kShift);
  }
  for (const Tick& t : y_ticks) {
    const double y = frame.to_px(frame.x0, t.value).y;
    cv::line(image, figure::fixed({p.x - 0.5, y}), figure::fixed({p.x + p.width - 0.5, y}), figure::kGridInk, 1,
             cv::LINE_AA, figure::kShift);
  }
}

// Frame, ticks with labels (an x label that would overlap the previous one is left out) and axis titles.
void draw_axes(cv::Mat& image, const PlotFrame& frame, const std::vector<Tick>& x_ticks,
               const std::vector<Tick>& y_ticks, const std::string& x_label, const std::string& y_label) {
  const cv::Rect& p = frame.plot_px;
  cv::rectangle(image, {p.x - 1, p.y - 1}, {p.x + p.width, p.y + p.height}, figure::kInk, 1, cv::LINE_8);
  const double bottom = p.y + p.height;
  double free_from = -1e9;  // x where the next tick label may start
  for (const Tick& t : x_ticks) {
    const double x = frame.to_px(t.value, frame.y0).x;
    cv::line(image, figure::fixed({x, bottom}), figure::fixed({x, bottom + 5.0}), figure::kInk, 1, cv::LINE_AA,
             figure::kShift);
    const double half = 0.5 * figure::text_size(t.label, figure::kTickFont).width;
    if (x - half < free_from) continue;
    figure::put_text(image, t.label, {x, bottom + 17.0}, figure::kTickFont, figure::kInk, Align::centre);
    free_from = x + half + 8.0;
  }
  int widest = 0;
  for (const Tick& t : y_ticks) {
    const double y = frame.to_px(frame.x0, t.value).y;
    cv::line(image, figure::fixed({p.x - 6.0, y}), figure::fixed({p.x - 1.0, y}), figure::kInk, 1, cv::LINE_AA,
             figure::kShift);
    figure::put_text(image, t.label, {p.x - 10.0, y}, figure::kTickFont, figure::kInk, Align::right);
    widest = std::max(widest, figure::text_size(t.label, figure::kTickFont).width);
  }
  figure::put_text(image, x_label, {p.x + 0.5 * p.width, bottom + 42.0}, figure::kLabelFont, figure::kInk,
                   Align::centre);
  figure::put_text_vertical(image, y_label, {p.x - 10.0 - widest - 16.0, p.y + 0.5 * p.height},
                            figure::kLabelFont, figure::kInk);
}

// One point of a series: x in plot units, y, and the half height of its error bar.
struct Point {
  double x, y, error;
};

void draw_series(cv::Mat& image, const PlotFrame& frame, const std::vector<Point>& points, double dodge_px,
                 const cv::Scalar& color) {
  const auto px = [&](double x, double y) { return frame.to_px(x, y) + cv::Point2d(dodge_px, 0.0); };
  std::vector<cv::Point2d> line;
  for (const Point& p : points) line.push_back(px(p.x, p.y));
  figure::polyline(image, line, color, 2);
  for (const Point& p : points) {
    if (p.error <= 0.0) continue;
    const cv::Point2d lo = px(p.x, p.y - p.error), hi = px(p.x, p.y + p.error);
    cv::line(image, figure::fixed(lo), figure::fixed(hi), color, 1, cv::LINE_AA, figure::kShift);
    for (const cv::Point2d& end : {lo, hi}) {
      cv::line(image, figure::fixed(end - cv::Point2d(4, 0)), figure::fixed(end + cv::Point2d(4, 0)), color, 1,
               cv::LINE_AA, figure::kShift);
    }
  }
  for (const cv::Point2d& p : line) {
    cv::circle(image, figure::fixed(p), 6 << figure::kShift, figure::kWhite, cv::FILLED, cv::LINE_AA, figure::kShift);
    cv::circle(image, figure::fixed(p), 4 << figure::kShift, color, cv::FILLED, cv::LINE_AA, figure::kShift);
  }
}

// The table as series: one per scene, in order of first appearance.
struct Series {
  std::string scene;
  std::vector<Point> path_ratio;  ///< rows with completed runs only
  std::vector<Point> success;
};

}  // namespace

bool chartable(const SweepTable& table) {
  if (table.axes.size() != 1 || table.rows.empty()) return false;
  return std::all_of(table.rows.begin(), table.rows.end(),
                     [](const TableRow& row) { return row.params.front().is_number(); });
}

cv::Mat draw_sweep_chart(const SweepTable& table) {
  if (!chartable(table)) throw std::invalid_argument("draw_sweep_chart: expected one numeric axis");
  const std::string& axis = table.axes.front();
  const bool log2_x = std::all_of(table.rows.begin(), table.rows.end(),
                                  [](const TableRow& row) { return power_of_two(row.params.front().get<double>()); });
  const auto to_x = [&](double v) { return log2_x ? std::log2(v) : v; };

  std::vector<Series> series;
  std::vector<Tick> x_ticks;
  double ratio_lo = 1.0, ratio_hi = 1.0;  // the ideal ratio 1 is always in view
  for (const TableRow& row : table.rows) {
    auto it = std::find_if(series.begin(), series.end(), [&](const Series& s) { return s.scene == row.scene; });
    if (it == series.end()) it = series.insert(series.end(), Series{row.scene, {}, {}});
    const double x = to_x(row.params.front().get<double>());
    if (row.path_ratio) {
      it->path_ratio.push_back({x, row.path_ratio->mean, row.path_ratio->sd});
      ratio_lo = std::min(ratio_lo, row.path_ratio->mean - row.path_ratio->sd);
      ratio_hi = std::max(ratio_hi, row.path_ratio->mean + row.path_ratio->sd);
    }
    it->success.push_back({x, 100.0 * row.success_rate, 0.0});
    if (std::none_of(x_ticks.begin(), x_ticks.end(), [&](const Tick& t) { return t.value == x; })) {
      x_ticks.push_back({x, value_label(row.params.front())});
    }
  }
  for (Series& s : series) {
    for (auto* points : {&s.path_ratio, &s.success}) {
      std::sort(points->begin(), points->end(), [](const Point& a, const Point& b) { return a.x < b.x; });
    }
  }
  std::sort(x_ticks.begin(), x_ticks.end(), [](const Tick& a, const Tick& b) { return a.value < b.value; });

  // Data ranges with a margin, so no point sits on the frame.
  const double x_min = x_ticks.front().value, x_max = x_ticks.back().value;
  const double x_pad = x_max > x_min ? 0.08 * (x_max - x_min) : 1.0;
  const double ratio_pad = std::max(0.08 * (ratio_hi - ratio_lo), 0.02);
  const PlotFrame ratio_frame{{kLeftPlotX, kPlotTop, kPlotWidth, kPlotHeight}, x_min - x_pad, x_max + x_pad,
                              ratio_lo - ratio_pad, ratio_hi + ratio_pad};
  const PlotFrame success_frame{{kRightPlotX, kPlotTop, kPlotWidth, kPlotHeight}, x_min - x_pad, x_max + x_pad,
                                -5.0, 105.0};

  // The legend is as wide as the longest scene name needs (within limits); the image ends after it.
  int legend_width = kMinLegendWidth;
  for (const Series& s : series) {
    legend_width = std::max(legend_width, figure::text_size(s.scene, figure::kLegendFont).width + 72);
  }
  legend_width = std::min(legend_width, kMaxLegendWidth);
  const int width = kLegendX + legend_width + 15;

  cv::Mat image(kHeight, width, CV_8UC3, figure::kWhite);
  figure::put_title(image, table.name + ": path length and success rate vs " + axis, {0, 0, width, kTitleBandPx});
  const std::string x_label = axis + (log2_x ? " (log2 scale)" : "");
  const auto ratio_y = linear_ticks(ratio_frame.y0, ratio_frame.y1, kPlotHeight / figure::kTickSpacingPx);
  std::vector<Tick> success_y;
  for (int v = 0; v <= 100; v += 20) success_y.push_back({double(v), std::to_string(v)});

  const struct {
    const PlotFrame& frame;
    const std::vector<Tick>& y_ticks;
    std::string subtitle, y_label;
    std::vector<Point> Series::*points;
    std::optional<double> reference_y;  ///< a dashed line: the ideal value
  } panels[] = {
      {ratio_frame, ratio_y, "Normalized path length (mean +/- sd)", "path length / nominal route",
       &Series::path_ratio, 1.0},
      {success_frame, success_y, "Success rate (%)", "runs reaching the goal (%)", &Series::success, std::nullopt},
  };
  for (const auto& panel : panels) {
    const cv::Rect& p = panel.frame.plot_px;
    draw_grid(image, panel.frame, x_ticks, panel.y_ticks);
    if (panel.reference_y) {
      const double y = panel.frame.to_px(panel.frame.x0, *panel.reference_y).y;
      figure::dashed_polyline(image, {{p.x - 0.5, y}, {p.x + p.width - 0.5, y}}, figure::kMutedInk, 1, 6.0, 4.0);
    }
    figure::put_text(image, panel.subtitle, {p.x + 0.5 * p.width, p.y - 18.0}, figure::kLabelFont, figure::kInk,
                     Align::centre);
    for (std::size_t i = 0; i < series.size(); ++i) {
      const double dodge = (static_cast<double>(i) - 0.5 * (series.size() - 1.0)) * kDodgePx;
      draw_series(image, panel.frame, series[i].*panel.points, dodge, run_color(i));
    }
    draw_axes(image, panel.frame, x_ticks, panel.y_ticks, x_label, panel.y_label);
  }

  std::vector<figure::LegendEntry> entries;
  for (std::size_t i = 0; i < series.size(); ++i) {
    const cv::Scalar color = run_color(i);
    entries.push_back({[color](cv::Mat& m, cv::Point2d c) {
                         figure::polyline(m, {c - cv::Point2d(14, 0), c + cv::Point2d(14, 0)}, color, 2);
                         cv::circle(m, figure::fixed(c), 4 << figure::kShift, color, cv::FILLED, cv::LINE_AA,
                                    figure::kShift);
                       },
                       series[i].scene});
  }
  figure::draw_legend(image, {kLegendX, kPlotTop, legend_width, figure::legend_height(entries.size())}, entries);
  return image;
}

void write_sweep_chart(const SweepTable& table, const std::filesystem::path& png) {
  std::vector<uchar> bytes;
  if (!cv::imencode(".png", draw_sweep_chart(table), bytes)) throw std::runtime_error("cannot encode the chart");
  write_file_atomically(png, std::string(bytes.begin(), bytes.end()));
}

}  // namespace campo
