#include "render/map_figure.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "campo/scene_loader.hpp"
#include "render/map_plot.hpp"
#include "render/run_files.hpp"
#include "run/event_log.hpp"
#include "tests/render/figure_test_support.hpp"

namespace campo {
namespace {

using namespace figure::test;

TEST(FiguresMap, HasTheDocumentedSize) {
  const Scene scene = test_scene();
  const RunView run = test_run();
  const FigureStyle style = small_style();
  const FigureLayout layout = map_layout(scene, run, style);
  const cv::Mat image = draw_map(scene, run, style).raster();
  ASSERT_EQ(image.type(), CV_8UC3);
  EXPECT_EQ(image.size(), layout.image_px);
  // Bounds: x from -8 to 8 plus the 3 m margin is the longer side.
  EXPECT_EQ(layout.plot_px.width, style.max_size_px);
  EXPECT_DOUBLE_EQ(layout.px_per_unit.x(), style.max_size_px / 22.0);
  EXPECT_EQ(layout.px_per_unit.x(), layout.px_per_unit.y());
  EXPECT_EQ(image.cols, kFigureLeftPx + layout.plot_px.width + kFigurePanelPx);
  EXPECT_EQ(image.rows, kFigureTitlePx + layout.plot_px.height + kFigureBottomPx);
  // North-south: y from -2 to 2 (waypoints, discarded) plus margin, at least.
  EXPECT_GE(layout.plot_px.height, static_cast<int>(10.0 * layout.px_per_unit.y()));
  EXPECT_NEAR(layout.min.x(), -11.0, 1e-9);
}

TEST(FiguresMap, GrowsToWholeObstaclesNearTheBorderOnly) {
  Scene scene = test_scene();
  RunView run = test_run();
  run.mission.clear();
  run.planned.clear();
  run.discarded.clear();
  // Track bounds y in [-1, 1] (2 m at least), margin 3: the map would end at y = +-4.
  FigureStyle style = small_style();
  style.max_size_px = 2000;  // the legend column then needs no extra height
  const FigureLayout plain = map_layout(scene, run, style);
  const double top = plain.min.y() + plain.plot_px.height / plain.px_per_unit.y();
  // The box at y = 4 (extent up to about 4.8) is cut by the border at y = 4 and shown whole.
  EXPECT_GT(top, 4.7);
  EXPECT_LT(top, 5.0);
  EXPECT_NEAR(plain.min.x(), -11.0, 1e-9);  // nothing to grow for east-west

  // A 100 m wall across the map would grow it by far more than the margin: cut instead.
  Shape wall = scene.shapes[1];
  wall.size_m = {0.5, 100.0, 2.0};
  wall.pose = Eigen::Isometry3d(Eigen::Translation3d(2.0, 0.0, 1.0));
  scene.shapes.push_back(wall);
  const FigureLayout cut = map_layout(scene, run, style);
  EXPECT_NEAR(cut.min.y(), plain.min.y(), 1e-9);
}

TEST(FiguresMap, AMissionOnAGridShowsTheWholeGrid) {
  // A 20 x 30 grid of 2 m cells from (-10, -20): the track (x -8..8, y 0)
  // crosses a small part of it; the map shows all of it, plus the margin.
  const Scene scene = parse_scene(nlohmann::json::parse(R"j({"objects": [
    {"alias": "ground", "type": "plane"},
    {"alias": "field", "type": "grid_obstacles", "origin_m": [-10, -20], "cell_size_m": 2, "rows": 30, "cols": 20,
     "boxes": [{"rows": [28, 30], "cols": 20, "height_m": 5}]},
    {"alias": "drone", "type": "quadrotor", "pose": {"position_m": [-8, 0, 3]},
     "mission": {"grid": "field", "waypoints": [{"cell": [11, 9], "agl_m": 3}]}}]})j"),
                                  "inline.json", std::filesystem::temp_directory_path());
  ASSERT_TRUE(scene.vehicles.front().mission_area_m);
  EXPECT_EQ(scene.vehicles.front().mission_area_m->min(), Eigen::Vector2d(-10.0, -20.0));
  EXPECT_EQ(scene.vehicles.front().mission_area_m->max(), Eigen::Vector2d(30.0, 40.0));
  FigureStyle style = small_style();
  style.max_size_px = 2000;
  const FigureLayout layout = map_layout(scene, test_run(), style);
  EXPECT_NEAR(layout.min.x(), -10.0 - style.margin_m, 1e-9);
  EXPECT_NEAR(layout.min.y(), -20.0 - style.margin_m, 1e-9);
  EXPECT_GE(layout.min.x() + layout.plot_px.width / layout.px_per_unit.x(), 30.0 + style.margin_m - 1e-6);
  EXPECT_GE(layout.min.y() + layout.plot_px.height / layout.px_per_unit.y(), 40.0 + style.margin_m - 1e-6);
}

