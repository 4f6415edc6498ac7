// The generator objects' declared fields: what they write reads back to the
// same generator input (so run records and docs show what the loader takes),
// and their checks name the offending key.
#include "scene/generator_fields.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "scene/sensor_fields.hpp"

namespace campo {
namespace {

using ::testing::HasSubstr;

template <class Config>
Config read_back(const ConfigFields<Config>& fields, const Config& config) {
  Config out;
  fields.read(JsonNode(fields.write(config), "inline.json", ""), out);
  return out;
}

template <class Config>
std::string fields_error_of(const ConfigFields<Config>& fields, const nlohmann::json& j) {
  try {
    Config c;
    fields.read(JsonNode(j, "inline.json", "/objects/0"), c);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(GeneratorFields, TreesWriteWhatTheyRead) {
  TreesConfig c;
  c.count = 7;
  c.crown = CrownShape::cone;
  c.trunk_radius_m = {0.1, 0.2};
  c.keep_out = {{1.0, 2.0, 3.0}, {-4.0, 5.0, 0.5}};
  c.seed = 18446744073709551615ull;
  const TreesConfig back = read_back(trees_fields(), c);
  EXPECT_EQ(back.count, 7);
  EXPECT_EQ(back.crown, CrownShape::cone);
  EXPECT_EQ(back.trunk_radius_m, c.trunk_radius_m);
  ASSERT_EQ(back.keep_out.size(), 2u);
  EXPECT_EQ(back.keep_out[1], c.keep_out[1]);
  EXPECT_EQ(back.seed, c.seed);
  EXPECT_EQ(trees_fields().write(back), trees_fields().write(c));
}

TEST(GeneratorFields, GridBoxesWriteWhatTheyRead) {
  GridObstaclesConfig c;
  c.rows = 10;
  c.cols = 20;
  c.boxes = {{2, 2, 3, 5, 4.0}, {1, 10, 20, 20, 7.5}};
  const GridObstaclesConfig back = read_back(grid_obstacles_fields(), c);
  ASSERT_EQ(back.boxes.size(), 2u);
  EXPECT_EQ(back.boxes[0].row_first, 2);
  EXPECT_EQ(back.boxes[0].row_last, 2);
  EXPECT_EQ(back.boxes[0].col_last, 5);
  EXPECT_EQ(back.boxes[1].row_last, 10);
  EXPECT_EQ(back.boxes[1].height_m, 7.5);
  // A single cell is written as an index, a block as [first, last].
  const nlohmann::json j = grid_obstacles_fields().write(c);
  EXPECT_EQ(j["boxes"][0]["rows"], 2);
  EXPECT_EQ(j["boxes"][0]["cols"], nlohmann::json({3, 5}));
}

TEST(GeneratorFields, VineyardTerrainAndNoiseWriteWhatTheyRead) {
  VineyardConfig v;
  v.row_count = 3;
  v.obstacle_size_m = {0.5, 0.5};
  EXPECT_EQ(vineyard_fields().write(read_back(vineyard_fields(), v)), vineyard_fields().write(v));
  RollingTerrainConfig t;
  t.waves = 9;
  t.size_m = {30.0, 40.0};
  EXPECT_EQ(rolling_terrain_fields().write(read_back(rolling_terrain_fields(), t)), rolling_terrain_fields().write(t));
  StateNoiseConfig n;
  n.heading_stddev_deg = 3.0;
  EXPECT_EQ(read_back(state_noise_fields(), n).heading_stddev_deg, 3.0);
}

TEST(GeneratorFields, ChecksNameTheKey) {
  EXPECT_THAT(fields_error_of(trees_fields(), {{"trunk_radius_m", {0.3, 0.1}}}),
              HasSubstr("/objects/0/trunk_radius_m: expected [min, max] with min <= max"));
  EXPECT_THAT(fields_error_of(trees_fields(), {{"crown", "palm"}}), HasSubstr("/objects/0/crown"));
  // A block's cells are checked against the grid's rows, read before it.
  const nlohmann::json outside = {{"rows", 5}, {"boxes", {{{"rows", 6}, {"cols", 1}, {"height_m", 2}}}}};
  EXPECT_THAT(fields_error_of(grid_obstacles_fields(), outside), HasSubstr("/objects/0/boxes/0/rows"));
  EXPECT_THAT(fields_error_of(grid_obstacles_fields(), {{"boxes", {{{"rows", 1}, {"cols", 1}}}}}),
              HasSubstr("/objects/0/boxes/0: missing required key \"height_m\""));
  // Loader limits bound the counts.
  SceneLimits small;
  small.max_trees = 3;
  EXPECT_THAT(fields_error_of(trees_fields(small), {{"count", 4}}),
              HasSubstr("/objects/0/count: expected an integer in [0, 3]"));
  EXPECT_THAT(fields_error_of(vineyard_fields(), {{"spare", 1}}), HasSubstr("/objects/0/spare: unknown key"));
}

}  // namespace
}  // namespace campo
