// RenderPlan::describe and RenderStats::describe: the report's text, diagnostics ([[gnu::cold]],
// optimized for size). A file of its own, out of the unity build: in the unit it shared with
// Setup.cpp, any change to the report's code moved GCC's inlining there (the report's stream
// operators once cost the set-up's bins their inline push_back, bench/core-frame-issue11.md
// section 19; this text without a stream made runTriangle a call in the set-up of float points
// and 64-bit cells, section 59).
#include "facet/RenderPlan.h"

#include <charconv>
#include <string>
#include <string_view>
#include <type_traits>

namespace facet {
namespace {

// The report's text, appended to one string: what std::ostringstream printed, without the
// stream (a locale, an ios_base, a buffer and a copy at every describe(), 35-50 µs serial
// after each frame the VTK filter renders, which puts the text in its field data; 15 µs
// without). Numbers as the stream's defaults print them: integers in decimal, floating point
// as printf's %.6g (std::to_chars' general format at precision 6 is specified as that;
// tests/core/RenderPlanTextTest.cpp holds the stream's text).
class Text {
 public:
  Text() { text_.reserve(2048); }
  Text& operator<<(const char* s) {
    text_.append(s);
    return *this;
  }
  Text& operator<<(std::string_view s) {
    text_.append(s);
    return *this;
  }
  template <class T>
  requires(std::is_integral_v<T> && !std::is_same_v<T, bool> && !std::is_same_v<T, char>) Text&
  operator<<(T value) {
    char digits[24];
    const std::to_chars_result end = std::to_chars(digits, digits + sizeof digits, value);
    text_.append(digits, end.ptr);
    return *this;
  }
  Text& operator<<(double value) {
    char digits[32];
    const std::to_chars_result end =
        std::to_chars(digits, digits + sizeof digits, value, std::chars_format::general, 6);
    text_.append(digits, end.ptr);
    return *this;
  }
  std::string take() { return std::move(text_); }

 private:
  std::string text_;
};

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

[[gnu::cold]] void describeLights(Text& out, const RenderPlan::LightCulling& l) {
  out << " (" << l.dark << " dark, " << l.outsideCone << " outside their cone, " << l.belowTolerance
      << " at most " << l.tolerance << "); error bound " << l.errorBound << " linear, "
      << l.errorBound8Bit << "/255" << (l.errorBound8Bit == 0 ? ": the same bytes" : "");
}

[[gnu::cold]] void describeRule(Text& out, const RenderPlan& plan, Rule rule) {
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
[[gnu::cold]] void describeBackFacingBlocks(Text& out, const RenderPlan& plan) {
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

[[gnu::cold]] std::string RenderPlan::describe() const {
  Text out;
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
  return out.take();
}

[[gnu::cold]] std::string RenderStats::describe() const {
  Text out;
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
  return out.take();
}

}  // namespace facet
