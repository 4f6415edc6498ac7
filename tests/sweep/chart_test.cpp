// The sweep chart: when it applies, and that it is drawn the same every time.
#include "sweep/chart.hpp"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <gtest/gtest.h>

namespace campo {
namespace {

TableRow row(const std::string& scene, nlohmann::json value, double ratio, double sd, double success) {
  TableRow r;
  r.scene = scene;
  r.params = {std::move(value)};
  r.runs = 3;
  r.success_rate = success;
  r.path_ratio = MeanSd{ratio, sd};
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

TEST(SweepChart, SameTableSameBytes) {
  const cv::Mat image = draw_sweep_chart(resolution_table());
  EXPECT_EQ(image.type(), CV_8UC3);
  EXPECT_GT(image.cols, 1000);
  EXPECT_GT(image.rows, 400);
  std::vector<uchar> a, b;
  cv::imencode(".png", image, a);
  cv::imencode(".png", draw_sweep_chart(resolution_table()), b);
  EXPECT_EQ(a, b);
  // Not blank: the two series are drawn in colour.
  cv::Mat hsv;
  cv::cvtColor(image, hsv, cv::COLOR_BGR2HSV);
  std::vector<cv::Mat> channels;
  cv::split(hsv, channels);
  EXPECT_GT(cv::countNonZero(channels[1] > 100), 500);
}

TEST(SweepChart, LinearAxisForOtherValues) {
  SweepTable table{"speeds", {"speed"}, {}};
  for (double v : {0.3, 0.6, 0.9, 1.2}) table.rows.push_back(row("two_barriers", v, 1.0 + v / 10, 0.01, 1.0));
  const cv::Mat image = draw_sweep_chart(table);
  EXPECT_FALSE(image.empty());
}

}  // namespace
}  // namespace campo
