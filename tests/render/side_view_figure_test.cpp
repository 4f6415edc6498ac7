#include "render/side_view_figure.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "campo/scene_loader.hpp"
#include "render/figure_canvas.hpp"
#include "tests/render/figure_test_support.hpp"

namespace campo {
namespace {

using namespace figure::test;

TEST(FiguresSideView, HasTheDocumentedSize) {
  const Scene scene = test_scene();
  const FigureStyle style = small_style();
  const FigureLayout layout = side_view_layout(scene, test_run(), style);
  const cv::Mat image = draw_side_view(scene, test_run(), style).raster();
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
  const cv::Mat image = draw_side_view(scene, run, style).raster();
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
  const cv::Mat image = draw_side_view(scene, run, style).raster();
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
    const cv::Mat image = draw_side_view(scene, run, style).raster();
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
  EXPECT_EQ(png(draw_side_view(scene, test_run(), small_style()).raster()),
            png(draw_side_view(scene, test_run(), small_style()).raster()));
}

TEST(FiguresSideView, WritesPdfAndSvgWithTextAsText) {
  const Scene scene = test_scene();
  expect_vector_outputs(draw_side_view(scene, test_run(), small_style()),
                        {"Test figure", "altitude (m)", "above ground (m)", "vehicle altitude"});
}

// Rows of `image` within `area` holding ink (darker than the light greys of grids and bands), in runs of
// consecutive rows: the lines of text in a column of labels.
std::vector<std::pair<int, int>> ink_row_runs(const cv::Mat& image, const cv::Rect& area) {
  std::vector<std::pair<int, int>> runs;
  for (int y = area.y; y < area.y + area.height; ++y) {
    bool ink = false;
    for (int x = area.x; x < area.x + area.width && !ink; ++x) {
      const cv::Vec3b c = image.at<cv::Vec3b>(y, x);
      ink = c[0] < 150 && c[1] < 150 && c[2] < 150;
    }
    if (!ink) continue;
    if (!runs.empty() && runs.back().second == y - 1) runs.back().second = y;
    else runs.emplace_back(y, y);
  }
  return runs;
}

TEST(FiguresSideView, HighestAndLowestLabelsOfNearlyEqualHeightsDoNotOverlap) {
  // Issue 31: two_barriers' side view drew "highest 1.52 m" over "lowest 1.50 m". Over flat ground at 0 m a track
  // 1.50 m up rising to 1.52 m gives two labels 0.02 m apart (a pixel or so in the panel): they must read as two
  // lines of text, one above the other, in the column right of the panel.
  const char* text = R"j({"objects": [
    {"alias": "flat", "type": "heightfield", "expression": "0", "size_m": [60, 60], "spacing_m": 0.5,
     "color": [0.5, 0.6, 0.35]}]})j";
  const Scene scene = parse_scene(nlohmann::json::parse(text), "inline.json", std::filesystem::temp_directory_path());
  RunView run = test_run();
  for (std::size_t i = 0; i < run.track.size(); ++i) {
    run.track[i].position_m.z() = 1.50 + 0.02 * static_cast<double>(i) / (run.track.size() - 1);
  }
  for (Waypoint& w : run.mission) w.position_m.z() = 1.5;
  const FigureStyle style = small_style();
  const FigureLayout layout = side_view_layout(scene, run, style);
  ASSERT_FALSE(layout.agl_plot_px.empty());
  const cv::Mat image = draw_side_view(scene, run, style).raster();
  const cv::Rect& panel = layout.agl_plot_px;
  const cv::Rect labels(panel.x + panel.width + 8, panel.y - 30, image.cols - panel.x - panel.width - 8,
                        panel.height + 60);
  const auto lines = ink_row_runs(image, labels);
  ASSERT_EQ(lines.size(), 2u) << "two separate lines of text";
  EXPECT_GE(lines[1].first - lines[0].second, 3) << "blank rows between them";
  // Each line no taller than one line of kLabelFont (cap height, descenders and anti-aliasing).
  const int line_px = figure::text_size("hg", figure::kLabelFont).height;
  for (const auto& [top, bottom] : lines) EXPECT_LE(bottom - top + 1, 2 * line_px);
  // Both texts are there: the upper the highest, the lower the lowest.
  expect_vector_outputs(draw_side_view(scene, run, style), {"highest 1.52 m", "lowest 1.50 m"});

  // Equal heights print the same: one label.
  for (TrackPoint& t : run.track) t.position_m.z() = 1.5;
  const cv::Mat flat = draw_side_view(scene, run, style).raster();
  EXPECT_EQ(ink_row_runs(flat, labels).size(), 1u);
}

