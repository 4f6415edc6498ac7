#pragma once
/// What every seed's claims measure with: a sweep run for a claim (its command
/// recorded on the claim), and fractions with their 95 % intervals, in the
/// report's words and in claims.json.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "reproduce/report.hpp"
#include "reproduce/workbench.hpp"
#include "sweep/results.hpp"

namespace campo {

/// What a sweep of the report gave: where it wrote and its runs.
struct SweepRuns {
  std::filesystem::path dir;
  ResultsFile results;
  /// The runs of `planner` (all runs when empty), in the file's order.
  std::vector<const RunResult*> of(const std::string& planner) const;
};

/// Runs the sweep `spec_file` (reduced by `reduce` in a quick report, see
/// Workbench::spec) into work/`name`, keeping its runs, and records the
/// command on `claim`.
SweepRuns run_sweep(const Workbench& bench, Claim& claim, const std::string& spec_file, const std::string& name,
                    const std::function<void(nlohmann::json&)>& reduce);

/// "17/20 (85 %, 95 % interval 64-95 %)" (Wilson score interval); "no runs" when n is 0.
std::string rate_text(int k, int n);

/// {"k": 17, "n": 20, "wilson95": [0.64, 0.95]}.
nlohmann::json rate_json(int k, int n);

}  // namespace campo
