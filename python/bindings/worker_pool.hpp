#pragma once
/// A fixed set of threads that run the tasks of one call together (the vector
/// environment's steps): the calling thread works too, and the call returns
/// when every task has run. Tasks are handed out one by one from a shared
/// counter, so a slow environment does not hold up the others' threads.
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
  const std::function<void(std::size_t)>* task_ = nullptr;
  std::size_t count_ = 0;
  std::size_t next_ = 0;        // the next task to hand out
  std::size_t running_ = 0;     // tasks handed out and not finished
  std::size_t generation_ = 0;  // batches started, so a worker wakes once per batch
  std::exception_ptr error_;
  bool stopping_ = false;
};

}  // namespace campo::python
