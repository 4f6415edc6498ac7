#include "scene/scene_overrides.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "campo/json_reader.hpp"

namespace campo {
namespace {

using ::testing::HasSubstr;

nlohmann::json document() {
  return nlohmann::json::parse(R"({"world": {"seed": 1}, "objects": [
    {"alias": "box", "type": "cuboid", "size_m": [1, 2, 3]},
    {"alias": "drone", "type": "quadrotor", "planner": {"name": "straight", "params": {}}}]})");
}

std::string error_of(const std::string& assignment) {
  nlohmann::json d = document();
  try {
    apply_override(d, assignment);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(SceneOverrides, SetsValuesByPointerAndAlias) {
  nlohmann::json d = document();
  apply_override(d, "/world/seed=42");
  apply_override(d, "/objects/0/size_m/1=5.5");
  apply_override(d, "/objects/drone/planner/params/speed_mps=1.2");
  apply_override(d, "/objects/box/color=[1,0,0]");
  apply_override(d, "/objects/drone/planner/name=other");
  EXPECT_EQ(d["world"]["seed"], 42);
  EXPECT_EQ(d["objects"][0]["size_m"][1], 5.5);
  EXPECT_EQ(d["objects"][1]["planner"]["params"]["speed_mps"], 1.2);
  EXPECT_EQ(d["objects"][0]["color"], nlohmann::json({1, 0, 0}));
  EXPECT_EQ(d["objects"][1]["planner"]["name"], "other");  // not JSON: taken as a string
  apply_override(d, "/objects/drone/params/controller/speed_limit_mps=1");
  EXPECT_EQ(d["objects"][1]["params"]["controller"]["speed_limit_mps"], 1);  // created on the way
}

TEST(SceneOverrides, ReportsBadPaths) {
  EXPECT_THAT(error_of("world.seed=3"), HasSubstr("command line: --set world.seed=3: expected PATH=VALUE"));
  EXPECT_THAT(error_of("/world/seed"), HasSubstr("expected PATH=VALUE"));
  EXPECT_THAT(error_of("/objects/7/size_m=1"), HasSubstr("index 7 out of range at /objects/7"));
  EXPECT_THAT(error_of("/objects/tree/size_m=1"), HasSubstr("no element with alias \"tree\" at /objects/tree"));
  EXPECT_THAT(error_of("/world/seed/x=1"), HasSubstr("cannot descend into a number at /world/seed/x"));
}

}  // namespace
}  // namespace campo

namespace campo {
namespace {

TEST(SceneOverrides, UnescapesPointerSegments) {
  nlohmann::json d = nlohmann::json::parse(R"({"a/b": {"c~d": 1}})");
  apply_override(d, "/a~1b/c~0d=2");
  EXPECT_EQ(d["a/b"]["c~d"], 2);
}

}  // namespace
}  // namespace campo
