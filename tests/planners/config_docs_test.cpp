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
                                                      // What each planner records of its own, as it declares it.
                                                      {"depth_reactive decisions",
                                                       depth_reactive_record().description.decisions.markdown()},
                                                      {"depth_reactive replan",
                                                       depth_reactive_record().description.replan.markdown()},
                                                      {"dstar_lite_3d decisions",
                                                       dstar_lite_3d_record().description.decisions.markdown()},
                                                      {"dstar_lite_3d replan",
                                                       dstar_lite_3d_record().description.replan.markdown()},
                                                      {"rover_route decisions",
                                                       rover_route_record().description.decisions.markdown()},
                                                      {"rover_route replan",
                                                       rover_route_record().description.replan.markdown()},
                                                  });
}

}  // namespace
}  // namespace campo
