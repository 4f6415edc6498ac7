#pragma once
/// Runs jobs each in its own forked process, a few at a time, so that a job
/// that crashes, hangs or throws cannot take the others (or the caller) down.
/// POSIX only (fork, pipes, poll).
#include <cstddef>
#include <functional>
#include <string>

namespace campo {

struct ProcessPoolConfig {
  int jobs = 1;                 ///< processes at a time, >= 1
  double time_limit_s = 3600.0; ///< wall clock per job; a job still running then is killed
  double tick_s = 0.25;         ///< how often `on_tick` is called while jobs run
};

/// How one job ended.
struct JobOutcome {
  bool ok = false;           ///< the job returned normally; `output` is what it returned
  std::string output;
  std::string reason;        ///< when not ok: "killed by signal 11 (Segmentation fault)", "exceeded ...", "threw: ..."
  std::string stderr_tail;   ///< the last lines the job wrote to stdout or stderr (at most 2 KB)
  double wall_time_s = 0.0;  ///< from fork to exit, measured by the caller
  double work_time_s = 0.0;  ///< inside the job (0 when it did not return): wall_time_s - work_time_s is the pool's cost
};

/// Runs work(i) for every i in [0, count), each in a child process forked
/// from this one (so the job sees this process's memory as it was, and
/// nothing it does comes back except its returned string). At most
/// `config.jobs` run at once, started in index order; `on_done(i, outcome)`
/// is called in this process as each ends, in the order they end. Must be
/// called from a single-threaded process. Children die with this process.
void run_isolated(std::size_t count, const std::function<std::string(std::size_t)>& work,
                  const std::function<void(std::size_t, const JobOutcome&)>& on_done,
                  const ProcessPoolConfig& config, const std::function<void()>& on_tick = {});

}  // namespace campo
