// campo reproduce: the reproduction report of the seed theses (docs/reproductions.md).
#include <chrono>
#include <filesystem>
#include <iostream>
#include <thread>

#include <unistd.h>

#include "campo/json_reader.hpp"
#include "core/output_dir.hpp"
#include "reproduce/claims.hpp"
#include "reproduce/report.hpp"
#include "reproduce/workbench.hpp"
#include "run/provenance.hpp"
#include "tools/commands.hpp"

namespace campo::cli {

namespace {

namespace fs = std::filesystem;

struct ReproduceOptions {
  std::string report = "docs/reproductions.md";
  std::string work = "out/reproduce";
  bool quick = false;
  int jobs = 0;  ///< 0: every core
  std::string check_against;  ///< a committed report whose verdicts the new one must repeat
};

fs::path this_executable() {
  std::error_code error;
  const fs::path self = fs::read_symlink("/proc/self/exe", error);
  if (error) throw std::runtime_error("cannot find the campo executable (/proc/self/exe)");
  return self;
}

int reproduce(const ReproduceOptions& o) {
  // The experiments name the bundled scenes by their paths in the source tree.
  if (!fs::exists("scenes/sweeps/resolution_000.json")) {
    throw InputError("command line", "", "campo reproduce runs from campo's source directory (where scenes/ is); "
                     "scenes/sweeps/resolution_000.json is not here");
  }
  const fs::path report = o.report;
  check_output_file(report, "--report");
  // Read before anything is written: --check-against may be the report being regenerated.
  const std::string committed = o.check_against.empty() ? std::string() : read_text_file(o.check_against);
  const fs::path claims_file = report.parent_path() / "claims.json";
  check_output_file(claims_file, "--report (claims.json beside it)");
  check_output_directory(o.work, "--work");
  check_output_directory(report.parent_path() / report.stem(), "--report (its figures' folder)");
  const auto start = std::chrono::steady_clock::now();
  WorkbenchConfig config;
  config.campo_binary = this_executable();
  config.work_dir = o.work;
  config.figure_dir = report.parent_path() / report.stem();
  config.figure_prefix = report.stem().string() + "/";
  config.quick = o.quick;
  config.jobs = o.jobs > 0 ? o.jobs : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const Workbench bench(config);

  std::vector<Claim> claims;
  for (auto* seed_claims : {&seed_000_claims, &seed_001_claims, &seed_003_claims}) {
    for (Claim& claim : seed_claims(bench)) {
      std::cerr << "campo reproduce: " << claim.seed << " " << claim.title << ": " << verdict_name(claim.verdict)
                << "\n";
      claims.push_back(std::move(claim));
    }
  }
  ReportInfo info;
  info.campo_version = campo_version_string();
  info.command = std::string("campo reproduce") + (o.quick ? " --quick" : "") +
                 (o.report != ReproduceOptions{}.report ? " --report " + o.report : "");
  info.quick = o.quick;
  info.jobs = config.jobs;
  info.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  write_file_atomically(claims_file, claims_json(claims, info).dump(2) + "\n");
  const std::string markdown = format_report(claims, info);
  write_file_atomically(report, markdown);
  std::cout << "campo reproduce: " << report_headline(claims) << "\nreport in " << report.string() << ", "
            << claims_file.string() << ", figures in " << config.figure_dir.string() << "\n";
  if (o.check_against.empty()) return kOk;
  const std::vector<std::string> differences = verdict_differences(committed, markdown);
  if (differences.empty()) {
    std::cout << "campo reproduce: the headline and every verdict are those of " << o.check_against << "\n";
    return kOk;
  }
  std::cerr << "campo reproduce: the headline or verdicts differ from " << o.check_against
            << " (- there, + now):\n";
  for (const std::string& line : differences) std::cerr << line << "\n";
  return kInternalError;
}

}  // namespace

Command add_reproduce(CLI::App& app) {
  auto o = std::make_shared<ReproduceOptions>();
  app.add_option("--report", o->report, "Where to write the report (default: docs/reproductions.md; the figures go "
                                        "to a directory of the same name beside it)");
  app.add_option("--work", o->work, "Directory for the sweeps and runs (default: out/reproduce; emptied first)");
  app.add_flag("--quick", o->quick,
               "Reduced experiments (fewer seeds, resolutions and runs): the test suite's version, seconds instead "
               "of minutes; its numbers are not the reproduction");
  app.add_option("--jobs,-j", o->jobs, "Runs at a time in the sweeps (default: every available core)")
      ->check(CLI::Range(1, 1024));
  app.add_option("--check-against", o->check_against,
                 "A committed report (docs/reproductions.md): after writing the new report, exit 1 listing the "
                 "lines of the headline and the verdict table that differ from it")
      ->check(existing_file());
  app.footer(
      "Runs every experiment of the seed theses that campo reproduces (the bundled scenes and sweep specs), from "
      "campo's source directory, each as the campo command the report lists, and writes the report: for every "
      "claim the thesis's words or numbers with their source, the settings in which campo departs from the "
      "thesis (each run with the thesis's own setting beside it), campo's measurement, its commands, figures and "
      "a verdict judged on the thesis's own criterion (reproduced, reproduced with departures, deviates, not "
      "reproduced, extension); and claims.json beside the report (per claim its id, seeds, thesis source and "
      "value, measured values, verdict and departures). A claim whose experiment fails is reported as not "
      "reproduced with the reason; the other claims still are.\n"
      "Examples: campo reproduce\n"
      "          campo reproduce --quick --report out/quick/reproductions.md --work out/quick/work\n"
      "          campo reproduce --report out/check/reproductions.md --check-against docs/reproductions.md");
  return [o] { return reproduce(*o); };
}

}  // namespace campo::cli
