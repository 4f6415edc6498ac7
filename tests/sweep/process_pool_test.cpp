// Each job in its own process: crashes, hangs and exceptions are reported,
// never shared; results come back whatever the completion order.
#include "sweep/process_pool.hpp"

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <iostream>
#include <map>
#include <stdexcept>
#include <thread>

#include <sys/wait.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace campo {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

std::map<std::size_t, JobOutcome> run_all(std::size_t count, const std::function<std::string(std::size_t)>& work,
                                          ProcessPoolConfig config) {
  std::map<std::size_t, JobOutcome> outcomes;
  run_isolated(count, work, [&](std::size_t i, const JobOutcome& o) { EXPECT_TRUE(outcomes.emplace(i, o).second); },
               config);
  return outcomes;
}

TEST(ProcessPool, ReturnsEveryJobsOutputOnce) {
  for (int jobs : {1, 3}) {
    const auto outcomes = run_all(10, [](std::size_t i) { return "job " + std::to_string(i * i); }, {.jobs = jobs});
    ASSERT_EQ(outcomes.size(), 10u);
    for (const auto& [i, o] : outcomes) {
      EXPECT_TRUE(o.ok) << o.reason;
      EXPECT_EQ(o.output, "job " + std::to_string(i * i));
      EXPECT_GE(o.wall_time_s, o.work_time_s);
    }
  }
}

// A child that returned is reaped without holding up the next job, and none is left behind.
// The sweep's overhead per run is wall_time_s - work_time_s: never negative, even when a child starts its
// job before its parent returns from fork() (the parent's clock starts before the fork). Many short jobs,
// more at a time than there are cores, so children often run first.
TEST(ProcessPool, WallTimeHoldsTheJobsTimeSoOverheadIsNeverNegative) {
  const auto outcomes = run_all(
      120,
      [](std::size_t i) {
        volatile double x = 0.0;
        for (std::size_t k = 0; k < 20000 + 1000 * (i % 7); ++k) x = x + 1.0 / static_cast<double>(k + 1);
        return std::to_string(x);
      },
      {.jobs = 6});
  ASSERT_EQ(outcomes.size(), 120u);
  for (const auto& [i, o] : outcomes) {
    ASSERT_TRUE(o.ok) << o.reason;
    EXPECT_GT(o.work_time_s, 0.0) << i;
    EXPECT_GE(o.wall_time_s - o.work_time_s, 0.0) << "job " << i;
  }
}

TEST(ProcessPool, ReturnedChildrenAreReapedAndNoneIsLeft) {
  const auto outcomes = run_all(20, [](std::size_t i) { return std::to_string(i); }, {.jobs = 2});
  ASSERT_EQ(outcomes.size(), 20u);
  for (const auto& [i, o] : outcomes) EXPECT_TRUE(o.ok) << o.reason;
  // Every child has been waited for: there is no child left to wait for.
  errno = 0;
  EXPECT_EQ(::waitpid(-1, nullptr, WNOHANG), -1);
  EXPECT_EQ(errno, ECHILD);
}

TEST(ProcessPool, AJobCannotChangeTheCallersMemory) {
  int counter = 0;
  const auto outcomes = run_all(4, [&](std::size_t) { return std::to_string(++counter); }, {.jobs = 2});
  EXPECT_EQ(counter, 0);
  for (const auto& [i, o] : outcomes) EXPECT_EQ(o.output, "1");  // each saw the counter as it was
}

// The faults a closed-loop run could have, by design: each is reported with
// its reason, and the jobs around it complete.
TEST(ProcessPool, CrashesHangsAndExceptionsAreIsolated) {
  const auto outcomes = run_all(
      6,
      [](std::size_t i) -> std::string {
        switch (i) {
          case 1:
            // As the kernel would, whatever handler a sanitizer installed.
            std::signal(SIGSEGV, SIG_DFL);
            std::raise(SIGSEGV);
            break;
          case 2: std::this_thread::sleep_for(std::chrono::seconds(30)); break;
          case 3: throw std::runtime_error("bad run");
          case 4:
            std::cerr << "about to give up\n";
            std::exit(3);
          default: break;
        }
        return "fine";
      },
      {.jobs = 2, .time_limit_s = 1.0});
  ASSERT_EQ(outcomes.size(), 6u);
  for (std::size_t i : {0u, 5u}) {
    EXPECT_TRUE(outcomes.at(i).ok);
    EXPECT_EQ(outcomes.at(i).output, "fine");
  }
  EXPECT_FALSE(outcomes.at(1).ok);
  EXPECT_THAT(outcomes.at(1).reason, StartsWith("killed by signal 11 ("));
  EXPECT_FALSE(outcomes.at(2).ok);
  EXPECT_EQ(outcomes.at(2).reason, "exceeded the time limit of 1 s and was killed");
  EXPECT_LT(outcomes.at(2).wall_time_s, 10.0);
  EXPECT_FALSE(outcomes.at(3).ok);
  EXPECT_EQ(outcomes.at(3).reason, "threw: bad run");
  EXPECT_FALSE(outcomes.at(4).ok);
  EXPECT_EQ(outcomes.at(4).reason, "exited with code 3 without a result");
  EXPECT_EQ(outcomes.at(4).stderr_tail, "about to give up");
}

TEST(ProcessPool, LargeOutputsArriveWhole) {
  const auto outcomes = run_all(3, [](std::size_t i) { return std::string(1 << 20, static_cast<char>('a' + i)); },
                                {.jobs = 3});
  for (const auto& [i, o] : outcomes) {
    ASSERT_TRUE(o.ok) << o.reason;
    EXPECT_EQ(o.output, std::string(1 << 20, static_cast<char>('a' + i)));
  }
}

TEST(ProcessPool, AnErrorInTheCallbackStopsEverything) {
  EXPECT_THROW(run_isolated(
                   5, [](std::size_t) { return std::string("x"); },
                   [](std::size_t, const JobOutcome&) { throw std::runtime_error("disk full"); }, {.jobs = 2}),
               std::runtime_error);
}

}  // namespace
}  // namespace campo
