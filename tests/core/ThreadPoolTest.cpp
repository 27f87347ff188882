// ThreadPool's first stage (FirstStage): every one of its tasks finished, its writes seen, before
// any later task of the job starts, on any thread; a failure in it stops the job.

#include <atomic>
#include <cstddef>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "ThreadPool.h"

namespace facet::testing {
namespace {

using detail::FirstStage;
using detail::FunctionRef;
using detail::ThreadPool;

// Long enough that a thread which took a later task could overtake a running first one.
void busyWork(std::size_t i) {
  volatile std::size_t sink = i;
  for (int k = 0; k < 20000; ++k)
    sink = sink * 31 + 7;
}

TEST(ThreadPoolFirstStage, FinishesBeforeAnyLaterTaskOnEveryThread) {
  constexpr std::size_t kFirst = 9, kLater = 40;
  for (const int threads : {1, 2, 8}) {
    ThreadPool pool(threads);
    std::size_t violations = 0, laterRun = 0;
    for (int job = 0; job < 50; ++job) {
      std::vector<int> written(kFirst, 0);  // plain ints: the stage's ordering publishes them
      std::atomic<std::size_t> seenUnwritten{0}, later{0};
      auto first = [&](std::size_t i) {
        busyWork(i);
        written[i] = job + 1;
      };
      auto task = [&](std::size_t) {
        for (const int w : written)
          if (w != job + 1) seenUnwritten.fetch_add(1);
        later.fetch_add(1);
      };
      std::size_t callerFinished = 0;
      auto afterCaller = [&](std::size_t finished) {
        callerFinished = finished;
        return true;
      };
      EXPECT_TRUE(pool.run(kLater, task, afterCaller, FirstStage{kFirst, first}));
      EXPECT_LE(callerFinished, kLater);  // only the later tasks are counted
      violations += seenUnwritten.load();
      laterRun += later.load();
    }
    EXPECT_EQ(violations, 0u) << threads << " threads";
    EXPECT_EQ(laterRun, 50 * kLater) << threads << " threads";
  }
}

TEST(ThreadPoolFirstStage, RunsAloneWithoutLaterTasks) {
  ThreadPool pool(2);
  std::atomic<std::size_t> ran{0};
  auto first = [&](std::size_t) { ran.fetch_add(1); };
  auto none = [](std::size_t) { FAIL() << "no later task"; };
  EXPECT_TRUE(pool.run(0, none, {}, FirstStage{5, first}));
  EXPECT_EQ(ran.load(), 5u);
}

TEST(ThreadPoolFirstStage, AFailureInItStopsTheJobAndIsRethrown) {
  for (const int threads : {1, 2, 8}) {
    ThreadPool pool(threads);
    std::atomic<std::size_t> later{0};
    auto first = [](std::size_t i) {
      if (i == 0) throw std::runtime_error("first stage");
    };
    auto task = [&](std::size_t) { later.fetch_add(1); };
    EXPECT_THROW(pool.run(8, task, {}, FirstStage{4, first}), std::runtime_error);
    EXPECT_EQ(later.load(), 0u) << threads << " threads";
  }
}

}  // namespace
}  // namespace facet::testing
