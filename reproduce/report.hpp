#pragma once
/// The reproduction report (docs/reproductions.md): for every claim of the
/// seed theses, the thesis's words or numbers, what campo measured with the
/// commands that measured it, the figures, and a verdict.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace campo {

/// How campo's measurement compares with a thesis's claim, judged on the
/// thesis's own criterion (a tolerance of campo's own never changes it).
enum class Verdict {
  reproduced,                  ///< the thesis's criterion holds with the thesis's setup
  reproduced_with_departures,  ///< it holds, but only with the listed departures from the thesis
  deviates,                    ///< it does not hold; the claim gives the cause with evidence
  not_reproduced,              ///< it does not hold, cause unknown (or nothing was measured)
  extension,                   ///< campo's own experiment where the thesis reports no result
};

/// "reproduced", "reproduced with departures", "deviates", "not reproduced", "extension".
const char* verdict_name(Verdict verdict);

/// What a claim is, for its verdict: a result of the thesis judged on its
/// criterion, or campo's own experiment (an input checked against the thesis's
/// tables, or a study the thesis proposes without results).
enum class ClaimKind { thesis_result, extension };

/// The verdict from what was measured, the one rule every claim goes through:
/// an extension is one whatever it measured; otherwise the thesis's criterion
/// holding gives reproduced (or with departures, when any setting differs from
/// the thesis's), and failing gives deviates when the cause is shown with
/// evidence, else not reproduced. `criterion_holds` is empty when nothing
/// could be measured (not reproduced).
Verdict judge(ClaimKind kind, std::optional<bool> criterion_holds, bool has_departures, bool cause_known);

/// A setting in which campo's experiment differs from the thesis's, disclosed
/// where the claim is, with the thesis's own setting run beside it.
struct Departure {
  std::string setting;              ///< what differs: "row spacing"
  std::string thesis;               ///< the thesis's setting, with its source: "4 m (003 §5.2)"
  std::string campo;                ///< campo's setting: "5 m"
  std::string why;                  ///< why campo departs
  std::string with_thesis_setting;  ///< the same experiment with the thesis's setting: what it gave, measured
};

/// A figure of a claim: a PNG and what it shows.
struct Figure {
  std::string file;     ///< relative to the report
  std::string caption;  ///< one sentence
};

/// One claim of a thesis and campo's answer to it.
struct Claim {
  std::string id;                     ///< stable, for claims.json: "000-table-5-1"
  std::string seed;                   ///< "000", "001", "003"
  std::string title;                  ///< "Table 5.1 side by side"
  std::string source;                 ///< where in the thesis: "000 §5.5, Tabella 5.1"
  std::string thesis_value;           ///< the sentence or number judged on: "never exceeds 1.10"
  std::string thesis;                 ///< the thesis's words or numbers in full, Markdown, with its section
  std::vector<std::string> commands;  ///< the commands that produced the measurement, in order
  std::string seeds;                  ///< the seeds measured: "1-10", "0"
  std::string measured;               ///< campo's result, Markdown
  nlohmann::json measured_values = nlohmann::json::object();  ///< the numbers the verdict is judged on
  std::vector<Departure> departures;  ///< every setting that differs from the thesis's
  std::vector<Figure> figures;
  Verdict verdict = Verdict::not_reproduced;
  std::string verdict_reason;         ///< why this verdict, in one or two sentences
};

/// A claim of `seed` titled `title`, filled in by `measure`. When `measure`
/// throws (a command failed), the claim keeps what it had (the thesis's
/// words) and is not reproduced, the reason saying why, and the report goes on.
Claim measure_claim(const std::string& seed, const std::string& title, const std::function<void(Claim&)>& measure);

/// Whether all the targets of a claim hold, and which failed: the verdict's evidence.
struct TargetCheck {
  std::vector<std::string> held;
  std::vector<std::string> failed;
  /// Records `description` as held or failed.
  void expect(bool holds, const std::string& description);
  Verdict verdict() const { return failed.empty() ? Verdict::reproduced : Verdict::not_reproduced; }
  /// "All targets hold: A; B." or "Not met: C. Met: A; B."
  std::string summary() const;
};

/// Where and how the report was produced.
struct ReportInfo {
  std::string campo_version;  ///< campo_version_string(), which names the commit the code was built from
  std::string command;        ///< the command that regenerates the report
  bool quick = false;         ///< reduced experiments (the test suite's version)
  double wall_time_s = 0.0;   ///< how long the whole report took
  int jobs = 1;               ///< runs at a time
};

/// The report as Markdown: a summary table of every claim and its verdict,
/// then one section per seed thesis with one subsection per claim.
std::string format_report(const std::vector<Claim>& claims, const ReportInfo& info);

/// claims.json: per claim its id, seed, title, thesis source and value, seeds,
/// measured values, verdict (with its reason) and departures; with `info`.
nlohmann::json claims_json(const std::vector<Claim>& claims, const ReportInfo& info);

/// The headline of the report: "**N claims: ...**", every verdict counted, and the departures.
std::string report_headline(const std::vector<Claim>& claims);

/// What a report concludes, taken from its Markdown: the headline and the
/// table of claims and verdicts, line by line, without the run's timing or
/// provenance. Empty when `report_markdown` has no headline.
std::vector<std::string> report_verdict_lines(const std::string& report_markdown);

/// The lines of `regenerated`'s verdicts that differ from `committed`'s
/// (report_verdict_lines), each prefixed "- " (only in the committed report)
/// or "+ " (only in the regenerated one); empty when the verdicts agree.
std::vector<std::string> verdict_differences(const std::string& committed, const std::string& regenerated);

/// A Markdown table: header cells, then rows of cells ('|' in cells escaped).
std::string markdown_table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows);

/// `value` with `decimals` digits after the point ("1.05").
std::string fixed(double value, int decimals);

}  // namespace campo
