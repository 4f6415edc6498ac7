#include "reproduce/report.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <exception>
#include <map>
#include <sstream>

namespace campo {

const char* verdict_name(Verdict verdict) {
  switch (verdict) {
    case Verdict::reproduced: return "reproduced";
    case Verdict::reproduced_with_departures: return "reproduced with departures";
    case Verdict::deviates: return "deviates";
    case Verdict::not_reproduced: return "not reproduced";
    case Verdict::extension: return "extension";
  }
  return "?";
}

Verdict judge(ClaimKind kind, std::optional<bool> criterion_holds, bool has_departures, bool cause_known) {
  if (kind == ClaimKind::extension) return Verdict::extension;
  if (!criterion_holds) return Verdict::not_reproduced;
  if (*criterion_holds) return has_departures ? Verdict::reproduced_with_departures : Verdict::reproduced;
  return cause_known ? Verdict::deviates : Verdict::not_reproduced;
}

void TargetCheck::expect(bool holds, const std::string& description) {
  (holds ? held : failed).push_back(description);
}

namespace {

std::string joined(const std::vector<std::string>& parts, const std::string& separator) {
  std::string out;
  for (std::size_t i = 0; i < parts.size(); ++i) out += (i ? separator : "") + parts[i];
  return out;
}

std::string escape_cell(const std::string& cell) {
  std::string out;
  for (char c : cell) {
    if (c == '|') out += "\\|";
    else if (c == '\n') out += ' ';
    else out += c;
  }
  return out;
}

const char* seed_title(const std::string& seed) {
  if (seed == "000") return "Seed 000: reactive depth-map navigation of a quadrotor";
  if (seed == "001") return "Seed 001: LIDAR mapping and D* Lite on a quadrotor";
  if (seed == "003") return "Seed 003: a skid-steer rover in a vineyard";
  return "Other claims";
}

// GitHub-style heading anchors: lower case, spaces to '-', punctuation dropped.
std::string anchor(const std::string& heading) {
  std::string out;
  for (unsigned char c : heading) {
    if (std::isalnum(c)) out += static_cast<char>(std::tolower(c));
    else if (c == ' ' || c == '-') out += '-';
    else if (c == '_') out += '_';
  }
  return out;
}

std::string claim_heading(const Claim& claim) { return claim.seed + ": " + claim.title; }

}  // namespace

std::string TargetCheck::summary() const {
  // Long lists of held targets would bury the failed ones: named up to four, else counted.
  const std::size_t total = held.size() + failed.size();
  const std::string held_text = held.size() <= 4 ? joined(held, "; ") : std::to_string(held.size()) + " others";
  if (failed.empty()) return "All " + std::to_string(total) + " targets hold" + (held.size() <= 4 ? ": " + held_text : "") + ".";
  std::string out = "Not met (" + std::to_string(failed.size()) + " of " + std::to_string(total) + "): " +
                    joined(failed, "; ") + ".";
  if (!held.empty()) out += " Met: " + held_text + ".";
  return out;
}

Claim measure_claim(const std::string& seed, const std::string& title, const std::function<void(Claim&)>& measure) {
  Claim claim;
  claim.seed = seed;
  claim.title = title;
  try {
    measure(claim);
  } catch (const std::exception& e) {
    claim.measured = "The experiment did not complete: " + std::string(e.what()) + ".";
    claim.figures.clear();
    claim.verdict = Verdict::not_reproduced;
    claim.verdict_reason = "Nothing was measured.";
  }
  return claim;
}

std::string fixed(double value, int decimals) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
  return buffer;
}

std::string markdown_table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows) {
  std::ostringstream out;
  out << "|";
  for (const std::string& h : header) out << " " << escape_cell(h) << " |";
  out << "\n|";
  for (std::size_t i = 0; i < header.size(); ++i) out << " --- |";
  out << "\n";
  for (const auto& row : rows) {
    out << "|";
    for (std::size_t i = 0; i < header.size(); ++i) out << " " << (i < row.size() ? escape_cell(row[i]) : "") << " |";
    out << "\n";
  }
  return out.str();
}

std::vector<std::string> report_verdict_lines(const std::string& report_markdown) {
  std::vector<std::string> lines;
  std::istringstream in(report_markdown);
  std::string line;
  bool headline_seen = false;
  while (std::getline(in, line)) {
    if (!headline_seen) {
      // The headline is the first bold line counting the claims ("**15 claims: ...**").
      headline_seen = line.rfind("**", 0) == 0 && line.find(" claims: ") != std::string::npos;
      if (headline_seen) lines.push_back(line);
      continue;
    }
    if (line.rfind("|", 0) == 0) {
      lines.push_back(line);
    } else if (lines.size() > 1) {
      break;  // the end of the verdict table
    }
  }
  return lines;
}

std::vector<std::string> verdict_differences(const std::string& committed, const std::string& regenerated) {
  const std::vector<std::string> before = report_verdict_lines(committed);
  const std::vector<std::string> after = report_verdict_lines(regenerated);
  std::vector<std::string> out;
  for (const std::string& line : before) {
    if (std::find(after.begin(), after.end(), line) == after.end()) out.push_back("- " + line);
  }
  for (const std::string& line : after) {
    if (std::find(before.begin(), before.end(), line) == before.end()) out.push_back("+ " + line);
  }
  // The same lines in another order (claims reordered) differ too.
  if (out.empty() && before != after) {
    for (const std::string& line : before) out.push_back("- " + line);
    for (const std::string& line : after) out.push_back("+ " + line);
  }
  if (before.empty() && out.empty()) out.push_back("- (no headline in the committed report)");
  return out;
}

