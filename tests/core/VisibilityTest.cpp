// Depth buffer vs painter's order, and back-face culling.

#include <algorithm>
#include <map>
#include <random>
#include <utility>
#include <vector>

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

// The definition, written the plain way: every polygon has 3 points or more, every directed
// edge a -> b is no loop, appears once, and so does b -> a; and the signed volume is positive.
bool closedByDefinition(const Mesh& mesh) {
  std::map<std::pair<std::int64_t, std::int64_t>, int> directed;
  double volume = 0.0;
  glm::dvec3 center(0.0);
  for (const glm::dvec3& p : mesh.points)
    center += p / static_cast<double>(mesh.points.size());
  for (std::size_t p = 0; p < mesh.polygonCount(); ++p) {
    const std::int64_t* ids = mesh.connectivity.data() + mesh.offsets[p];
    const std::int64_t n = mesh.offsets[p + 1] - mesh.offsets[p];
    if (n < 3) return false;
    for (std::int64_t k = 0; k < n; ++k)
      ++directed[{ids[k], ids[(k + 1) % n]}];
    for (std::int64_t k = 1; k + 1 < n; ++k) {
      volume +=
          glm::dot(mesh.points[ids[0]] - center,
                   glm::cross(mesh.points[ids[k]] - center, mesh.points[ids[k + 1]] - center));
    }
  }
  for (const auto& [edge, count] : directed) {
    const auto twin = directed.find({edge.second, edge.first});
    if (edge.first == edge.second || count != 1 || twin == directed.end() || twin->second != 1)
      return false;
  }
  return !mesh.connectivity.empty() && volume > 0.0;
}

Mesh withPolygons(const Mesh& mesh, const std::vector<std::vector<std::int64_t>>& polygons) {
  Mesh out;
  out.points = mesh.points;
  for (const auto& polygon : polygons)
    out.addPolygon(polygon);
  return out;
}

std::vector<std::vector<std::int64_t>> polygonsOf(const Mesh& mesh) {
  std::vector<std::vector<std::int64_t>> polygons;
  for (std::size_t p = 0; p < mesh.polygonCount(); ++p) {
    polygons.emplace_back(mesh.connectivity.begin() + mesh.offsets[p],
                          mesh.connectivity.begin() + mesh.offsets[p + 1]);
  }
  return polygons;
}

