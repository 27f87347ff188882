#pragma once

// What the tests of two-pass frames and their whole-block reject (HiddenBlocks.h) share: the
// fixture that gives the plan, the reject and its counting back after each test, and the
// scenes' parts (a front-facing square, a fan of back faces as one back-face block).

#include <cmath>
#include <cstdint>
#include <vector>

#include "EveryTargetTest.h"
#include "HiddenBlocks.h"
#include "Raster.h"
#include "Setup.h"
#include "TestRender.h"
#include "facet/Mesh.h"

namespace facet::testing {

class TwoPassTest : public EveryTargetTest {
 protected:
  void TearDown() override {
    detail::planTwoPassFrames();
    detail::enableHiddenBlocks(true);
    detail::countHiddenBlocks(false);
    detail::enableFrontPassConeSkip(true);
    EveryTargetTest::TearDown();
  }
  static std::vector<detail::SimdTarget> targets() { return detail::simdTargets(); }
  static void use(const detail::SimdTarget& target) { detail::useSimdTarget(target.bits); }
  // Renders the scene on every SIMD target, the reject's counts cleared before each render:
  // check(rendered, counts).
  template <class Check>
  static void renderOnEveryTarget(const Scene& scene, const Camera& camera, int width, int height,
                                  const RenderOptions& options, const Check& check) {
    for (const detail::SimdTarget& target : targets()) {
      SCOPED_TRACE(target.name);
      use(target);
      detail::countHiddenBlocks(true);
      const Rendered rendered = renderScene(scene, camera, width, height, options);
      check(rendered, detail::hiddenBlockCounts());
    }
  }
  static RenderOptions optionsWith(int threads) {
    RenderOptions options;
    options.visibility = Visibility::ZBuffer;
    options.threads = threads;
    return options;
  }
};

// A square of 2·cells² front-facing triangles in the plane z = z0 + slope·x, seen from +Z.
inline void addFrontSquare(Mesh& mesh, int cells, double half, double z0, double slope) {
  const std::int64_t corner = static_cast<std::int64_t>(mesh.points.size());
  for (int y = 0; y <= cells; ++y) {
    for (int x = 0; x <= cells; ++x) {
      const double px = -half + 2.0 * half * x / cells, py = -half + 2.0 * half * y / cells;
      mesh.addPoint({px, py, z0 + slope * px});
    }
  }
  for (int y = 0; y < cells; ++y) {
    for (int x = 0; x < cells; ++x) {
      const std::int64_t p = corner + y * (cells + 1) + x;
      mesh.addPolygon({p, p + 1, p + cells + 2});
      mesh.addPolygon({p, p + cells + 2, p + cells + 1});
    }
  }
}

// A fan of 256 triangles around (0, 0, apexZ), radius 0.3, as one back-face block: wound
// clockwise seen from +Z (the eye's side), so back faces; its rim at z = rimZ.
inline void addBackFan(Mesh& mesh, double apexZ, double rimZ) {
  const std::int64_t apex = mesh.addPoint({0.0, 0.0, apexZ});
  const std::int64_t first = static_cast<std::int64_t>(mesh.points.size());
  constexpr int kSides = 256;
  for (int i = 0; i < kSides; ++i) {
    const double angle = 2.0 * 3.14159265358979323846 * i / kSides;
    mesh.addPoint({0.3 * std::cos(angle), 0.3 * std::sin(angle), rimZ});
  }
  for (int i = 0; i < kSides; ++i)
    mesh.addPolygon({apex, first + (i + 1) % kSides, first + i});
}

}  // namespace facet::testing
