#include "render/figures.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "campo/scene_loader.hpp"
#include "render/run_files.hpp"
#include "run/event_log.hpp"

namespace campo {
namespace {

const cv::Vec3b kBackground(255, 255, 255);

// Rolling terrain, a rotated red box north of the track and a blue post south of it.
Scene test_scene() {
  const char* text = R"j({"objects": [
    {"alias": "hill", "type": "heightfield", "expression": "0.8*sin(x/4) + 0.5*cos(y/5)",
     "size_m": [60, 60], "spacing_m": 0.5, "color": [0.5, 0.6, 0.35]},
    {"alias": "box", "type": "cuboid", "size_m": [2, 1, 3],
     "pose": {"position_m": [0, 4, 1.5], "rpy_deg": [0, 0, 30]}, "color": [0.8, 0.2, 0.2]},
    {"alias": "post", "type": "cylinder", "radius_m": 0.5, "height_m": 4,
     "pose": {"position_m": [-4, -2.5, 2]}, "color": [0.2, 0.3, 0.8]}
  ]})j";
  return parse_scene(nlohmann::json::parse(text), "inline.json", std::filesystem::temp_directory_path());
}

// Flies east along y = 0 from x = -8 to x = 8 at 1 m/s, 3 m above the datum.
RunView test_run() {
  RunView run;
  run.label = "run_a";
  run.outcome = "reached";
  for (int i = 0; i <= 160; ++i) {
    TrackPoint p;
    p.time_s = 0.1 * i;
    p.position_m = {-8.0 + 0.1 * i, 0.0, 3.0};
    p.speed_mps = 1.0;
    run.track.push_back(p);
  }
  run.mission = {Waypoint{{-2.0, 0.0, 3.0}, {}}, Waypoint{{4.0, 2.0, 3.0}, {}}, Waypoint{{8.0, 0.0, 3.0}, {}}};
  run.reached = {0, 2};
  run.planned = {{1.0, -1.0, 3.0}};
  run.discarded = {{5.0, -2.0, 3.0}};
  return run;
}

FigureStyle small_style() {
  FigureStyle style;
  style.max_size_px = 600;
  style.title = "Test figure";
  return style;
}

int colour_distance(const cv::Vec3b& a, const cv::Vec3b& b) {
  return std::abs(a[0] - b[0]) + std::abs(a[1] - b[1]) + std::abs(a[2] - b[2]);
}

// Smallest colour distance to `want` within `radius` pixels of `p`.
int nearest_colour(const cv::Mat& image, cv::Point2d p, const cv::Vec3b& want, int radius = 2) {
  int best = 3 * 255;
  const cv::Point c(static_cast<int>(std::lround(p.x)), static_cast<int>(std::lround(p.y)));
  for (int dy = -radius; dy <= radius; ++dy) {
    for (int dx = -radius; dx <= radius; ++dx) {
      best = std::min(best, colour_distance(image.at<cv::Vec3b>(c.y + dy, c.x + dx), want));
    }
  }
  return best;
}

int non_background(const cv::Mat& image, const cv::Rect& area) {
  int n = 0;
  const cv::Mat roi = image(area);
  for (auto it = roi.begin<cv::Vec3b>(); it != roi.end<cv::Vec3b>(); ++it) n += *it != kBackground;
  return n;
}

std::vector<uchar> png(const cv::Mat& image) {
  std::vector<uchar> bytes;
  EXPECT_TRUE(cv::imencode(".png", image, bytes));
  return bytes;
}

cv::Vec3b at(const cv::Mat& image, cv::Point2d p) {
  return image.at<cv::Vec3b>(static_cast<int>(std::lround(p.y)), static_cast<int>(std::lround(p.x)));
}

// ---------------------------------------------------------------- map