TEST(FiguresMap, DrawsTheTrackInItsTimeColours) {
  const Scene scene = test_scene();
  const RunView run = test_run();
  const FigureStyle style = small_style();
  const FigureLayout layout = map_layout(scene, run, style);
  const cv::Mat image = draw_map(scene, run, style).raster();
  // Away from the markers: t = 2.5 s, 7 s, 13 s of 16 s.
  for (const int i : {25, 70, 130}) {
    const TrackPoint& p = run.track[i];
    const cv::Vec3b want = sequential_color(p.time_s / run.track.back().time_s);
    EXPECT_LT(nearest_colour(image, layout.to_px(p.position_m.head<2>()), want), 24) << "at t = " << p.time_s;
  }
  // Coloured by speed, a constant speed is one colour all along.
  FigureStyle by_speed = style;
  by_speed.coloring = TrackColoring::speed;
  const cv::Mat speed = draw_map(scene, run, by_speed).raster();
  for (const int i : {25, 130}) {
    EXPECT_LT(nearest_colour(speed, layout.to_px(run.track[i].position_m.head<2>()), sequential_color(1.0)), 24);
  }
}

// Where a run collided is marked (issue 31): a red disc at the point touched; a video's frame shows it from then on.
TEST(FiguresMap, MarksWhereTheRunCollided) {
  const Scene scene = test_scene();
  RunView run = test_run();
  const FigureStyle style = small_style();
  const Eigen::Vector3d point(2.0, -1.0, 1.0);
  const FigureLayout before = map_layout(scene, run, style);
  EXPECT_GT(colour_distance(at(draw_map(scene, run, style).raster(), before.to_px({2.0, -1.0}) + cv::Point2d(5, 0)),
                            {40, 39, 214}), 100);
  run.collisions.emplace_back(3.0, point);
  const FigureLayout layout = map_layout(scene, run, style);  // the legend has one entry more
  const cv::Mat image = draw_map(scene, run, style).raster();
  // Inside the disc (radius 7 px), off its white cross's diagonals.
  EXPECT_LT(colour_distance(at(image, layout.to_px({2.0, -1.0}) + cv::Point2d(5, 0)), {40, 39, 214}), 10);
  RecordedRun recorded;
  recorded.view = run;
  EXPECT_TRUE(run_view_at(recorded, 2.9).collisions.empty());
  ASSERT_EQ(run_view_at(recorded, 3.0).collisions.size(), 1u);
  EXPECT_EQ(run_view_at(recorded, 3.0).collisions.front().second, point);
}

TEST(FiguresMap, DrawsObstaclesWaypointsLegendTitleAndColourBar) {
  const Scene scene = test_scene();
  const RunView run = test_run();
  const FigureStyle style = small_style();
  const FigureLayout layout = map_layout(scene, run, style);
  const cv::Mat image = draw_map(scene, run, style).raster();
  // Footprints in the shapes' own colours (BGR).
  EXPECT_LT(colour_distance(at(image, layout.to_px({0.0, 4.0})), {51, 51, 204}), 3);
  EXPECT_LT(colour_distance(at(image, layout.to_px({-4.0, -2.5})), {204, 77, 51}), 3);
  // Waypoint 1 was reached (a filled marker), waypoint 2 was not (an open one).
  const cv::Point2d offset(-6.0, 0.0);
  EXPECT_LT(colour_distance(at(image, layout.to_px({-2.0, 0.0}) + offset), {34, 34, 34}), 10);
  EXPECT_EQ(at(image, layout.to_px({4.0, 2.0}) + offset), kBackground);
  // Title, legend and colour bar are drawn where the layout says.
  EXPECT_GT(non_background(image, layout.title_px), 200);
  ASSERT_FALSE(layout.legend_px.empty());
  EXPECT_GT(non_background(image, layout.legend_px), 1000);
  ASSERT_FALSE(layout.colorbar_px.empty());
  const cv::Rect& bar = layout.colorbar_px;
  const int mid = bar.x + bar.width / 2;
  EXPECT_LT(colour_distance(image.at<cv::Vec3b>(bar.y + 1, mid), sequential_color(1.0)), 12);
  EXPECT_LT(colour_distance(image.at<cv::Vec3b>(bar.y + bar.height - 2, mid), sequential_color(0.0)), 12);
  EXPECT_GT(non_background(image, layout.scalebar_px), 100);
  // Tick labels left of and below the plot.
  EXPECT_GT(non_background(image, {0, layout.plot_px.y, kFigureLeftPx - 2, layout.plot_px.height}), 300);
  EXPECT_GT(non_background(image, {layout.plot_px.x, layout.plot_px.br().y + 2, layout.plot_px.width, kFigureBottomPx - 4}), 300);
}

