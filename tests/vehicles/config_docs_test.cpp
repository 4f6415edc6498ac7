// docs/vehicles.md's parameter tables are the ones the vehicles' field
// declarations generate (tests/docs_tables_support.hpp; regenerate them with
// CAMPO_UPDATE_DOCS=1 build/tests/test_vehicles --gtest_filter='ConfigDocs.*').
#include <gtest/gtest.h>

#include "tests/docs_tables_support.hpp"
#include "vehicles/quadrotor.hpp"
#include "vehicles/rover.hpp"

namespace campo {
namespace {

TEST(ConfigDocs, VehiclesTablesAreTheDeclaredFields) {
  test_support::expect_docs_tables("docs/vehicles.md", {
                                                      {"quadrotor", quadrotor_config_fields().markdown()},
                                                      {"rover", rover_config_fields().markdown()},
                                                  });
}

}  // namespace
}  // namespace campo
