// docs/scene-format.md's tables of the "world" block and of a sensor's settings are the ones
// their field declarations generate (tests/docs_tables_support.hpp; regenerate with
// CAMPO_UPDATE_DOCS=1 build/tests/test_scene --gtest_filter='ConfigDocs.*').
#include <gtest/gtest.h>

#include "scene/sensor_fields.hpp"
#include "scene/world_config.hpp"
#include "tests/docs_tables_support.hpp"

namespace campo {
namespace {

TEST(ConfigDocs, WorldAndSensorTablesAreTheDeclaredFields) {
  test_support::expect_docs_tables("docs/scene-format.md", {{"world", world_config_fields().markdown()},
                                                           {"sensor", lidar_config_fields().markdown()}});
}

}  // namespace
}  // namespace campo
