// Depth buffer vs painter's order, and back-face culling.

#include <algorithm>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "../support/TestMeshes.h"
#include "../support/TestRender.h"

namespace facet::testing {
namespace {

// Quad A lies in z = 0; quad B in the plane z = x, so they intersect along x = 0. Seen from
// above, B is nearer where x > 0 and A where x < 0.
Mesh intersectingQuads() {
  Mesh mesh;
  for (glm::dvec3 p : {glm::dvec3{-1, -1, 0},
                       {1, -1, 0},
                       {1, 1, 0},
                       {-1, 1, 0},
                       {-1, -1, -1},
                       {1, -1, 1},
                       {1, 1, 1},
                       {-1, 1, -1}}) {
    mesh.addPoint(p);
  }
  mesh.addPolygon({0, 1, 2, 3});  // A: polygon 0
  mesh.addPolygon({4, 5, 6, 7});  // B: polygon 1
  return mesh;
}

Camera topDown() {
  Camera camera;
  camera.parallelProjection = true;
  camera.parallelScale = 1.2;
  camera.position = {0, 0, 5};
  camera.focalPoint = {0, 0, 0};
  camera.nearClip = 1.0;
  camera.farClip = 10.0;
  return camera;
}

TEST(Visibility, ZBufferResolvesIntersectingPolygons) {
  const Mesh quads = intersectingQuads();
  const Rendered r = renderScene(oneMeshScene(quads.view()), topDown(), 120, 120);
  int checked = 0;
  for (int y = 15; y < 105; ++y) {
    for (int x = 12; x < 108; ++x) {
      if (x >= 57 && x <= 62) continue;  // the intersection line
      const int expected = x < 60 ? 0 : 1;
      ASSERT_EQ(r.framebuffer.polygonIdAt(x, y), expected) << "pixel (" << x << ", " << y << ")";
      ++checked;
    }
  }
  EXPECT_GT(checked, 8000);
}

TEST(Visibility, PainterOrderCannotResolveIntersectingPolygons) {
  // Both centroids are at the same depth: the tie goes to polygon order, so B (drawn last)
  // covers A everywhere, including where A is nearer. This is the documented limitation.
  const Mesh quads = intersectingQuads();
  RenderOptions painter;
  painter.visibility = Visibility::PainterSort;
  const Rendered r = renderScene(oneMeshScene(quads.view()), topDown(), 120, 120, painter);
  EXPECT_EQ(r.framebuffer.polygonIdAt(30, 60), 1) << "A is nearer here, yet B was painted over it";
  EXPECT_EQ(r.framebuffer.polygonIdAt(90, 60), 1);
}

TEST(Visibility, PainterOrderDrawsFarToNear) {
  Mesh stack;  // two parallel squares, the far one listed last
  for (double z : {0.5, -0.5}) {
    const std::int64_t base = static_cast<std::int64_t>(stack.points.size());
    for (glm::dvec3 p : {glm::dvec3{-1, -1, z}, {1, -1, z}, {1, 1, z}, {-1, 1, z}})
      stack.addPoint(p);
    stack.addPolygon({base, base + 1, base + 2, base + 3});
  }
  RenderOptions painter;
  painter.visibility = Visibility::PainterSort;
  const Rendered r = renderScene(oneMeshScene(stack.view()), topDown(), 64, 64, painter);
  EXPECT_EQ(r.framebuffer.polygonIdAt(32, 32), 0) << "the near square must end on top";
  const Rendered z = renderScene(oneMeshScene(stack.view()), topDown(), 64, 64);
  EXPECT_EQ(z.framebuffer.polygonIdAt(32, 32), 0);
  EXPECT_NEAR(z.framebuffer.depthAt(32, 32), r.framebuffer.depthAt(32, 32), 1e-7);
}

void expectSameImage(const Framebuffer& a, const Framebuffer& b) {
  ASSERT_EQ(a.pixelCount(), b.pixelCount());
  std::size_t differences = 0;
  for (std::size_t i = 0; i < a.pixelCount(); ++i) {
    differences += a.color()[i] != b.color()[i] || a.depth()[i] != b.depth()[i] ||
                   a.polygonId()[i] != b.polygonId()[i];
  }
  EXPECT_EQ(differences, 0u);
}

// Skipping a closed mesh's back faces leaves the same picture: every color and polygon id.
// Depths too but at the few samples only snapping covers (within 1/512 pixel beyond a
// polygon's edge): drawn with its back faces, a mesh takes the snapped plane's key there
// so that silhouettes fold as culling would; without them, the unsnapped plane's
// (Rasterizer.cpp, TriangleDepth).
void expectSamePicture(const Framebuffer& culled, const Framebuffer& all) {
  ASSERT_EQ(culled.pixelCount(), all.pixelCount());
  std::size_t differentPixels = 0, differentDepths = 0, covered = 0;
  for (std::size_t i = 0; i < culled.pixelCount(); ++i) {
    differentPixels +=
        culled.color()[i] != all.color()[i] || culled.polygonId()[i] != all.polygonId()[i];
    covered += all.polygonId()[i] != Framebuffer::kBackgroundId;
    differentDepths += culled.depth()[i] != all.depth()[i];
    EXPECT_NEAR(culled.depth()[i], all.depth()[i], 1e-3) << "pixel " << i;
  }
  EXPECT_EQ(differentPixels, 0u);
  EXPECT_LE(differentDepths, covered / 1000) << "of " << covered << " covered pixels";
}

TEST(Culling, ClosedMeshLooksTheSameWithAndWithoutCulling) {
  const Mesh spot = readObj(sharedMeshPath("spot.obj"));
  LightSet lights;
  lights.lights.push_back(
      PointLight{{3.0, 2.0, 4.0}, Color(1.0f, 0.9f, 0.8f), 1.0, NoAttenuation{}});
  for (const glm::dvec3 direction : {glm::dvec3(0, 0, -1), glm::dvec3(1, -0.5, 0.3)}) {
    Material culled;
    culled.backfaceCulling = true;
    const Camera camera = fitCamera(spot, direction);
    const Rendered with = renderScene(oneMeshScene(spot.view(), culled, lights), camera, 400, 300);
    const Rendered without =
        renderScene(oneMeshScene(spot.view(), Material{}, lights), camera, 400, 300);
    EXPECT_GT(with.stats.polygonsCulled, spot.polygonCount() / 3);
    EXPECT_EQ(without.stats.polygonsCulled, 0u);
    EXPECT_GT(with.stats.pixelsCovered, 10000u);
    expectSamePicture(with.framebuffer, without.framebuffer);
  }
}

TEST(Culling, BackFacesOfAnOpenSurfaceDisappear) {
  Mesh square;
  for (glm::dvec3 p : {glm::dvec3{-1, -1, 0}, {-1, 1, 0}, {1, 1, 0}, {1, -1, 0}})
    square.addPoint(p);
  square.addPolygon({0, 1, 2, 3});  // clockwise seen from +z: a back face
  Material culled;
  culled.backfaceCulling = true;
  EXPECT_EQ(renderScene(oneMeshScene(square.view(), culled), topDown(), 32, 32).stats.pixelsCovered,
            0u);
  EXPECT_GT(renderScene(oneMeshScene(square.view()), topDown(), 32, 32).stats.pixelsCovered, 500u);
}

}  // namespace
}  // namespace facet::testing

