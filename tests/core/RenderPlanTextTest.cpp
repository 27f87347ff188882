// RenderStats::describe's text, number by number: the text std::ostringstream printed (the
// report's first implementation, before section 59 of bench/core-frame-issue11.md wrote it
// without a stream), for two stats with every field the text prints set, integers up to
// SIZE_MAX, negative ones, and doubles small, large, negative, subnormal, infinite and NaN.

#include <cstddef>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "facet/RenderPlan.h"

namespace facet::testing {
namespace {

// Two RenderStats with every field the text prints set, numbers of every shape.
facet::RenderStats describedStats(int which) {
  facet::RenderStats s;
  facet::RenderPlan& p = s.plan;
  p.width = 1920;
  p.height = 1080;
  p.threads = which == 0 ? 2 : 1;
  p.tileSize = 64;
  p.tilesX = 30;
  p.tilesY = 17;
  p.path = which == 0 ? facet::RenderPath::Full : facet::RenderPath::Reshade;
  p.pathReason = "a reason";
  p.meshes = which == 0 ? 3 : 1;
  p.polygons = 500000;
  p.points = std::numeric_limits<std::size_t>::max();
  p.parallelProjection = which == 1;
  p.visibility = which == 0 ? facet::Visibility::ZBuffer : facet::Visibility::PainterSort;
  p.depthOutput = which == 0;
  p.directLighting = which == 0;
  p.positionalLights = which == 0;
  p.specular = which == 1;
  p.polygonCenters = which == 0;
  p.viewerDirection = which == 1;
  p.twoSidedLighting = which == 1;
  p.backfaceCulling = which == 0;
  p.closedSurfaces = which == 0;
  p.rasterRoutine = "depth test";
  p.setupRoutine = "per mesh";
  p.shadeRoutine = "one light";
  p.twoPassFrame = which == 0;
  p.everyFacePolygonsPerCoveredPixel = which == 0 ? 0.1 : 1234567.0;
  p.blocksHiddenBehindFront = 17;
  p.polygonsHiddenBehindFront = 12345;
  for (int r = 0; r < facet::kRuleCount; ++r) {
    p.rules[static_cast<std::size_t>(r)].allowed = (r + which) % 3 != 0;
    p.rules[static_cast<std::size_t>(r)].fired = (r + which) % 2 == 0;
    p.rules[static_cast<std::size_t>(r)].skipped = static_cast<std::size_t>(r) * 1000003u;
  }
  p.lightCulling.lights = 8;
  p.lightCulling.dark = 1;
  p.lightCulling.outsideCone = 2;
  p.lightCulling.belowTolerance = 3;
  p.lightCulling.tolerance = which == 0 ? 1e-5 : 0.5 / 255.0;
  p.lightCulling.errorBound = which == 0 ? std::numeric_limits<double>::infinity() : 2.5e+20;
  p.lightCulling.errorBound8Bit = which == 0 ? 0 : -7;
  p.blocksTested = 977;
  p.blocksOutside = 12;
  p.blocksBackFacing = which == 0 ? 0 : 5;
  p.polygonsBackFacing = 2560;
  p.depthComplexity = which == 0 ? std::numeric_limits<double>::quiet_NaN() : 2.86116123;
  p.meanTriangleBox = which == 0 ? 296.6449 : 1e-320;
  s.validateSeconds = 4.0951e-05;
  s.transformSeconds = 0.000182702;
  s.setupSeconds = which == 0 ? 0.0 : 123.456789;
  s.rasterSeconds = -0.0136032;
  s.shadeSeconds = 1.0 / 3.0;
  s.totalSeconds = 100000.0;
  s.polygonsDrawn = 1;
  s.polygonsShaded = 2;
  s.polygonsCulled = 3;
  s.polygonsOutside = 4;
  s.polygonsDegenerate = 5;
  s.polygonsNonFinite = 6;
  s.polygonsHidden = 7;
  s.trianglesBinned = 8;
  s.trianglesClipped = 9;
  s.trianglesHidden = 10;
  s.fragmentsWritten = 849984;
  s.pixelsCovered = 0;
  s.aborted = which == 1;
  return s;
}

const char* const kStreamText[2] = {
    R"(Facet render plan: 1920x1080 pixels, 2 threads, 30x17 tiles of 64 px
  path: full render (a reason)
  scene: 3 meshes, 500000 polygons, 18446744073709551615 points; perspective projection
  visibility: z-buffer (depth test on, no sort); depth output on
  lighting: flat, once per polygon that wins a pixel; direct lights incl. point/spot; specular off (skipped)
  per polygon: normals computed, centers computed, viewer direction skipped
  two-sided lighting off, back-face culling on, back faces of closed surfaces skipped unless the near plane cuts them
  routines: raster depth test; set-up per mesh; shade one light
  every face: two passes (back faces after the front faces); 0.1 polygons per covered pixel of the previous frame (before a first frame: estimated from the blocks' projected boxes; two passes from 1); 12345 back faces hidden behind the front faces, not set up (17 whole blocks, the rest in runs of a few ids)
  rules (off / idle / fired: what each left out):
    off   lights that reach nothing: 0 lights of 8 (1 dark, 2 outside their cone, 3 at most 1e-05); error bound inf linear, 0/255: the same bytes
    idle  geometry outside the view: 1000003 polygons not transformed or set up (12 of 977 blocks tested)
    fired hidden geometry (hierarchical z): 2000006 triangles not painted (estimated depth complexity nan, mean triangle box 296.645 px)
    off   ambient only: 3000009 polygons shaded without normal or light loop
    fired one color for a whole mesh: 4000012 meshes shaded without a color fetch
    idle  closed surfaces: 5000015 closed meshes skipping back faces
    idle  back-facing blocks (with geometry outside the view): 2560 polygons counted culled, not set up (0 blocks)
  counted: 1 polygons drawn, 2 shaded, 3 culled, 4 outside, 5 degenerate, 6 non-finite, 7 hidden behind the front faces; 8 triangles binned, 9 clipped, 10 hidden; 849984 fragments, 0 pixels covered
  seconds: validate 4.0951e-05, transform 0.000182702, set-up 0, raster -0.0136032, shade 0.333333, total 100000
)",
    R"(Facet render plan: 1920x1080 pixels, 1 thread, 30x17 tiles of 64 px
  path: re-shade the previous frame (no transform, set-up or raster) (a reason)
  scene: 1 mesh, 500000 polygons, 18446744073709551615 points; parallel projection
  visibility: painter's order (centroid sort, no depth test); depth output off
  lighting: flat, once per polygon that wins a pixel; ambient only; specular on
  per polygon: normals skipped, centers skipped, viewer direction computed
  two-sided lighting on, back-face culling off, back faces of closed surfaces drawn (none marked closed)
  routines: raster depth test; set-up per mesh; shade one light
  every face: one pass; 1.23457e+06 polygons per covered pixel of the previous frame (before a first frame: estimated from the blocks' projected boxes; two passes from 1)
  rules (off / idle / fired: what each left out):
    idle  lights that reach nothing: 0 lights of 8 (1 dark, 2 outside their cone, 3 at most 0.00196078); error bound 2.5e+20 linear, -7/255
    fired geometry outside the view: 1000003 polygons not transformed or set up (12 of 977 blocks tested)
    off   hidden geometry (hierarchical z): 2000006 triangles not painted (estimated depth complexity 2.86116, mean triangle box 9.99989e-321 px)
    fired ambient only: 3000009 polygons shaded without normal or light loop
    idle  one color for a whole mesh: 4000012 meshes shaded without a color fetch
    off   closed surfaces: 5000015 closed meshes skipping back faces
    fired back-facing blocks (with geometry outside the view): 2560 polygons counted culled, not set up (5 blocks)
  counted: 1 polygons drawn, 2 shaded, 3 culled, 4 outside, 5 degenerate, 6 non-finite, 7 hidden behind the front faces; 8 triangles binned, 9 clipped, 10 hidden; 849984 fragments, 0 pixels covered; stopped early
  seconds: validate 4.0951e-05, transform 0.000182702, set-up 123.457, raster -0.0136032, shade 0.333333, total 100000
)"};

TEST(RenderPlanText, IsTheStreamsText) {
  for (int which = 0; which < 2; ++which) {
    SCOPED_TRACE(which);
    const facet::RenderStats stats = describedStats(which);
    EXPECT_EQ(stats.describe(), kStreamText[which]);
    // The plan's text opens the stats' text.
    EXPECT_EQ(stats.describe().rfind(stats.plan.describe(), 0), 0u);
  }
}

}  // namespace
}  // namespace facet::testing
