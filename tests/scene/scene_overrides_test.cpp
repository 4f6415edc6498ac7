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

std::string override_error_of(const std::string& assignment) {
  nlohmann::json d = document();
  try {
    apply_override(d, parse_override(assignment));
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(SceneOverrides, SetsValuesByPointerAndAlias) {
  nlohmann::json d = document();
  apply_override(d, parse_override("/world/seed=42"));
  apply_override(d, parse_override("/objects/0/size_m/1=5.5"));
  apply_override(d, parse_override("/objects/drone/planner/params/speed_mps=1.2"));
  apply_override(d, parse_override("/objects/box/color=[1,0,0]"));
  apply_override(d, parse_override("/objects/drone/planner/name=other"));
  EXPECT_EQ(d["world"]["seed"], 42);
  EXPECT_EQ(d["objects"][0]["size_m"][1], 5.5);
  EXPECT_EQ(d["objects"][1]["planner"]["params"]["speed_mps"], 1.2);
  EXPECT_EQ(d["objects"][0]["color"], nlohmann::json({1, 0, 0}));
  EXPECT_EQ(d["objects"][1]["planner"]["name"], "other");  // not JSON: taken as a string
  apply_override(d, parse_override("/objects/drone/params/controller/speed_limit_mps=1"));
  EXPECT_EQ(d["objects"][1]["params"]["controller"]["speed_limit_mps"], 1);  // created on the way
}

// Where an override assigned, aliases resolved to the index they named: how
// `campo run --planner` finds the overrides of the vehicle's planner (issue 31).
TEST(SceneOverrides, ReturnsThePointerAssignedWithIndices) {
  nlohmann::json d = document();
  EXPECT_EQ(apply_override(d, parse_override("/objects/drone/planner/params/speed_mps=2")), "/objects/1/planner/params/speed_mps");
  EXPECT_EQ(apply_override(d, parse_override("/objects/0/size_m/2=4")), "/objects/0/size_m/2");
  EXPECT_EQ(apply_override(d, parse_override("/world/a~1b=1")), "/world/a~1b");  // segments escaped as written
  EXPECT_EQ(parse_override("/world/seed=2").value, 2);
  EXPECT_EQ(parse_override("/objects/0/alias=crate").value, "crate");  // not JSON: a string
  EXPECT_EQ(parse_override("/objects/0/size_m=[1,2,3]").value, nlohmann::json::parse("[1,2,3]"));
}

TEST(SceneOverrides, ReportsBadPaths) {
  EXPECT_THAT(override_error_of("world.seed=3"), HasSubstr("command line: --set world.seed=3: expected PATH=VALUE"));
  EXPECT_THAT(override_error_of("/world/seed"), HasSubstr("expected PATH=VALUE"));
  EXPECT_THAT(override_error_of("/objects/7/size_m=1"), HasSubstr("index 7 out of range at /objects/7"));
  EXPECT_THAT(override_error_of("/objects/tree/size_m=1"), HasSubstr("no element with alias \"tree\" at /objects/tree"));
  EXPECT_THAT(override_error_of("/world/seed/x=1"), HasSubstr("cannot descend into a number at /world/seed/x"));
}

}  // namespace
}  // namespace campo

namespace campo {
namespace {

TEST(SceneOverrides, UnescapesPointerSegments) {
  nlohmann::json d = nlohmann::json::parse(R"({"a/b": {"c~d": 1}})");
  apply_override(d, parse_override("/a~1b/c~0d=2"));
  EXPECT_EQ(d["a/b"]["c~d"], 2);
}

TEST(SceneOverrides, ArrayIndicesAreRfc6901s) {
  // "04" is not index 4 (RFC 6901: no leading zeros): refused, naming the pointer and what was expected.
  EXPECT_EQ(override_error_of("/objects/01/alias=x"),
            "command line: --set /objects/01/alias=x: expected an array index in [0, 2) without leading zeros "
            "(RFC 6901) or the alias of an element of /objects, got \"01\" (a leading zero) at /objects/01");
  EXPECT_THAT(override_error_of("/objects/00=1"), HasSubstr("got \"00\" (a leading zero) at /objects/00"));
  EXPECT_THAT(override_error_of("/objects/0/size_m/01=1"),
              HasSubstr("expected an array index in [0, 3) without leading zeros (RFC 6901) or the alias of an element "
                        "of /objects/0/size_m, got \"01\""));
  // Neither a sign, a space, a suffix nor "-" (past the end) is an index; no element has such an alias.
  for (const std::string segment : {"+1", " 1", "1a", "-", "0x1", "1e0", ""}) {
    EXPECT_THAT(override_error_of("/objects/" + segment + "/alias=x"),
                HasSubstr("no element with alias \"" + segment + "\" at /objects/" + segment +
                          "; expected an array index in [0, 2) without leading zeros (RFC 6901)"))
        << segment;
  }
  EXPECT_THAT(override_error_of("/objects/99999999999999999999999/alias=x"),
              HasSubstr("index 99999999999999999999999 out of range at /objects/99999999999999999999999"));
  // "0" and indices without leading zeros still work, and so do aliases made of digits that are not indices.
  nlohmann::json d = document();
  apply_override(d, parse_override("/objects/0/size_m/0=7"));
  EXPECT_EQ(d["objects"][0]["size_m"][0], 7);
  d["objects"][0]["alias"] = "1a";
  apply_override(d, parse_override("/objects/1a/size_m/2=8"));
  EXPECT_EQ(d["objects"][0]["size_m"][2], 8);
}

TEST(SceneOverrides, OnlyTildeZeroAndTildeOneAreEscapes) {
  EXPECT_THAT(override_error_of("/world/a~2b=1"),
              HasSubstr("--set /world/a~2b=1: expected '~' followed by 0 or 1 (RFC 6901: \"~0\" is '~', \"~1\" is '/') "
                        "in \"a~2b\" at /world/a~2b"));
  EXPECT_THAT(override_error_of("/world/a~=1"), HasSubstr("expected '~' followed by 0 or 1"));
}

TEST(SceneOverrides, ControlCharactersInAPointerAreEscaped) {
  using namespace std::string_literals;
  const std::string error = override_error_of("/objects/\x1b[2J\0/alias=x"s);
  EXPECT_THAT(error, HasSubstr("no element with alias \"\\x1b[2J\\x00\" at /objects/\\x1b[2J\\x00"));
  EXPECT_EQ(error.find('\x1b'), std::string::npos);
}

}  // namespace
}  // namespace campo
