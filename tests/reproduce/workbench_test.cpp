#include "reproduce/workbench.hpp"

#include <gtest/gtest.h>

namespace campo {
namespace {

TEST(CommandLine, QuotesOnlyWordsAShellWouldSplitOrExpand) {
  EXPECT_EQ(command_line({"campo", "run", "scenes/wall.json", "--out", "out/a_b-1.5"}),
            "campo run scenes/wall.json --out out/a_b-1.5");
  EXPECT_EQ(command_line({"campo", "--set", "/objects/drone/planner/name=x y"}),
            "campo --set '/objects/drone/planner/name=x y'");
  EXPECT_EQ(command_line({"it's", ""}), "'it'\\''s' ''");
}

}  // namespace
}  // namespace campo
