// Every error of a sweep spec at once (issue 31, point 3), each with its
// line, column, pointer and the names of the axes and planners along it.
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "campo/json_reader.hpp"
#include "sweep/sweep_spec.hpp"

namespace campo {
namespace {

using ::testing::HasSubstr;

// Lines and columns below are counted by hand in this text (line 1 is the empty one after R"j( ).
const std::string kSeveral = R"j(
{
  "campo_sweep": 1,
  "scenes": ["two_barriers", "no such scene"],
  "axes": [
    {"name": "speed", "values": [1, 2], "set": ["objects/drone/planner/params/speed_mps"]},
    {"name": "Bad", "values": [1], "set": ["/world/seed2"]}
  ],
  "seeds": {"count": 0},
  "colour": 1
}
)j";

TEST(SweepSpecErrors, SeveralIndependentErrorsAreAllReportedWithTheirPlaces) {
  try {
    read_sweep_spec_text(kSeveral, "spec.json");
    FAIL() << "accepted";
  } catch (const InputError& e) {
    ASSERT_EQ(e.count(), 5u) << e.what();
    const auto& issues = e.issues();
    EXPECT_EQ(issues[0].pointer, "/scenes/1");
    EXPECT_EQ(issues[0].line, 4);
    EXPECT_EQ(issues[0].column, 30);

    EXPECT_EQ(issues[1].pointer, "/axes/0/set/0");
    EXPECT_EQ(issues[1].aliases, "speed");
    EXPECT_EQ(issues[1].line, 6);
    EXPECT_EQ(issues[1].column, 49);
    EXPECT_THAT(issues[1].message, HasSubstr("expected a JSON pointer into the scene"));

    EXPECT_EQ(issues[2].pointer, "/axes/1/name");
    EXPECT_EQ(issues[2].line, 7);
    EXPECT_EQ(issues[2].column, 6);
    EXPECT_THAT(issues[2].message, HasSubstr("expected an axis name of up to 32 lower-case letters"));

    EXPECT_EQ(issues[3].pointer, "/seeds/count");
    EXPECT_EQ(issues[3].line, 9);
    EXPECT_EQ(issues[3].column, 13);
    EXPECT_EQ(issues[3].message, "expected an integer in [1, 100000], got 0");

    EXPECT_EQ(issues[4].pointer, "/colour");
    EXPECT_EQ(issues[4].line, 10);
    EXPECT_EQ(issues[4].column, 3);
    EXPECT_THAT(issues[4].message, HasSubstr("unknown key \"colour\""));

    EXPECT_THAT(e.what(), HasSubstr("spec.json:6:49: /axes/0/set/0 (speed): expected a JSON pointer"));
    EXPECT_THAT(e.what(), HasSubstr("\nspec.json:9:13: /seeds/count: expected an integer in [1, 100000], got 0\n"));
  }
}

TEST(SweepSpecErrors, AnotherFormatVersionStopsAtOnce) {
  try {
    read_sweep_spec_text(R"({"campo_sweep": 2, "scenes": [], "colour": 1})", "spec.json");
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.count(), 1u) << e.what();
    EXPECT_EQ(e.pointer(), "/campo_sweep");
  }
}

}  // namespace
}  // namespace campo
