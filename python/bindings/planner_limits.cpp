#include "python/bindings/planner_limits.hpp"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <new>
#include <stdexcept>
#include <thread>
#include <utility>
#include <vector>

#include <pthread.h>
#include <signal.h>
#include <sys/syscall.h>
#include <unistd.h>

#include "campo/json_reader.hpp"
#include "session/run_session.hpp"

namespace campo::python {

namespace py = pybind11;

namespace {

// How often the watchdog looks (the limits' resolution), and how often it
// interrupts again a call that swallowed campo.PlannerInterrupted.
constexpr auto kPollInterval = std::chrono::milliseconds(50);
constexpr auto kInterruptAgain = std::chrono::milliseconds(500);

// The Python exceptions, created by bind_limits (never freed: the watchdog may use them to the end).
PyObject* g_interrupted = nullptr;
PyObject* g_exit = nullptr;

// Raised into Python by the signal handler and the guarded os._exit.
struct Interrupted : std::runtime_error {
  using std::runtime_error::runtime_error;
};
struct ExitCalled : std::runtime_error {
  using std::runtime_error::runtime_error;
};

bool on_main_thread() {
  thread_local const bool main = ::syscall(SYS_gettid) == ::getpid();
  return main;
}

std::string seconds_text(double s) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", s);
  return text;
}

double read_limit(const char* variable, double fallback, const char* unit) {
  const char* value = std::getenv(variable);
  if (!value || !*value) return fallback;
  char* end = nullptr;
  errno = 0;
  const double x = std::strtod(value, &end);
  if (end == value || *end != '\0' || errno == ERANGE || !std::isfinite(x) || x < 0.0) {
    throw InputError("environment", variable,
                     std::string("expected a number of ") + unit + " >= 0 (0: no limit), got \"" + value + "\"");
  }
  return x;
}

}  // namespace

// One guarded planner, as the watchdog sees it (every field under Watchdog::mutex but the constants).
struct GuardEntry {
  std::string name;
  PlannerLimits limits;
  std::size_t baseline_bytes = 0;
  // The call in progress.
  bool in_call = false;
  std::uint64_t call_seq = 0;
  std::string call;
  WallClock::time_point call_start;
  bool call_on_main = false;
  unsigned long call_thread = 0;  // Python's thread identifier
  pthread_t call_pthread{};
  std::optional<WallClock::time_point> last_interrupt;
  bool async_sent = false;
  // Why the watchdog ended it, set once.
  std::optional<std::string> failure;
  // os._exit's status, when the planner called it during a call.
  std::optional<int> exit_status;
  // Whether failure or exit_status is set: read without the lock on every call.
  std::atomic<bool> flagged{false};
};

namespace {

// The watchdog: one thread for the process, made when the first planner is
// guarded and never stopped (it sleeps while no planner is guarded). Never
// destroyed, so that it outlives every static at exit.
class Watchdog {
 public:
  static Watchdog& get() {
    static Watchdog* const watchdog = [] {
      auto* w = new Watchdog;
      // A forked child (each run of a sweep) has none of its parent's threads, and the mutex may
      // have been held by one of them: the child's watchdog starts anew at its first planner.
      ::pthread_atfork(nullptr, nullptr, [] { get().reset_in_forked_child(); });
      return w;
    }();
    return *watchdog;
  }

  std::mutex mutex;
  std::vector<GuardEntry*> entries;
  bool handler_installed = false;  // the Python handler of the interrupt signal (main thread only)
  std::uint64_t next_seq = 0;

  void add(GuardEntry* e) {
    std::lock_guard lock(mutex);
    entries.push_back(e);
    start_thread_locked();
    wake_.notify_one();
  }

  /// With `mutex` held: the watching thread runs (once per process).
  void start_thread_locked() {
    if (thread_started_) return;
    thread_started_ = true;
    std::thread([this] { loop(); }).detach();
  }

  void reset_in_forked_child() {
    new (&mutex) std::mutex;
    new (&wake_) std::condition_variable;
    thread_started_ = false;
  }

  void remove(GuardEntry* e) {
    std::lock_guard lock(mutex);
    entries.erase(std::remove(entries.begin(), entries.end(), e), entries.end());
  }

 private:
  struct Interrupt {
    GuardEntry* entry;
    std::uint64_t seq;
    bool main;
    pthread_t pthread;
  };

  void loop() {
    std::unique_lock lock(mutex);
    for (;;) {
      if (entries.empty()) {
        wake_.wait(lock);
        continue;
      }
      const auto now = WallClock::now();
      const bool watch_memory =
          std::any_of(entries.begin(), entries.end(), [](const GuardEntry* e) { return e->limits.memory_limit_mib > 0; });
      const std::size_t rss = watch_memory ? resident_bytes() : 0;
      std::vector<Interrupt> interrupts;
      for (GuardEntry* e : entries) {
        if (!e->failure) {
          e->failure = breach(*e, now, rss);
          if (e->failure) e->flagged = true;
        }
        if (e->failure && e->in_call && (!e->last_interrupt || now - *e->last_interrupt >= kInterruptAgain)) {
          e->last_interrupt = now;
          interrupts.push_back({e, e->call_seq, e->call_on_main, e->call_pthread});
        }
      }
      if (!interrupts.empty()) {
        lock.unlock();
        for (const Interrupt& i : interrupts) interrupt(i);
        lock.lock();
      }
      wake_.wait_for(lock, kPollInterval);
    }
  }

