#pragma once
/// A fixed set of threads that run the tasks of one call together (the vector
/// environment's steps): the calling thread works too, and the call returns
/// when every task has run. Tasks are handed out one by one from a shared
/// counter, so a slow environment does not hold up the others' threads.
///
/// A call of one task runs in the caller alone. Between calls a worker spins
/// for a moment (kSpin) before it sleeps, and the caller spins as long for the
/// last tasks before it sleeps: a sleeping thread takes tens to hundreds of
/// microseconds to wake (60 us median, 150 us at the 90th percentile on the
/// 2-vCPU KVM machine of docs/PERFORMANCE.md), as long as a whole environment
/// step at 64 x 64, and a vector environment steps again within microseconds
/// of the previous step's return.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace campo::python {

class WorkerPool {
 public:
  /// How long a thread spins for the next call (a worker) or the last tasks (the caller) before it sleeps.
  static constexpr std::chrono::microseconds kSpin{200};

  /// `threads` >= 1 in all, the calling thread included.
  explicit WorkerPool(int threads);
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  int threads() const { return static_cast<int>(workers_.size()) + 1; }
  /// Runs task(i) for every i in [0, count) and waits for all; rethrows the
  /// first exception a task threw (the other tasks still run).
  void run(std::size_t count, const std::function<void(std::size_t)>& task);

 private:
  void work();
  // Takes tasks of the current batch until none is left; the caller holds no lock.
  void drain();

  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::condition_variable finished_;
  const std::function<void(std::size_t)>* task_ = nullptr;  // guarded by mutex_, as the next three
  std::size_t count_ = 0;
  std::size_t next_ = 0;  // the next task to hand out
  std::exception_ptr error_;
  // Changed under mutex_ (so that sleepers miss no change) and read without it by spinning threads.
  std::atomic<std::size_t> done_{0};        // tasks of the current batch finished
  std::atomic<std::size_t> generation_{0};  // batches started, so a worker joins each once
  std::atomic<bool> stopping_{false};
};

}  // namespace campo::python