// Distance of `p` to the segment a-b, pixels.
double segment_distance(cv::Point2d p, cv::Point2d a, cv::Point2d b) {
  const cv::Point2d d = b - a;
  const double t = std::clamp((p - a).dot(d) / d.dot(d), 0.0, 1.0);
  return cv::norm(a + t * d - p);
}

TEST(FiguresMap, HighlightsTheTrackWhileAvoiding) {
  const Scene scene = test_scene();
  const RunView plain = test_run();
  RunView run = plain;
  run.avoiding_s = {{9.0, 12.0}};  // x from 1 to 4 along y = 0
  FigureStyle style = small_style();
  style.max_size_px = 2000;  // the legend column then needs no extra height: both maps share their frame
  const FigureLayout layout = map_layout(scene, run, style), plain_layout = map_layout(scene, plain, style);
  ASSERT_EQ(layout.plot_px, plain_layout.plot_px);
  ASSERT_EQ(layout.min, plain_layout.min);
  const cv::Mat image = draw_map(scene, run, style).raster(), before = draw_map(scene, plain, style).raster();
  const cv::Vec3b amber(100, 196, 255);
  // Beside the track line (its halo is 5 px wide, the band 15 px), on both sides, all along the interval.
  for (double x = 1.2; x <= 3.8; x += 0.2) {
    for (const double side : {-5.0, 5.0}) {
      const cv::Point2d p = layout.to_px({x, 0.0}) + cv::Point2d(0.0, side);
      EXPECT_LT(colour_distance(at(image, p), amber), 12) << "x = " << x << ", side " << side;
    }
  }
  // The track line itself is drawn over the band, in its time colour.
  EXPECT_LT(nearest_colour(image, layout.to_px({2.5, 0.0}), sequential_color(10.5 / 16.0), 1), 24);
  // Nothing else changed in the plot: every changed pixel lies within the band around the part of the
  // track driven while avoiding (half its width plus two pixels of anti-aliasing).
  const cv::Point2d a = layout.to_px({1.0, 0.0}), b = layout.to_px({4.0, 0.0});
  int changed = 0;
  const cv::Rect& plot = layout.plot_px;
  for (int r = plot.y; r < plot.y + plot.height; ++r) {
    for (int c = plot.x; c < plot.x + plot.width; ++c) {
      if (image.at<cv::Vec3b>(r, c) == before.at<cv::Vec3b>(r, c)) continue;
      ++changed;
      ASSERT_LE(segment_distance({double(c), double(r)}, a, b), 7.5 + 2.0) << "pixel " << c << ", " << r;
    }
  }
  EXPECT_GT(changed, static_cast<int>(10.0 * (b.x - a.x)));
  // Elsewhere beside the track: no amber.
  for (const double x : {-6.0, -3.0, 0.0, 5.5, 7.0}) {
    for (const double side : {-5.0, 5.0}) {
      EXPECT_GT(colour_distance(at(image, layout.to_px({x, 0.0}) + cv::Point2d(0.0, side)), amber), 60) << "x = " << x;
    }
  }
  // One more legend entry, whose symbol is the band's colour.
  EXPECT_GT(layout.legend_px.height, plain_layout.legend_px.height);
  int amber_in_legend = 0;
  const cv::Mat legend = image(layout.legend_px);
  for (auto it = legend.begin<cv::Vec3b>(); it != legend.end<cv::Vec3b>(); ++it) amber_in_legend += colour_distance(*it, amber) < 12;
  EXPECT_GT(amber_in_legend, 100);
  // Overlays do not highlight.
  EXPECT_EQ(png(draw_overlay(scene, {run}, style).raster()), png(draw_overlay(scene, {plain}, style).raster()));
}