  // Why `e` must stop now, if it must.
  static std::optional<std::string> breach(const GuardEntry& e, WallClock::time_point now, std::size_t rss) {
    const PlannerLimits& l = e.limits;
    if (e.in_call && l.call_limit_s > 0 &&
        std::chrono::duration<double>(now - e.call_start).count() > l.call_limit_s) {
      return e.call + " of " + e.name + " did not return within the per-call limit of " + seconds_text(l.call_limit_s) +
             " s wall clock (" + kCallLimitVariable + ", or campo.run(call_limit_s=)) and was interrupted";
    }
    if (l.memory_limit_mib > 0 && rss > e.baseline_bytes) {
      const double grown_mib = static_cast<double>(rss - e.baseline_bytes) / (1024.0 * 1024.0);
      if (grown_mib > l.memory_limit_mib) {
        char text[64];
        std::snprintf(text, sizeof text, "%.0f MiB", grown_mib);
        return "the process's resident memory grew by " + std::string(text) + " since " + e.name +
               " was made, past the limit of " + seconds_text(l.memory_limit_mib) + " MiB (" + kMemoryLimitVariable +
               ")" + (e.in_call ? ", during " + e.call : std::string());
      }
    }
    return std::nullopt;
  }

  // Raises campo.PlannerInterrupted in the call: a signal to the main thread
  // (whose Python handler raises it, and which wakes a blocking system call),
  // else an asynchronous exception, delivered at the thread's next bytecode.
  void interrupt(const Interrupt& i) {
    if (i.main) {
      bool signal = false;
      {
        std::lock_guard lock(mutex);
        signal = handler_installed;
      }
      if (signal) {
        ::pthread_kill(i.pthread, planner_interrupt_signal());
        return;
      }
    }
    if (!Py_IsInitialized() || _Py_IsFinalizing()) return;
    const PyGILState_STATE gil = PyGILState_Ensure();
    {
      std::lock_guard lock(mutex);
      const bool same_call = std::find(entries.begin(), entries.end(), i.entry) != entries.end() &&
                             i.entry->in_call && i.entry->call_seq == i.seq;
      if (same_call) {
        PyThreadState_SetAsyncExc(i.entry->call_thread, g_interrupted);
        i.entry->async_sent = true;
      }
    }
    PyGILState_Release(gil);
  }

  std::condition_variable wake_;
  bool thread_started_ = false;
};

}  // namespace

PlannerLimits limits_from_environment() {
  PlannerLimits limits;
  limits.call_limit_s = read_limit(kCallLimitVariable, limits.call_limit_s, "seconds");
  limits.memory_limit_mib = read_limit(kMemoryLimitVariable, limits.memory_limit_mib, "MiB");
  return limits;
}

namespace {
thread_local std::optional<PlannerLimits> t_scoped_limits;
}  // namespace

PlannerLimits current_limits() { return t_scoped_limits ? *t_scoped_limits : limits_from_environment(); }

ScopedLimits::ScopedLimits(PlannerLimits limits) : previous_(t_scoped_limits) { t_scoped_limits = limits; }

ScopedLimits::~ScopedLimits() { t_scoped_limits = previous_; }

std::size_t resident_bytes() {
  std::FILE* f = std::fopen("/proc/self/statm", "r");
  if (!f) return 0;
  unsigned long size = 0, resident = 0;
  const int read = std::fscanf(f, "%lu %lu", &size, &resident);
  std::fclose(f);
  return read == 2 ? resident * static_cast<std::size_t>(::sysconf(_SC_PAGESIZE)) : 0;
}

PlannerGuard::PlannerGuard(std::string name, PlannerLimits limits) : entry_(std::make_unique<GuardEntry>()) {
  entry_->name = std::move(name);
  entry_->limits = limits;
  entry_->baseline_bytes = limits.memory_limit_mib > 0 ? resident_bytes() : 0;
  Watchdog::get().add(entry_.get());
}

PlannerGuard::~PlannerGuard() { Watchdog::get().remove(entry_.get()); }

const std::string& PlannerGuard::name() const { return entry_->name; }

std::optional<std::string> PlannerGuard::failure() const {
  std::lock_guard lock(Watchdog::get().mutex);
  return entry_->failure;
}