TEST(ClosedSurface, NonManifoldAndDegenerateMeshes) {
  // Outward tetrahedra: (0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1), points 0 to 3, and
  // a second one (a) beside it, (b) moved by (1, 0, 0) to touch it at point 1 only (a pinched
  // surface: every edge still has its two faces) and (c) turned 180 degrees about the first's
  // edge 0-3 (four faces at that edge).
  const std::vector<std::vector<std::int64_t>> faces{{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  const auto twoTetrahedra = [&](const std::vector<glm::dvec3>& second,
                                 const std::vector<std::int64_t>& secondIds) {
    Mesh mesh;
    for (glm::dvec3 p : {glm::dvec3{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}})
      mesh.addPoint(p);
    for (glm::dvec3 p : second)
      mesh.addPoint(p);
    for (const auto& face : faces)
      mesh.addPolygon(face);
    for (const auto& face : faces)
      mesh.addPolygon({secondIds[face[0]], secondIds[face[1]], secondIds[face[2]]});
    return mesh;
  };
  const Mesh apart = twoTetrahedra({{3, 0, 0}, {4, 0, 0}, {3, 1, 0}, {3, 0, 1}}, {4, 5, 6, 7});
  const Mesh pinched = twoTetrahedra({{2, 0, 0}, {1, 1, 0}, {1, 0, 1}}, {1, 4, 5, 6});
  const Mesh fourFacesAtAnEdge = twoTetrahedra({{-1, 0, 0}, {0, -1, 0}}, {0, 4, 5, 3});
  EXPECT_TRUE(isClosedSurface(apart.view()));
  EXPECT_TRUE(isClosedSurface(pinched.view())) << "pinched at a point, closed edge by edge";
  EXPECT_FALSE(isClosedSurface(fourFacesAtAnEdge.view()));
  for (const Mesh* mesh : {&apart, &pinched, &fourFacesAtAnEdge})
    EXPECT_EQ(isClosedSurface(mesh->view()), closedByDefinition(*mesh));

  const Mesh box = makeBox({0, 0, 0}, {1, 1, 1});
  const auto boxFaces = polygonsOf(box);
  auto twice = boxFaces;
  twice.push_back(boxFaces[0]);
  EXPECT_FALSE(isClosedSurface(withPolygons(box, twice).view())) << "a face drawn twice";
  auto sliver = boxFaces;
  sliver.push_back({boxFaces[0].rbegin(), boxFaces[0].rend()});
  sliver.push_back(boxFaces[0]);
  EXPECT_FALSE(isClosedSurface(withPolygons(box, sliver).view())) << "a two-sided sliver added";
  auto loop = boxFaces;
  loop[0] = {loop[0][0], loop[0][0], loop[0][1], loop[0][2]};
  EXPECT_FALSE(isClosedSurface(withPolygons(box, loop).view())) << "a repeated corner";
  auto line = boxFaces;
  line.push_back({0, 1});
  EXPECT_FALSE(isClosedSurface(withPolygons(box, line).view())) << "a 2-point polygon";
  EXPECT_FALSE(isClosedSurface(withPolygons(box, {}).view())) << "no polygons";
}

// Triangle strips as the VTK filter hands them over (vtkTriangleStrip::DecomposeStrip: odd
// triangles swap their first two points): a sphere's bands as strips, its caps as triangles,
// is closed; without its last strip triangle it is not.
TEST(ClosedSurface, StripTrianglesOfASphere) {
  const int theta = 12, rings = 6;
  const Mesh sphere = makeUvSphere(theta, rings + 2);
  const auto at = [&](int ring, int i) -> std::int64_t { return 2 + ring * theta + i % theta; };
  std::vector<std::vector<std::int64_t>> triangles;
  for (int i = 0; i < theta; ++i) {
    triangles.push_back({0, at(0, i), at(0, i + 1)});
    triangles.push_back({1, at(rings - 1, i + 1), at(rings - 1, i)});
  }
  for (int ring = 0; ring + 1 < rings; ++ring) {
    std::vector<std::int64_t> strip;
    for (int i = 0; i <= theta; ++i)
      strip.insert(strip.end(), {at(ring, i), at(ring + 1, i)});
    for (std::size_t k = 0; k + 2 < strip.size(); ++k) {
      const bool odd = k % 2 == 1;
      triangles.push_back(
          {odd ? strip[k + 1] : strip[k], odd ? strip[k] : strip[k + 1], strip[k + 2]});
    }
  }
  const Mesh strips = withPolygons(sphere, triangles);
  EXPECT_TRUE(isClosedSurface(strips.view()));
  EXPECT_TRUE(closedByDefinition(strips));
  triangles.pop_back();
  EXPECT_FALSE(isClosedSurface(withPolygons(sphere, triangles).view()));
}

// Random edits of closed meshes (a face flipped, dropped, doubled or split off, points merged,
// corners rotated, faces shuffled): the check agrees with the definition every time, with
// 64- and 32-bit connectivity.
TEST(ClosedSurface, AgreesWithTheDefinitionOnRandomEdits) {
  std::mt19937 random(11);
  const Mesh sphere = makeUvSphere(9, 7), box = makeBox({0, 0, 0}, {1, 2, 3});
  const Mesh spot = readObj(sharedMeshPath("spot.obj"));  // 5856 triangles: one trial in ten
  int closedSeen = 0, openSeen = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const Mesh& base = trial % 10 == 9 ? spot : trial % 2 == 0 ? sphere : box;
    auto faces = polygonsOf(base);
    const auto pick = [&](std::size_t n) {
      return std::uniform_int_distribution<std::size_t>(0, n - 1)(random);
    };
    const std::size_t f = pick(faces.size());
    switch (trial / 2 % 7) {
      case 0:
        std::reverse(faces[f].begin(), faces[f].end());
        break;
      case 1:
        faces.erase(faces.begin() + static_cast<std::ptrdiff_t>(f));
        break;
      case 2:
        faces.push_back(faces[f]);
        break;
      case 3:
        faces[f][pick(faces[f].size())] = faces[f][pick(faces[f].size())];
        break;
      case 4: {
        const std::int64_t from = static_cast<std::int64_t>(pick(base.points.size()));
        const std::int64_t to = static_cast<std::int64_t>(pick(base.points.size()));
        for (auto& face : faces)
          std::replace(face.begin(), face.end(), from, to);
        break;
      }
      case 5:
        std::rotate(faces[f].begin(), faces[f].begin() + 1, faces[f].end());
        break;
      default:
        std::shuffle(faces.begin(), faces.end(), random);
        break;
    }
    const Mesh edited = withPolygons(base, faces);
    const bool expected = closedByDefinition(edited);
    (expected ? closedSeen : openSeen) += 1;
    ASSERT_EQ(isClosedSurface(edited.view()), expected) << "trial " << trial;
    const std::vector<std::int32_t> offsets(edited.offsets.begin(), edited.offsets.end());
    const std::vector<std::int32_t> ids(edited.connectivity.begin(), edited.connectivity.end());
    MeshView narrow = edited.view();
    narrow.polygons = PolygonArray::of(offsets, ids);
    ASSERT_EQ(isClosedSurface(narrow), expected) << "trial " << trial << ", 32-bit ids";
  }
  EXPECT_GT(closedSeen, 50);  // both answers exercised
  EXPECT_GT(openSeen, 50);
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
