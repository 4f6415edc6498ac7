#pragma once
/// The limits a Python planner is held to (docs/python.md, "Limits"): a
/// wall-clock limit on every call into its code and a bound on how much the
/// process's resident memory may grow while it runs. One watchdog thread watches
/// every guarded planner and ends a call past a limit by raising
/// campo.PlannerInterrupted in it: through a signal when the call runs on
/// the main thread (which also wakes a time.sleep), as an asynchronous
/// exception otherwise. The same signal from a run past its own wall-clock
/// limit (planner_interrupt_signal) interrupts the main thread's call
/// in progress. The limits concern the host, never the simulation:
/// a run that stays within them is the same run, bit for bit.
#include <chrono>
#include <cstddef>
#include <memory>
#include <optional>
#include <string>

#include <pybind11/pybind11.h>

namespace campo::python {

using WallClock = std::chrono::steady_clock;

/// Limits of one Python planner.
struct PlannerLimits {
  double call_limit_s = 60.0;        ///< wall clock of one call (plan, parameters, the constructor), s; 0: none
  double memory_limit_mib = 4096.0;  ///< growth of the process's resident memory since the planner was made, MiB; 0: none
};

/// The environment variables that set the limits.
inline constexpr const char* kCallLimitVariable = "CAMPO_PYTHON_CALL_LIMIT_S";
inline constexpr const char* kMemoryLimitVariable = "CAMPO_PYTHON_MEMORY_LIMIT_MIB";

/// The defaults with CAMPO_PYTHON_CALL_LIMIT_S and CAMPO_PYTHON_MEMORY_LIMIT_MIB
/// applied; InputError naming the variable for a value that is not a number >= 0.
PlannerLimits limits_from_environment();

/// The limits of planners made now on this thread: those a ScopedLimits
/// sets (campo.run(call_limit_s=)), else limits_from_environment().
PlannerLimits current_limits();

/// Sets current_limits() on this thread while it exists.
class ScopedLimits {
 public:
  explicit ScopedLimits(PlannerLimits limits);
  ~ScopedLimits();
  ScopedLimits(const ScopedLimits&) = delete;
  ScopedLimits& operator=(const ScopedLimits&) = delete;

 private:
  std::optional<PlannerLimits> previous_;
};

/// The process's resident memory, bytes (0 when it cannot be read).
std::size_t resident_bytes();

struct GuardEntry;

/// A planner registered with the watchdog, from its construction to its end.
class PlannerGuard {
 public:
  /// `name` is the planner's name in messages ("python:module:Class").
  PlannerGuard(std::string name, PlannerLimits limits);
  ~PlannerGuard();
  PlannerGuard(const PlannerGuard&) = delete;
  PlannerGuard& operator=(const PlannerGuard&) = delete;

  const std::string& name() const;
  /// Why the watchdog ended the planner, if it did: every later call is refused with it.
  std::optional<std::string> failure() const;

 private:
  friend class GuardedCall;
  std::unique_ptr<GuardEntry> entry_;
};

/// One call into the planner's Python code, watched while it exists. Made
/// with the interpreter's lock held; throws std::runtime_error with the
/// planner's failure when it already failed (no call is made then).
class GuardedCall {
 public:
  /// `what` names the call in messages: "plan()", "parameters()", "the constructor".
  GuardedCall(PlannerGuard& guard, std::string what);
  ~GuardedCall();
  GuardedCall(const GuardedCall&) = delete;
  GuardedCall& operator=(const GuardedCall&) = delete;

  /// After the call: throws std::runtime_error naming the planner, the call
  /// and the limit when the watchdog ended it, or when the planner asked the
  /// process to exit (os._exit) during it.
  void check() const;

 private:
  PlannerGuard& guard_;
};

/// Binds campo.PlannerInterrupted and campo.PlannerExit, and, on the main
/// thread, installs the handler of the signal that interrupts a call there.
void bind_limits(pybind11::module_& m);

/// In an interpreter campo embeds (campo run, a sweep's runs): os._exit
/// (and posix._exit) called by this process raise campo.PlannerExit instead
/// of ending it, so the run ends as failed with its files written; a forked
/// child's os._exit is the real one.
void guard_process_exit();

}  // namespace campo::python
