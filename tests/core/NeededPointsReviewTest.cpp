// review29's checks of the needed-point flags (order25: FrameMesh::neededPoints, from each
// back-face block's two spans or its list of scattered flags, BackBlock::scatteredPointFlags):
// no point a drawn polygon uses is left untransformed, for meshes whose polygons name points
// far apart (ids scrambled), share points across blocks, have 4 corners, and are edited in
// place under a new version by the Renderer that drew the old one.

#include <cmath>
#include <cstdint>
#include <numeric>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "../support/SameRender.h"
#include "../support/TestRender.h"
#include "BackFacingBlocks.h"
#include "facet/Renderer.h"

namespace facet::testing {
namespace {

// A closed UV sphere of quads (triangles at the poles), its point ids scrambled by
// `stride` (odd, coprime with the count: a polygon's corners land thousands of ids apart, and
// every point is shared by up to four polygons of different blocks).
Mesh scrambledQuadSphere(int theta, int phi, std::size_t stride, bool quads) {
  const std::size_t count = 2 + static_cast<std::size_t>(theta) * (phi - 1);
  const auto id = [&](std::size_t natural) {
    return static_cast<std::int64_t>((natural * stride) % count);
  };
  Mesh mesh;
  mesh.points.resize(count);
  const auto place = [&](std::size_t natural, const glm::dvec3& p) {
    mesh.points[id(natural)] = p;
  };
  place(0, {0.0, 1.0, 0.0});
  place(1, {0.0, -1.0, 0.0});
  const double pi = 3.14159265358979323846;
  const auto ring = [&](int j, int i) {
    return 2 + static_cast<std::size_t>(j) * theta + (i % theta);
  };
  for (int j = 0; j < phi - 1; ++j) {
    const double polar = pi * (j + 1) / phi;
    for (int i = 0; i < theta; ++i) {
      const double azimuth = 2.0 * pi * i / theta;
      place(ring(j, i), {std::sin(polar) * std::cos(azimuth), std::cos(polar),
                         -std::sin(polar) * std::sin(azimuth)});
    }
  }
  for (int i = 0; i < theta; ++i)  // the caps, outward (counter-clockwise seen from outside)
    mesh.addPolygon({id(0), id(ring(0, i)), id(ring(0, i + 1))});
  for (int j = 0; j + 1 < phi - 1; ++j) {
    for (int i = 0; i < theta; ++i) {
      const std::int64_t a = id(ring(j, i)), b = id(ring(j + 1, i)), c = id(ring(j + 1, i + 1)),
                         d = id(ring(j, i + 1));
      if (quads) {
        mesh.addPolygon({a, b, c, d});
      } else {
        mesh.addPolygon({a, b, c});
        mesh.addPolygon({a, c, d});
      }
    }
  }
  for (int i = 0; i < theta; ++i)
    mesh.addPolygon({id(1), id(ring(phi - 2, i + 1)), id(ring(phi - 2, i))});
  return mesh;
}

// Close enough that part of the sphere is out of view (its blocks culled, their points left
// out), from a few directions.
Camera closeCamera(int view) {
  const double a = 0.9 * view + 0.3;
  Camera camera;
  camera.focalPoint = {0.4 * std::cos(a), 0.3 * std::sin(a), 0.0};
  camera.position = camera.focalPoint + 3.0 * glm::dvec3(std::sin(a), 0.3, std::cos(a));
  camera.viewAngleDegrees = 22.0;
  return camera;
}

// Renders with the blocks outside the view and the back-face blocks left out, or neither
// (closed surfaces skip their back faces either way).
Rendered renderCulled(const Scene& scene, const Camera& camera, bool culled) {
  detail::ScopedBackBlockSettings::Settings settings = detail::ScopedBackBlockSettings::current();
  settings.skipping = culled;
  const detail::ScopedBackBlockSettings scoped(settings);
  RenderOptions options;
  options.rules.geometryOutsideView = culled;
  return renderScene(scene, camera, 320, 240, options);
}

// Triangles (back-face blocks skipped) and quads (blocks outside the view alone), both with
// scattered point ids: culling on renders the bytes and draws the polygons of culling off.
TEST(NeededPointsReview, ScatteredQuadsAndTrianglesRenderAsWithoutCulling) {
  std::size_t outside = 0, backFacing = 0;
  for (const bool quads : {false, true}) {
    SCOPED_TRACE(quads ? "quads" : "triangles");
    const Mesh mesh = scrambledQuadSphere(200, 150, 1009, quads);
    MeshView view = mesh.view();
    view.closedSurface = true;
    view.version = 1;
    for (int v = 0; v < 4; ++v) {
      SCOPED_TRACE("view " + std::to_string(v));
      const Rendered on = renderCulled(oneMeshScene(view), closeCamera(v), true);
      const Rendered off = renderCulled(oneMeshScene(view), closeCamera(v), false);
      // Polygons left out whole are counted culled or outside instead of one by one.
      EXPECT_EQ(differingPixels(off.framebuffer, on.framebuffer), 0u);
      EXPECT_EQ(off.stats.polygonsDrawn, on.stats.polygonsDrawn);
      EXPECT_EQ(off.stats.fragmentsWritten, on.stats.fragmentsWritten);
      outside += on.stats.plan.blocksOutside;
      backFacing += on.stats.plan.blocksBackFacing;
    }
  }
  EXPECT_GT(outside, 0u);  // the test tests both ways of leaving points out
  EXPECT_GT(backFacing, 0u);
}

// A field of 9,216 separate quads in 9 patches of 32 × 32, listed patch by patch (a
// view-culling block of 1,024 polygons is one patch). Each quad's first three corners have
// consecutive ids; its fourth corner an id of its own, 40 apart from the next quad's (the
// points between unused), so that no other corner shares its needed-point flag and its
// block's two spans are scattered. Fails when a scattered block lists only its polygons'
// first three corners (the closed sphere above cannot tell: every corner is shared).
TEST(NeededPointsReview, SeparateQuadsKeepTheirFourthCorners) {
  constexpr int kPatches = 3, kPatchSide = 32;
  constexpr std::size_t kQuads = kPatches * kPatches * kPatchSide * kPatchSide;
  constexpr std::size_t kFourthSpacing = 40;
  Mesh mesh;
  mesh.points.assign(3 * kQuads + kFourthSpacing * kQuads, glm::dvec3(0.0));
  std::size_t quad = 0;
  for (int patch = 0; patch < kPatches * kPatches; ++patch) {
    for (int row = 0; row < kPatchSide; ++row) {
      for (int column = 0; column < kPatchSide; ++column, ++quad) {
        const double x = -4.8 + 0.1 * ((patch % kPatches) * kPatchSide + column);
        const double y = -4.8 + 0.1 * ((patch / kPatches) * kPatchSide + row);
        const auto first = static_cast<std::int64_t>(3 * quad);
        const auto fourth = static_cast<std::int64_t>(3 * kQuads + kFourthSpacing * quad);
        mesh.points[3 * quad] = {x, y, 0.0};
        mesh.points[3 * quad + 1] = {x + 0.08, y, 0.0};
        mesh.points[3 * quad + 2] = {x + 0.08, y + 0.08, 0.0};
        mesh.points[static_cast<std::size_t>(fourth)] = {x, y + 0.08, 0.0};
        mesh.addPolygon({first, first + 1, first + 2, fourth});
      }
    }
  }
  MeshView view = mesh.view();
  view.version = 1;
  Camera camera;
  camera.position = {0.3, 0.2, 8.0};
  camera.focalPoint = {0.3, 0.2, 0.0};
  camera.viewAngleDegrees = 15.0;  // about 2.1 of the field's 9.6 units across
  const Rendered on = renderCulled(oneMeshScene(view), camera, true);
  const Rendered off = renderCulled(oneMeshScene(view), camera, false);
  EXPECT_GT(on.stats.plan.blocksOutside, 2u);
  EXPECT_GT(on.stats.pixelsCovered, 20000u);
  EXPECT_EQ(differingPixels(off.framebuffer, on.framebuffer), 0u);
  EXPECT_EQ(off.stats.polygonsDrawn, on.stats.polygonsDrawn);
  EXPECT_EQ(off.stats.fragmentsWritten, on.stats.fragmentsWritten);
}

// The same arrays edited in place (another scrambling of the points, the connectivity
// rewritten) under a new version: the Renderer that drew the old version must transform the
// new version's needed points, not the old one's.
TEST(NeededPointsReview, AVersionEditedInPlaceTransformsItsOwnPoints) {
  for (const bool quads : {false, true}) {
    SCOPED_TRACE(quads ? "quads" : "triangles");
    Mesh mesh = scrambledQuadSphere(200, 150, 1009, quads);
    const Mesh edited = scrambledQuadSphere(200, 150, 3001, quads);
    ASSERT_EQ(edited.points.size(), mesh.points.size());
    ASSERT_EQ(edited.connectivity.size(), mesh.connectivity.size());
    MeshView view = mesh.view();
    view.closedSurface = true;
    view.version = 1;
    Renderer renderer;
    renderer.setThreadCount(2);
    renderer.setVisibility(Visibility::ZBuffer);
    renderer.setTwoSidedLighting(true);
    Framebuffer framebuffer(320, 240);
    for (int frame = 0; frame < 2; ++frame)
      renderer.render(oneMeshScene(view), closeCamera(1), framebuffer);
    std::copy(edited.points.begin(), edited.points.end(), mesh.points.begin());
    std::copy(edited.connectivity.begin(), edited.connectivity.end(), mesh.connectivity.begin());
    view.version = 2;
    Rendered again{Framebuffer(320, 240), {}};
    again.stats = renderer.render(oneMeshScene(view), closeCamera(1), again.framebuffer);
    const Rendered fresh = renderCulled(oneMeshScene(view), closeCamera(1), true);
    expectSameRender(fresh, again);
    EXPECT_GT(fresh.stats.plan.blocksOutside, 0u);
  }
}

}  // namespace
}  // namespace facet::testing
