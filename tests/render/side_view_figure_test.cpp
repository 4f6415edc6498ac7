#include "render/side_view_figure.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <opencv2/core.hpp>

#include "tests/render/figure_test_support.hpp"

namespace campo {
namespace {

using namespace figure::test;

TEST(FiguresSideView, HasTheDocumentedSize) {
  const Scene scene = test_scene();
  const FigureStyle style = small_style();
  const FigureLayout layout = side_view_layout(scene, test_run(), style);
  const cv::Mat image = draw_side_view(scene, test_run(), style);
  EXPECT_EQ(image.size(), layout.image_px);
  EXPECT_EQ(layout.plot_px.width, style.max_size_px);
  EXPECT_GE(layout.plot_px.height, 240);
  EXPECT_EQ(image.cols, kFigureLeftPx + style.max_size_px + kFigurePanelPx);
  // The test scene has ground beneath the track: the height-above-ground panel below.
  ASSERT_FALSE(layout.agl_plot_px.empty());
  EXPECT_EQ(layout.agl_plot_px.width, style.max_size_px);
  EXPECT_EQ(layout.agl_plot_px.height, std::max(120, static_cast<int>(std::lround(0.12 * style.max_size_px))));
  EXPECT_EQ(layout.agl_plot_px.y, kFigureTitlePx + layout.plot_px.height + kFigureBottomPx);
  EXPECT_EQ(image.rows, kFigureTitlePx + layout.plot_px.height + kFigureBottomPx + layout.agl_plot_px.height +
                            kFigureBottomPx);
  EXPECT_GT(non_background(image, layout.agl_plot_px), 1000);
  EXPECT_TRUE(layout.scalebar_px.empty());
  EXPECT_GT(non_background(image, layout.title_px), 100);
  EXPECT_GT(non_background(image, layout.legend_px), 1000);
}

TEST(FiguresSideView, FillsTheTerrainBelowAFlyingTrack) {
  const Scene scene = test_scene();
  const RunView run = test_run();
  const FigureStyle style = small_style();
  const FigureLayout layout = side_view_layout(scene, run, style);
  const cv::Mat image = draw_side_view(scene, run, style);
  const int plot_bottom = layout.plot_px.y + layout.plot_px.height - 1;
  // Away from the markers: start at 0 m, waypoints at 6, 12 and 16 m.
  for (const int i : {20, 90, 100}) {
    // Distance along the track is horizontal: 0.1 m per sample here.
    const double s = 0.1 * i;
    const Eigen::Vector3d& q = run.track[i].position_m;
    const double ground = *scene.ground_height(q.x(), q.y());
    ASSERT_LT(ground + 1.0, q.z());
    const cv::Point2d vehicle = layout.to_px({s, q.z()}), surface = layout.to_px({s, ground});
    const int col = static_cast<int>(std::lround(vehicle.x));
    // The vehicle's curve (blue), open air below it, then the terrain fill down to the plot's bottom.
    const cv::Vec3b curve = at(image, vehicle);
    EXPECT_GT(curve[0], curve[2] + 60) << "sample " << i;
    const cv::Vec3b fill = image.at<cv::Vec3b>(plot_bottom - 2, col);
    EXPECT_NE(fill, kBackground);
    EXPECT_EQ(image.at<cv::Vec3b>(static_cast<int>(surface.y) + 6, col), fill);
    const cv::Vec3b air = at(image, (vehicle + surface) * 0.5);
    EXPECT_GT(colour_distance(air, fill), 60) << "sample " << i;
  }
}

TEST(FiguresSideView, ThePanelBelowShowsTheHeightAboveGround) {
  // The vehicle's curve in the lower panel sits at altitude minus ground
  // height; the band between the lowest and highest is shaded behind it.
  const Scene scene = test_scene();
  const RunView run = test_run();
  const FigureStyle style = small_style();
  const FigureLayout layout = side_view_layout(scene, run, style);
  const cv::Mat image = draw_side_view(scene, run, style);
  double lo = INFINITY, hi = -INFINITY;
  for (const TrackPoint& t : run.track) {
    const double h = t.position_m.z() - *scene.ground_height(t.position_m.x(), t.position_m.y());
    lo = std::min(lo, h);
    hi = std::max(hi, h);
  }
  const cv::Rect& r = layout.agl_plot_px;
  const double pad = std::max(0.15 * (hi - lo), 0.3);
  const double y0 = std::min(0.0, lo - pad), y1 = hi + pad;
  const auto row_of = [&](double h) { return r.y - 0.5 + (y1 - h) / (y1 - y0) * r.height; };  // PlotFrame::to_px
  for (const int i : {20, 90}) {
    const Eigen::Vector3d& q = run.track[i].position_m;
    const double h = q.z() - *scene.ground_height(q.x(), q.y());
    const double s = 0.1 * i;  // horizontal distance along the track (see above)
    const int col = static_cast<int>(std::lround(layout.to_px({s, 0.0}).x));
    const cv::Vec3b curve = image.at<cv::Vec3b>(static_cast<int>(std::lround(row_of(h))), col);
    EXPECT_GT(curve[0], curve[2] + 60) << "sample " << i;  // the vehicle's blue
  }
}

TEST(FiguresSideView, IsDeterministic) {
  const Scene scene = test_scene();
  EXPECT_EQ(png(draw_side_view(scene, test_run(), small_style())), png(draw_side_view(scene, test_run(), small_style())));
}

}  // namespace
}  // namespace campo