TEST(FiguresMap, ReadsAvoidanceIntervalsFromTheRunRecord) {
  const auto avoiding = [](bool on) { return decisions_to_json({.avoiding = on}); };
  const auto dir = std::filesystem::temp_directory_path() / "campo_figures_avoiding";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "scene.json") << R"j({"objects": []})j";
  {
    std::ofstream csv(dir / "trajectory.csv");
    csv << "time_s,x_m,y_m,z_m,vx_mps,vy_mps,vz_mps\n";
    for (int i = 0; i <= 10; ++i) csv << i << "," << i << ",0,0,1,0,0\n";
  }
  const nlohmann::json record = {
      {"metrics", {{"outcome", "reached"}}},
      {"parameters", {{"mission", nlohmann::json::array({{{"position_m", {10, 0, 0}}}})}}},
      {"events",
       {{{"time_s", 1.0}, {"decisions", avoiding(true)}},
        {{"time_s", 2.0}, {"decisions", avoiding(true)}},  // still on
        {{"time_s", 3.5}, {"decisions", avoiding(false)}},
        {{"time_s", 4.0}, {"decisions", avoiding(false)}},  // already off
        {{"time_s", 6.0}, {"decisions", avoiding(true)}}}},  // open: closes at the last track time
  };
  std::ofstream(dir / "run.json") << record.dump();
  const RecordedRun run = load_run_dir(dir);
  const std::vector<std::pair<double, double>> want{{1.0, 3.5}, {6.0, 10.0}};
  EXPECT_EQ(run.view.avoiding_s, want);
  std::filesystem::remove_all(dir);
}

TEST(FiguresMap, DrawsExactlyTheGivenBounds) {
  FigureStyle style = small_style();
  style.bounds_m = Eigen::AlignedBox2d(Eigen::Vector2d(-3.0, -2.0), Eigen::Vector2d(5.0, 2.0));
  const FigureLayout layout = map_layout(test_scene(), test_run(), style);
  // The plot is 8 m wide from x = -3 on, with equal scales: no margin, not the track's extent
  // (16 m); so flat a plot grows in height to fit the legend, about the box's centre line y = 0.
  EXPECT_NEAR(layout.min.x(), -3.0, 1e-9);
  EXPECT_NEAR(layout.plot_px.width / layout.px_per_unit.x(), 8.0, 1.0 / layout.px_per_unit.x());
  EXPECT_NEAR(layout.px_per_unit.x(), layout.px_per_unit.y(), 1e-9);
  EXPECT_LE(layout.min.y(), -2.0);
  EXPECT_NEAR(layout.min.y() + 0.5 * layout.plot_px.height / layout.px_per_unit.y(), 0.0, 1.0 / layout.px_per_unit.y());
}

TEST(FiguresMap, IsDeterministic) {
  const Scene scene = test_scene();
  const RunView run = test_run();
  EXPECT_EQ(png(draw_map(scene, run, small_style()).raster()), png(draw_map(scene, run, small_style()).raster()));
}

// PDF and SVG from the same drawing: the texts as text, renderings close to the PNG.
TEST(FiguresMap, WritesPdfAndSvgOfTheSameDrawing) {
  const Scene scene = test_scene();
  RunView run = test_run();
  run.collisions.emplace_back(3.0, Eigen::Vector3d(2.0, -1.0, 1.0));
  expect_vector_outputs(draw_map(scene, run, small_style()),
                        {"Test figure", "x, east (m)", "y, north (m)", "time (s)", "start", "collision"});
}

TEST(FiguresMap, DrawsAnEmptyRunAroundTheScene) {
  const Scene scene = test_scene();
  const RunView empty;
  const cv::Mat image = draw_map(scene, empty, small_style()).raster();
  const FigureLayout layout = map_layout(scene, empty, small_style());
  EXPECT_EQ(image.size(), layout.image_px);
  EXPECT_TRUE(layout.colorbar_px.empty());
  // The obstacles' extent plus margin.
  EXPECT_LT(layout.min.x(), -4.5 - 3.0 + 1e-6);
}

TEST(FiguresMap, RejectsABadStyle) {
  FigureStyle style;
  style.max_size_px = 50;
  EXPECT_THROW(draw_map(test_scene(), test_run(), style), std::invalid_argument);
  style = {};
  style.margin_m = -1.0;
  EXPECT_THROW(draw_overlay(test_scene(), {test_run()}, style), std::invalid_argument);
}

// ---------------------------------------------------------------- overlay

