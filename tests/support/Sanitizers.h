// What a test's search spans under a sanitizer. The sanitized suites (ASan + UBSan, TSan) run the
// core 5-20x slower; what they add is memory and race checking of every path, which a smaller
// search still walks. The Release suite keeps the full searches and compares every thread count.
#pragma once

#include <initializer_list>
#include <vector>

namespace facet::testing {

// GCC defines __SANITIZE_*__; clang 14 (the sanitized builds' compiler) answers __has_feature.
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
inline constexpr bool kUnderSanitizer = true;
#elif defined(__has_feature)
inline constexpr bool kUnderSanitizer =
    __has_feature(address_sanitizer) || __has_feature(thread_sanitizer);
#else
inline constexpr bool kUnderSanitizer = false;
#endif

// A random search's trial count: `full` in the Release suite, a fifth under a sanitizer.
constexpr int trialsToRun(int full) {
  return kUnderSanitizer ? full / 5 : full;
}

// The thread counts a test renders at: all of `counts` in the Release suite; under a sanitizer
// only the last (the most workers: where races and out-of-bounds writes show).
inline std::vector<int> threadCountsToRun(std::initializer_list<int> counts) {
  if (kUnderSanitizer) return {*(counts.end() - 1)};
  return counts;
}

}  // namespace facet::testing
