// review29's checks of ThreadPool after the caller's and the workers' loops became one
// (runNextTask): every task runs once, the caller's progress counts only the later tasks and
// grows, a cancellation or an exception stops the job and leaves the pool fit for the next
// one, with and without a first stage, on 1, 2 and 8 threads.

#include <atomic>
#include <cstddef>
#include <stdexcept>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "ThreadPool.h"

namespace facet::testing {
namespace {

using detail::FirstStage;
using detail::ThreadPool;

void spin(std::size_t i) {
  volatile std::size_t sink = i;
  for (int k = 0; k < 2000; ++k)
    sink = sink * 31 + 7;
}

// Holds the workers' tasks until the caller has finished `tasks` of its own: on a loaded
// machine the workers may otherwise take every task before the caller runs one, and the
// caller's callback (progress, cancellation) is called only after its own tasks.
class CallerFirst {
 public:
  explicit CallerFirst(std::size_t tasks) : tasks_(tasks) {}
  void holdWorker() const {
    if (std::this_thread::get_id() == caller_) return;
    while (!released_.load())
      std::this_thread::yield();
  }
  void callerFinished(std::size_t finished) {
    if (finished >= tasks_) released_.store(true);
  }

 private:
  std::size_t tasks_;
  std::thread::id caller_ = std::this_thread::get_id();
  std::atomic<bool> released_{false};
};

// Each task of a job once, each first-stage task once, the caller's counts rising and never
// above the later tasks' count (the first stage is not progress).
TEST(ThreadPoolReview, EveryTaskOnceAndTheCallersCountsRise) {
  constexpr std::size_t kFirst = 5, kLater = 61;
  for (const int threads : {1, 2, 8}) {
    SCOPED_TRACE(::testing::Message() << threads << " threads");
    ThreadPool pool(threads);
    for (int job = 0; job < 40; ++job) {
      const std::size_t first = job % 2 == 0 ? kFirst : 0;
      std::vector<std::atomic<int>> ran(kLater), ranFirst(kFirst);
      auto stage = [&](std::size_t i) {
        spin(i);
        ranFirst[i].fetch_add(1);
      };
      auto task = [&](std::size_t i) {
        spin(i);
        ran[i].fetch_add(1);
      };
      std::size_t last = 0, calls = 0;
      bool rising = true;
      auto afterCaller = [&](std::size_t finished) {
        rising = rising && finished > last && finished <= kLater;
        last = finished;
        ++calls;
        return true;
      };
      ASSERT_TRUE(pool.run(kLater, task, afterCaller, FirstStage{first, stage}));
      EXPECT_TRUE(rising) << "job " << job;
      for (std::size_t i = 0; i < kLater; ++i)
        EXPECT_EQ(ran[i].load(), 1) << "task " << i;
      for (std::size_t i = 0; i < kFirst; ++i)
        EXPECT_EQ(ranFirst[i].load(), i < first ? 1 : 0) << "first-stage task " << i;
      if (threads == 1) {
        EXPECT_EQ(last, kLater);  // the caller ran them all, and counted each
      }
    }
  }
}

// The caller's callback stops the job: run() returns false, the tasks left are not started,
// and the next job runs whole.
TEST(ThreadPoolReview, ACancelledJobLeavesThePoolWhole) {
  constexpr std::size_t kLater = 4000;
  for (const int threads : {1, 2, 8}) {
    SCOPED_TRACE(::testing::Message() << threads << " threads");
    ThreadPool pool(threads);
    for (const std::size_t first : {std::size_t{0}, std::size_t{3}}) {
      std::atomic<std::size_t> started{0};
      auto stage = [](std::size_t i) { spin(i); };
      CallerFirst callerFirst(3);
      auto task = [&](std::size_t i) {
        started.fetch_add(1);
        callerFirst.holdWorker();
        spin(i);
      };
      auto stopAtThree = [&](std::size_t finished) {
        if (finished < 3) return true;
        callerFirst.callerFinished(finished);
        return false;
      };
      EXPECT_FALSE(pool.run(kLater, task, stopAtThree, FirstStage{first, stage}));
      // The held workers are let go just before the callback returns false: between the two
      // a preempted caller may let them take a few more, never the thousands left.
      EXPECT_LT(started.load(), kLater);
      std::atomic<std::size_t> ran{0};
      auto count = [&](std::size_t) { ran.fetch_add(1); };
      EXPECT_TRUE(pool.run(kLater, count, {}, FirstStage{first, stage}));
      EXPECT_EQ(ran.load(), kLater);
    }
  }
}

// A later task's exception, and the caller's callback's, reach run()'s caller once every
// thread has left; the next job runs whole (nothing of the failure is left behind).
TEST(ThreadPoolReview, ExceptionsAfterAFirstStageAreRethrownAndForgotten) {
  constexpr std::size_t kLater = 64;
  for (const int threads : {1, 2, 8}) {
    SCOPED_TRACE(::testing::Message() << threads << " threads");
    ThreadPool pool(threads);
    std::atomic<std::size_t> firstRan{0};
    auto stage = [&](std::size_t i) {
      spin(i);
      firstRan.fetch_add(1);
    };
    auto throwing = [](std::size_t i) {
      spin(i);
      if (i == 17) throw std::runtime_error("task 17");
    };
    EXPECT_THROW(pool.run(kLater, throwing, {}, FirstStage{4, stage}), std::runtime_error);
    EXPECT_EQ(firstRan.load(), 4u);  // the first stage finished before task 17 could start
    CallerFirst callerFirst(2);
    auto throwingCallback = [&](std::size_t finished) -> bool {
      callerFirst.callerFinished(finished);
      if (finished >= 2) throw std::logic_error("callback");
      return true;
    };
    auto quiet = [&](std::size_t i) {
      callerFirst.holdWorker();
      spin(i);
    };
    EXPECT_THROW(pool.run(kLater, quiet, throwingCallback, FirstStage{4, stage}), std::logic_error);
    std::atomic<std::size_t> ran{0};
    auto count = [&](std::size_t) { ran.fetch_add(1); };
    EXPECT_TRUE(pool.run(kLater, count, {}, FirstStage{4, stage}));
    EXPECT_EQ(ran.load(), kLater);
  }
}

}  // namespace
}  // namespace facet::testing