std::vector<RunView> three_runs() {
  std::vector<RunView> runs(3, test_run());
  for (std::size_t k = 0; k < runs.size(); ++k) {
    runs[k].label = "run_" + std::to_string(k);
    for (auto& p : runs[k].track) p.position_m.y() = -1.0 + 1.0 * k;
  }
  runs[2].outcome = "collision";
  return runs;
}

TEST(FiguresOverlay, DrawsEachRunInItsOwnColour) {
  const Scene scene = test_scene();
  const std::vector<RunView> runs = three_runs();
  const FigureStyle style = small_style();
  const FigureLayout layout = overlay_layout(scene, runs, style);
  const cv::Mat image = draw_overlay(scene, runs, style).raster();
  EXPECT_EQ(image.size(), layout.image_px);
  EXPECT_EQ(image.cols, kFigureLeftPx + style.max_size_px + kFigurePanelPx);
  EXPECT_TRUE(layout.colorbar_px.empty());
  for (std::size_t k = 0; k < runs.size(); ++k) {
    const cv::Scalar c = run_color(k);
    const cv::Vec3b want(static_cast<uchar>(c[0]), static_cast<uchar>(c[1]), static_cast<uchar>(c[2]));
    EXPECT_LT(nearest_colour(image, layout.to_px(runs[k].track[30].position_m.head<2>()), want), 10) << "run " << k;
    EXPECT_NE(run_color(k), run_color(k + 1));
  }
  // The ten seeds of a reproduction's overlay each get their own colour.
  for (std::size_t a = 0; a < kRunColors; ++a) {
    for (std::size_t b = a + 1; b < kRunColors; ++b) EXPECT_NE(run_color(a), run_color(b)) << a << " " << b;
  }
  EXPECT_EQ(run_color(kRunColors), run_color(0));
  EXPECT_GT(non_background(image, layout.legend_px), 1000);
  EXPECT_GT(non_background(image, layout.title_px), 100);
}

TEST(FiguresOverlay, ListsEveryRunInTheLegend) {
  const Scene scene = test_scene();
  std::vector<RunView> runs = three_runs();
  const int three = overlay_layout(scene, runs, small_style()).legend_px.height;
  runs.push_back(runs.front());
  const int four = overlay_layout(scene, runs, small_style()).legend_px.height;
  EXPECT_GT(four, three);
}

// Two crowns of different shades whose bottoms (4 m, 5.2 m) are above every track point (3 m above flat ground), a
// crown of the first one's colour reaching down to 1.5 m, and a post at flight height.
Scene band_scene() {
  const char* text = R"j({"objects": [
    {"alias": "ground", "type": "plane"},
    {"alias": "crown_1", "type": "sphere", "radius_m": 1.0, "pose": {"position_m": [0, 4, 5]},
     "color": [0.2, 0.6, 0.2]},
    {"alias": "low_crown_2", "type": "sphere", "radius_m": 1.0, "pose": {"position_m": [4, -3.5, 2.5]},
     "color": [0.2, 0.6, 0.2]},
    {"alias": "crown_3", "type": "sphere", "radius_m": 0.8, "pose": {"position_m": [-6, 4, 6]},
     "color": [0.25, 0.55, 0.2]},
    {"alias": "post", "type": "cylinder", "radius_m": 0.5, "height_m": 4,
     "pose": {"position_m": [-4, -2.5, 2]}, "color": [0.2, 0.3, 0.8]}
  ]})j";
  return parse_scene(nlohmann::json::parse(text), "inline.json", std::filesystem::temp_directory_path());
}

std::vector<std::string> legend_texts(const figure::MapPlan& plan) {
  std::vector<std::string> out;
  for (const auto& e : plan.legend) out.push_back(e.text);
  return out;
}

