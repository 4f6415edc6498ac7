// campo reproduce --quick end to end: every claim measured, every figure drawn.
#include <filesystem>
#include <regex>

#include <gmock/gmock.h>

#include "tests/cli_support.hpp"

namespace campo::testing {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

class ReproduceCli : public CliTest {};

TEST_F(ReproduceCli, QuickReportMeasuresEveryClaimAndDrawsItsFigures) {
  const auto report = dir_ / "reproductions.md";
  const Result r = campo("reproduce --quick --jobs 2 --report " + report.string() + " --work " + (dir_ / "work").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string text = slurp(report);
  EXPECT_THAT(text, HasSubstr("**Quick version**"));
  for (const char* heading : {"### 000: Table 5.1 side by side", "### 000: Fig. 5.6, several runs on one map",
                              "### 000: Fig. 5.5, terrain following",
                              "### 000: Future work: field of view and maximum range",
                              "### 001: Obstacles as Tabelle 5.1, 5.3 and 5.5",
                              "### 001: Routes as Tabelle 5.2, 5.4 and 5.6, in latitude and longitude",
                              "### 001: The slot in the obstacle field", "### 001: The zigzag weave",
                              "### 001: The wall climbed over", "### 001: Cost model and LIDAR mounting",
                              "### 001: Bridge: column mapping against OctoMap",
                              "### 003: Fig. 45, random obstacles on the route",
                              "### 003: No local-minimum problems, with the printed follow-the-gap",
                              "### 003: Fig. 46, a crossing obstacle and follow-the-gap",
                              "### 003: Fig. 44, hysteresis against gap indecision",
                              "### 003: Precise tracking without obstacles, slower in curves",
                              "### 003: Fig. 35, the lookahead distance", "### 003: Fig. 33, Dubins route along the rows",
                              "### 003: Rejoining the route from a start off it"}) {
    EXPECT_THAT(text, HasSubstr(heading));
  }
  // Every experiment completed (a failed one would say so), every figure exists.
  EXPECT_THAT(text, Not(HasSubstr("did not complete")));
  const std::regex figure(R"(!\[[^\]]*\]\(([^)]+)\))");
  int figures = 0;
  for (std::sregex_iterator it(text.begin(), text.end(), figure), end; it != end; ++it, ++figures) {
    const auto png = dir_ / (*it)[1].str();
    ASSERT_TRUE(std::filesystem::exists(png)) << png;
    EXPECT_EQ(slurp(png).substr(1, 3), "PNG") << png;
  }
  EXPECT_GE(figures, 14);
  // The table of Table 5.1 has the thesis's 12 rows and campo's rows with the run counts.
  EXPECT_THAT(text, HasSubstr("| 7 | 64 | 4 | 5 | 24.99 | 1.07 | 2:09.6 |"));
  EXPECT_THAT(text, HasSubstr("| trees_rolling_terrain | 64 | 1 |"));
}

TEST_F(ReproduceCli, RefusesToEmptyADirectoryItDidNotMake) {
  std::filesystem::create_directories(dir_ / "mine");
  write("mine/thesis.tex", "precious");
  const Result r = campo("reproduce --quick --report " + (dir_ / "r.md").string() + " --work " +
                         (dir_ / "mine").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("was not made by campo reproduce"));
  EXPECT_EQ(slurp(dir_ / "mine/thesis.tex"), "precious");
  EXPECT_FALSE(std::filesystem::exists(dir_ / "r.md"));
}

}  // namespace
}  // namespace campo::testing
