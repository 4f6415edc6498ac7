#pragma once
/// How far a sweep has come, as one line: a bar for terminals, plain text for logs.
#include <cstddef>
#include <optional>
#include <string>

namespace campo {

struct SweepProgress {
  std::size_t total = 0;    ///< runs to do in this invocation
  std::size_t done = 0;     ///< finished (completed or failed)
  std::size_t failed = 0;   ///< of those, failed
  std::size_t running = 0;
  double elapsed_s = 0.0;   ///< wall clock since the first run started
};

/// Remaining wall time at the pace so far; empty before the first run ends.
std::optional<double> eta_s(const SweepProgress& p);

/// "1h02m", "4m05s", "12s".
std::string format_duration(double seconds);

/// "[#########...........] 37/100 done, 2 failed, 2 running | 12.3 runs/min | ETA 4m05s",
/// the bar `bar_width` characters wide.
std::string progress_bar(const SweepProgress& p, int bar_width = 30);

/// The same without the bar, for logs: "progress: 37/100 done, 2 failed, ...".
std::string progress_line(const SweepProgress& p);

}  // namespace campo
