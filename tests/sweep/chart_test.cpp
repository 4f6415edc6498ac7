// The sweep chart and plots: when they apply, what they show, and that they
// are drawn the same every time.
#include "sweep/chart.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "campo/json_reader.hpp"
#include "render/figure_canvas.hpp"
#include "render/figure_style.hpp"
#include "render/figures.hpp"
#include "sweep/table.hpp"
#include "tests/render/vector_outputs.hpp"
#include "tests/sweep/results_fixture.hpp"

namespace campo {
namespace {

namespace fs = std::filesystem;

TableRow row(const std::string& scene, nlohmann::json value, double ratio, double sd, double success) {
  TableRow r;
  r.scene = scene;
  r.params = {std::move(value)};
  r.runs = 3;
  r.success_rate = success;
  r.path_ratio = MeanSd{ratio, sd};
  r.path_ratio_reached = MeanSd{ratio, sd};
  return r;
}

SweepTable resolution_table() {
  SweepTable table{"resolution_000", {"resolution"}, {}};
  for (int res : {256, 128, 64, 32, 16}) {
    table.rows.push_back(row("two_barriers", res, 1.02 + 1.0 / res, 0.01, res >= 32 ? 1.0 : 2.0 / 3.0));
  }
  for (int res : {256, 128, 64, 32, 16}) {
    table.rows.push_back(row("trees_rolling_terrain", res, 1.04 + 2.0 / res, 0.02, res >= 64 ? 1.0 : 1.0 / 3.0));
  }
  table.rows.back().path_ratio.reset();  // no completed run at 16: no path point
  table.rows.back().path_ratio_reached.reset();
  return table;
}

TEST(SweepChart, OnlyForOneNumericAxis) {
  EXPECT_TRUE(chartable(resolution_table()));
  SweepTable two_axes = resolution_table();
  two_axes.axes.push_back("speed");
  EXPECT_FALSE(chartable(two_axes));
  SweepTable text{"t", {"planner"}, {row("s", "straight", 1.0, 0.0, 1.0)}};
  EXPECT_FALSE(chartable(text));
  EXPECT_FALSE(chartable(SweepTable{"t", {"resolution"}, {}}));
  EXPECT_THROW(draw_sweep_chart(text), std::invalid_argument);
}

// The PNG bytes of a chart.
std::string png(const SweepTable& table) { return draw_sweep_chart(table).encode(figure::FigureFormat::png); }

TEST(SweepChart, SameTableSameBytes) {
  const cv::Mat image = draw_sweep_chart(resolution_table()).raster();
  EXPECT_EQ(image.type(), CV_8UC3);
  EXPECT_GT(image.cols, 1000);
  EXPECT_GT(image.rows, 400);
  EXPECT_EQ(png(resolution_table()), png(resolution_table()));
  // Not blank: the two series are drawn in colour.
  cv::Mat hsv;
  cv::cvtColor(image, hsv, cv::COLOR_BGR2HSV);
  std::vector<cv::Mat> channels;
  cv::split(hsv, channels);
  EXPECT_GT(cv::countNonZero(channels[1] > 100), 500);
}

TEST(SweepChart, PathRatioOfTheReachedRunsOnly) {
  const std::string base = png(resolution_table());
  // An aborted run's short path lowers the all-run mean: the chart does not show it.
  SweepTable aborted = resolution_table();
  aborted.rows[1].path_ratio = MeanSd{0.6, 0.4};
  EXPECT_EQ(png(aborted), base);
  SweepTable longer = resolution_table();
  longer.rows[1].path_ratio_reached = MeanSd{1.3, 0.05};
  EXPECT_NE(png(longer), base);
}

// The chart's error bars are the 95 % interval the tables and plots give (MeanSd::ci95), not ± sd.
TEST(SweepChart, ErrorBarsAreTheConfidenceIntervalNotTheSd) {
  SweepTable with_ci = resolution_table();
  with_ci.rows[1].path_ratio_reached = MeanSd{1.03, 0.01, Interval{1.0, 1.2}};
  SweepTable other_sd = with_ci;
  other_sd.rows[1].path_ratio_reached->sd = 0.3;  // the sd alone changes nothing drawn
  EXPECT_EQ(png(with_ci), png(other_sd));
  SweepTable wider = with_ci;
  wider.rows[1].path_ratio_reached->ci95 = Interval{0.9, 1.4};
  EXPECT_NE(png(wider), png(with_ci));
  // The summary's intervals are those of values >= 0: from two runs of ratios 1 and 2 none reaches below 0.
  RunningStats two;
  two.add(1.0);
  two.add(2.0);
  EXPECT_GT(two.values(Support::non_negative).ci95->low, 0.0);
  EXPECT_LT(two.values(Support::real).ci95->low, 0.0);  // the t interval would
}

// The centres of the markers drawn in `color`, left to right: the pixels of that colour, eroded
// until only the markers' discs (8 px across) remain of them, not the series' lines (3 px) or
// error bars (1.5 px).
std::vector<cv::Point2d> marker_centres(const cv::Mat& image, const cv::Scalar& color) {
  cv::Mat mask;
  const cv::Scalar tolerance(10, 10, 10);
  cv::inRange(image, color - tolerance, color + tolerance, mask);
  cv::erode(mask, mask, cv::getStructuringElement(cv::MORPH_ELLIPSE, {5, 5}));
  cv::Mat labels, stats, centroids;
  const int count = cv::connectedComponentsWithStats(mask, labels, stats, centroids);
  std::vector<cv::Point2d> centres;
  for (int i = 1; i < count; ++i) centres.emplace_back(centroids.at<double>(i, 0), centroids.at<double>(i, 1));
  std::sort(centres.begin(), centres.end(), [](const cv::Point2d& a, const cv::Point2d& b) { return a.x < b.x; });
  return centres;
}

// The largest distance of (values[i], px[i]) from their least-squares line: 0 when px is an affine function of values.
double affine_misfit_px(const std::vector<double>& values, const std::vector<double>& px) {
  const double n = static_cast<double>(values.size());
  double sv = 0, sp = 0, svv = 0, svp = 0;
  for (std::size_t i = 0; i < values.size(); ++i) {
    sv += values[i];
    sp += px[i];
    svv += values[i] * values[i];
    svp += values[i] * px[i];
  }
  const double slope = (n * svp - sv * sp) / (n * svv - sv * sv);
  const double offset = (sp - slope * sv) / n;
  double worst = 0.0;
  for (std::size_t i = 0; i < values.size(); ++i) worst = std::max(worst, std::abs(offset + slope * values[i] - px[i]));
  return worst;
}

// Values that are not all powers of two are placed in proportion to their value: read back from the
// markers drawn, their x pixels are an affine function of the values, in both panels. The last gap
// (0.9 to 2.1) is four times the first (0.3 to 0.6): a log2 axis would make it 1.22 times, one of
// categories the same.
TEST(SweepChart, LinearAxisForOtherValues) {
  const std::vector<double> values{0.3, 0.6, 0.9, 1.2, 2.1};
  SweepTable table{"speeds", {"speed"}, {}};
  for (double v : values) {
    table.rows.push_back(row("two_barriers", v, 1.0 + v / 10, 0.01, 1.0));
    table.rows.back().reached = table.rows.back().runs;
  }
  const cv::Mat image = draw_sweep_chart(table).raster();
  const std::vector<cv::Point2d> markers = marker_centres(image, run_color(0));
  // Five in each panel, left then right, and the legend's, right of both.
  ASSERT_EQ(markers.size(), 2 * values.size() + 1);
  for (const std::size_t panel : {0u, 1u}) {
    const std::vector<cv::Point2d> m(markers.begin() + panel * values.size(),
                                     markers.begin() + (panel + 1) * values.size());
    std::vector<double> x_px, y_px;
    for (const cv::Point2d& p : m) {
      x_px.push_back(p.x);
      y_px.push_back(p.y);
    }
    EXPECT_LT(affine_misfit_px(values, x_px), 1.0) << "panel " << panel;
    EXPECT_NEAR((x_px[4] - x_px[2]) / (x_px[1] - x_px[0]), 4.0, 0.05) << "panel " << panel;
    // The y axes are linear too: the path ratios (1 + v / 10) rise with v; every success rate is 100 %.
    if (panel == 0) {
      EXPECT_LT(affine_misfit_px(values, y_px), 1.0);
      EXPECT_LT(y_px.back(), y_px.front() - 10.0);
    } else {
      EXPECT_LT(*std::max_element(y_px.begin(), y_px.end()) - *std::min_element(y_px.begin(), y_px.end()), 1.0);
    }
  }
}

// The chart as PDF and SVG: the panels' titles, an axis label and the legend as text in the PDF,
// and both render like the PNG.
TEST(SweepChart, PdfAndSvgHoldTheSameChart) {
  figure::test::expect_vector_outputs(draw_sweep_chart(resolution_table()),
                                      {"Normalized path length, reached runs", "Success rate", field_heading("resolution"),
                                       "two_barriers", "trees_rolling_terrain", "rate, 95% Wilson"});
}

// Where --out / --chart put each format: a figure extension replaced, any other name extended.
TEST(FigureFiles, ExtensionReplacedOrAppended) {
  using figure::FigureFormat;
  const std::vector<FigureFormat> all{FigureFormat::png, FigureFormat::pdf, FigureFormat::svg};
  EXPECT_EQ(figure::figure_files("out/fig.png", all),
            (std::vector<fs::path>{"out/fig.png", "out/fig.pdf", "out/fig.svg"}));
  EXPECT_EQ(figure::figure_files("fig.png", {FigureFormat::pdf}), std::vector<fs::path>{"fig.pdf"});
  EXPECT_EQ(figure::figure_files("fig.SVG", {FigureFormat::png}), std::vector<fs::path>{"fig.png"});
  EXPECT_EQ(figure::figure_files("fig", {FigureFormat::png, FigureFormat::pdf}),
            (std::vector<fs::path>{"fig.png", "fig.pdf"}));
  EXPECT_EQ(figure::figure_files("run.v2", {FigureFormat::svg}), std::vector<fs::path>{"run.v2.svg"});
  EXPECT_EQ(figure::figure_files("dir.d/fig", {FigureFormat::png}), std::vector<fs::path>{"dir.d/fig.png"});
}

class SweepPlot : public testing::FixtureSweepTest {
 protected:
  // Pixels within `tolerance` of `color` (BGR) in `region`.
  static int pixels_of(const cv::Mat& image, const cv::Scalar& color, const cv::Rect& region, int tolerance = 12) {
    cv::Mat mask;
    const cv::Scalar t(tolerance, tolerance, tolerance);
    cv::inRange(image(region), color - t, color + t, mask);
    return cv::countNonZero(mask);
  }

