#pragma once

// Heap accounting for the benchmarks: the global operator new/delete of the benchmark binary
// keep the bytes in use and their peak (usable sizes, as glibc's malloc reports them).

#include <cstddef>

namespace facet::bench {

std::size_t heapBytesInUse();
std::size_t heapPeakBytes();
// Starts a new peak from the bytes in use now.
void resetHeapPeak();

}  // namespace facet::bench
