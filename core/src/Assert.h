#pragma once

// Internal invariants: checked in debug and sanitizer builds (FACET_ENABLE_ASSERTS), free in
// release builds.

#include <cstdio>
#include <cstdlib>

#if !defined(NDEBUG) || defined(FACET_ENABLE_ASSERTS)
#define FACET_ASSERT(condition)                                                                    \
  do {                                                                                             \
    if (!(condition)) {                                                                            \
      std::fprintf(stderr, "%s:%d: facet invariant failed: %s\n", __FILE__, __LINE__, #condition); \
      std::abort();                                                                                \
    }                                                                                              \
  } while (false)
#else
#define FACET_ASSERT(condition) ((void)0)
#endif