std::string report_headline(const std::vector<Claim>& claims) {
  std::map<Verdict, int> counts;
  std::size_t departures = 0, with_departures = 0;
  for (const Claim& c : claims) {
    ++counts[c.verdict];
    departures += c.departures.size();
    with_departures += !c.departures.empty();
  }
  return "**" + std::to_string(claims.size()) + " claims: " + std::to_string(counts[Verdict::reproduced]) +
         " reproduced, " + std::to_string(counts[Verdict::reproduced_with_departures]) +
         " reproduced with departures, " + std::to_string(counts[Verdict::deviates]) + " deviate, " +
         std::to_string(counts[Verdict::not_reproduced]) + " not reproduced, " +
         std::to_string(counts[Verdict::extension]) + " extensions; " + std::to_string(departures) +
         " departures from the theses disclosed in " + std::to_string(with_departures) + " claims.**";
}

nlohmann::json claims_json(const std::vector<Claim>& claims, const ReportInfo& info) {
  nlohmann::json out = {{"campo_version", info.campo_version}, {"command", info.command}, {"quick", info.quick},
                        {"claims", nlohmann::json::array()}};
  for (const Claim& c : claims) {
    nlohmann::json departures = nlohmann::json::array();
    for (const Departure& d : c.departures) {
      departures.push_back({{"setting", d.setting}, {"thesis", d.thesis}, {"campo", d.campo}, {"why", d.why},
                            {"with_thesis_setting", d.with_thesis_setting}});
    }
    out["claims"].push_back({{"id", c.id},
                             {"seed", c.seed},
                             {"title", c.title},
                             {"source", c.source},
                             {"thesis_value", c.thesis_value},
                             {"seeds", c.seeds},
                             {"measured", c.measured_values},
                             {"verdict", verdict_name(c.verdict)},
                             {"verdict_reason", c.verdict_reason},
                             {"departures", departures}});
  }
  return out;
}

std::string format_report(const std::vector<Claim>& claims, const ReportInfo& info) {
  std::ostringstream out;
  out << "# Reproductions of the seed theses\n\n"
      << "Generated by `" << info.command << "` with " << info.campo_version << " in "
      << fixed(info.wall_time_s / 60.0, 1) << " min (" << info.jobs << " runs at a time). "
      << "Every number below was measured by the commands listed under it; every figure was drawn by the same "
      << "command. Do not edit this file by hand: change campo and regenerate it.\n\n";
  if (info.quick) {
    out << "**Quick version**: reduced experiments (fewer seeds, resolutions and runs) for the test suite; "
        << "its numbers are not the reproduction.\n\n";
  }
  out << report_headline(claims) << "\n\n"
      << "Verdicts are judged on each thesis's own criterion, quoted with its source: *reproduced* (it holds with "
      << "the thesis's setup), *reproduced with departures* (it holds only with the departures listed under the "
      << "claim, each run with the thesis's own setting beside it), *deviates* (it does not hold; the cause is "
      << "given with evidence), *not reproduced* (it does not hold, cause unknown), *extension* (campo's own "
      << "experiment where the thesis reports no result).\n\n";
  std::vector<std::vector<std::string>> summary;
  for (const Claim& c : claims) {
    summary.push_back({c.seed, "[" + c.title + "](#" + anchor(claim_heading(c)) + ")", c.source,
                       verdict_name(c.verdict), std::to_string(c.departures.size())});
  }
  out << markdown_table({"Seed", "Claim", "Judged on", "Verdict", "Departures"}, summary) << "\n";

  std::string seed;
  for (const Claim& c : claims) {
    if (c.seed != seed) {
      seed = c.seed;
      out << "## " << seed_title(seed) << "\n\n";
    }
    out << "### " << claim_heading(c) << "\n\n";
    if (!c.source.empty()) {
      out << "**Judged on.** " << c.source << (c.thesis_value.empty() ? "" : ": " + c.thesis_value) << "\n\n";
    }
    out << "**The thesis.** " << c.thesis << "\n\n";
    if (!c.departures.empty()) {
      std::vector<std::vector<std::string>> rows;
      for (const Departure& d : c.departures) rows.push_back({d.setting, d.thesis, d.campo, d.why, d.with_thesis_setting});
      out << "**Departures from the thesis.**\n\n"
          << markdown_table({"Setting", "Thesis", "campo", "Why", "With the thesis's setting"}, rows) << "\n";
    }
    if (!c.commands.empty()) {
      out << "**Commands.**\n\n```\n";
      for (const std::string& command : c.commands) out << command << "\n";
      out << "```\n\n";
    }
    out << "**Measured.** " << (c.seeds.empty() ? "" : "Seeds " + c.seeds + ". ") << c.measured << "\n\n";
    for (const Figure& figure : c.figures) {
      out << "![" << figure.caption << "](" << figure.file << ")\n*" << figure.caption << "*\n\n";
    }
    out << "**Verdict: " << verdict_name(c.verdict) << ".** " << c.verdict_reason << "\n\n";
  }
  return out.str();
}

}  // namespace campo