namespace facet::testing {
namespace {

TEST(ClosedSurface, DetectsClosedOutwardMeshes) {
  EXPECT_TRUE(isClosedSurface(makeUvSphere(16, 12).view()));
  EXPECT_TRUE(isClosedSurface(makeBox({0, 0, 0}, {1, 2, 3}).view()));
  EXPECT_TRUE(isClosedSurface(readObj(sharedMeshPath("spot.obj")).view()));
  EXPECT_FALSE(isClosedSurface(readObj(sharedMeshPath("stanford-bunny.obj")).view()))
      << "the bunny has holes at its base";

  Mesh inverted = makeUvSphere(16, 12);  // closed but wound inward: negative volume
  for (std::size_t p = 0; p < inverted.polygonCount(); ++p) {
    std::reverse(inverted.connectivity.begin() + inverted.offsets[p],
                 inverted.connectivity.begin() + inverted.offsets[p + 1]);
  }
  EXPECT_FALSE(isClosedSurface(inverted.view()));

  Mesh open = makeBox({0, 0, 0}, {1, 1, 1});
  open.offsets.pop_back();
  open.connectivity.resize(open.offsets.back());
  EXPECT_FALSE(isClosedSurface(open.view())) << "a box without its last face";

  Mesh flipped = makeBox({0, 0, 0}, {1, 1, 1});
  std::reverse(flipped.connectivity.begin(), flipped.connectivity.begin() + 4);
  EXPECT_FALSE(isClosedSurface(flipped.view())) << "one face wound the other way";
}

TEST(ClosedSurface, SkippingHiddenBackFacesChangesNoPixel) {
  const Mesh spot = readObj(sharedMeshPath("spot.obj"));
  LightSet lights;
  lights.lights.push_back(PointLight{{3.0, 2.0, 4.0}, Color(1.0f), 1.0, NoAttenuation{}});
  MeshView closed = spot.view();
  closed.closedSurface = true;
  for (const glm::dvec3 direction : {glm::dvec3(0, 0, -1), glm::dvec3(-1, 0.4, 0.2)}) {
    const Camera camera = fitCamera(spot, direction);
    const Rendered hinted = renderScene(oneMeshScene(closed, {}, lights), camera, 400, 300);
    const Rendered plain = renderScene(oneMeshScene(spot.view(), {}, lights), camera, 400, 300);
    EXPECT_EQ(hinted.stats.closedMeshesSkippingBackFaces, 1u);
    EXPECT_GT(hinted.stats.polygonsCulled, spot.polygonCount() / 3);
    EXPECT_LT(hinted.stats.trianglesBinned, plain.stats.trianglesBinned);
    expectSamePicture(hinted.framebuffer, plain.framebuffer);
  }
}

TEST(ClosedSurface, BackFacesReturnWhenTheNearPlaneCutsTheMesh) {
  const Mesh sphere = makeUvSphere(40, 30);
  MeshView closed = sphere.view();
  closed.closedSurface = true;
  Camera camera = fitCamera(sphere);
  camera.nearClip = glm::length(camera.position - camera.focalPoint);  // through the center
  const Rendered hinted = renderScene(oneMeshScene(closed), camera, 200, 200);
  const Rendered plain = renderScene(oneMeshScene(sphere.view()), camera, 200, 200);
  EXPECT_EQ(hinted.stats.closedMeshesSkippingBackFaces, 0u);
  expectSameImage(hinted.framebuffer, plain.framebuffer);
  EXPECT_GT(hinted.stats.pixelsCovered, 5000u) << "the inside of the far half shows";
}

}  // namespace
}  // namespace facet::testing
