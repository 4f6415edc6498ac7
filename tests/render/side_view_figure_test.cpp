#include "render/side_view_figure.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

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

TEST(FiguresSideView, MissionAltitudeIsLinearBetweenKnots) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<double> z = mission_altitude_m({-1.0, 0.0, 5.0, 10.0, 15.0, 20.0, 25.0}, {{0.0, 0.0}, {10.0, 10.0}, {20.0, 10.0}});
  const std::vector<double> expected{nan, 0.0, 5.0, 10.0, 10.0, 10.0, nan};
  ASSERT_EQ(z.size(), expected.size());
  for (std::size_t i = 0; i < z.size(); ++i) {
    if (std::isnan(expected[i])) EXPECT_TRUE(std::isnan(z[i])) << i;
    else EXPECT_DOUBLE_EQ(z[i], expected[i]) << i;
  }
  // A climb at one distance (two knots there): the later altitude from there on.
  const std::vector<double> step = mission_altitude_m({2.5, 5.0, 7.5}, {{0.0, 0.0}, {5.0, 0.0}, {5.0, 7.0}, {10.0, 7.0}});
  EXPECT_DOUBLE_EQ(step[0], 0.0);
  EXPECT_DOUBLE_EQ(step[1], 7.0);
  EXPECT_DOUBLE_EQ(step[2], 7.0);
  EXPECT_TRUE(mission_altitude_m({1.0}, {}).size() == 1 && std::isnan(mission_altitude_m({1.0}, {})[0]));
}

TEST(FiguresSideView, DrawsTheMissionAltitudeWhereTheTrackLeavesIt) {
  // The mission asks for 6 m at its second waypoint while the track stays at 3 m: the dashed grey line rises from
  // 3 m at the first waypoint's closest approach (6 m along the track) to 6 m at the second's (12 m), above the track.
  const Scene scene = test_scene();
  const FigureStyle style = small_style();
  // Dark neutral pixels between 7 and 10.5 m along the track and 3.6 to 6 m high: away from the markers (at 6, 12
  // and 16 m) and from the track's line at 3 m; the grid's lines are lighter.
  const auto grey_above_track = [&](const RunView& run) {
    const FigureLayout layout = side_view_layout(scene, run, style);
    const cv::Mat image = draw_side_view(scene, run, style);
    const cv::Point2d low = layout.to_px({7.0, 3.6}), high = layout.to_px({10.5, 6.0});
    int grey = 0;
    for (int y = static_cast<int>(high.y); y <= static_cast<int>(low.y); ++y) {
      for (int x = static_cast<int>(low.x); x <= static_cast<int>(high.x); ++x) {
        if (!layout.plot_px.contains({x, y})) continue;  // a lower plot ends below 3.6 m
        const cv::Vec3b c = image.at<cv::Vec3b>(y, x);
        grey += std::abs(c[0] - c[1]) < 8 && std::abs(c[1] - c[2]) < 8 && c[0] < 160;
      }
    }
    return grey;
  };
  RunView raised = test_run();
  raised.mission[1].position_m.z() = 6.0;
  EXPECT_GT(grey_above_track(raised), 10);
  // With the waypoints there at the track's altitude the line lies under the track: nothing grey above it (a last
  // waypoint 7 m up at the end keeps the plot's range over the region looked at).
  RunView flat = test_run();
  flat.mission.push_back(Waypoint{{8.0, 0.0, 7.0}, {}});
  ASSERT_GT(side_view_layout(scene, flat, style).to_px({7.0, 6.0}).y, side_view_layout(scene, flat, style).plot_px.y);
  EXPECT_EQ(grey_above_track(flat), 0);
}

TEST(FiguresSideView, IsDeterministic) {
  const Scene scene = test_scene();
  EXPECT_EQ(png(draw_side_view(scene, test_run(), small_style())), png(draw_side_view(scene, test_run(), small_style())));
}

}  // namespace
}  // namespace campo