TEST(FiguresMap, HasTheDocumentedSize) {
  const Scene scene = test_scene();
  const RunView run = test_run();
  const FigureStyle style = small_style();
  const FigureLayout layout = map_layout(scene, run, style);
  const cv::Mat image = draw_map(scene, run, style);
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
  const cv::Mat image = draw_map(scene, run, style);
  // Away from the markers: t = 2.5 s, 7 s, 13 s of 16 s.
  for (const int i : {25, 70, 130}) {
    const TrackPoint& p = run.track[i];
    const cv::Vec3b want = sequential_color(p.time_s / run.track.back().time_s);
    EXPECT_LT(nearest_colour(image, layout.to_px(p.position_m.head<2>()), want), 24) << "at t = " << p.time_s;
  }
  // Coloured by speed, a constant speed is one colour all along.
  FigureStyle by_speed = style;
  by_speed.coloring = TrackColoring::speed;
  const cv::Mat speed = draw_map(scene, run, by_speed);
  for (const int i : {25, 130}) {
    EXPECT_LT(nearest_colour(speed, layout.to_px(run.track[i].position_m.head<2>()), sequential_color(1.0)), 24);
  }
}

TEST(FiguresMap, DrawsObstaclesWaypointsLegendTitleAndColourBar) {
  const Scene scene = test_scene();
  const RunView run = test_run();
  const FigureStyle style = small_style();
  const FigureLayout layout = map_layout(scene, run, style);
  const cv::Mat image = draw_map(scene, run, style);
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
  const cv::Mat image = draw_map(scene, run, style), before = draw_map(scene, plain, style);
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
  EXPECT_EQ(png(draw_overlay(scene, {run}, style)), png(draw_overlay(scene, {plain}, style)));
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

// A mover crossing the track northward from t = 2 s at 1 m/s.
Scene scene_with_mover() {
  const char* text = R"j({"objects": [
    {"alias": "ground", "type": "plane"},
    {"alias": "walker", "type": "mover", "shape": {"type": "cylinder", "radius_m": 0.4, "height_m": 1.7,
     "color": [0.1, 0.7, 0.1]}, "path_m": [[2, -4, 0.85], [2, 4, 0.85]], "speed_mps": 1, "start_time_s": 2}
  ]})j";
  return parse_scene(nlohmann::json::parse(text), "inline.json", std::filesystem::temp_directory_path());
}

TEST(FiguresSequence, DrawsOnePanelPerInstantTwoARow) {
  const Scene scene = scene_with_mover();
  const RunView run = test_run();
  EXPECT_THROW(draw_sequence(scene, run, {}, {1.5, 1.0}, small_style()), std::invalid_argument);
  const std::vector<SequencePanel> same{{6.0, "(a)", std::nullopt}, {6.0, "(a)", std::nullopt}};
  const cv::Mat twins = draw_sequence(scene, run, same, {1.5, 1.0}, small_style());
  ASSERT_EQ(twins.cols % 2, 0);
  const int w = twins.cols / 2;
  // Equal instants, equal panels; the panel is a map of the documented bands.
  EXPECT_EQ(cv::norm(twins(cv::Rect(0, 0, w, twins.rows)), twins(cv::Rect(w, 0, w, twins.rows)), cv::NORM_L1), 0.0);
  EXPECT_GT(w, kFigureLeftPx + kFigurePanelPx);
  // Four instants: two rows of two; the mover and the track differ between them.
  const std::vector<SequencePanel> four{
      {1.0, "(a)", 0.0}, {4.0, "(b)", -30.0}, {6.0, "(c)", 30.0}, {9.0, "(d)", std::nullopt}};
  const cv::Mat grid = draw_sequence(scene, run, four, {1.5, 1.0}, small_style());
  EXPECT_EQ(grid.cols, twins.cols);
  ASSERT_EQ(grid.rows % 2, 0);
  const int h = grid.rows / 2;
  EXPECT_GT(cv::norm(grid(cv::Rect(0, 0, w, h)), grid(cv::Rect(w, 0, w, h)), cv::NORM_L1), 0.0);
  EXPECT_GT(cv::norm(grid(cv::Rect(0, h, w, h)), grid(cv::Rect(w, h, w, h)), cv::NORM_L1), 0.0);
  EXPECT_EQ(png(grid), png(draw_sequence(scene, run, four, {1.5, 1.0}, small_style())));
}

