#include "facet/RenderPlan.h"

#include <sstream>

// The report's functions are [[gnu::cold]]: diagnostics, optimized for size. This file shares a
// unity translation unit with Setup.cpp, and GCC's inline-unit-growth budget is per unit: the
// report's inlined stream operators spent what the set-up's settle() needs to keep its bins'
// push_back inline (bench/core-frame-issue11.md, section 19: +6 M instructions a frame at 500k).
namespace facet {
namespace {

const char* onOff(bool value) {
  return value ? "on" : "off";
}
const char* doneOrSkipped(bool value) {
  return value ? "computed" : "skipped";
}

const char* pathName(RenderPath path) {
  switch (path) {
    case RenderPath::Full:
      return "full render";
    case RenderPath::Reshade:
      return "re-shade the previous frame (no transform, set-up or raster)";
    case RenderPath::Resolve:
      return "resolve the previous frame's colors only";
  }
  return "";
}

// What each rule counts when it fires.
const char* unitOf(Rule rule) {
  switch (rule) {
    case Rule::LightsThatReachNothing:
      return "lights";
    case Rule::GeometryOutsideView:
      return "polygons not transformed or set up";
    case Rule::HiddenGeometry:
      return "triangles not painted";
    case Rule::AmbientOnly:
      return "polygons shaded without normal or light loop";
    case Rule::OneColor:
      return "meshes shaded without a color fetch";
    case Rule::ClosedSurfaces:
      return "closed meshes skipping back faces";
  }
  return "";
}

[[gnu::cold]] void describeLights(std::ostream& out, const RenderPlan::LightCulling& l) {
  out << " (" << l.dark << " dark, " << l.outsideCone << " outside their cone, " << l.belowTolerance
      << " at most " << l.tolerance << "); error bound " << l.errorBound << " linear, "
      << l.errorBound8Bit << "/255" << (l.errorBound8Bit == 0 ? ": the same bytes" : "");
}

[[gnu::cold]] void describeRule(std::ostream& out, const RenderPlan& plan, Rule rule) {
  const RuleOutcome& outcome = plan.rule(rule);
  out << "    "
      << (!outcome.allowed ? "off   "
          : outcome.fired  ? "fired "
                           : "idle  ")
      << ruleName(rule) << ": " << outcome.skipped << " " << unitOf(rule);
  if (rule == Rule::LightsThatReachNothing) {
    out << " of " << plan.lightCulling.lights;
    describeLights(out, plan.lightCulling);
  } else if (rule == Rule::GeometryOutsideView) {
    out << " (" << plan.blocksOutside << " of " << plan.blocksTested << " blocks tested)";
  } else if (rule == Rule::HiddenGeometry) {
    out << " (estimated depth complexity " << plan.depthComplexity << ", mean triangle box "
        << plan.meanTriangleBox << " px)";
  }
  out << "\n";
}

// The back-facing blocks skipped with Rule::GeometryOutsideView: a line of their own, as
// their polygons are counted culled, not outside.
[[gnu::cold]] void describeBackFacingBlocks(std::ostream& out, const RenderPlan& plan) {
  const bool allowed = plan.rule(Rule::GeometryOutsideView).allowed;
  out << "    "
      << (!allowed                    ? "off   "
          : plan.blocksBackFacing > 0 ? "fired "
                                      : "idle  ")
      << "back-facing blocks (with " << ruleName(Rule::GeometryOutsideView)
      << "): " << plan.polygonsBackFacing << " polygons counted culled, not set up ("
      << plan.blocksBackFacing << " blocks)\n";
}

}  // namespace

const char* ruleName(Rule rule) {
  switch (rule) {
    case Rule::LightsThatReachNothing:
      return "lights that reach nothing";
    case Rule::GeometryOutsideView:
      return "geometry outside the view";
    case Rule::HiddenGeometry:
      return "hidden geometry (hierarchical z)";
    case Rule::AmbientOnly:
      return "ambient only";
    case Rule::OneColor:
      return "one color for a whole mesh";
    case Rule::ClosedSurfaces:
      return "closed surfaces";
  }
  return "";
}

bool RenderRules::allows(Rule rule) const {
  switch (rule) {
    case Rule::LightsThatReachNothing:
      return lightsThatReachNothing;
    case Rule::GeometryOutsideView:
      return geometryOutsideView;
    case Rule::HiddenGeometry:
      return hiddenGeometry != HierarchicalZ::Off;
    case Rule::AmbientOnly:
      return ambientOnly;
    case Rule::OneColor:
      return oneColor;
    case Rule::ClosedSurfaces:
      return closedSurfaces;
  }
  return false;
}

[[gnu::cold]] std::string RenderPlan::describe() const {
  std::ostringstream out;
  out << "Facet render plan: " << width << "x" << height << " pixels, " << threads
      << (threads == 1 ? " thread, " : " threads, ") << tilesX << "x" << tilesY << " tiles of "
      << tileSize << " px\n";
  out << "  path: " << pathName(path) << " (" << pathReason << ")\n";
  out << "  scene: " << meshes << (meshes == 1 ? " mesh, " : " meshes, ") << polygons
      << " polygons, " << points << " points; " << (parallelProjection ? "parallel" : "perspective")
      << " projection\n";
  out << "  visibility: "
      << (visibility == Visibility::ZBuffer ? "z-buffer (depth test on, no sort)"
                                            : "painter's order (centroid sort, no depth test)")
      << "; depth output " << onOff(depthOutput) << "\n";
  out << "  lighting: flat, once per polygon that wins a pixel; "
      << (directLighting
              ? (positionalLights ? "direct lights incl. point/spot" : "directional lights only")
              : "ambient only")
      << "; specular " << (specular ? "on" : "off (skipped)") << "\n";
  out << "  per polygon: normals " << doneOrSkipped(directLighting) << ", centers "
      << doneOrSkipped(polygonCenters) << ", viewer direction " << doneOrSkipped(viewerDirection)
      << "\n";
  out << "  two-sided lighting " << onOff(twoSidedLighting) << ", back-face culling "
      << onOff(backfaceCulling) << ", back faces of closed surfaces "
      << (closedSurfaces ? "skipped unless the near plane cuts them" : "drawn (none marked closed)")
      << "\n";
  out << "  routines: raster " << rasterRoutine << "; set-up " << setupRoutine << "; shade "
      << shadeRoutine << "\n";
  out << "  every face: "
      << (twoPassFrame ? "two passes (back faces after the front faces)" : "one pass") << "; "
      << everyFacePolygonsPerCoveredPixel
      << " polygons per covered pixel of the previous frame (before a first frame: estimated from "
         "the blocks' projected boxes; two passes from 1)";
  if (twoPassFrame)
    out << "; " << polygonsHiddenBehindFront << " back faces hidden behind the front faces, not "
        << "set up (" << blocksHiddenBehindFront << " whole blocks, the rest in runs of a few ids)";
  out << "\n";
  out << "  rules (off / idle / fired: what each left out):\n";
  for (int r = 0; r < kRuleCount; ++r)
    describeRule(out, *this, static_cast<Rule>(r));
  describeBackFacingBlocks(out, *this);
  return out.str();
}

[[gnu::cold]] std::string RenderStats::describe() const {
  std::ostringstream out;
  out << plan.describe();
  out << "  counted: " << polygonsDrawn << " polygons drawn, " << polygonsShaded << " shaded, "
      << polygonsCulled << " culled, " << polygonsOutside << " outside, " << polygonsDegenerate
      << " degenerate, " << polygonsNonFinite << " non-finite, " << polygonsHidden
      << " hidden behind the front faces; " << trianglesBinned << " triangles binned, "
      << trianglesClipped << " clipped, " << trianglesHidden << " hidden; " << fragmentsWritten
      << " fragments, " << pixelsCovered << " pixels covered" << (aborted ? "; stopped early" : "")
      << "\n";
  out << "  seconds: validate " << validateSeconds << ", transform " << transformSeconds
      << ", set-up " << setupSeconds << ", raster " << rasterSeconds << ", shade " << shadeSeconds
      << ", total " << totalSeconds << "\n";
  return out.str();
}

}  // namespace facet
