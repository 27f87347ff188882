#pragma once

// The fixture of the tests that run SIMD lanes on every instruction set this CPU has
// (SetupBatch.h's useSimdTarget): run-time dispatch is given back after each test, also after
// an assertion ended it early, so no later test runs pinned to the last target tried.

#include <gtest/gtest.h>

#include <thread>

#include "SetupBatch.h"

namespace facet::testing {

class EveryTargetTest : public ::testing::Test {
 protected:
  void TearDown() override { detail::useSimdTarget(0); }
};

// A process's first dispatch, two renders starting at once: `take` (which picks a SIMD target's
// function) called on two threads together right after the chosen target is forgotten, 20
// times; both calls must give `expected`, the best target's.
template <class Take>
void expectFirstDispatchOnTwoThreadsGives(Take take, decltype(take()) expected) {
  for (int round = 0; round < 20; ++round) {
    detail::forgetSimdTarget();
    decltype(take()) taken[2] = {};
    std::thread other([&] { taken[1] = take(); });
    taken[0] = take();
    other.join();
    ASSERT_EQ(taken[0], expected) << "round " << round;
    ASSERT_EQ(taken[1], expected) << "round " << round;
  }
}

}  // namespace facet::testing
