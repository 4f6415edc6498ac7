#include "reproduce/evidence.hpp"

#include <algorithm>

#include "sweep/statistics.hpp"

namespace campo {

std::vector<const RunResult*> SweepRuns::of(const std::string& planner) const {
  std::vector<const RunResult*> out;
  for (const RunResult& r : results.runs) {
    if (planner.empty() || r.planner == planner) out.push_back(&r);
  }
  return out;
}

SweepRuns run_sweep(const Workbench& bench, Claim& claim, const std::string& spec_file, const std::string& name,
                    const std::function<void(nlohmann::json&)>& reduce) {
  const std::filesystem::path spec = bench.spec(spec_file, reduce);
  SweepRuns out;
  out.dir = bench.work(name);
  claim.commands.push_back(bench.campo({"sweep", spec.string(), "--out", out.dir.string(), "--keep-runs", "--jobs",
                                        std::to_string(bench.jobs())}));
  out.results = read_results(out.dir / "results.jsonl");
  return out;
}

std::string rate_text(int k, int n) {
  if (n <= 0) return "no runs";
  const Interval ci = wilson_interval(k, n);
  return std::to_string(k) + "/" + std::to_string(n) + " (" + fixed(100.0 * k / n, 0) + " %, 95 % interval " +
         fixed(100.0 * ci.low, 0) + "-" + fixed(100.0 * ci.high, 0) + " %)";
}

nlohmann::json rate_json(int k, int n) {
  const Interval ci = wilson_interval(k, std::max(n, 1));
  return {{"k", k}, {"n", n}, {"wilson95", {ci.low, ci.high}}};
}

}  // namespace campo
