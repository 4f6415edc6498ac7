#include "sweep/process_pool.hpp"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <stdexcept>
#include <vector>

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

namespace campo {

namespace {

using Clock = std::chrono::steady_clock;

constexpr std::size_t kTailBytes = 2048;
// First byte of a child's result pipe: what the job did.
constexpr char kReturned = 'R';
constexpr char kThrew = 'E';

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

void write_all(int fd, const char* data, std::size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;  // the parent is gone: nothing left to tell
    data += n;
    size -= static_cast<std::size_t>(n);
  }
}

// The child's side: run the job, send what happened, never return.
[[noreturn]] void run_child(std::size_t index, const std::function<std::string(std::size_t)>& work, pid_t parent,
                            int result_fd, int log_fd) {
  // A child outliving a killed sweep would go on writing files nobody reads.
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != parent) ::_exit(1);
  ::dup2(log_fd, STDOUT_FILENO);
  ::dup2(log_fd, STDERR_FILENO);
  ::close(log_fd);
  const Clock::time_point start = Clock::now();
  std::string message(1, kReturned);
  try {
    const std::string output = work(index);
    const double work_s = seconds_since(start);
    message.append(reinterpret_cast<const char*>(&work_s), sizeof work_s);
    message += output;
  } catch (const std::exception& e) {
    message = std::string(1, kThrew) + e.what();
  } catch (...) {
    message = std::string(1, kThrew) + "an exception that is not a std::exception";
  }
  write_all(result_fd, message.data(), message.size());
  // Closed before exiting, so the parent has the result at once: the kernel's
  // teardown of this process (milliseconds for one that rendered with OSMesa)
  // then overlaps the next run instead of delaying it.
  ::close(result_fd);
  ::close(STDOUT_FILENO);
  ::close(STDERR_FILENO);
  // No destructors, no atexit handlers, no flushing of the parent's buffered output.
  ::_exit(0);
}

struct Child {
  std::size_t index = 0;
  pid_t pid = -1;
  int result_fd = -1;
  int log_fd = -1;
  std::string result;
  std::string log;
  Clock::time_point start;
  bool killed = false;  // for exceeding the time limit
};

// Reads what is available; false at end of file (the fd is then closed).
bool drain(int& fd, std::string& into, std::size_t keep_tail) {
  char buffer[65536];
  const ssize_t n = ::read(fd, buffer, sizeof buffer);
  if (n < 0 && (errno == EINTR || errno == EAGAIN)) return true;
  if (n <= 0) {
    ::close(fd);
    fd = -1;
    return false;
  }
  into.append(buffer, static_cast<std::size_t>(n));
  if (keep_tail > 0 && into.size() > 2 * keep_tail) into.erase(0, into.size() - keep_tail);
  return true;
}

std::string tail_lines(const std::string& log) {
  std::string tail = log.size() > kTailBytes ? log.substr(log.size() - kTailBytes) : log;
  if (log.size() > kTailBytes) {
    if (const auto newline = tail.find('\n'); newline != std::string::npos) tail.erase(0, newline + 1);
  }
  while (!tail.empty() && (tail.back() == '\n' || tail.back() == '\r')) tail.pop_back();
  return tail;
}

std::string format_seconds(double s) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", s);
  return text;
}

JobOutcome outcome_of(const Child& child, int status, const ProcessPoolConfig& config) {
  JobOutcome outcome;
  outcome.wall_time_s = seconds_since(child.start);
  outcome.stderr_tail = tail_lines(child.log);
  if (child.killed) {
    outcome.reason = "exceeded the time limit of " + format_seconds(config.time_limit_s) + " s and was killed";
  } else if (WIFSIGNALED(status)) {
    const int signal = WTERMSIG(status);
    outcome.reason = "killed by signal " + std::to_string(signal) + " (" + ::strsignal(signal) + ")";
  } else if (WIFEXITED(status) && WEXITSTATUS(status) != 0) {
    outcome.reason = "exited with code " + std::to_string(WEXITSTATUS(status)) + " without a result";
  } else if (child.result.empty()) {
    outcome.reason = "ended without a result";
  } else if (child.result.front() == kThrew) {
    outcome.reason = "threw: " + child.result.substr(1);
  } else if (child.result.size() < 1 + sizeof(double)) {
    outcome.reason = "sent a truncated result";
  } else {
    outcome.ok = true;
    std::memcpy(&outcome.work_time_s, child.result.data() + 1, sizeof(double));
    outcome.output = child.result.substr(1 + sizeof(double));
  }
  return outcome;
}

// Whether the child sent a complete result of a job that returned (it then exits with 0).
bool returned_result(const Child& child) {
  return !child.killed && child.result.size() >= 1 + sizeof(double) && child.result.front() == kReturned;
}

// Reaps the children in `exiting` that have exited (all of them, waiting, when `wait`).
void reap_exited(std::vector<pid_t>& exiting, bool wait) {
  std::erase_if(exiting, [wait](pid_t pid) {
    pid_t reaped;
    while ((reaped = ::waitpid(pid, nullptr, wait ? 0 : WNOHANG)) < 0 && errno == EINTR) {
    }
    return reaped != 0;
  });
}

