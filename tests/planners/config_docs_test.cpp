// docs/planners.md's parameter tables are the ones the planners' field
// declarations generate (tests/docs_tables_support.hpp; regenerate them with
// CAMPO_UPDATE_DOCS=1 build/tests/test_planners --gtest_filter='ConfigDocs.*').
#include <gtest/gtest.h>

#include "planners/depth_reactive.hpp"
#include "planners/dstar_lite_3d.hpp"
#include "planners/rover_route.hpp"
#include "planners/straight.hpp"
#include "tests/docs_tables_support.hpp"

namespace campo {
namespace {

TEST(ConfigDocs, PlannersTablesAreTheDeclaredFields) {
  test_support::expect_docs_tables("docs/planners.md", {
                                                      {"straight", straight_config_fields().markdown()},
                                                      {"depth_reactive", depth_reactive_config_fields().markdown()},
                                                      {"dstar_lite_3d", dstar_lite_3d_config_fields().markdown()},
                                                      {"rover_route", rover_route_config_fields().markdown()},
                                                  });
}

}  // namespace
}  // namespace campo
