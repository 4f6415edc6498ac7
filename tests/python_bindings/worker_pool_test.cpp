// The worker pool behind campo.gym's vector environment (python/bindings/worker_pool): every task of a
// call runs exactly once, calls follow each other, tasks of one call run at the same time on several
// threads, and a task's exception reaches the caller after the others ran. Plain C++ (no Python), so it
// runs under the sanitizers too.
#include "python/bindings/worker_pool.hpp"

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

namespace campo::python {
namespace {

TEST(WorkerPool, RunsEveryTaskOnceForAnyCountAndThreads) {
  for (int threads = 1; threads <= 4; ++threads) {
    WorkerPool pool(threads);
    EXPECT_EQ(pool.threads(), threads);
    for (std::size_t count : {0u, 1u, 2u, 3u, 7u, 64u}) {
      std::vector<std::atomic<int>> runs(count);
      pool.run(count, [&](std::size_t i) { runs[i].fetch_add(1); });
      for (std::size_t i = 0; i < count; ++i) EXPECT_EQ(runs[i].load(), 1) << threads << " threads, task " << i;
    }
  }
}

TEST(WorkerPool, ManyCallsInARowEachComplete) {
  WorkerPool pool(2);
  std::atomic<long> sum{0};
  for (int call = 0; call < 2000; ++call) {
    pool.run(3, [&](std::size_t i) { sum.fetch_add(static_cast<long>(i) + 1); });
    ASSERT_EQ(sum.load(), 6L * (call + 1)) << "call " << call << " returned before its tasks ended";
  }
}

TEST(WorkerPool, TasksOfOneCallRunAtTheSameTimeOnTwoThreads) {
  // Each task waits for the other to start: one thread alone would time out (and say so).
  WorkerPool pool(2);
  std::atomic<int> started{0};
  std::atomic<int> met{0};
  pool.run(2, [&](std::size_t) {
    started.fetch_add(1);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (started.load() < 2 && std::chrono::steady_clock::now() < deadline) std::this_thread::yield();
    if (started.load() == 2) met.fetch_add(1);
  });
  EXPECT_EQ(met.load(), 2);
}

TEST(WorkerPool, AnExceptionReachesTheCallerAfterTheOtherTasksRan) {
  WorkerPool pool(2);
  std::atomic<int> ran{0};
  EXPECT_THROW(pool.run(10,
                        [&](std::size_t i) {
                          ran.fetch_add(1);
                          if (i == 3) throw std::runtime_error("task 3");
                        }),
               std::runtime_error);
  EXPECT_EQ(ran.load(), 10);
  // The pool is usable after it.
  std::atomic<int> again{0};
  pool.run(4, [&](std::size_t) { again.fetch_add(1); });
  EXPECT_EQ(again.load(), 4);
}

}  // namespace
}  // namespace campo::python
