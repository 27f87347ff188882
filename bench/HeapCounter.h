#pragma once

// Heap accounting for the benchmarks: the global operator new/delete of the benchmark binary
// keep the bytes in use and their peak (glibc's usable sizes; an aligned buffer counts the
// bytes asked for: HeapCounter.cpp says why).

#include <cstddef>

namespace facet::bench {

std::size_t heapBytesInUse();
std::size_t heapPeakBytes();
// Starts a new peak from the bytes in use now.
void resetHeapPeak();

}  // namespace facet::bench
