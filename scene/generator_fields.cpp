#include "scene/generator_fields.hpp"

#include <cstddef>
#include <string>
#include <tuple>
#include <utility>

namespace campo {

namespace {

const Range kGeneratorLength{0.0, 1e6, true, false};
const Range kCoordinate = Range::closed(-1e6, 1e6);

// Reads "[first, last]" or a single index, 1-based, within [1, max].
std::pair<int, int> read_index_range(const JsonNode& node, int max) {
  if (node.value().is_array()) {
    const auto items = node.as_array(2, 2);
    const int first = static_cast<int>(items[0].as_int(1, max));
    const int last = static_cast<int>(items[1].as_int(first, max));
    return {first, last};
  }
  const int index = static_cast<int>(node.as_int(1, max));
  return {index, index};
}

nlohmann::json index_range_json(int first, int last) {
  return first == last ? nlohmann::json(first) : nlohmann::json{first, last};
}

}  // namespace

ConfigFields<RollingTerrainConfig> rolling_terrain_fields() {
  using C = RollingTerrainConfig;
  return ConfigFields<C>()
      .vector("size_m", &C::size_m, kGeneratorLength, "m", "extent along x and y, centred on the pose")
      .number("spacing_m", &C::spacing_m, kGeneratorLength, "m", "vertex spacing")
      .number("amplitude_m", &C::amplitude_m, Range::closed(0.0, 1e4), "m", "max |height| above or below 0")
      .number("wavelength_m", &C::wavelength_m, kGeneratorLength, "m", "dominant hill wavelength")
      .integer("waves", &C::waves, {1, 32}, "", "superposed plane waves")
      .seed("seed", &C::seed, "directions, phases and wavelengths of the waves");
}

ConfigFields<TreesConfig> trees_fields(const SceneLimits& limits) {
  using C = TreesConfig;
  return ConfigFields<C>()
      .vector("area_min_m", &C::area_min_m, kCoordinate, "m", "south-west corner of the rectangle, world x, y")
      .vector("area_max_m", &C::area_max_m, kCoordinate, "m",
              "north-east corner, greater than `area_min_m` in x and y")
      .integer("count", &C::count, {0, limits.max_trees}, "", "number of trees; an error if they cannot be placed")
      .number("min_spacing_m", &C::min_spacing_m, Range::non_negative(), "m", "between trunk centres")
      .interval("trunk_radius_m", &C::trunk_radius_m, kGeneratorLength, "m", "uniform in [min, max]")
      .interval("trunk_height_m", &C::trunk_height_m, kGeneratorLength, "m", "uniform in [min, max]")
      .choice("crown", &C::crown, {{"sphere", CrownShape::sphere}, {"cone", CrownShape::cone}}, "crown shape")
      .interval("crown_radius_m", &C::crown_radius_m, kGeneratorLength, "m", "uniform in [min, max]")
      .number("crown_height_ratio", &C::crown_height_ratio, Range{0.0, 1e3, true, false}, "",
              "cone height / cone radius")
      .custom("keep_out", "m", "up to 1000 {`center_m`: [x, y], `radius_m` > 0}",
              "circles kept free of trunks (start and goal areas)",
              [](const JsonNode& n, C& c) {
                c.keep_out.clear();
                for (const JsonNode& zone : n.as_array(0, 1000)) {
                  ObjectReader z(zone);
                  const Eigen::Vector2d center = z.required("center_m").as_vector2(kCoordinate);
                  const double radius = z.required("radius_m").as_number(kGeneratorLength);
                  z.finish();
                  c.keep_out.emplace_back(center.x(), center.y(), radius);
                }
              },
              [](const C& c, nlohmann::json& j) {
                nlohmann::json zones = nlohmann::json::array();
                for (const Eigen::Vector3d& z : c.keep_out) {
                  zones.push_back({{"center_m", {z.x(), z.y()}}, {"radius_m", z.z()}});
                }
                j["keep_out"] = zones;
              })
      .seed("seed", &C::seed, "positions and sizes");
}

ConfigFields<VineyardConfig> vineyard_fields(const SceneLimits& limits) {
  using C = VineyardConfig;
  return ConfigFields<C>()
      .vector("field_size_m", &C::field_size_m, kGeneratorLength, "m", "fenced area, x by y, centred on the pose")
      .integer("row_count", &C::row_count, {1, 500}, "", "vine rows, along local y")
      .number("row_spacing_m", &C::row_spacing_m, kGeneratorLength, "m", "centre to centre, across x")
      .number("headland_m", &C::headland_m, Range::non_negative(), "m", "free space between row ends and the fence")
      .number("post_spacing_m", &C::post_spacing_m, kGeneratorLength, "m", "posts along a row, both ends included")
      .number("post_radius_m", &C::post_radius_m, kGeneratorLength, "m", "post cylinders")
      .number("post_height_m", &C::post_height_m, kGeneratorLength, "m", "post cylinders")
      .number("canopy_width_m", &C::canopy_width_m, kGeneratorLength, "m", "canopy box across the row")
      .number("canopy_bottom_m", &C::canopy_bottom_m, Range::non_negative(), "m", "canopy bottom above ground")
      .number("canopy_top_m", &C::canopy_top_m, kGeneratorLength, "m", "canopy top above ground")
      .number("fence_height_m", &C::fence_height_m, kGeneratorLength, "m", "perimeter fence")
      .number("fence_thickness_m", &C::fence_thickness_m, kGeneratorLength, "m", "perimeter fence")
      .integer("obstacle_count", &C::obstacle_count, {0, limits.max_generated_obstacles}, "",
               "random boxes between rows")
      .interval("obstacle_size_m", &C::obstacle_size_m, kGeneratorLength, "m", "edge lengths (x, y, z alike), uniform")
      .number("obstacle_passage_m", &C::obstacle_passage_m, Range::non_negative(), "m",
              "each obstacle leaves a free passage at least this wide on one side (0: anywhere between the rows)")
      .seed("seed", &C::seed, "obstacle positions and sizes");
}

ConfigFields<GridObstaclesConfig> grid_obstacles_fields(const SceneLimits& limits) {
  using C = GridObstaclesConfig;
  const int max_boxes = limits.max_generated_obstacles;
  return ConfigFields<C>()
      .vector("origin_m", &C::origin_m, kCoordinate, "m", "south-west corner of cell (1, 1): x₀, y₀")
      .number("cell_size_m", &C::cell_size_m, kGeneratorLength, "m", "cell edge s")
      .integer("rows", &C::rows, {1, limits.max_grid_cells_per_axis}, "", "cells along y (south to north)")
      .integer("cols", &C::cols, {1, limits.max_grid_cells_per_axis}, "", "cells along x (west to east)")
      // After rows and cols: a block's cells are checked against them.
      .custom("boxes", "",
              "up to " + std::to_string(max_boxes) +
                  " {`rows`, `cols`: an index or [first, last], 1-based, inclusive; `height_m` > 0}",
              "blocks of cells; `height_m`: top above the highest ground under the block",
              [max_boxes](const JsonNode& n, C& c) {
                c.boxes.clear();
                for (const JsonNode& box_node : n.as_array(0, static_cast<std::size_t>(max_boxes))) {
                  ObjectReader b(box_node);
                  GridBox box;
                  std::tie(box.row_first, box.row_last) = read_index_range(b.required("rows"), c.rows);
                  std::tie(box.col_first, box.col_last) = read_index_range(b.required("cols"), c.cols);
                  box.height_m = b.required("height_m").as_number(kGeneratorLength);
                  b.finish();
                  c.boxes.push_back(box);
                }
              },
              [](const C& c, nlohmann::json& j) {
                nlohmann::json boxes = nlohmann::json::array();
                for (const GridBox& b : c.boxes) {
                  boxes.push_back({{"rows", index_range_json(b.row_first, b.row_last)},
                                   {"cols", index_range_json(b.col_first, b.col_last)},
                                   {"height_m", b.height_m}});
                }
                j["boxes"] = boxes;
              });
}

}  // namespace campo
