#pragma once

/// @file RenderPlan.h
/// The work a render does, decided once from the scene and from what changed since the
/// previous render ("leave out what the scene does not need"), the rules that left work
/// out, and what the render then counted and cost.

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>

#include "facet/Scene.h"

namespace facet {

/// The rules that leave out work a scene does not need. Each leaves every pixel as it was
/// (tests/core/RulesTest.cpp), except LightsThatReachNothing with a tolerance above 0, which
/// stays within the bound the plan reports.
enum class Rule {
  /// Lights that reach no mesh are left out of the shading: zero intensity or black color, a
  /// spot cone that misses every mesh's bounding box, a positional light whose attenuated
  /// contribution over the boxes is at most RenderRules::lightTolerance.
  LightsThatReachNothing,
  /// Blocks of 1024 polygons whose bounding box lies outside the view are neither transformed
  /// nor set up (versioned meshes: the boxes are kept per MeshView::version).
  GeometryOutsideView,
  /// Hierarchical z: a triangle wholly behind what the 8 × 8 pixel blocks it overlaps already
  /// show is not painted.
  HiddenGeometry,
  /// Without direct light: no normals, no light loop, one shade per color value.
  AmbientOnly,
  /// A mesh without per-polygon colors is shaded without fetching a color per polygon.
  OneColor,
  /// The back faces of closed meshes (MeshView::closedSurface) are skipped while the near
  /// plane does not cut them.
  ClosedSurfaces,
};
inline constexpr int kRuleCount = 6;

/// The rule's name, as describe() prints it.
const char* ruleName(Rule rule);

/// When hierarchical z runs.
enum class HierarchicalZ {
  Off,
  /// When the set-up's estimate of depth complexity says it pays (RenderPlan::depthComplexity).
  Auto,
  On,
};

/// Which rules may fire. All are on by default; a rule turned off makes the renderer do that
/// work anyway, for the same image, which is how bench/ measures what each one saves.
struct RenderRules {
  bool lightsThatReachNothing = true;  ///< (default: on)
  /// A positional light is left out when its contribution to any channel of any polygon is
  /// at most this, in linear color units ([0, 1] is black to full). The plan reports the
  /// bound on the error this introduces (RenderPlan::LightCulling). 0 leaves out only lights
  /// that contribute nothing at all. (default: 0)
  double lightTolerance = 0.0;
  /// Blocks of polygons outside the view are not transformed or set up; with it, so are the
  /// blocks of back faces certain to be culled (a mesh that skips its back faces: a closed
  /// surface, or a culling material), reported as RenderPlan::blocksBackFacing. (default: on)
  bool geometryOutsideView = true;
  HierarchicalZ hiddenGeometry = HierarchicalZ::Auto;  ///< (default: Auto)
  bool ambientOnly = true;                             ///< (default: on)
  bool oneColor = true;                                ///< (default: on)
  bool closedSurfaces = true;                          ///< (default: on)
  /// Reuse the previous frame when only the lights, materials, colors or background changed
  /// (see Renderer::render, "Incremental rendering"). (default: on)
  bool incremental = true;

  bool allows(Rule rule) const;
  friend bool operator==(const RenderRules&, const RenderRules&) = default;
};

/// How much of the previous frame a render reused.
enum class RenderPath {
  Full,     ///< every phase ran
  Reshade,  ///< only the lights, materials, colors or two-sided lighting changed: shade, resolve
  Resolve,  ///< only the background changed, or nothing: the pixels' colors, from kept colors
};

/// What one rule did in one render.
struct RuleOutcome {
  bool allowed = false;     ///< RenderRules lets it fire
  bool fired = false;       ///< it left work out
  std::size_t skipped = 0;  ///< how much: lights, polygons, triangles, shades or back faces
};

/// Which code paths a render takes, and why. Every flag that is false is work skipped.
struct RenderPlan {
  /// Which path ran and why ("first render", "the camera changed", ...).
  RenderPath path = RenderPath::Full;
  const char* pathReason = "";

