// Every error of a scene at once (issue 31, point 3): each with its file,
// line, column, JSON pointer and the aliases along it; bounded, then counted;
// and hints about the ground that name the right cause.
#include <algorithm>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "campo/scene_loader.hpp"

namespace campo {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

// The InputError that loading `text` as "several.json" throws; fails the test if none.
InputError input_error_of(const std::string& text) {
  try {
    load_scene_text(text, "several.json");
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "the scene loaded";
  return InputError("", "", "");
}

// Lines and columns below are counted by hand in this text (the raw string starts with a newline: line 1 is empty).
const std::string kSeveral = R"j(
{
  "world": {"physics_step_s": -1},
  "objects": [
    {"alias": "ground", "type": "plane"},
    {"alias": "box", "type": "cuboid", "size_m": [1, -2, 1]},
    {"alias": "forest", "type": "dummy", "children": [
      {"alias": "tree4", "type": "cylinder", "radius_m": 0.2, "height_m": 3, "colour": [1, 0, 0]}
    ]},
    {"alias": "ball", "type": "sphere", "radius_m": "big"}
  ]
}
)j";

TEST(SceneErrors, SeveralIndependentErrorsAreAllReportedWithTheirPlaces) {
  const InputError e = input_error_of(kSeveral);
  ASSERT_EQ(e.count(), 4u) << e.what();
  ASSERT_EQ(e.issues().size(), 4u);
  const auto& issues = e.issues();

  EXPECT_EQ(issues[0].pointer, "/world/physics_step_s");
  EXPECT_EQ(issues[0].aliases, "");
  EXPECT_EQ(issues[0].line, 3);
  EXPECT_EQ(issues[0].column, 13);  // the key's opening quote

  EXPECT_EQ(issues[1].pointer, "/objects/1/size_m/1");
  EXPECT_EQ(issues[1].aliases, "box");
  EXPECT_EQ(issues[1].line, 6);
  EXPECT_EQ(issues[1].column, 54);  // the element -2 itself
  EXPECT_EQ(issues[1].message, "expected a number in (0, 1e+06], got -2");

  EXPECT_EQ(issues[2].pointer, "/objects/2/children/0/colour");
  EXPECT_EQ(issues[2].aliases, "forest/tree4");
  EXPECT_EQ(issues[2].line, 8);
  EXPECT_EQ(issues[2].column, 78);
  EXPECT_THAT(issues[2].message, HasSubstr("unknown key \"colour\""));

  EXPECT_EQ(issues[3].pointer, "/objects/3/radius_m");
  EXPECT_EQ(issues[3].aliases, "ball");
  EXPECT_EQ(issues[3].line, 10);
  EXPECT_EQ(issues[3].column, 41);

  // One line each, as campo prints them.
  const std::string what = e.what();
  EXPECT_THAT(what, HasSubstr("several.json:6:54: /objects/1/size_m/1 (box): expected a number in (0, 1e+06], got -2\n"));
  EXPECT_THAT(what, HasSubstr("several.json:8:78: /objects/2/children/0/colour (forest/tree4): unknown key \"colour\""));
  EXPECT_THAT(what, HasSubstr("several.json:10:41: /objects/3/radius_m (ball): expected a number in (0, 1e+06], got \"big\""));
  // The first error stays the exception's file, pointer and message.
  EXPECT_EQ(e.file(), "several.json");
  EXPECT_EQ(e.pointer(), "/world/physics_step_s");
}

TEST(SceneErrors, AnObjectWithAnErrorIsCheckedInFull) {
  // Three errors in one object: each of its keys is checked on its own.
  const InputError e = input_error_of(R"({"objects": [
    {"alias": "can", "type": "cylinder", "radius_m": -1, "height_m": -2, "friction": 99, "wheels": 4}]})");
  ASSERT_EQ(e.count(), 4u) << e.what();
  EXPECT_EQ(e.issues()[0].pointer, "/objects/0/friction");
  EXPECT_EQ(e.issues()[1].pointer, "/objects/0/radius_m");
  EXPECT_EQ(e.issues()[2].pointer, "/objects/0/height_m");
  EXPECT_EQ(e.issues()[3].pointer, "/objects/0/wheels");
  for (const InputIssue& issue : e.issues()) EXPECT_EQ(issue.aliases, "can");
}

TEST(SceneErrors, ReportsTheFirstTwentyThenCountsTheRest) {
  std::string objects;
  for (int i = 0; i < 25; ++i) {
    objects += (i == 0 ? "" : ",\n") + ("{\"alias\": \"b" + std::to_string(i) + "\", \"type\": \"sphere\", \"radius_m\": 1, \"spin\": 1}");
  }
  const InputError e = input_error_of("{\"objects\": [\n" + objects + "]}");
  EXPECT_EQ(e.count(), 25u);
  ASSERT_EQ(e.issues().size(), InputErrors::kMaxKept);
  EXPECT_EQ(e.issues().back().pointer, "/objects/19/spin");
  EXPECT_EQ(e.issues().back().line, 21);
  const std::string what = e.what();
  EXPECT_THAT(what, ::testing::EndsWith("\n... and 5 more errors"));
  EXPECT_EQ(std::count(what.begin(), what.end(), '\n'), 20);  // 20 errors and the count, one line each
}

