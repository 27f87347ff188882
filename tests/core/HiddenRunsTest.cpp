// The back pass's runs taken in SIMD lanes (HiddenRuns.h) against their bounds taken vertex by
// vertex (RunBounds::add), on every instruction set this CPU has.

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "../support/EveryTargetTest.h"
#include "HiddenRuns.h"
#include "SetupBatch.h"

namespace facet::testing {
namespace {

using detail::RunBounds;
using detail::RunSource;
using detail::RunTally;
using detail::WindowVertex;

// The polygons of a window of 8 ids take their corners from one cluster of 8 points (HiddenRuns'
// constructor), so that a run spans a few pixels; every 41st polygon (when `quads`) has a
// fourth corner.
template <class Index>
struct TestPolygons {
  std::vector<Index> offsets{0}, connectivity;
  TestPolygons(std::size_t count, std::size_t points, bool quads, std::mt19937& random) {
    std::uniform_int_distribution<std::size_t> point(0, 7);
    for (std::size_t p = 0; p < count; ++p) {
      const int corners = quads && p % 41 == 4 ? 4 : 3;
      const std::size_t cluster = (p / 8 * 37) % (points / 8);
      for (int j = 0; j < corners; ++j)
        connectivity.push_back(static_cast<Index>(8 * cluster + point(random)));
      offsets.push_back(static_cast<Index>(connectivity.size()));
    }
  }
  detail::Polygons<Index> view() const { return {offsets.data(), connectivity.data()}; }
};

// The runs as Setup.cpp took them before they were in lanes: vertex by vertex.
template <class Index>
std::vector<std::uint32_t> shownByVertex(const detail::HiddenRunTest& test,
                                         const RunSource<Index>& source,
                                         const std::vector<std::uint32_t>& ids, RunTally& tally) {
  std::vector<std::uint32_t> shown;
  for (std::size_t k = 0; k < ids.size();) {
    const std::uint32_t window = (ids[k] - source.firstId) / detail::kHiddenRunIds;
    RunBounds bounds;
    std::size_t i = k;
    for (; i < ids.size() && (ids[i] - source.firstId) / detail::kHiddenRunIds == window; ++i) {
      const std::size_t polygon = ids[i] - source.firstId;
      if (source.polygons.size(polygon) != 3) {
        bounds.outcodes |= RunBounds::kNotTriangle;
        continue;
      }
      for (std::size_t j = 0; j < 3; ++j)
        bounds.add(source.vertices[source.polygons.pointId(polygon, j)]);
    }
    const bool hidden = test.hidden(bounds);
    ++tally.runs, tally.polygons += i - k;
    if (hidden) ++tally.hiddenRuns, tally.hiddenPolygons += i - k;
    for (; k < i; ++k)
      if (!hidden) shown.push_back(ids[k]);
  }
  return shown;
}

// The lanes' shown ids (shownOfRuns writes their positions in `ids`), and each triangle's
// corners as they were read, checked against the mesh's.
template <class Index>
std::vector<std::uint32_t> shownByLanes(const detail::HiddenRunTest& test,
                                        const RunSource<Index>& source,
                                        const std::vector<std::uint32_t>& ids, RunTally& tally) {
  std::vector<std::uint32_t> at(ids.size() + 1);
  std::vector<WindowVertex> corners(3 * ids.size() + 1);
  at.resize(detail::shownOfRuns(test, source, ids, at.data(), corners.data(), tally));
  std::vector<std::uint32_t> shown;
  for (const std::uint32_t i : at)
    shown.push_back(ids.at(i));
  for (std::size_t i = 0; i < ids.size(); ++i) {
    const std::size_t polygon = ids[i] - source.firstId;
    if (source.polygons.size(polygon) != 3) continue;
    for (std::size_t j = 0; j < 3; ++j) {
      const WindowVertex& v = source.vertices[source.polygons.pointId(polygon, j)];
      EXPECT_EQ(std::memcmp(&corners[3 * i + j], &v, sizeof v), 0)
          << "polygon " << ids[i] << " corner " << j;
    }
  }
  return shown;
}

class HiddenRuns : public EveryTargetTest {
 protected:
  HiddenRuns() : grid_(100, 70) {  // 2 × 2 tiles, the last ones partial
    std::mt19937 random(29);
    // Keys of both signs (a parallel projection's are negative), some blocks background.
    std::uniform_real_distribution<float> key(-0.8f, 0.1f), block(0.0f, 0.8f), unit(0.0f, 1.0f);
    front_.resize(grid_);
    for (std::size_t t = 0; t < grid_.count(); ++t) {
      float measured[detail::FrontDepthBlocks::kPerTile];
      for (float& b : measured)
        b = unit(random) < 0.02f ? -std::numeric_limits<float>::infinity() : block(random);
      front_.store(t, measured);
    }
    // Points in clusters a few pixels across (a run's box then spans a few blocks), some
    // partly off the image; some outside a clip plane or not finite; residues anything (they
    // share the outcode's word).
    std::uniform_int_distribution<int> cluster(-20 * 256, 110 * 256), spread(-6 * 256, 6 * 256);
    std::uniform_int_distribution<int> residue(-128, 127);
    for (int c = 0; c < 400; ++c) {
      const int cx = cluster(random), cy = cluster(random);
      for (int k = 0; k < 8; ++k) {
        WindowVertex v;
        v.x = cx + spread(random), v.y = cy + spread(random);
        v.depth = key(random);
        v.residueX = static_cast<std::int8_t>(residue(random));
        v.residueY = static_cast<std::int8_t>(residue(random));
        const float odd = unit(random);
        if (odd < 0.003f) {
          v.outcode = detail::kNonFinite, v.depth = std::numeric_limits<float>::quiet_NaN();
        } else if (odd < 0.006f) {
          v.outcode = detail::kBeyondRight;
        }
        vertices_.push_back(v);
      }
    }
  }

