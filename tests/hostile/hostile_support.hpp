#pragma once
// The limits every hostile input runs under and the way the hostile tests run
// `campo` with them (hostile_test.cpp, mesh_hostile_test.cpp).
#include <cstdlib>
#include <filesystem>
#include <string>

#include <sys/wait.h>

#include "tests/cli_support.hpp"
#include "tests/sanitizers.hpp"

namespace campo::hostile {

#if defined(CAMPO_TEST_UNDER_ASAN)
// AddressSanitizer reserves terabytes of address space (no RLIMIT_AS) and runs
// a few times slower; its own RSS limit stands in for the memory limit.
inline constexpr int kSecondsPerCommand = 40;
inline const std::string kLimits = "ASAN_OPTIONS=detect_leaks=0:hard_rss_limit_mb=3072 ";
#else
inline constexpr int kSecondsPerCommand = 10;
inline const std::string kLimits = "ulimit -v 1048576; ";  // 1 GiB of address space
#endif

struct Outcome {
  int exit_code;  ///< 124/137: killed at the time limit; 128+N: signal N
  std::string err;
};

inline std::string quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

/// Runs `campo ARGS` in `dir` with the limits; stdout is discarded.
inline Outcome run_campo(const std::string& args, const std::filesystem::path& dir) {
  const std::filesystem::path err = dir / "stderr.txt";
  const std::string command = "cd " + quoted(dir.string()) + " && (" + kLimits + "exec timeout -s KILL " +
                              std::to_string(kSecondsPerCommand) + " " + CAMPO_BINARY + " " + args +
                              ") >/dev/null 2>" + quoted(err.string());
  const int status = std::system(command.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status), testing::slurp(err)};
}

}  // namespace campo::hostile
