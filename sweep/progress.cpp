#include "sweep/progress.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace campo {

namespace {

std::string counts_and_pace(const SweepProgress& p) {
  char text[160];
  std::snprintf(text, sizeof text, "%zu/%zu done, %zu failed, %zu running", p.done, p.total, p.failed, p.running);
  std::string line = text;
  if (p.done > 0 && p.elapsed_s > 0.0) {
    std::snprintf(text, sizeof text, " | %.1f runs/min", 60.0 * static_cast<double>(p.done) / p.elapsed_s);
    line += text;
  }
  const auto eta = eta_s(p);
  line += " | ETA " + (eta ? format_duration(*eta) : std::string("--"));
  return line;
}

}  // namespace

std::optional<double> eta_s(const SweepProgress& p) {
  if (p.done == 0) return std::nullopt;
  return p.elapsed_s / static_cast<double>(p.done) * static_cast<double>(p.total - p.done);
}

std::string format_duration(double seconds) {
  const long s = std::lround(std::max(seconds, 0.0));
  char text[32];
  if (s >= 3600) {
    std::snprintf(text, sizeof text, "%ldh%02ldm", s / 3600, (s % 3600) / 60);
  } else if (s >= 60) {
    std::snprintf(text, sizeof text, "%ldm%02lds", s / 60, s % 60);
  } else {
    std::snprintf(text, sizeof text, "%lds", s);
  }
  return text;
}

std::string progress_bar(const SweepProgress& p, int bar_width) {
  const double fraction = p.total == 0 ? 1.0 : static_cast<double>(p.done) / static_cast<double>(p.total);
  const int filled = static_cast<int>(std::floor(fraction * bar_width));
  // Appended piece by piece: GCC 12 warns (-Wrestrict, wrongly) on "[" + a temporary string.
  std::string bar = "[";
  bar.append(static_cast<std::size_t>(filled), '#');
  bar.append(static_cast<std::size_t>(bar_width - filled), '.');
  bar += "] ";
  bar += counts_and_pace(p);
  return bar;
}

std::string progress_line(const SweepProgress& p) { return "progress: " + counts_and_pace(p); }

}  // namespace campo
