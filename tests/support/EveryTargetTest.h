#pragma once

// The fixture of the tests that run SIMD lanes on every instruction set this CPU has
// (SetupBatch.h's useSimdTarget): run-time dispatch is given back after each test, also after
// an assertion ended it early, so no later test runs pinned to the last target tried.

#include <gtest/gtest.h>

#include "SetupBatch.h"

namespace facet::testing {

class EveryTargetTest : public ::testing::Test {
 protected:
  void TearDown() override { detail::useSimdTarget(0); }
};

}  // namespace facet::testing