  Visibility visibility = Visibility::ZBuffer;
  bool depthTest = true;     ///< z-buffer mode
  bool sortByDepth = false;  ///< painter mode: sort polygons by centroid depth
  /// Some light other than the ambient one reaches the scene. Without one, a polygon's color
  /// does not depend on its orientation: no normal is computed, and a mesh without
  /// per-polygon colors is shaded once for all its polygons.
  bool directLighting = false;
  bool positionalLights = false;  ///< point or spot lights: per-polygon distance and angle
  bool specular = false;          ///< some material has Ks > 0 under a direct light
  /// Polygons seen from their back (Conventions.h, "Facing") are lit with the normal flipped.
  bool twoSidedLighting = true;
  /// The direction to the viewer is needed (specular).
  bool viewerDirection = false;
  /// Polygon centers are needed (positional lights, or a perspective viewer direction).
  bool polygonCenters = false;
  bool backfaceCulling = false;  ///< some material culls back faces
  /// Some mesh is marked MeshView::closedSurface: its back faces are skipped in frames where
  /// the near plane does not cut it (RenderStats::closedMeshesSkippingBackFaces).
  bool closedSurfaces = false;
  bool parallelProjection = false;
  bool depthOutput = true;  ///< window depth written (Renderer::setDepthOutput)

  /// The rules, indexed by Rule.
  std::array<RuleOutcome, kRuleCount> rules{};
  const RuleOutcome& rule(Rule r) const { return rules[static_cast<int>(r)]; }
  RuleOutcome& rule(Rule r) { return rules[static_cast<int>(r)]; }

  /// What Rule::LightsThatReachNothing left out, and the error it may introduce.
  struct LightCulling {
    std::size_t lights = 0;          ///< direct lights in the scene
    std::size_t dark = 0;            ///< zero intensity or black color
    std::size_t outsideCone = 0;     ///< spot lights whose cone misses every mesh
    std::size_t belowTolerance = 0;  ///< contribution at most the tolerance (or exactly 0)
    std::uint64_t culledMask = 0;    ///< bit i: LightSet::lights[i] was left out (i < 64)
    double tolerance = 0.0;          ///< RenderRules::lightTolerance
    /// The largest change the lights left out can make to a channel, in linear units (the
    /// sum of their bounds), and the same on 8-bit output: ⌊255·bound⌋ + 1 when the bound is
    /// above 0 (the rounding to bytes may tip one step), else 0: the same bytes.
    double errorBound = 0.0;
    int errorBound8Bit = 0;
  } lightCulling;

  /// Rule::GeometryOutsideView: blocks of polygons tested and found outside the view.
  std::size_t blocksTested = 0, blocksOutside = 0;
  /// Blocks of back faces of meshes that skip them, each certain to be culled whole, not set
  /// up (their polygons are counted as culled, RenderStats::polygonsCulled), with their
  /// points not transformed unless a drawn block uses them; allowed with
  /// Rule::GeometryOutsideView, reported on a line of its own. `polygonsBackFacing`: the
  /// polygons in them.
  std::size_t blocksBackFacing = 0, polygonsBackFacing = 0;
  /// Rule::HiddenGeometry's estimate: the pixels of the triangles' bounding boxes over the
  /// image's pixels (known once set up). Hierarchical z pays where the triangles are large
  /// and overlap many times.
  double depthComplexity = 0.0;
  double meanTriangleBox = 0.0;  ///< pixels in the average triangle's bounding box

