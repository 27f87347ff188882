#pragma once

/// @file Renderer.h
/// The rasterizer: a Scene and a Camera in, a Framebuffer out.
///
/// Pipeline (Sixth 3D's phases, made robust; see ../shared/DESIGN.md):
///  1. transform every point in double precision relative to the eye, to clip space and, if
///     inside the guard band and the near/far range, to 8-bit sub-pixel window coordinates;
///  2. per polygon: decide which side the viewer sees (Conventions.h, "Facing") and cull it
///     whole if back faces are skipped; triangulate (fan, ear clipping, VTK's fan for
///     self-intersecting polygons: Triangulate.h); clip what crosses the near/far planes or
///     the guard band in homogeneous space (any finite coordinates, up to ±DBL_MAX); drop
///     zero-area triangles by their exact integer area; bin into screen tiles;
///  3. per tile, one thread each: clear, then paint the tile's triangles in polygon order
///     (with the depth test, every front face before every back face) with integer edge
///     functions, a top-left fill rule and pixel centers at +0.5 (depth key and polygon id;
///     the nearer key wins, an exact tie keeps the front face, then the earlier polygon);
///  4. light each polygon that won a pixel, once (flat shading is a function of the polygon,
///     so hidden polygons are never lit), then color every pixel from its polygon id and
///     turn its depth key into window depth.
/// The result is bit-identical for every thread count, and re-rendering the same scene at
/// the same size allocates nothing.
///
/// Before step 1 the render is planned (RenderPlan.h): rules leave out what the scene does
/// not need (lights that reach nothing, blocks of polygons outside the view, triangles
/// behind what a tile shows, normals without direct light, ...) and the routines that do the
/// work are chosen once. Every render returns the plan in RenderStats: what ran, what was
/// left out and why.
///
/// Incremental rendering. When the meshes are versioned (MeshView::version) and the camera,
/// size, visibility and geometry are those of the previous render into the same planes, a
/// render reuses that frame: new lights, materials, colors or two-sided lighting re-shade it
/// from its polygon ids (no transform, set-up or raster); a new background only recolors
/// it. Each gives the bytes a full render would. The caller keeps the depth and polygon-id
/// planes as the previous render left them (the color plane is rewritten whole); a caller
/// that wrote into them, or cannot be sure, calls forgetPreviousFrame() or turns
/// RenderRules::incremental off. RenderPlan::path says which path ran, and why.

#include <cstdint>
#include <functional>
#include <memory>
#include <span>

#include "facet/Camera.h"
#include "facet/Color.h"
#include "facet/Framebuffer.h"
#include "facet/RenderPlan.h"
#include "facet/Scene.h"

namespace facet {

namespace detail {
struct EstimateHook;
}

class Renderer {
 public:
  /// Called on the thread that called render(), with the fraction done in [0, 1]. Return
  /// false to stop: render() then returns soon with RenderStats::aborted set and a
  /// partially painted (but valid) framebuffer. An exception it throws leaves render() once
  /// every thread has stopped; the next render draws what a new renderer would (tested).
  using ProgressCallback = std::function<bool(double fraction)>;
  /// Called with each band of rows [y0, y1] of `target` (the planes the render draws into)
  /// once the render has resolved it: its colors, depths and polygon ids are those render()
  /// returns. Every row of the target comes once per completed render, the bands in no set
  /// order and concurrently on the renderer's threads: for elementwise work on the image
  /// while its ids are in cache (the VTK filter widens the polygon ids of a band into its
  /// CellId array), in place of a second pass over the planes. (Large color and depth planes
  /// are streamed past the caches when nothing in the render reads them back.) A stopped render may
  /// have passed some bands before it clears the target; an exception the callback throws leaves
  /// render() as the progress callback's does. With depth output off the depth plane holds
  /// depth keys. Under a QualityRenderer, `target` is the planes that renderer hands the
  /// render: its sample grid when it supersamples, and at one sample a band whose polygons
  /// it reshades afterwards does not have its final colors yet. Every pixel of the band
  /// outside columns [x0, x1) shows the background (its polygon id is negative; x0 == x1: the
  /// whole band): the columns of the tiles the band's polygons cover, or the whole row, so
  /// that the callback need not read background ids the resolve left unread (not in cache).
  using ResolvedRowsCallback =
      std::function<void(const FramebufferView& target, int y0, int y1, int x0, int x1)>;

