#include "reproduce/report.hpp"

#include <stdexcept>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace campo {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

TEST(TargetCheck, AnyFailedTargetMeansNotReproduced) {
  TargetCheck check;
  check.expect(true, "success 100 %");
  EXPECT_EQ(check.verdict(), Verdict::reproduced);
  EXPECT_EQ(check.summary(), "All 1 targets hold: success 100 %.");
  check.expect(false, "no path ratio above 1.15");
  EXPECT_EQ(check.verdict(), Verdict::not_reproduced);
  EXPECT_EQ(check.summary(), "Not met (1 of 2): no path ratio above 1.15. Met: success 100 %.");
  for (int i = 0; i < 5; ++i) check.expect(true, "clearance " + std::to_string(i));
  EXPECT_EQ(check.summary(), "Not met (1 of 7): no path ratio above 1.15. Met: 6 others.");
}

TEST(MeasureClaim, AFailedExperimentIsReportedNotThrown) {
  const Claim claim = measure_claim("001", "The slot", [](Claim& c) {
    c.thesis = "the drone passes the slot";
    c.figures.push_back({"x.png", "x"});
    throw std::runtime_error("\"campo run scenes/x.json\" failed (exit code 2)");
  });
  EXPECT_EQ(claim.seed, "001");
  EXPECT_EQ(claim.thesis, "the drone passes the slot");
  EXPECT_TRUE(claim.figures.empty());
  EXPECT_EQ(claim.verdict, Verdict::not_reproduced);
  EXPECT_THAT(claim.measured, HasSubstr("exit code 2"));
}

TEST(MarkdownTable, EscapesPipesAndPadsShortRows) {
  EXPECT_EQ(markdown_table({"a", "b"}, {{"1|2"}, {"3", "4"}}),
            "| a | b |\n| --- | --- |\n| 1\\|2 |  |\n| 3 | 4 |\n");
}

TEST(FormatReport, CountsVerdictsAndLinksEveryClaim) {
  Claim a;
  a.seed = "000";
  a.title = "Table 5.1 side by side";
  a.thesis = "ratio 1.01-1.07";
  a.commands = {"campo sweep scenes/sweeps/resolution_000.json --out w"};
  a.measured = "ratio 1.04";
  a.figures = {{"reproductions/a.png", "The runs."}};
  a.verdict = Verdict::reproduced;
  a.verdict_reason = "All targets hold.";
  Claim b = a;
  b.seed = "003";
  b.title = "Fig. 46, follow-the-gap";
  b.figures.clear();
  b.verdict = Verdict::deviates;
  ReportInfo info;
  info.campo_version = "campo 0.1.0 (git abc)";
  info.command = "campo reproduce";
  const std::string text = format_report({a, b}, info);
  EXPECT_THAT(text, HasSubstr("**2 claims: 1 reproduced, 1 with a stated deviation, 0 not reproduced.**"));
  EXPECT_THAT(text, HasSubstr("| 000 | [Table 5.1 side by side](#000-table-51-side-by-side) | reproduced |"));
  EXPECT_THAT(text, HasSubstr("### 003: Fig. 46, follow-the-gap"));
  EXPECT_THAT(text, HasSubstr("## Seed 003"));
  EXPECT_THAT(text, HasSubstr("![The runs.](reproductions/a.png)\n*The runs.*"));
  EXPECT_THAT(text, HasSubstr("**Verdict: deviates.**"));
  EXPECT_THAT(text, Not(HasSubstr("Quick version")));
}

}  // namespace
}  // namespace campo