// Kills and reaps every child: the caller is leaving (an exception in on_done).
void kill_all(std::vector<Child>& running) {
  for (Child& c : running) {
    ::kill(c.pid, SIGKILL);
    ::waitpid(c.pid, nullptr, 0);
    for (int* fd : {&c.result_fd, &c.log_fd}) {
      if (*fd >= 0) ::close(*fd);
    }
  }
  running.clear();
}

Child spawn(std::size_t index, const std::function<std::string(std::size_t)>& work) {
  int result_pipe[2];
  int log_pipe[2];
  if (::pipe2(result_pipe, O_CLOEXEC) != 0) throw std::runtime_error(std::string("pipe: ") + std::strerror(errno));
  if (::pipe2(log_pipe, O_CLOEXEC) != 0) {
    ::close(result_pipe[0]);
    ::close(result_pipe[1]);
    throw std::runtime_error(std::string("pipe: ") + std::strerror(errno));
  }
  // Whatever this process has buffered must not be written twice.
  std::cout.flush();
  std::cerr.flush();
  std::fflush(nullptr);
  const pid_t parent = ::getpid();
  // The clock starts before the fork: the child may run (and start timing its job) before this process
  // returns from fork(), so a start taken after it could make wall_time_s shorter than work_time_s.
  const Clock::time_point start = Clock::now();
  const pid_t pid = ::fork();
  if (pid < 0) {
    for (int fd : {result_pipe[0], result_pipe[1], log_pipe[0], log_pipe[1]}) ::close(fd);
    throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
  }
  if (pid == 0) {
    ::close(result_pipe[0]);
    ::close(log_pipe[0]);
    run_child(index, work, parent, result_pipe[1], log_pipe[1]);
  }
  ::close(result_pipe[1]);
  ::close(log_pipe[1]);
  Child child;
  child.index = index;
  child.pid = pid;
  child.result_fd = result_pipe[0];
  child.log_fd = log_pipe[0];
  child.start = start;
  return child;
}

}  // namespace

void run_isolated(std::size_t count, const std::function<std::string(std::size_t)>& work,
                  const std::function<void(std::size_t, const JobOutcome&)>& on_done,
                  const ProcessPoolConfig& config, const std::function<void()>& on_tick) {
  if (config.jobs < 1) throw std::invalid_argument("run_isolated: jobs must be >= 1");
  std::vector<Child> running;
  std::vector<pid_t> exiting;  // returned their result, not yet reaped
  std::size_t next = 0;
  Clock::time_point last_tick = Clock::now();
  try {
    while (next < count || !running.empty()) {
      while (running.size() < static_cast<std::size_t>(config.jobs) && next < count) {
        running.push_back(spawn(next++, work));
      }
      // Wait for output, an exit, the nearest deadline or the next tick.
      std::vector<pollfd> fds;
      double wait_s = config.tick_s;
      for (const Child& c : running) {
        for (int fd : {c.result_fd, c.log_fd}) {
          if (fd >= 0) fds.push_back({fd, POLLIN, 0});
        }
        if (!c.killed) wait_s = std::min(wait_s, config.time_limit_s - seconds_since(c.start));
      }
      const int timeout_ms = static_cast<int>(std::clamp(std::ceil(wait_s * 1000.0), 0.0, 60000.0));
      if (::poll(fds.data(), fds.size(), timeout_ms) < 0 && errno != EINTR) {
        throw std::runtime_error(std::string("poll: ") + std::strerror(errno));
      }
      for (auto it = running.begin(); it != running.end();) {
        Child& c = *it;
        for (const pollfd& p : fds) {
          if (p.revents == 0) continue;
          if (p.fd == c.result_fd) drain(c.result_fd, c.result, 0);
          if (p.fd == c.log_fd) drain(c.log_fd, c.log, kTailBytes);
        }
        if (c.result_fd < 0 && c.log_fd < 0) {
          // Both pipes closed: the child is exiting. One that returned its
          // result closed them just before _exit(0): reaped later, while the
          // next run starts. Any other is waited for, for its exit status.
          int status = 0;
          pid_t reaped = ::waitpid(c.pid, &status, WNOHANG);
          if (reaped == 0 && returned_result(c)) {
            exiting.push_back(c.pid);
          } else {
            while (reaped <= 0 && (reaped = ::waitpid(c.pid, &status, 0)) < 0 && errno == EINTR) {
            }
          }
          const JobOutcome outcome = outcome_of(c, status, config);
          const std::size_t index = c.index;
          it = running.erase(it);
          on_done(index, outcome);
          continue;
        }
        if (!c.killed && seconds_since(c.start) >= config.time_limit_s) {
          ::kill(c.pid, SIGKILL);
          c.killed = true;
        }
        ++it;
      }
      reap_exited(exiting, false);
      if (on_tick && seconds_since(last_tick) >= config.tick_s) {
        last_tick = Clock::now();
        on_tick();
      }
    }
    reap_exited(exiting, true);
  } catch (...) {
    kill_all(running);
    reap_exited(exiting, true);
    throw;
  }
}

}  // namespace campo
