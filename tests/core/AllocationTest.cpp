// Re-rendering the same scene at the same size allocates nothing: every global operator new
// is counted, and the second render must not call it.

#include <atomic>
#include <cstdlib>
#include <new>

#include <gtest/gtest.h>

#include "../support/TestMeshes.h"
#include "../support/TestRender.h"

namespace {
std::atomic<std::size_t> allocations{0};
}

// GCC 12 with optimization takes the free() in these replacement operators for a mismatch
// with the operator new they replace (a false positive: both sides are these, on malloc).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void* operator new(std::size_t size) {
  allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}
void* operator new(std::size_t size, std::align_val_t alignment) {
  allocations.fetch_add(1, std::memory_order_relaxed);
  const std::size_t a = static_cast<std::size_t>(alignment);
  if (void* p = std::aligned_alloc(a, (size + a - 1) / a * a)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p, std::align_val_t) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t, std::align_val_t) noexcept {
  std::free(p);
}
#pragma GCC diagnostic pop

namespace facet::testing {
namespace {

TEST(Allocation, SecondRenderOfTheSameSceneAllocatesNothing) {
  const Mesh bunny = readObj(sharedMeshPath("stanford-bunny.obj"));
  const Mesh beast = readObj(sharedMeshPath("beast.obj"));  // quads and n-gons, too
  LightSet lights;
  lights.lights.push_back(PointLight{{0.3, 0.4, 0.5}, Color(1.0f), 1.0, QuadraticAttenuation{}});
  lights.lights.push_back(SpotLight{});
  Material material;
  material.specular = 0.3;
  Scene scene = oneMeshScene(bunny.view(), material, lights);
  for (Visibility visibility : {Visibility::ZBuffer, Visibility::PainterSort}) {
    Renderer renderer;
    renderer.setThreadCount(2);
    renderer.setVisibility(visibility);
    Framebuffer fb(320, 240);
    Camera camera = fitCamera(bunny);
    camera.nearClip *= 1.2;  // clip too
    // The first render knows no covered pixels (and the near plane cuts the bunny's boxes, so
    // no estimate: the image's pixels): the plan may take two passes from the second on
    // (chooseTwoPassFrame, Plan.h), which then allocates their buffers once; the render after
    // a render of the same plan allocates nothing.
    renderer.render(scene, camera, fb);
    const bool settled = renderer.render(scene, camera, fb).plan.twoPassFrame;
    EXPECT_EQ(settled, visibility == Visibility::ZBuffer);  // 70k polygons, ~20k pixels covered
    const std::size_t before = allocations.load();
    const RenderStats stats = renderer.render(scene, camera, fb);
    EXPECT_EQ(allocations.load() - before, 0u);
    EXPECT_GT(stats.trianglesClipped, 0u);

    Scene ngons = oneMeshScene(beast.view(), material, lights);
    const Camera beastCamera = fitCamera(beast);
    renderer.render(ngons, beastCamera, fb);
    renderer.render(ngons, beastCamera, fb);  // the plan settled (above)
    const std::size_t beforeNgons = allocations.load();
    renderer.render(ngons, beastCamera, fb);
    EXPECT_EQ(allocations.load() - beforeNgons, 0u);
  }
}

}  // namespace
}  // namespace facet::testing
