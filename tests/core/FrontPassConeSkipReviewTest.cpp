// review26: the front pass's whole-block deferral (SetupContext::deferCertainBackBlocks) and the
// one key rule for back faces (every26) against scenes the every27 test does not reach: several
// versioned meshes (chunks of each), quads mixed with triangles, a mesh cut by the near plane,
// the eye inside a mesh, parallel projection, one-sided lighting. Each must give one pass's
// bytes and counts (polygonsHidden aside) and the skip-off two-pass frame's bytes and counts.

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "../support/SameRender.h"
#include "../support/Sanitizers.h"
#include "../support/TestMeshes.h"
#include "../support/TestRender.h"
#include "../support/TwoPassScenes.h"

namespace facet::testing {
namespace {

class FrontPassConeSkipReview : public TwoPassTest {};

struct ConeSkipView {
  std::string name;
  Camera camera;
  bool twoSided = true;
};

void expectOnePassCountsOf(const Rendered& one, const Rendered& two) {
  EXPECT_EQ(differingPixels(one.framebuffer, two.framebuffer), 0u) << "pixels differ";
  const RenderStats &s = one.stats, &t = two.stats;
  EXPECT_EQ(s.polygonsDrawn + s.polygonsOutside + s.polygonsDegenerate,
            t.polygonsDrawn + t.polygonsOutside + t.polygonsDegenerate + t.polygonsHidden);
  EXPECT_EQ(s.polygonsCulled, t.polygonsCulled);
  EXPECT_EQ(s.polygonsNonFinite, t.polygonsNonFinite);
  EXPECT_EQ(s.fragmentsWritten, t.fragmentsWritten);
  EXPECT_EQ(s.pixelsCovered, t.pixelsCovered);
}

TEST_F(FrontPassConeSkipReview, ManyMeshesClippedInsideAndParallelRenderAsOnePass) {
  const Mesh a = makeUvSphere(300, 302);
  Mesh b = makeUvSphere(200, 202, 0.6);
  for (auto& p : b.points)
    p += glm::dvec3(0.9, 0.3, -0.5);
  const Mesh box = makeBox({-1.5, -1.5, -2.0}, {1.5, 1.5, -1.6});  // quads
  std::vector<MeshView> views = {a.view(), b.view(), box.view()};
  for (std::size_t i = 0; i < views.size(); ++i)
    views[i].version = i + 1;  // measured: cones and boxes
  Scene scene;
  for (const MeshView& v : views)
    scene.meshes.push_back({v, {}});

  std::vector<ConeSkipView> cases;
  cases.push_back({"fit", fitCamera(a, glm::dvec3(-0.6, -0.2, -1.0))});
  Camera near = cases[0].camera;
  near.nearClip = glm::length(near.position - near.focalPoint) - 0.5;  // cuts sphere a
  cases.push_back({"near plane cuts", near});
  Camera inside;
  inside.position = {0.1, 0.05, 0.2};
  inside.focalPoint = {0.1, 0.05, -1.0};
  inside.viewAngleDegrees = 70.0;
  cases.push_back({"eye inside", inside});
  Camera parallel = cases[0].camera;
  parallel.parallelProjection = true;
  parallel.parallelScale = 1.6;
  cases.push_back({"parallel", parallel});
  cases.push_back({"one-sided lighting", cases[0].camera, false});

  for (const ConeSkipView& c : cases) {
    for (int threads : threadCountsToRun({1, 3})) {
      SCOPED_TRACE(c.name + ", " + std::to_string(threads) + " threads");
      RenderOptions options = optionsWith(threads);
      options.twoSidedLighting = c.twoSided;
      detail::enableTwoPassFrames(false);
      const Rendered one = renderScene(scene, c.camera, 320, 240, options);
      detail::enableTwoPassFrames(true);
      detail::enableFrontPassConeSkip(false);
      const Rendered classified = renderScene(scene, c.camera, 320, 240, options);
      detail::enableFrontPassConeSkip(true);
      std::size_t deferred = 0;
      renderOnEveryTarget(scene, c.camera, 320, 240, options,
                          [&](const Rendered& skipped, const detail::HiddenBlockCounts& counts) {
                            ASSERT_TRUE(skipped.stats.plan.twoPassFrame);
                            expectSameRender(classified, skipped);
                            expectOnePassCountsOf(one, skipped);
                            deferred += counts.deferredWhole;
                          });
      EXPECT_GT(one.stats.pixelsCovered, 1000u);
      EXPECT_GT(deferred, 0u);  // the skip acted
    }
  }
}

}  // namespace
}  // namespace facet::testing