GuardedCall::GuardedCall(PlannerGuard& guard, std::string what) : guard_(guard) {
  Watchdog& w = Watchdog::get();
  GuardEntry& e = *guard.entry_;
  std::lock_guard lock(w.mutex);
  if (e.failure) throw std::runtime_error(*e.failure);
  w.start_thread_locked();  // a planner made before a fork is watched in the child too
  e.in_call = true;
  e.call_seq = ++w.next_seq;
  e.call = std::move(what);
  e.call_start = WallClock::now();
  e.call_on_main = on_main_thread();
  e.call_thread = PyThread_get_thread_ident();
  e.call_pthread = ::pthread_self();
  e.last_interrupt.reset();
  e.async_sent = false;
}

GuardedCall::~GuardedCall() {
  Watchdog& w = Watchdog::get();
  GuardEntry& e = *guard_.entry_;
  std::lock_guard lock(w.mutex);
  e.in_call = false;
  // An asynchronous exception not delivered (the call returned first) must not hit the caller's next bytecode.
  if (e.async_sent) PyThreadState_SetAsyncExc(e.call_thread, nullptr);
  e.async_sent = false;
}

void GuardedCall::check() const {
  Watchdog& w = Watchdog::get();
  const GuardEntry& e = *guard_.entry_;
  if (!e.flagged) return;
  std::lock_guard lock(w.mutex);
  if (e.exit_status) {
    throw std::runtime_error(e.call + " of " + e.name + " called os._exit(" + std::to_string(*e.exit_status) +
                             "): campo ended the run as failed instead of the process");
  }
  if (e.failure) throw std::runtime_error(*e.failure);
}

void bind_limits(py::module_& m) {
  auto& interrupted = py::register_exception<Interrupted>(m, "PlannerInterrupted", PyExc_BaseException);
  auto& exit_called = py::register_exception<ExitCalled>(m, "PlannerExit", PyExc_BaseException);
  g_interrupted = interrupted.ptr();
  g_exit = exit_called.ptr();
  interrupted.attr("__doc__") =
      "Raised in a Python planner's call that a limit ended (the per-call or the run's wall-clock limit, memory): "
      "a BaseException, so that `except Exception` does not swallow it (docs/python.md, Limits).";
  exit_called.attr("__doc__") =
      "Raised by os._exit called from a Python planner in a process campo embeds: the run ends as failed "
      "instead of the process.";

  // The interrupt signal raises in the main thread's call in progress, if there is one; else nothing.
  m.def("_on_interrupt_signal", [](int, const py::object&) {
    Watchdog& w = Watchdog::get();
    std::string message;
    {
      std::lock_guard lock(w.mutex);
      const unsigned long me = PyThread_get_thread_ident();
      const auto e = std::find_if(w.entries.begin(), w.entries.end(),
                                  [&](const GuardEntry* g) { return g->in_call && g->call_thread == me; });
      if (e == w.entries.end()) return;
      message = (*e)->failure ? *(*e)->failure : (*e)->call + " of " + (*e)->name + " was interrupted: the run's "
                                                                                    "wall-clock limit passed";
    }
    throw Interrupted(message);
  });
  if (!on_main_thread()) return;  // only the main thread may install signal handlers
  try {
    py::module_::import("signal").attr("signal")(planner_interrupt_signal(), m.attr("_on_interrupt_signal"));
    std::lock_guard lock(Watchdog::get().mutex);
    Watchdog::get().handler_installed = true;
  } catch (py::error_already_set&) {
    // Another interpreter than the main one: calls are interrupted by asynchronous exceptions only.
  }
}

void guard_process_exit() {
  static const pid_t campo_pid = ::getpid();
  py::module_ os = py::module_::import("os");
  py::module_ posix = py::module_::import("posix");
  static py::object real_exit = os.attr("_exit");
  const py::cpp_function guarded(
      [](int status) {
        if (::getpid() != campo_pid) {
          real_exit(status);  // a forked child (multiprocessing): its own exit
          return;
        }
        Watchdog& w = Watchdog::get();
        {
          std::lock_guard lock(w.mutex);
          const unsigned long me = PyThread_get_thread_ident();
          bool in_call = false;
          for (GuardEntry* e : w.entries) {
            if (e->in_call && e->call_thread == me) {
              e->exit_status = status;
              e->flagged = true;
              in_call = true;
            }
          }
          // Another thread (one the planner started): the planners fail at their next call.
          for (GuardEntry* e : w.entries) {
            if (!in_call && !e->failure) {
              e->failure = "a thread of the process called os._exit(" + std::to_string(status) + ") while " + e->name +
                           " ran: campo ended the run as failed instead of the process";
              e->flagged = true;
            }
          }
        }
        throw ExitCalled("os._exit(" + std::to_string(status) + ") called by a Python planner inside campo: the "
                         "run ends as failed instead of the process");
      },
      py::arg("status"), py::name("_exit"),
      py::doc("os._exit, guarded by campo: a planner's call cannot end the process campo runs it in"));
  os.attr("_exit") = guarded;
  posix.attr("_exit") = guarded;
}

}  // namespace campo::python