  /// Every face drawn (meshes not skipping back faces) in two passes: the front faces painted
  /// first, then the back faces set up against them, whole blocks (and runs of a few ids) of
  /// back faces that the front faces hide everywhere dropped before set-up (their polygons counted
  /// hidden, RenderStats::polygonsHidden, never painted: none could change a pixel). Chosen when
  /// those meshes have at least one polygon per pixel the previous frame covered
  /// (`everyFacePolygonsPerCoveredPixel`; before a first frame, the pixels of the 8 × 8 cells
  /// the meshes' blocks' projected boxes touch, or the image's when a mesh has no bounds),
  /// where the set-up and painting saved outweigh the depth and id planes' second pass.
  bool twoPassFrame = false;
  double everyFacePolygonsPerCoveredPixel = 0.0;
  std::size_t blocksHiddenBehindFront = 0, polygonsHiddenBehindFront = 0;

  /// The routines chosen for this render (llvmpipe's habit: pick the routine once, not test
  /// per triangle or pixel): painting a tile, setting up a mesh's polygons and shading them.
  /// "per mesh" when meshes differ; the set-up's is known once the render has transformed.
  const char* rasterRoutine = "";
  const char* setupRoutine = "";
  const char* shadeRoutine = "";
  int threads = 1;
  int tileSize = 0;  ///< square tiles of this many pixels, each painted by one thread
  int tilesX = 0, tilesY = 0;
  int width = 0, height = 0;
  std::size_t meshes = 0;
  std::size_t points = 0;
  std::size_t polygons = 0;

  /// A few lines saying what will be done, what is left out and why.
  std::string describe() const;
};

/// What one render did and what it cost. Times are wall-clock seconds; phases a path did not
/// run take 0.
struct RenderStats {
  RenderPlan plan;
  double validateSeconds = 0.0;   ///< mesh structure checks (once per version when versioned)
  double transformSeconds = 0.0;  ///< points to window coordinates (and painter's sort)
  double setupSeconds = 0.0;      ///< clip, cull, triangulate, bin
  double rasterSeconds = 0.0;     ///< paint the tiles (depth keys, polygon ids), window depths
  double shadeSeconds = 0.0;      ///< light the shown polygons, color the pixels (the estimate
                                  ///< and the resolved-rows callback included)
  double totalSeconds = 0.0;

  // The counts describe the frame in the framebuffer: an incremental render repeats those of
  // the render that drew its geometry, except polygonsShaded.
  std::size_t polygonsDrawn = 0;  ///< sent to the tiles
  /// Lit: the polygons that won a pixel while painting (those visible in the image, and any
  /// overdrawn later).
  std::size_t polygonsShaded = 0;
  std::size_t polygonsCulled = 0;      ///< back-facing, culled or hidden (closed surface)
  std::size_t polygonsOutside = 0;     ///< outside the view, or covering no pixel center
  std::size_t polygonsDegenerate = 0;  ///< fewer than 3 points, or zero area
  std::size_t polygonsNonFinite = 0;   ///< using a point with a NaN or infinite coordinate
  /// Back faces a two-pass frame dropped, in whole blocks or runs of a few ids hidden behind the
  /// front faces, before any per-polygon work (RenderPlan::polygonsHiddenBehindFront): neither
  /// drawn nor binned, outside nor degenerate. Drawn + outside + degenerate + hidden is one pass's
  /// drawn + outside + degenerate for the same frame.
  std::size_t polygonsHidden = 0;
  std::size_t trianglesBinned = 0;   ///< triangles handed to the tiles
  std::size_t trianglesClipped = 0;  ///< triangles that went through the clipper
  std::size_t trianglesHidden = 0;   ///< not painted: behind the tile (Rule::HiddenGeometry)
  std::size_t fragmentsWritten = 0;  ///< pixel writes, counting overdraw
  std::size_t pixelsCovered = 0;     ///< pixels showing a polygon at the end (samples of a
                                     ///< QualityRenderer's grid when it supersamples)
  std::size_t closedMeshesSkippingBackFaces = 0;  ///< closed meshes wholly in front of near
  bool aborted = false;                           ///< the progress callback asked to stop

  /// The plan's description, then what was counted and the time per phase.
  std::string describe() const;
};

}  // namespace facet