  std::string error_of(const PlotRequest& request) const {
    try {
      draw_sweep_plot(runs_, layout_, request);
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  }

};

TEST_F(SweepPlot, LinePlotIsAPaperSizedDeterministicPngWithALegend) {
  const PlotRequest request{.x = "resolution", .y = "path_ratio", .group = "scene"};
  const figure::Canvas canvas = draw_sweep_plot(runs_, layout_, request);
  const cv::Mat image = canvas.raster();
  EXPECT_EQ(image.type(), CV_8UC3);
  EXPECT_EQ(image.cols, 1600);
  EXPECT_EQ(image.rows, 1000);
  EXPECT_EQ(canvas.encode(figure::FigureFormat::png),
            draw_sweep_plot(runs_, layout_, request).encode(figure::FigureFormat::png));

  // Both series' colours inside the plot area (below the title, left of x 1070) and in the legend (right of
  // x 1100: at most 30 % of the width, and the legend's interval name makes it about that wide).
  const cv::Rect plot(170, 150, 900, 700), legend(1100, 150, 500, 300);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_GT(pixels_of(image, run_color(i), plot), 200) << "series " << i;
    EXPECT_GT(pixels_of(image, run_color(i), legend), 50) << "legend entry " << i;
  }
  EXPECT_EQ(pixels_of(image, run_color(2), plot), 0);  // two series only
  // Text on top (the title) and dark pixels left of the plot (tick labels and the y label).
  cv::Mat grey;
  cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  EXPECT_GT(cv::countNonZero(grey(cv::Rect(300, 10, 1000, 60)) < 100), 500);
  EXPECT_GT(cv::countNonZero(grey(cv::Rect(0, 150, 160, 700)) < 100), 300);
  // The legend box ends 30 px before the right edge and its texts within it: nothing drawn beyond.
  EXPECT_EQ(cv::countNonZero(grey(cv::Rect(1572, 0, 28, 1000)) < 250), 0);

