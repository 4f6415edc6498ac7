// docs/scene-format.md's table of the "world" block is the one its field declarations
// generate (tests/docs_tables_support.hpp; regenerate with
// CAMPO_UPDATE_DOCS=1 build/tests/test_scene --gtest_filter='ConfigDocs.*').
#include <gtest/gtest.h>

#include "scene/world_config.hpp"
#include "tests/docs_tables_support.hpp"

namespace campo {
namespace {

TEST(ConfigDocs, WorldTableIsTheDeclaredFields) {
  test_support::expect_docs_tables("docs/scene-format.md", {{"world", world_config_fields().markdown()}});
}

}  // namespace
}  // namespace campo
