// docs/scene-format.md's tables of the "world" block, the generators, a vehicle's state noise and a
// sensor's settings are the ones
// their field declarations generate (tests/docs_tables_support.hpp; regenerate with
// CAMPO_UPDATE_DOCS=1 build/tests/test_scene --gtest_filter='ConfigDocs.*').
#include <gtest/gtest.h>

#include "scene/dem_source.hpp"
#include "scene/generator_fields.hpp"
#include "scene/mesh_sources.hpp"
#include "scene/sensor_fields.hpp"
#include "scene/world_config.hpp"
#include "tests/docs_tables_support.hpp"

namespace campo {
namespace {

TEST(ConfigDocs, SceneTablesAreTheDeclaredFields) {
  test_support::expect_docs_tables("docs/scene-format.md",
                                   {{"world", world_config_fields().markdown()},
                                    {"dem", dem_fields().markdown()},
                                    {"mesh", mesh_source_fields().markdown()},
                                    {"rolling_terrain", rolling_terrain_fields().markdown()},
                                    {"trees", trees_fields().markdown()},
                                    {"vineyard", vineyard_fields().markdown()},
                                    {"grid_obstacles", grid_obstacles_fields().markdown()},
                                    {"state_noise", state_noise_fields().markdown()},
                                    {"sensor", range_sensor_config_fields().markdown()},
                                    {"imu", imu_config_fields().markdown()},
                                    {"rgb_camera", rgb_camera_config_fields().markdown()}});
}

}  // namespace
}  // namespace campo