TEST(FiguresSideView, LabelsApartKeepsSeparateLabelsAndSpreadsCloseOnes) {
  EXPECT_EQ(labels_apart_px(10.0, 50.0, 22.0), std::make_pair(10.0, 50.0));
  const auto [a, b] = labels_apart_px(100.0, 102.0, 22.0);
  EXPECT_DOUBLE_EQ(b - a, 22.0);
  EXPECT_DOUBLE_EQ(0.5 * (a + b), 101.0);  // about their midpoint
  const auto [c, d] = labels_apart_px(100.0, 100.0, 22.0);
  EXPECT_DOUBLE_EQ(c, 89.0);
  EXPECT_DOUBLE_EQ(d, 111.0);
}

TEST(FiguresSideView, AGoalNotReachedIsDrawnWhereItLiesBeyondTheTrack) {
  // Issue 31: a failed run's side view put the goal star at the end of the track. The run stops at x = 2 m (10 m
  // along the track) short of its goal at (8, 0, 3): the goal is 6 m further on in a straight line, 16 m along the
  // distance axis (goal_distance_m), at its altitude.
  EXPECT_DOUBLE_EQ(goal_distance_m(10.0, {2.0, 0.0, 1.0}, {5.0, 4.0, 9.0}), 15.0);  // 3-4-5, heights ignored
  const Scene scene = test_scene();
  RunView run = test_run();
  run.track.resize(101);
  run.outcome = "timeout";
  run.reached = {0};
  run.mission[2].position_m.z() = 4.0;  // above the track's 3 m, away from its line
  const FigureStyle style = small_style();
  const FigureLayout layout = side_view_layout(scene, run, style);
  const cv::Mat image = draw_side_view(scene, run, style).raster();
  const cv::Vec3b star_red(40, 39, 214);  // the open star's outline, BGR
  const cv::Point2d goal = layout.to_px({16.0, 4.0});
  ASSERT_TRUE(layout.plot_px.contains(cv::Point(goal)));
  // The open star: red outline 13 px out at the top point, white inside.
  EXPECT_LT(nearest_colour(image, goal + cv::Point2d(0, -12), star_red, 2), 60);
  EXPECT_EQ(at(image, goal), kBackground);
  // Nothing red at the track's end, where the star used to be.
  EXPECT_GT(nearest_colour(image, layout.to_px({10.0, 4.0}), star_red, 12), 150);
  // The dashed line on to the goal: red pixels half-way between the track's end (10 m, 3 m) and the goal.
  EXPECT_LT(nearest_colour(image, layout.to_px({13.0, 3.5}), star_red, 3), 80);
  // A reached goal stays at the track's closest approach (its end, 16 m along the whole track).
  const RunView whole = test_run();
  const FigureLayout whole_layout = side_view_layout(scene, whole, style);
  const cv::Mat reached = draw_side_view(scene, whole, style).raster();
  const cv::Vec3b filled_red(40, 39, 214);
  EXPECT_LT(nearest_colour(reached, whole_layout.to_px({16.0, 3.0}), filled_red, 3), 40);
}

}  // namespace
}  // namespace campo