  EXPECT_EQ(canvas.write(dir_ / "plot.png", {figure::FigureFormat::png}),
            std::vector<fs::path>{dir_ / "plot.png"});
  EXPECT_EQ(cv::imread((dir_ / "plot.png").string()).size(), image.size());
}

// The plot as PDF and SVG: title, axis labels, the note and the legend as text; both render like the PNG.
TEST_F(SweepPlot, PdfAndSvgHoldTheSamePlot) {
  const PlotRequest request{.x = "resolution", .y = "path_ratio", .group = "scene", .title = "Ratio by resolution"};
  figure::test::expect_vector_outputs(draw_sweep_plot(runs_, layout_, request),
                                      {"Ratio by resolution", field_heading("resolution"), metric_heading("path_ratio"),
                                       "two_barriers", field_heading("scene"), "mean, 95% CI (log t)"});
  // A box plot too (boxes are filled rectangles, outliers circles).
  figure::test::expect_vector_outputs(draw_sweep_plot(runs_, layout_, {.x = "scene", .y = "sim_time_s", .group = "resolution"}),
                                      {field_heading("scene"), "two_barriers"});
}

TEST_F(SweepPlot, BoxPlotForCategoriesAndRatesInPercent) {
  const cv::Mat box = draw_sweep_plot(runs_, layout_, {.x = "scene", .y = "sim_time_s", .group = "resolution"}).raster();
  const cv::Rect plot(170, 150, 1000, 700);
  // Boxes filled with the series' colour lightened (resolution 32), medians darker (16: equal values, flat boxes).
  EXPECT_GT(pixels_of(box, figure::lighten(run_color(0), 0.55), plot, 4), 500);
  EXPECT_GT(pixels_of(box, figure::shade(run_color(1), 0.55), plot, 4), 100);
  // Forcing a box plot of a numeric field, and a line plot of a rate, work too.
  EXPECT_FALSE(draw_sweep_plot(runs_, layout_, {.x = "resolution", .y = "sim_time_s", .kind = PlotKind::box})
                   .raster()
                   .empty());
  const cv::Mat rate = draw_sweep_plot(runs_, layout_, {.x = "resolution", .y = "success"}).raster();
  EXPECT_GT(pixels_of(rate, run_color(0), plot), 200);
  EXPECT_NE(cv::norm(rate, box, cv::NORM_L1), 0.0);
}

TEST_F(SweepPlot, ErrorsNameTheOption) {
  EXPECT_THAT(error_of({.x = "resolution", .y = "path_ratios"}),
              ::testing::HasSubstr("command line: --y: expected a metric of the runs (success, "));
  EXPECT_THAT(error_of({.x = "res", .y = "success"}), ::testing::HasSubstr("command line: --x: expected a field"));
  EXPECT_THAT(error_of({.x = "scene", .y = "success", .group = "scene"}),
              ::testing::HasSubstr("--group: a field other than --x"));
  EXPECT_THAT(error_of({.x = "scene", .y = "success", .kind = PlotKind::line}),
              ::testing::HasSubstr("--kind: line needs numeric values of --x \"scene\"; use --kind box"));
}

}  // namespace
}  // namespace campo
