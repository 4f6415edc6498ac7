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

TEST(Judge, EveryVerdictFromTheCriterionTheDeparturesAndTheCause) {
  EXPECT_EQ(judge(ClaimKind::thesis_result, true, false, false), Verdict::reproduced);
  EXPECT_EQ(judge(ClaimKind::thesis_result, true, true, false), Verdict::reproduced_with_departures);
  EXPECT_EQ(judge(ClaimKind::thesis_result, false, true, true), Verdict::deviates);
  EXPECT_EQ(judge(ClaimKind::thesis_result, false, false, false), Verdict::not_reproduced);
  EXPECT_EQ(judge(ClaimKind::thesis_result, std::nullopt, false, true), Verdict::not_reproduced);
  // An extension is one whatever it measured: nothing in the thesis to hold it to.
  EXPECT_EQ(judge(ClaimKind::extension, true, false, false), Verdict::extension);
  EXPECT_EQ(judge(ClaimKind::extension, false, true, true), Verdict::extension);
}

TEST(FormatReport, DisclosesDeparturesAndWritesClaimsJson) {
  Claim c;
  c.id = "003-fig-45";
  c.seed = "003";
  c.title = "Fig. 45";
  c.source = "003 §5.2, Fig. 45";
  c.thesis_value = "the rover avoids every obstacle";
  c.seeds = "1-20";
  c.measured_values = {{"avoided_fraction", 0.95}};
  c.departures = {{"row spacing", "4 m (003 §5.2)", "5 m", "follow-the-gap stalls at 4 m", "stalled in 7 of 20"}};
  c.verdict = judge(ClaimKind::thesis_result, true, !c.departures.empty(), false);
  ReportInfo info;
  info.campo_version = "campo 0.2.0 (git abc)";
  const std::string text = format_report({c}, info);
  EXPECT_THAT(text, HasSubstr("1 reproduced with departures"));
  EXPECT_THAT(text, HasSubstr("1 departures from the theses disclosed in 1 claims"));
  EXPECT_THAT(text, HasSubstr("**Judged on.** 003 §5.2, Fig. 45: the rover avoids every obstacle"));
  EXPECT_THAT(text, HasSubstr("| row spacing | 4 m (003 §5.2) | 5 m | follow-the-gap stalls at 4 m | stalled in 7 of 20 |"));
  EXPECT_THAT(text, HasSubstr("**Measured.** Seeds 1-20."));
  const nlohmann::json json = claims_json({c}, info);
  EXPECT_EQ(json["campo_version"], "campo 0.2.0 (git abc)");
  ASSERT_EQ(json["claims"].size(), 1u);
  EXPECT_EQ(json["claims"][0]["id"], "003-fig-45");
  EXPECT_EQ(json["claims"][0]["verdict"], "reproduced with departures");
  EXPECT_EQ(json["claims"][0]["measured"]["avoided_fraction"], 0.95);
  EXPECT_EQ(json["claims"][0]["departures"][0]["with_thesis_setting"], "stalled in 7 of 20");
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
  EXPECT_THAT(text, HasSubstr("**2 claims: 1 reproduced, 0 reproduced with departures, 1 deviate, 0 not reproduced, "
                              "0 extensions; 0 departures from the theses disclosed in 0 claims.**"));
  EXPECT_THAT(text, HasSubstr("| 000 | [Table 5.1 side by side](#000-table-51-side-by-side) |  | reproduced | 0 |"));
  EXPECT_THAT(text, HasSubstr("### 003: Fig. 46, follow-the-gap"));
  EXPECT_THAT(text, HasSubstr("## Seed 003"));
  EXPECT_THAT(text, HasSubstr("![The runs.](reproductions/a.png)\n*The runs.*"));
  EXPECT_THAT(text, HasSubstr("**Verdict: deviates.**"));
  EXPECT_THAT(text, Not(HasSubstr("Quick version")));
}


// A report as format_report writes it, with the parts that change from run to run (timing, commit).
std::string report_text(const std::string& headline, const std::vector<std::string>& rows, const std::string& minutes) {
  std::string text = "# Reproductions of the seed theses\n\nGenerated by `campo reproduce` with campo 0.1.0 (git 0123) in " +
                     minutes + " min.\n\n" + headline + "\n\nVerdicts are judged ...\n\n| Seed | Claim | Verdict |\n| --- | --- | --- |\n";
  for (const std::string& row : rows) text += row + "\n";
  return text + "\n## Seed 000\n\n| Scene | Runs |\n| --- | --- |\n| trees | 10 |\n";
}

TEST(ReportVerdicts, TakesTheHeadlineAndTheVerdictTableOnly) {
  const std::string text = report_text("**2 claims: 1 reproduced, 1 deviate.**", {"| 000 | A | reproduced |", "| 001 | B | deviates |"}, "9.5");
  EXPECT_EQ(report_verdict_lines(text),
            (std::vector<std::string>{"**2 claims: 1 reproduced, 1 deviate.**", "| Seed | Claim | Verdict |",
                                      "| --- | --- | --- |", "| 000 | A | reproduced |", "| 001 | B | deviates |"}));
  EXPECT_TRUE(report_verdict_lines("# A report\n\nno headline\n| a | b |\n").empty());
}

TEST(ReportVerdicts, OnlyAChangedVerdictOrHeadlineIsADifference) {
  const std::string headline = "**2 claims: 1 reproduced, 1 deviate.**";
  const std::string committed = report_text(headline, {"| 000 | A | reproduced |", "| 001 | B | deviates |"}, "9.5");
  // Another duration and other measured tables below: the same verdicts.
  EXPECT_TRUE(verdict_differences(committed, report_text(headline, {"| 000 | A | reproduced |", "| 001 | B | deviates |"}, "12.0")).empty());
  const std::string changed = report_text("**2 claims: 0 reproduced, 1 deviate, 1 not reproduced.**",
                                          {"| 000 | A | not reproduced |", "| 001 | B | deviates |"}, "9.5");
  EXPECT_EQ(verdict_differences(committed, changed),
            (std::vector<std::string>{"- **2 claims: 1 reproduced, 1 deviate.**", "- | 000 | A | reproduced |",
                                      "+ **2 claims: 0 reproduced, 1 deviate, 1 not reproduced.**",
                                      "+ | 000 | A | not reproduced |"}));
  // The claims in another order differ; a committed file without a headline never agrees.
  EXPECT_FALSE(verdict_differences(committed, report_text(headline, {"| 001 | B | deviates |", "| 000 | A | reproduced |"}, "9.5")).empty());
  EXPECT_FALSE(verdict_differences("no report here", "neither here").empty());
}

}  // namespace
}  // namespace campo
