#include "render/sequence_figure.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <optional>
#include <stdexcept>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "campo/scene_loader.hpp"
#include "tests/render/figure_test_support.hpp"

namespace campo {
namespace {

using namespace figure::test;

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
  const cv::Mat twins = draw_sequence(scene, run, same, {1.5, 1.0}, small_style()).raster();
  ASSERT_EQ(twins.cols % 2, 0);
  const int w = twins.cols / 2;
  // Equal instants, equal panels; the panel is a map of the documented bands.
  EXPECT_EQ(cv::norm(twins(cv::Rect(0, 0, w, twins.rows)), twins(cv::Rect(w, 0, w, twins.rows)), cv::NORM_L1), 0.0);
  EXPECT_GT(w, kFigureLeftPx + kFigurePanelPx);
  // Four instants: two rows of two; the mover and the track differ between them.
  const std::vector<SequencePanel> four{
      {1.0, "(a)", 0.0}, {4.0, "(b)", -30.0}, {6.0, "(c)", 30.0}, {9.0, "(d)", std::nullopt}};
  const cv::Mat grid = draw_sequence(scene, run, four, {1.5, 1.0}, small_style()).raster();
  EXPECT_EQ(grid.cols, twins.cols);
  ASSERT_EQ(grid.rows % 2, 0);
  const int h = grid.rows / 2;
  EXPECT_GT(cv::norm(grid(cv::Rect(0, 0, w, h)), grid(cv::Rect(w, 0, w, h)), cv::NORM_L1), 0.0);
  EXPECT_GT(cv::norm(grid(cv::Rect(0, h, w, h)), grid(cv::Rect(w, h, w, h)), cv::NORM_L1), 0.0);
  EXPECT_EQ(png(grid), png(draw_sequence(scene, run, four, {1.5, 1.0}, small_style()).raster()));
}

// The panels are drawn into one canvas, not copied as pixels: the PDF holds every panel's caption and axis
// labels as text.
TEST(FiguresSequence, WritesPdfAndSvgWithEveryPanelAsVectors) {
  const std::vector<SequencePanel> two{{2.0, "(a) 2.0 s: before", 0.0}, {7.0, "(b) 7.0 s: after", std::nullopt}};
  const figure::Canvas sequence = draw_sequence(scene_with_mover(), test_run(), two, {1.5, 1.0}, small_style());
  expect_vector_outputs(sequence, {"(a) 2.0 s: before", "(b) 7.0 s: after", "x, east (m)"});
  // Each panel's axis title, once per panel.
  const std::string pdf = sequence.encode(figure::FigureFormat::pdf);
  const auto dir = std::filesystem::temp_directory_path() / ("campo_sequence_pdf_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "sequence.pdf", std::ios::binary) << pdf;
  const std::string text = without_spaces(run_command("pdftotext -q '" + (dir / "sequence.pdf").string() + "' -").text);
  std::size_t count = 0;
  for (std::size_t at = text.find("x,east(m)"); at != std::string::npos; at = text.find("x,east(m)", at + 1)) ++count;
  EXPECT_EQ(count, 2u);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace campo