TEST(SceneErrors, InvalidJsonStopsAtOnce) {
  try {
    load_scene_text("{\"objects\": [\n  {\"alias\": \"a\",}\n]}", "broken.json");
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.count(), 1u);
    EXPECT_THAT(e.what(), HasSubstr("broken.json: invalid JSON at line 2, column "));
  }
}

TEST(SceneErrors, APointOutsideTheTerrainSaysSoWithTheTerrainsExtent) {
  // The terrain is declared first: 40 m x 40 m centred on (10, 0), so x in [-10, 30], y in [-20, 20].
  const InputError e = input_error_of(R"({"objects": [
    {"alias": "hills", "type": "heightfield", "expression": "0", "size_m": [40, 40],
     "pose": {"position_m": [10, 0, 0]}},
    {"alias": "goal", "type": "dummy", "pose": {"position_m": [45, 0, 1], "above_ground": true}}]})");
  ASSERT_EQ(e.count(), 1u) << e.what();
  EXPECT_EQ(e.pointer(), "/objects/1/pose/above_ground");
  EXPECT_EQ(e.message(),
            "expected ground below the object: (45, 0) is outside the terrain declared before this object "
            "(\"hills\" covers x in [-10, 30] m, y in [-20, 20] m)");
  EXPECT_THAT(e.what(), Not(HasSubstr("declare the terrain")));
}

TEST(SceneErrors, APointWithNoTerrainDeclaredBeforeAsksForOne) {
  // The terrain comes after the object that stands on it.
  const InputError e = input_error_of(R"({"objects": [
    {"alias": "goal", "type": "dummy", "pose": {"position_m": [5, 0, 1], "above_ground": true}},
    {"alias": "hills", "type": "heightfield", "expression": "0", "size_m": [40, 40]}]})");
  ASSERT_EQ(e.count(), 1u) << e.what();
  EXPECT_EQ(e.message(),
            "expected ground below the object: no terrain below (5, 0); declare the terrain (heightfield, plane or "
            "rolling_terrain) before this object");
}

TEST(SceneErrors, AWaypointOutsideTheTerrainSaysSo) {
  const InputError e = input_error_of(R"({"objects": [
    {"alias": "hills", "type": "heightfield", "expression": "0", "size_m": [20, 10]},
    {"alias": "drone", "type": "quadrotor", "pose": {"position_m": [0, 0, 1]},
     "mission": {"waypoints": [{"position_m": [45, 0], "agl_m": 2}]}}]})");
  ASSERT_EQ(e.count(), 1u) << e.what();
  EXPECT_EQ(e.pointer(), "/objects/1/mission/waypoints/0/agl_m");
  EXPECT_EQ(e.issues()[0].aliases, "drone");
  EXPECT_EQ(e.message(),
            "expected a waypoint above terrain: (45, 0) is outside the terrain declared before this object "
            "(\"hills\" covers x in [-10, 10] m, y in [-5, 5] m)");
}

TEST(SceneErrors, ATerrainWithErrorsIsNamedAsTheCause) {
  // The terrain's own error, then the object on it: no "declare the terrain", which was declared.
  const InputError e = input_error_of(R"({"objects": [
    {"alias": "hills", "type": "heightfield", "expression": "0", "size_m": [40, -40]},
    {"alias": "goal", "type": "dummy", "pose": {"position_m": [5, 0, 1], "above_ground": true}}]})");
  ASSERT_EQ(e.count(), 2u) << e.what();
  EXPECT_EQ(e.issues()[0].pointer, "/objects/0/size_m/1");
  EXPECT_EQ(e.issues()[1].message,
            "expected ground below the object: no terrain below (5, 0): the terrain at /objects/0 has errors "
            "(reported with these)");
}

TEST(SceneErrors, AReferenceToAnObjectWithErrorsNamesThatObject) {
  const InputError e = input_error_of(R"({"objects": [
    {"alias": "gate", "type": "dummy", "pose": {"position_m": [5, 0]}},
    {"alias": "drone", "type": "quadrotor", "mission": {"waypoints": [{"frame": "gate"}]}}]})");
  ASSERT_EQ(e.count(), 2u) << e.what();
  EXPECT_EQ(e.issues()[0].pointer, "/objects/0/pose/position_m");
  EXPECT_EQ(e.issues()[1].pointer, "/objects/1/mission/waypoints/0/frame");
  EXPECT_THAT(e.issues()[1].message, HasSubstr("\"gate\" has errors"));
}

TEST(SceneErrors, LocatesPointersInJsonText) {
  const std::string text = "{\n  \"a\": [1, {\"b~/c\": \"x\\\"y\"}, 3],\n  \"d\": {\"e\\u0041\": 2}\n}";
  EXPECT_EQ(locate_json_pointer(text, "/a"), std::pair(2, 3));
  EXPECT_EQ(locate_json_pointer(text, "/a/0"), std::pair(2, 9));
  EXPECT_EQ(locate_json_pointer(text, "/a/1/b~0~1c"), std::pair(2, 13));
  EXPECT_EQ(locate_json_pointer(text, "/a/2"), std::pair(2, 30));
  EXPECT_EQ(locate_json_pointer(text, "/d/eA"), std::pair(3, 9));  // the key written with an escape
  EXPECT_EQ(locate_json_pointer(text, "/a/3"), std::nullopt);
  EXPECT_EQ(locate_json_pointer(text, "/x"), std::nullopt);
  EXPECT_EQ(locate_json_pointer(text, "/a/b"), std::nullopt);
}

}  // namespace
}  // namespace campo
