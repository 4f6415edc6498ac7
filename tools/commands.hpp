#pragma once
/// The `campo` subcommands. Each registers its options on the app and returns
/// the function that runs it; the function returns the process exit code.
#include <algorithm>
#include <functional>
#include <ostream>
#include <string>

#include <CLI/CLI.hpp>

#include "campo/json_reader.hpp"
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

/// Prints bad input as campo reports it: each error on a line of its own,
/// "error: " before it (the last line may be "error: ... and N more errors").
inline void print_input_error(std::ostream& out, const InputError& e) {
  const std::string text = e.what();
  for (std::size_t start = 0; start <= text.size();) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    out << "error: " << text.substr(start, end - start) << "\n";
    start = end + 1;
  }
}

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