  Renderer();
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  /// Threads that render; 0 means one per hardware thread. (default: 0)
  void setThreadCount(int threads);
  int threadCount() const;

  /// (default: Visibility::ZBuffer)
  void setVisibility(Visibility visibility) { visibility_ = visibility; }
  Visibility visibility() const { return visibility_; }

  /// Light back faces with their normal turned toward the viewer, as vtkRenderer does; off:
  /// lit as their winding says (so usually dark). (default: on)
  void setTwoSidedLighting(bool enabled) { twoSidedLighting_ = enabled; }
  bool twoSidedLighting() const { return twoSidedLighting_; }

  /// Color and alpha of pixels no polygon covers. (default: black, alpha 1)
  void setBackground(const Color& color, float alpha = 1.0f) {
    background_ = color;
    backgroundAlpha_ = alpha;
  }

  void setProgressCallback(ProgressCallback callback) { progress_ = std::move(callback); }

  /// (default: none)
  void setResolvedRowsCallback(ResolvedRowsCallback callback) {
    resolvedRows_ = std::move(callback);
  }

  /// Which rules may leave work out (all, by default; see RenderRules).
  void setRules(const RenderRules& rules);
  const RenderRules& rules() const { return rules_; }

  /// Write window depths into the depth plane. Off: the depth plane may be null (the renderer
  /// keeps one of its own) and otherwise holds depth keys (FrameTransform.h), not window
  /// depths, when render() returns. (default: on)
  void setDepthOutput(bool enabled) { depthOutput_ = enabled; }
  bool depthOutput() const { return depthOutput_; }

  /// The next render is a full one: for a caller that wrote into the planes of the previous
  /// render, or replaced arrays without a new version.
  void forgetPreviousFrame();

  /// The plan a full render of this scene through this camera into a width × height image
  /// would start with (the decisions the geometry settles — closed surfaces, hidden geometry
  /// — are made by the render). Throws facet::Error for invalid lights, materials, camera or
  /// size.
  RenderPlan plan(const Scene& scene, const Camera& camera, int width, int height) const;

  /// Renders the scene into the framebuffer (its size is the image size). Throws
  /// facet::Error, naming the offending value, for an invalid mesh structure, camera,
  /// light or material, before anything is painted.
  RenderStats render(const Scene& scene, const Camera& camera, Framebuffer& framebuffer) {
    return render(scene, camera, framebuffer.view());
  }

  /// The same, into planes the caller owns (see FramebufferView). Throws facet::Error for a
  /// size outside [1, kMaxImageSide] or a null plane (the depth plane may be null when depth
  /// output is off).
  RenderStats render(const Scene& scene, const Camera& camera, const FramebufferView& target);

  /// Per polygon id of the last render's scene (its meshes' polygons in order), nonzero for
  /// exactly the polygons a pixel of the image shows: the polygons the render lit. For work on
  /// the rendered image (the error estimate of QualityRenderer); valid until the next render,
  /// and only after a render that completed (an aborted one leaves them partial).
  std::span<const std::uint8_t> shownPolygons() const;

  /// Runs work(begin, end) over [0, count) in blocks of `grain`, on the renderer's threads
  /// (the caller's included), for elementwise work on a rendered image such as converting
  /// its ids. Returns when all blocks are done. The blocks must not depend on each other.
  void parallelFor(std::size_t count, std::size_t grain,
                   const std::function<void(std::size_t begin, std::size_t end)>& work);

 private:
  // QualityRenderer's error estimate, taken by the shade and resolve phases of its next
  // render (EstimateHook.h); null: none.
  friend class QualityRenderer;
  detail::EstimateHook* estimateHook_ = nullptr;

  struct Workspace;
  std::unique_ptr<Workspace> workspace_;
  Visibility visibility_ = Visibility::ZBuffer;
  bool twoSidedLighting_ = true;
  Color background_{0.0f};
  float backgroundAlpha_ = 1.0f;
  ProgressCallback progress_;
  ResolvedRowsCallback resolvedRows_;
  RenderRules rules_;
  bool depthOutput_ = true;
};

}  // namespace facet