TEST(FiguresOverlay, ObstaclesAboveTheFlightBandAreDrawnPaleAndNamedSo) {
  const Scene scene = band_scene();
  const std::vector<RunView> runs = three_runs();  // 3 m above the ground
  const FigureStyle style = small_style();
  const FigureLayout layout = overlay_layout(scene, runs, style);
  const cv::Mat image = draw_overlay(scene, runs, style).raster();
  const cv::Scalar green = figure::rgb(51, 153, 51), pale = figure::lighten(green, figure::kAboveBandLighten);
  const auto vec = [](const cv::Scalar& c) {
    return cv::Vec3b(static_cast<uchar>(std::lround(c[0])), static_cast<uchar>(std::lround(c[1])),
                     static_cast<uchar>(std::lround(c[2])));
  };
  // The crown above the band: pale, far from its own colour; the low crown in its own colour.
  const cv::Vec3b high = at(image, layout.to_px({0.0, 4.0})), low = at(image, layout.to_px({4.0, -3.5}));
  EXPECT_LT(colour_distance(high, vec(pale)), 6);
  EXPECT_GT(colour_distance(high, vec(green)), 200);
  EXPECT_LT(colour_distance(low, vec(green)), 6);

  std::vector<const RunView*> views;
  for (const RunView& r : runs) views.push_back(&r);
  const figure::MapPlan plan = figure::plan_map(scene, views, style, true);
  ASSERT_TRUE(plan.band_top_agl_m);
  EXPECT_DOUBLE_EQ(*plan.band_top_agl_m, 3.0);
  ASSERT_EQ(plan.above_band.size(), plan.footprints.size());
  for (std::size_t i = 0; i < plan.footprints.size(); ++i) {
    const std::string& alias = plan.footprints[i].shape->alias;
    EXPECT_EQ(plan.above_band[i], alias == "crown_1" || alias == "crown_3") << alias;
  }
  const std::vector<std::string> texts = legend_texts(plan);
  // One entry for the crowns above the band, whatever their shades.
  EXPECT_EQ(std::count(texts.begin(), texts.end(), "crown, above flight band"), 1);
  for (const char* want : {"crown, above flight band", "obstacle: low_crown", "obstacle: post",
                           "run_0 (reached)", "run_1 (reached)", "run_2 (collision)"}) {
    EXPECT_NE(std::find(texts.begin(), texts.end(), want), texts.end()) << want;
  }
  // Flown at 5.5 m, nothing is above the band any more.
  std::vector<RunView> high_runs = runs;
  for (auto& p : high_runs.front().track) p.position_m.z() = 5.5;
  std::vector<const RunView*> high_views{&high_runs.front()};
  const figure::MapPlan above_all = figure::plan_map(scene, high_views, style, true);
  EXPECT_TRUE(std::none_of(above_all.above_band.begin(), above_all.above_band.end(), [](bool b) { return b; }));
}

TEST(FiguresOverlay, LegendNamesEachSeedOfASweep) {
  const Scene scene = test_scene();
  std::vector<RunView> runs = three_runs();
  for (std::size_t k = 0; k < runs.size(); ++k) {
    runs[k].label = "trees_rolling_terrain__resolution-256__seed-" + std::to_string(k + 1);
  }
  std::vector<const RunView*> views;
  for (const RunView& r : runs) views.push_back(&r);
  const std::vector<std::string> texts = legend_texts(figure::plan_map(scene, views, small_style(), true));
  for (const char* want : {"seed-1 (reached)", "seed-2 (reached)", "seed-3 (collision)"}) {
    EXPECT_NE(std::find(texts.begin(), texts.end(), want), texts.end()) << want;
  }
}

TEST(FiguresMap, TheLegendGivesTheWindWhenThereIsSome) {
  Scene scene = test_scene();
  const std::vector<RunView> runs = three_runs();
  const std::vector<const RunView*> views{&runs[0]};
  const auto has_wind = [&](const std::string& want) {
    const std::vector<std::string> texts = legend_texts(figure::plan_map(scene, views, small_style(), false));
    return std::find(texts.begin(), texts.end(), want) != texts.end();
  };
  EXPECT_FALSE(has_wind("wind"));
  scene.world.wind.speed_mps = 4.0;
  EXPECT_TRUE(has_wind("wind 4 m/s"));
  scene.world.wind.gust = GustModel::dryden;
  scene.world.wind.turbulence_intensity_mps = 1.5;
  EXPECT_TRUE(has_wind("wind 4 m/s, turbulence 1.5 m/s"));
  scene.world.wind.speed_mps = 0.0;
  scene.world.wind.gust = GustModel::one_minus_cos;
  EXPECT_TRUE(has_wind("wind, 1-cos gust"));
}

TEST(FiguresOverlay, WritesPdfAndSvgOfTheSameDrawing) {
  expect_vector_outputs(draw_overlay(test_scene(), three_runs(), small_style()),
                        {"Test figure", "x, east (m)", "run_0 (reached)", "run_2 (collision)"});
}

TEST(FiguresOverlay, IsDeterministic) {
  const Scene scene = test_scene();
  EXPECT_EQ(png(draw_overlay(scene, three_runs(), small_style()).raster()), png(draw_overlay(scene, three_runs(), small_style()).raster()));
}

}  // namespace
}  // namespace campo