  // Of each block of 256 polygon ids from `firstId`, a random subset deferred: some windows
  // whole, some in part, some empty; then the lanes' answer against the vertex-by-vertex one
  // on every target.
  // `thrice`: the source takes offsets[p] = 3p without reading them (RunSource::offsetsThrice:
  // only without quads, where it holds).
  template <class Index>
  void expectTheRunsOfTheBounds(bool quads, bool thrice, RunTally& total) {
    constexpr std::uint32_t kFirstId = 768, kBlock = 256;
    std::mt19937 random(quads ? 7 : 11);
    const TestPolygons<Index> polygons(4 * kBlock, vertices_.size(), quads, random);
    const RunSource<Index> source{vertices_.data(), polygons.view(), kFirstId, !quads, thrice};
    const detail::HiddenRunTest test(grid_, front_);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (std::uint32_t block = 0; block < 4; ++block) {
      std::vector<std::uint32_t> ids;
      for (std::uint32_t window = 0; window < kBlock / detail::kHiddenRunIds; ++window) {
        const float density = unit(random);
        for (std::uint32_t k = 0; k < detail::kHiddenRunIds; ++k) {
          if (unit(random) < density)
            ids.push_back(kFirstId + block * kBlock + window * detail::kHiddenRunIds + k);
        }
      }
      RunTally expectedTally;
      const std::vector<std::uint32_t> expected = shownByVertex(test, source, ids, expectedTally);
      for (const detail::SimdTarget& target : detail::simdTargets()) {
        SCOPED_TRACE(target.name);
        detail::useSimdTarget(target.bits);
        RunTally tally;
        const std::vector<std::uint32_t> shown = shownByLanes(test, source, ids, tally);
        EXPECT_EQ(shown, expected) << "block " << block;
        EXPECT_EQ(tally.runs, expectedTally.runs);
        EXPECT_EQ(tally.hiddenRuns, expectedTally.hiddenRuns);
        EXPECT_EQ(tally.polygons, expectedTally.polygons);
        EXPECT_EQ(tally.hiddenPolygons, expectedTally.hiddenPolygons);
      }
      detail::useSimdTarget(0);
      total.runs += expectedTally.runs, total.hiddenRuns += expectedTally.hiddenRuns;
      total.polygons += expectedTally.polygons;
    }
  }

