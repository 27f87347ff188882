// The machine's memory bandwidth, STREAM-style, for the memory-bound limit of
// `make bench-peers`: T threads each sweep their own contiguous part of an array far larger
// than the last-level cache, and the best of several passes counts (as STREAM reports it).
//
//   read:  sum every 64-bit word (what reading a mesh costs)
//   write: store every 64-bit word with ordinary stores (what writing a framebuffer costs;
//          the cache line is read for ownership first, as the renderer's stores do)
//
//   build/bin/bandwidth_bench --threads 2 --mib 512 --passes 10
//
// Prints one JSON object: bytes swept per pass and the bandwidths in bytes per second.

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "facet/HugePageAllocator.h"

namespace {

struct Options {
  int threads = 2;
  std::size_t mib = 512;  // 14× the 36 MiB L3 of this machine type: every pass goes to DRAM
  int passes = 10;
};

Options parse(int argc, char** argv) {
  Options options;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string_view name = argv[i];
    const long value = std::strtol(argv[i + 1], nullptr, 10);
    if (value <= 0) {
      std::fprintf(stderr, "%s: %s needs a positive integer\n", argv[0], argv[i]);
      std::exit(2);
    }
    if (name == "--threads") {
      options.threads = int(value);
    } else if (name == "--mib") {
      options.mib = std::size_t(value);
    } else if (name == "--passes") {
      options.passes = int(value);
    } else {
      std::fprintf(stderr, "usage: %s [--threads T] [--mib M] [--passes P]\n", argv[0]);
      std::exit(2);
    }
  }
  if (argc % 2 == 0) {
    std::fprintf(stderr, "usage: %s [--threads T] [--mib M] [--passes P]\n", argv[0]);
    std::exit(2);
  }
  return options;
}

using Words = std::span<std::uint64_t>;

// Runs kernel(part, thread) on every thread's part at once; returns the wall-clock seconds.
double sweep(facet::HugePageVector<std::uint64_t>& array, int threads,
             const std::function<void(Words, int)>& kernel) {
  const std::size_t part = array.size() / threads;
  const auto start = std::chrono::steady_clock::now();
  {
    std::vector<std::jthread> workers;
    for (int t = 0; t < threads; ++t) {
      workers.emplace_back([&, t] { kernel(Words(array).subspan(t * part, part), t); });
    }
  }
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Bytes per second of the best of `passes` sweeps.
double bestBandwidth(facet::HugePageVector<std::uint64_t>& array, const Options& options,
                     const std::function<void(Words, int)>& kernel) {
  double best = 1e300;
  for (int pass = 0; pass < options.passes; ++pass) {
    best = std::min(best, sweep(array, options.threads, kernel));
  }
  const std::size_t swept = array.size() / options.threads * options.threads;
  return double(swept * sizeof(std::uint64_t)) / best;
}

}  // namespace

int main(int argc, char** argv) {
  const Options options = parse(argc, argv);
  // Huge pages, as Facet's framebuffer: the sweep measures DRAM, not page walks.
  facet::HugePageVector<std::uint64_t> array(options.mib * 1048576 / sizeof(std::uint64_t));
  std::vector<std::uint64_t> sums(options.threads);  // keeps the reads observable

  // Each thread first touches its own part (the pages then live near it). The stored value
  // is not one repeated byte, so the compiler keeps the stores instead of calling memset
  // (whose non-temporal stores would skip the read for ownership).
  const auto write = [](Words words, int thread) {
    for (std::uint64_t& word : words)
      word = 0x100 + thread;
  };
  sweep(array, options.threads, write);
  const auto read = [&](Words words, int thread) {
    std::uint64_t sum = 0;
    for (const std::uint64_t word : words)
      sum += word;
    sums[thread] += sum;
  };
  const double readBandwidth = bestBandwidth(array, options, read);
  const double writeBandwidth = bestBandwidth(array, options, write);

  std::uint64_t check = 0;
  for (const std::uint64_t sum : sums)
    check += sum;
  std::printf(
      "{\"threads\": %d, \"bytes\": %zu, \"passes\": %d, \"read_bytes_per_second\": %.6g, "
      "\"write_bytes_per_second\": %.6g, \"checksum\": %llu}\n",
      options.threads, array.size() * sizeof(std::uint64_t), options.passes, readBandwidth,
      writeBandwidth, static_cast<unsigned long long>(check));
  return 0;
}