TEST(FiguresMap, IsDeterministic) {
  const Scene scene = test_scene();
  const RunView run = test_run();
  EXPECT_EQ(png(draw_map(scene, run, small_style())), png(draw_map(scene, run, small_style())));
}

TEST(FiguresMap, DrawsAnEmptyRunAroundTheScene) {
  const Scene scene = test_scene();
  const RunView empty;
  const cv::Mat image = draw_map(scene, empty, small_style());
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

// Recorded hits are red dots on the map; the reconstructed height map colours
// each mapped cell by its top (lowest to highest across the colour bar) and
// leaves unmapped cells to the terrain.
TEST(FiguresHeightMap, ColoursMappedCellsByTheirTop) {
  const Scene scene = test_scene();
  RunView run = test_run();
  run.sensor_hits = {{-6.0, -3.0, 0.2}};
  const FigureStyle style = small_style();
  const cv::Mat map = draw_map(scene, run, style);
  EXPECT_LT(nearest_colour(map, map_layout(scene, run, style).to_px({-6.0, -3.0}), cv::Vec3b(40, 39, 214), 1), 24);

  EXPECT_THROW(draw_height_map(scene, run, style), std::invalid_argument);
  HeightMapView& h = run.height_map;
  h.origin_m = {-10.0, -5.0};
  h.cell_size_m = 2.0;
  h.columns = 10;
  h.rows = 5;
  h.top_m.assign(50, std::nan(""));
  h.top_m[1 * 10 + 2] = 0.0;   // cell (2, 1): x -6..-4, y -3..-1, the lowest top
  h.top_m[3 * 10 + 7] = 10.0;  // cell (7, 3): x 4..6, y 1..3, the highest
  h.top_m[1 * 10 + 6] = 2.5;   // cell (6, 1): x 2..4, y -3..-1, a quarter of the way
  const FigureLayout layout = height_map_layout(scene, run, style);
  const cv::Mat image = draw_height_map(scene, run, style);
  EXPECT_LT(colour_distance(at(image, layout.to_px({-5.0, -2.0})), sequential_color(0.0)), 6);
  EXPECT_LT(colour_distance(at(image, layout.to_px({5.0, 2.5})), sequential_color(1.0)), 6);
  EXPECT_LT(colour_distance(at(image, layout.to_px({3.0, -2.5})), sequential_color(0.25)), 6);
  // An unmapped cell shows the map's terrain, not a height colour.
  EXPECT_LT(colour_distance(at(image, layout.to_px({-1.0, -4.0})),
                            at(map, map_layout(scene, run, style).to_px({-1.0, -4.0}))),
            12);
  EXPECT_EQ(png(image), png(draw_height_map(scene, run, style)));
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
  const cv::Mat image = draw_overlay(scene, runs, style);
  EXPECT_EQ(image.size(), layout.image_px);
  EXPECT_EQ(image.cols, kFigureLeftPx + style.max_size_px + kFigurePanelPx);
  EXPECT_TRUE(layout.colorbar_px.empty());
  for (std::size_t k = 0; k < runs.size(); ++k) {
    const cv::Scalar c = run_color(k);
    const cv::Vec3b want(static_cast<uchar>(c[0]), static_cast<uchar>(c[1]), static_cast<uchar>(c[2]));
    EXPECT_LT(nearest_colour(image, layout.to_px(runs[k].track[30].position_m.head<2>()), want), 10) << "run " << k;
    EXPECT_NE(run_color(k), run_color(k + 1));
  }
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

TEST(FiguresOverlay, IsDeterministic) {
  const Scene scene = test_scene();
  EXPECT_EQ(png(draw_overlay(scene, three_runs(), small_style())), png(draw_overlay(scene, three_runs(), small_style())));
}

// ---------------------------------------------------------------- side view

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

// ---------------------------------------------------------------- depth

cv::Mat test_depth() {
  cv::Mat depth(16, 16, CV_32F);
  for (int r = 0; r < depth.rows; ++r) {
    for (int c = 0; c < depth.cols; ++c) depth.at<float>(r, c) = 0.05f + 0.05f * c;
  }
  depth.at<float>(0, 0) = 0.0f;    // below min range
  depth.at<float>(0, 15) = 1.0f;   // no return
  return depth;
}

DepthOverlays test_overlays(const cv::Mat& depth) {
  DepthOverlays o;
  cv::erode(depth, o.dilated, cv::Mat::ones(3, 3, CV_8U));
  cv::threshold(o.dilated, o.thresholded, 0.5, 255.0, cv::THRESH_BINARY);
  o.thresholded.convertTo(o.thresholded, CV_8U);
  o.chosen_pixel = cv::Point(5, 9);
  for (int c = 0; c < 16; ++c) o.scan_line.emplace_back(c, 9);
  return o;
}

bool is_ring_red(const cv::Vec3b& v) { return v[2] > 180 && v[1] < 90 && v[0] < 90; }

TEST(FiguresDepth, UpscalesEachPanelByAnIntegerFactor) {
  const cv::Mat depth = test_depth();
  const DepthOverlays overlays = test_overlays(depth);
  const DepthFigureLayout layout = depth_layout(depth, overlays, false);
  const cv::Mat image = draw_depth(depth, overlays, false, "Depth");
  EXPECT_EQ(image.size(), layout.image_px);
  EXPECT_EQ(layout.scale, 16);  // 16 px -> 256 px
  ASSERT_EQ(layout.panels_px.size(), 3u);
  for (const auto& panel : layout.panels_px) EXPECT_EQ(panel.size(), cv::Size(256, 256));
  EXPECT_EQ(image.cols, kDepthGapPx + 3 * 256 + 2 * kDepthGapPx + kDepthGapPx + kDepthColorbarPx);
  // Depth-map pixel (3, 4) is a block of scale x scale figure pixels of its grey.
  const uchar grey = cv::saturate_cast<uchar>(255.0 * depth.at<float>(4, 3));
  const cv::Rect block(layout.panels_px[0].x + 3 * 16, layout.panels_px[0].y + 4 * 16, 16, 16);
  const cv::Mat roi = image(block);
  for (auto it = roi.begin<cv::Vec3b>(); it != roi.end<cv::Vec3b>(); ++it) {
    ASSERT_EQ(*it, cv::Vec3b(grey, grey, grey));
  }
  // Thresholded panel: black or white only.
  const cv::Vec3b t = at(image, layout.to_px(2, {12, 2}));
  EXPECT_EQ(t, cv::Vec3b(255, 255, 255));
  EXPECT_EQ(at(image, layout.to_px(2, {2, 2})), cv::Vec3b(0, 0, 0));
  EXPECT_GT(non_background(image, layout.title_px), 100);
  EXPECT_GT(non_background(image, layout.colorbar_px), 1000);
}

TEST(FiguresDepth, DrawsTheChosenPixelAsARingAtItsScaledPosition) {
  const cv::Mat depth = test_depth();
  const DepthOverlays overlays = test_overlays(depth);
  const DepthFigureLayout layout = depth_layout(depth, overlays, false);
  const cv::Mat image = draw_depth(depth, overlays, false, "Depth");
  for (std::size_t panel = 0; panel < layout.panels_px.size(); ++panel) {
    const cv::Point2d centre = layout.to_px(panel, *overlays.chosen_pixel);
    int ring = 0, inside = 0;
    for (int dy = -40; dy <= 40; ++dy) {
      for (int dx = -40; dx <= 40; ++dx) {
        const double r = std::hypot(dx, dy);
        const bool red = is_ring_red(at(image, centre + cv::Point2d(dx, dy)));
        if (r < 0.5 * layout.scale) inside += red;
        else ring += red;
      }
    }
    EXPECT_GT(ring, 50) << "panel " << panel;   // a ring around the pixel ...
    EXPECT_EQ(inside, 0) << "panel " << panel;  // ... that leaves the pixel itself visible
  }
  // Nothing red far from the chosen pixel.
  EXPECT_FALSE(is_ring_red(at(image, layout.to_px(0, {14, 2}))));
}

TEST(FiguresDepth, DrawsTheProjectedWaypointWithItsSafetyEllipseAndTheNewWaypoint) {
  const cv::Mat depth = test_depth();
  DepthOverlays overlays = test_overlays(depth);
  overlays.waypoint_projection = cv::Point2d(10.5, 4.0);
  overlays.safety_ellipse_px = {3.0, 2.0};
  overlays.new_waypoint_pixel = cv::Point(3, 12);
  const DepthFigureLayout layout = depth_layout(depth, overlays, false);
  const cv::Mat image = draw_depth(depth, overlays, false, "Depth");
  ASSERT_EQ(layout.scale, 16);
  const cv::Vec3b magenta(220, 0, 220), blue(180, 119, 31);  // W' and planned-waypoint colours, BGR
  for (std::size_t panel = 0; panel < layout.panels_px.size(); ++panel) {
    const cv::Point2d w = layout.to_px(panel, *overlays.waypoint_projection);
    EXPECT_LT(nearest_colour(image, w, magenta), 30) << "panel " << panel;  // the plus on W'
    // The ellipse: 3 x 2 depth-map pixels, scaled, around W' and nothing between.
    for (const cv::Point2d d : {cv::Point2d(48, 0), cv::Point2d(-48, 0), cv::Point2d(0, 32), cv::Point2d(0, -32)}) {
      EXPECT_LT(nearest_colour(image, w + d, magenta), 30) << "panel " << panel << " offset " << d;
    }
    EXPECT_GT(nearest_colour(image, w + cv::Point2d(24, 0), magenta), 100) << "panel " << panel;
    EXPECT_LT(colour_distance(at(image, layout.to_px(panel, *overlays.new_waypoint_pixel)), blue), 30) << "panel " << panel;
  }
}

TEST(FiguresDepth, MarksSpecialValuesInColour) {
  const cv::Mat depth = test_depth();
  const DepthFigureLayout layout = depth_layout(depth, {}, true);
  const cv::Mat image = draw_depth(depth, {}, true, "Depth");
  ASSERT_EQ(layout.panels_px.size(), 1u);
  EXPECT_FALSE(layout.legend_px.empty());
  const cv::Vec3b too_near = at(image, layout.to_px(0, {0, 0}));
  const cv::Vec3b no_return = at(image, layout.to_px(0, {15, 0}));
  const cv::Vec3b far = at(image, layout.to_px(0, {15, 1}));  // 0.8
  EXPECT_EQ(far, sequential_color(depth.at<float>(1, 15)));
  EXPECT_GT(colour_distance(no_return, sequential_color(1.0)), 100);
  EXPECT_GT(colour_distance(too_near, sequential_color(0.0)), 100);
  EXPECT_NE(no_return, too_near);
}

TEST(FiguresDepth, IsDeterministic) {
  const cv::Mat depth = test_depth();
  EXPECT_EQ(png(draw_depth(depth, test_overlays(depth), true, "D")), png(draw_depth(depth, test_overlays(depth), true, "D")));
}

TEST(FiguresDepth, RejectsMapsOfTheWrongTypeOrSize) {
  const cv::Mat depth = test_depth();
  EXPECT_THROW(draw_depth(cv::Mat(), {}, false, ""), std::invalid_argument);
  EXPECT_THROW(draw_depth(cv::Mat::zeros(4, 4, CV_8U), {}, false, ""), std::invalid_argument);
  DepthOverlays wrong;
  wrong.dilated = cv::Mat::zeros(8, 8, CV_32F);
  EXPECT_THROW(draw_depth(depth, wrong, false, ""), std::invalid_argument);
  wrong = {};
  wrong.thresholded = cv::Mat::zeros(16, 16, CV_32F);
  EXPECT_THROW(draw_depth(depth, wrong, false, ""), std::invalid_argument);
}

}  // namespace
}  // namespace campo