  detail::TileGrid grid_;
  detail::FrontDepthBlocks front_;
  std::vector<WindowVertex> vertices_;
};

// Checked to fail with the lanes' y bounds taken from the x lane.
TEST_F(HiddenRuns, LanesDropTheRunsOfTheVertexBoundsOnEveryTarget) {
  for (const int kind : {0, 1, 2}) {
    const bool quads = kind == 1, thrice = kind == 2;
    SCOPED_TRACE(quads ? "some quads" : thrice ? "triangles, offsets not read" : "triangles");
    RunTally int32, int64;
    expectTheRunsOfTheBounds<std::int32_t>(quads, thrice, int32);
    expectTheRunsOfTheBounds<std::int64_t>(quads, thrice, int64);
    for (const RunTally& tally : {int32, int64}) {
      // Both answers occur often enough to tell lanes from vertices apart.
      EXPECT_GT(tally.hiddenRuns, tally.runs / 10) << tally.hiddenRuns << " of " << tally.runs;
      EXPECT_LT(tally.hiddenRuns, tally.runs - tally.runs / 10)
          << tally.hiddenRuns << " of " << tally.runs;
    }
  }
}

// The block's prefetches (the back pass asks for its ids' offsets or connectivity, then a
// triangle block's connectivity: prefetchRunsAhead, prefetchRunsNow) and the gathered corners at
// the edges: no ids, the last polygon alone, every id of the last block (the reach ends at the
// offsets' last entry and the connectivity's end; the sanitized build checks what they read);
// the same answer.
TEST_F(HiddenRuns, TheBlocksEdgesGiveTheVertexAnswerOnEveryTarget) {
  constexpr std::uint32_t kFirstId = 64, kCount = 128;
  for (const int kind : {0, 1, 2}) {
    const bool quads = kind == 1, thrice = kind == 2;
    SCOPED_TRACE(quads ? "some quads" : thrice ? "triangles, offsets not read" : "triangles");
    std::mt19937 random(quads ? 3 : 5);
    const TestPolygons<std::int64_t> polygons(kCount, vertices_.size(), quads, random);
    const RunSource<std::int64_t> source{vertices_.data(), polygons.view(), kFirstId, !quads,
                                         thrice};
    const detail::HiddenRunTest test(grid_, front_);
    std::vector<std::uint32_t> lastBlock;
    for (std::uint32_t id = kFirstId + kCount - 64; id < kFirstId + kCount; ++id)
      lastBlock.push_back(id);
    const std::vector<std::vector<std::uint32_t>> blocks = {
        {}, {kFirstId + kCount - 1}, {kFirstId}, lastBlock};
    for (const std::vector<std::uint32_t>& ids : blocks) {
      if (!ids.empty()) {
        detail::prefetchRunsAhead(source, ids.front(), ids.back());
        detail::prefetchRunsNow(source, ids.front(), ids.back());
      }
      RunTally expectedTally;
      const std::vector<std::uint32_t> expected = shownByVertex(test, source, ids, expectedTally);
      for (const detail::SimdTarget& target : detail::simdTargets()) {
        SCOPED_TRACE(target.name);
        detail::useSimdTarget(target.bits);
        RunTally tally;
        const std::vector<std::uint32_t> shown = shownByLanes(test, source, ids, tally);
        EXPECT_EQ(shown, expected) << ids.size() << " ids";
        EXPECT_EQ(tally.runs, expectedTally.runs);
        EXPECT_EQ(tally.hiddenPolygons, expectedTally.hiddenPolygons);
      }
      detail::useSimdTarget(0);
    }
  }
}

}  // namespace
}  // namespace facet::testing
