#include "render/height_map_figure.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <stdexcept>

#include <opencv2/core.hpp>

#include "render/map_figure.hpp"
#include "tests/render/figure_test_support.hpp"

namespace campo {
namespace {

using namespace figure::test;

// Recorded hits are red dots on the map; the reconstructed height map colours
// each mapped cell by its top (lowest to highest across the colour bar) and
// leaves unmapped cells to the terrain.
TEST(FiguresHeightMap, ColoursMappedCellsByTheirTop) {
  const Scene scene = test_scene();
  RunView run = test_run();
  run.sensor_hits = {{-6.0, -3.0, 0.2}};
  const FigureStyle style = small_style();
  const cv::Mat map = draw_map(scene, run, style).raster();
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
  const cv::Mat image = draw_height_map(scene, run, style).raster();
  EXPECT_LT(colour_distance(at(image, layout.to_px({-5.0, -2.0})), sequential_color(0.0)), 6);
  EXPECT_LT(colour_distance(at(image, layout.to_px({5.0, 2.5})), sequential_color(1.0)), 6);
  EXPECT_LT(colour_distance(at(image, layout.to_px({3.0, -2.5})), sequential_color(0.25)), 6);
  // An unmapped cell shows the map's terrain, not a height colour.
  EXPECT_LT(colour_distance(at(image, layout.to_px({-1.0, -4.0})),
                            at(map, map_layout(scene, run, style).to_px({-1.0, -4.0}))),
            12);
  EXPECT_EQ(png(image), png(draw_height_map(scene, run, style).raster()));
  expect_vector_outputs(draw_height_map(scene, run, style), {"Test figure", "x, east (m)", "mapped top, z (m)"});
}

// The cells reach the PDF as one image of a pixel per cell (10 x 5 here), not as a rectangle per cell.
TEST(FiguresHeightMap, EmbedsTheCellsAsOneImageOfAPixelPerCell) {
  const Scene scene = test_scene();
  RunView run = test_run();
  HeightMapView& h = run.height_map;
  h.origin_m = {-10.0, -5.0};
  h.cell_size_m = 2.0;
  h.columns = 10;
  h.rows = 5;
  h.top_m.assign(50, 1.0);
  h.top_m[0] = 0.0;
  const auto dir = std::filesystem::temp_directory_path() / ("campo_height_map_pdf_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  draw_height_map(scene, run, small_style()).write(dir / "heightmap", {figure::FigureFormat::pdf});
  // pdfimages -list: a header of two lines, then "page num type width height ..." per image.
  const CommandOutput list = run_command("pdfimages -list '" + (dir / "heightmap.pdf").string() + "'");
  EXPECT_EQ(list.status, 0);
  std::istringstream lines(list.text);
  std::string line;
  int cell_images = 0;
  while (std::getline(lines, line)) {
    std::istringstream fields(line);
    std::string page, num, type;
    int width = 0, height = 0;
    if (fields >> page >> num >> type >> width >> height && type == "image" && width == 10 && height == 5) ++cell_images;
  }
  EXPECT_EQ(cell_images, 1) << list.text;
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace campo
