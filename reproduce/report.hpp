#pragma once
/// The reproduction report (docs/reproductions.md): for every claim of the
/// seed theses, the thesis's words or numbers, what campo measured with the
/// commands that measured it, the figures, and a verdict.
#include <functional>
#include <string>
#include <vector>

namespace campo {

/// How campo's measurement compares with a thesis's claim.
enum class Verdict {
  reproduced,      ///< every target of the claim holds
  deviates,        ///< campo deliberately or measurably differs; the claim says how
  not_reproduced,  ///< a target does not hold
};

/// "reproduced", "deviates", "not reproduced".
const char* verdict_name(Verdict verdict);

/// A figure of a claim: a PNG and what it shows.
struct Figure {
  std::string file;     ///< relative to the report
  std::string caption;  ///< one sentence
};

/// One claim of a thesis and campo's answer to it.
struct Claim {
  std::string seed;                   ///< "000", "001", "003"
  std::string title;                  ///< "Table 5.1 side by side"
  std::string thesis;                 ///< the thesis's words or numbers, Markdown, with its section
  std::vector<std::string> commands;  ///< the commands that produced the measurement, in order
  std::string measured;               ///< campo's result, Markdown
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
  std::string campo_version;  ///< campo_version_string()
  std::string command;        ///< the command that regenerates the report
  bool quick = false;         ///< reduced experiments (the test suite's version)
  double wall_time_s = 0.0;   ///< how long the whole report took
  int jobs = 1;               ///< runs at a time
};

/// The report as Markdown: a summary table of every claim and its verdict,
/// then one section per seed thesis with one subsection per claim.
std::string format_report(const std::vector<Claim>& claims, const ReportInfo& info);

/// A Markdown table: header cells, then rows of cells ('|' in cells escaped).
std::string markdown_table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows);

/// `value` with `decimals` digits after the point ("1.05").
std::string fixed(double value, int decimals);

}  // namespace campo
