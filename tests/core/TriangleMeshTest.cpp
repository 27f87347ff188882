// Meshes known to be all triangles (MeshFacts::allTriangles): the fact is measured per mesh
// version, false for any other polygon, and the shade that reads such a mesh's corners
// without its offsets gives the bytes of the shade that reads them through the offsets.

#include <vector>

#include <gtest/gtest.h>

#include "../support/TestMeshes.h"
#include "../support/TestRender.h"
#include "MeshCache.h"
#include "PhaseRunner.h"
#include "ThreadPool.h"

namespace facet::testing {
namespace {

// The fact MeshCache measures for a mesh given as `view`.
bool measuredAllTriangles(const MeshView& view) {
  detail::ThreadPool pool(2);
  const detail::PhaseRunner::ProgressCallback noProgress;
  detail::PhaseRunner runner(pool, noProgress, detail::phasesOf(RenderPath::Full));
  detail::MeshCache cache;
  const Scene scene = oneMeshScene(view);
  EXPECT_TRUE(cache.update(runner, scene, false));
  return cache[0].allTriangles;
}

// A sphere of 20,000 triangles with one of them (at `at`) and the next made one quad.
Mesh sphereWithQuadAt(std::size_t at) {
  const Mesh sphere = makeUvSphere(100, 102);
  Mesh mesh;
  mesh.points = sphere.points;
  for (std::size_t p = 0; p < sphere.polygonCount(); ++p) {
    const auto* ids = sphere.connectivity.data() + sphere.offsets[p];
    if (p == at) {
      const auto* next = ids + 3;  // the two triangles share an edge: quad a b c d
      mesh.addPolygon({ids[0], ids[1], ids[2], next[2] == ids[0] ? next[1] : next[2]});
      ++p;
      continue;
    }
    mesh.addPolygon({ids[0], ids[1], ids[2]});
  }
  return mesh;
}

TEST(TriangleMeshes, AllTrianglesIsMeasuredPerVersionAndFalseForAnyOtherPolygon) {
  const Mesh sphere = makeUvSphere(100, 102);
  MeshView view = sphere.view();
  EXPECT_FALSE(measuredAllTriangles(view)) << "an unversioned mesh is not measured";
  view.version = 1;
  EXPECT_TRUE(measuredAllTriangles(view));
  // A quad first, in the middle (another measuring task's blocks) and last.
  for (const std::size_t at : {std::size_t{0}, std::size_t{10'001}, sphere.polygonCount() - 2}) {
    const Mesh withQuad = sphereWithQuadAt(at);
    MeshView quadView = withQuad.view();
    quadView.version = 1;
    EXPECT_FALSE(measuredAllTriangles(quadView)) << "quad at " << at;
  }
  EXPECT_FALSE(measuredAllTriangles(makeBox({0, 0, 0}, {1, 1, 1}).view()));
}

// Point lights (lit at centers), directional lights (by directions) and both, diffuse and
// specular: a versioned triangle mesh gives the bytes of the same mesh unversioned (its
// corners read through its offsets), on 1 and 2 threads. The diffuse renders under one kind
// of light shade in batches, the routine that reads a triangle mesh without its offsets.
TEST(TriangleMeshes, ShadingWithoutOffsetsGivesTheSameBytes) {
  const Mesh sphere = makeUvSphere(120, 122);
  const Camera camera = fitCamera(sphere, {-0.3, -0.2, -1.0});
  PointLight unattenuated{{1.5, 1.0, 2.0}, Color(0.9f), 1.0};
  unattenuated.attenuation = NoAttenuation{};  // the point lights ShadeBatch.h takes
  const Light point = unattenuated;
  const Light directional = DirectionalLight{{-1, -0.5, -1}, Color(0.6f), 1.0};
  for (const std::vector<Light>& lightList :
       {std::vector{point}, std::vector{directional}, std::vector{point, directional}}) {
    LightSet lights;
    lights.lights = lightList;
    for (const bool specular : {false, true}) {
      Material material;
      material.specular = specular ? 0.5 : 0.0;
      for (const int threads : {1, 2}) {
        RenderOptions options;
        options.threads = threads;
        MeshView unversioned = sphere.view();
        MeshView versioned = unversioned;
        versioned.version = 1;
        const Rendered read =
            renderScene(oneMeshScene(unversioned, material, lights), camera, 320, 240, options);
        const Rendered known =
            renderScene(oneMeshScene(versioned, material, lights), camera, 320, 240, options);
        ASSERT_GT(known.stats.polygonsShaded, 1000u);
        EXPECT_EQ(differingPixels(known.framebuffer, read.framebuffer), 0u)
            << lightList.size() << " lights, specular " << specular << ", " << threads
            << " threads";
      }
    }
  }
}

}  // namespace
}  // namespace facet::testing
