#pragma once
/// The `campo` subcommands. Each registers its options on the app and returns
/// the function that runs it; the function returns the process exit code.
#include <functional>

#include <CLI/CLI.hpp>

#include "tools/path_options.hpp"

namespace campo::cli {

/// Exit codes shared by every subcommand.
enum ExitCode : int {
  kOk = 0,            ///< the work completed (whatever a run's outcome)
  kInternalError = 1, ///< a bug or an I/O failure
  kBadInput = 2,      ///< invalid input; nothing was written
  kRegressed = 3,     ///< campo bench --compare: a figure is slower than its baseline
  kIncomplete = 4,    ///< campo plan --scen: --time-limit stopped it before every problem was tried
};

using Command = std::function<int()>;

Command add_validate(CLI::App& app);
Command add_run(CLI::App& app);
Command add_render(CLI::App& app);
Command add_scan(CLI::App& app);
Command add_bench(CLI::App& app);
Command add_sweep(CLI::App& app);
Command add_table(CLI::App& app);
Command add_plot(CLI::App& app);
Command add_merge(CLI::App& app);
Command add_plan(CLI::App& app);
Command add_reproduce(CLI::App& app);

}  // namespace campo::cli
