#pragma once

/// @file QualityRenderer.h
/// Quality modes above the flat Renderer: Gouraud and Phong shading, supersampling, an error
/// budget (adaptive), and the flat-shading error estimate (FlatErrorBound.h) — all by
/// visibility-buffer shading (Burns & Hunt 2013, "The Visibility Buffer: A Cache-Friendly
/// Approach to Deferred Shading"): the Renderer paints, per sample, the id of the polygon
/// seen and its depth; each covered sample is then shaded again from its polygon.
///
/// Per sample: the ray through the sample's window point (CameraRays, Reference.h) meets the
/// plane of the fan triangle that holds it (the polygon's triangles are the rasterizer's:
/// triangulateMesh); the exact ray/triangle intersection in double gives perspective-correct
/// barycentric weights. Gouraud lights every corner of a visible polygon once (its corner
/// normal, point and color) and interpolates the colors; Phong interpolates the normal (and
/// the point color) and lights the sample. Both use the one formula of Lighting.h and light
/// a polygon seen from its back with its normals turned toward the viewer, as flat does.
/// Colors: MeshView::scalarTexture, the scalars interpolated and looked up per sample
/// (vtkMapper's InterpolateScalarsBeforeMapping on); else MeshView::pointColors interpolated
/// (off: colors mapped at the points, then interpolated); else the polygon's color, else the
/// material's (pointColorAt, Mesh.h). Gouraud with a scalarTexture lights every corner twice,
/// for a black and a white surface, interpolates both and takes the sample's table color Cd
/// between them: dark + Cd ⊙ (bright − dark). The formula of Lighting.h is affine in Cd, so
/// that is the corner lighting of the sample's own color wherever no corner saturates — as
/// OpenGL's Gouraud shading of a textured surface (GL_MODULATE, separate specular color).
///
/// Supersampling: 4 or 16 samples per pixel on an ordered 2 × 2 or 4 × 4 grid (the Renderer
/// paints a 2× or 4× larger image), averaged with equal weights (a box filter) before the
/// one rounding to 8 bits. Depth and polygon id of an output pixel are those of one fixed
/// sample: the one at offset ((g/2 + 0.5)/g, (g/2 + 0.5)/g) from the pixel's corner for a
/// g × g grid, i.e. (0.75, 0.75) for 4 samples and (0.625, 0.625) for 16 — a sample nearest
/// the pixel center (for 4, all four are equally near; this one is chosen).
///
/// Flat shading with one sample and no estimate is the Renderer itself, unchanged: same
/// bytes, same cost. Every mode gives the same bytes for any thread count.

#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "facet/FlatErrorBound.h"
#include "facet/Framebuffer.h"
#include "facet/MeshTriangles.h"
#include "facet/ParallelFor.h"
#include "facet/Renderer.h"
#include "facet/VertexNormals.h"

namespace facet {

namespace detail {
struct EstimateSpace;
struct EstimateSums;
struct BoundTerms;
struct BatchLighting;
struct EstimateHook;
template <class Signature>
class FunctionRef;
}  // namespace detail

enum class Shading {
  Flat,     ///< one color per polygon, lit at its center (the Renderer's)
  Gouraud,  ///< lit at every corner, colors interpolated
  Phong,    ///< normals interpolated, lit at every sample
};

/// "flat", "gouraud", "phong".
const char* toString(Shading shading);

/// What shading beyond flat needs of one mesh, computed once per mesh version (not per
/// frame): the rasterizer's triangles, corner normals (MeshView::pointNormals when given,
/// else computeVertexNormals) and the shape of every polygon for the error bound.
struct ShadingMesh {
  ShadingMesh() = default;
  /// Validates the mesh (throws facet::Error, naming the problem: also point normals, point
  /// colors or scalar texture coordinates whose count is not the point count, or a scalar
  /// texture whose texels are not width × 2).
  /// `parallel` spreads the vertex normals over threads (computeVertexNormals).
  explicit ShadingMesh(const MeshView& mesh, const VertexNormalOptions& options = {},
                       const ParallelFor& parallel = {});

  std::vector<MeshTriangle> triangles;       ///< in polygon order
  std::vector<std::uint32_t> firstTriangle;  ///< per polygon, and one past the last
  VertexNormals normals;
  std::vector<PolygonShape> shapes;  ///< one per polygon
  std::size_t polygonCount() const { return shapes.size(); }
};

struct QualitySettings {
  Shading shading = Shading::Flat;  ///< (default: flat)
  /// 1, 4 or 16 samples per pixel (default: 1)
  int samplesPerPixel = 1;
  /// Adaptive quality: polygons whose flat-shading bound (plus 0.5 for rounding) is within
  /// this many 8-bit units stay flat, the others are Phong-shaded; `shading` is then
  /// ignored. Each sample is so within maximumError of the Phong image. Empty: off.
  /// (default: off)
  std::optional<double> maximumError{};
  /// Compute the flat-shading error estimate (QualityStats::predicted*, and the per-pixel
  /// image errorEstimate()). (default: off)
  bool estimateError = false;
  /// With estimateError, keep the per-pixel estimate (errorEstimate()); off, the render finds
  /// the summary alone without writing the image: flat at one sample per pixel under point and
  /// directional lights and a material without specular, one color per polygon, from one bound
  /// per block of 128 polygons in place of each polygon's (QualityStats::predicted*: at least
  /// the per-pixel estimate's, a little looser, at about a third of its cost); otherwise the
  /// same numbers as with the image. (default: on)
  bool errorEstimateImage = true;
  /// One shading per scene mesh, in place of `shading` (a VTK scene's actors each have their
  /// property's interpolation); empty: `shading` for every mesh. (default: empty)
  std::vector<Shading> meshShading{};
};

/// Throws facet::Error naming a bad value: samples other than 1, 4 or 16, a maximum error
/// that is negative or not finite. (meshShading's length is checked against the scene by
/// QualityRenderer::render.)
void validate(const QualitySettings& settings);

struct QualityStats {
  RenderStats render;         ///< the Renderer's pass (at the sample grid's size)
  double shadeSeconds = 0.0;  ///< re-shading and resolving the samples
  /// The error estimate's time outside the render (bounds and the per-pixel image); flat at one
  /// sample per pixel the render's shade and resolve take it (EstimateHook.h), and this is
  /// the summing of its rows (and, for meshes the shade did not bound, the separate pass).
  double estimateSeconds = 0.0;
  double totalSeconds = 0.0;
  std::size_t samplesReshaded = 0;  ///< samples shaded again (not kept flat)
  /// Polygons shaded per sample or per corner: those the renderer lit (Renderer::shownPolygons:
  /// the polygons its image shows).
  std::size_t polygonsReshaded = 0;
  /// The estimate (when asked): per pixel, an upper bound on how far the flat-shaded pixel is
  /// from the converged Phong image of the scene (the mesh reference, MeshReference.h), in
  /// 8-bit units of the largest channel — for each polygon the pixel's 3 × 3 samples see, its
  /// bound (FlatErrorBound.h) plus how far its flat color is from the pixel's, plus 0.5 for
  /// rounding — averaged over a pixel's samples; over the covered pixels, its root mean
  /// square and its maximum. Whatever the mode, it is flat shading's estimate. Silhouettes
  /// (the background a pixel mixes in) are not part of it. Without the image
  /// (errorEstimateImage off) each polygon's bound may be its block's (QualitySettings), so
  /// these are then at least the per-pixel estimate's.
  double predictedRmse = 0.0;
  double predictedMaxError = 0.0;
  /// The estimate is the previous render's, kept: this render only recolored that frame (a
  /// new background, RenderPath::Resolve), which changes no covered pixel.
  bool estimateKept = false;
};

class QualityRenderer {
 public:
  /// Renders through `renderer` (its threads, background, visibility, lighting side), which
  /// must outlive this object.
  explicit QualityRenderer(Renderer& renderer);
  QualityRenderer(QualityRenderer&&) noexcept;
  ~QualityRenderer();

  /// Renders the scene in the mode the settings ask for. `shading` holds one ShadingMesh per
  /// scene mesh (prepared once, kept while the meshes do not change), or is empty: shading
  /// per sample or per corner (Gouraud, Phong, adaptive) then computes them here, every
  /// render; flat shading with the estimate needs only each polygon's radius and normal
  /// spread, which this object keeps per mesh version (MeshView::version, which then
  /// also covers MeshView::pointNormals; an unversioned mesh is measured every render).
  /// Throws facet::Error for bad settings, a shading list that does not match the scene, or
  /// an image side that a 2× or 4× sample grid would take beyond kMaxImageSide; and whatever
  /// Renderer::render throws.
  QualityStats render(const Scene& scene, std::span<const ShadingMesh> shading,
                      const Camera& camera, const FramebufferView& target,
                      const QualitySettings& settings);
  QualityStats render(const Scene& scene, std::span<const ShadingMesh> shading,
                      const Camera& camera, Framebuffer& framebuffer,
                      const QualitySettings& settings) {
    return render(scene, shading, camera, framebuffer.view(), settings);
  }

  /// The last render's per-pixel estimate (QualityStats), row 0 at the bottom, 0 where no
  /// polygon shows; empty unless it was asked for (estimateError and errorEstimateImage). A render
  /// that only recolors the previous frame (RenderPath::Resolve: a new background) keeps the
  /// previous estimate, which must then be of the renderer's previous frame: render through this
  /// object only, or call Renderer::forgetPreviousFrame() after rendering without it.
  std::span<const float> errorEstimate() const { return estimate_; }

 private:
  struct Frame;
  std::span<const ShadingMesh> shadingFor(const Scene& scene, std::span<const ShadingMesh> given,
                                          bool reshades, bool estimates);
  std::size_t preparePolygons(const Frame& frame, bool bounds, bool corners);
  std::size_t boundFromCorners(const Frame& frame, std::size_t begin, std::size_t end,
                               const std::atomic<bool>* skip);
  void estimate(const Frame& frame, const FramebufferView& target, bool image, QualityStats& stats);
  void updateTerms(const Scene& scene);
  void hookUp(
      const Frame& frame, const detail::BatchLighting* facing,
      detail::FunctionRef<float(std::size_t, std::size_t, const glm::dvec3*, const glm::dvec3&)>
          boundOne,
      bool summary, detail::EstimateHook& hook);
  void estimateSummary(const Frame& frame, const FramebufferView& target, QualityStats& stats);
  void blockBounds(const Frame& frame);
  void finishFused(const Frame& frame, const detail::EstimateHook& hook,
                   const FramebufferView& target, QualityStats& stats);
  void shadeAndResolve(const Frame& frame, const FramebufferView& target, QualityStats& stats);

  Renderer& renderer_;
  Framebuffer samples_;  // the 2× or 4× sample grid
  std::vector<ShadingMesh> owned_;
  std::vector<float> estimate_;
  QualityStats estimated_;  // the last estimate's predicted*, for a render that keeps it
  // What an estimate was made for; the last one's in estimatedFor_ (empty: none).
  struct EstimateKey {
    int gridSide = 0;  // samples per pixel side
    int width = 0, height = 0;
    bool image = false;  // errorEstimate() kept
    // Whether an estimate made for this key answers a request for `wanted`: the same grid and
    // size, and the image when it is wanted.
    bool servesFor(const EstimateKey& wanted) const {
      return gridSide == wanted.gridSide && width == wanted.width && height == wanted.height &&
             (image || !wanted.image);
    }
  };
  std::optional<EstimateKey> estimatedFor_;
  // The estimate's per-task space (QualityRenderer.cpp), one per thread.
  std::vector<std::unique_ptr<detail::EstimateSpace>> spaces_;

  // Per scene mesh, the estimate's camera-independent part for one version of its arrays
  // (QualityRenderer.cpp).
  struct MeshTerms;
  std::vector<MeshTerms> terms_;
  std::vector<float> polygonBounds_;  // per polygon id, 8-bit units (visible ones only)
  // The same in the per-pixel estimate's fixed point (EstimateRows.h: fixedBoundOf), an even
  // count.
  std::vector<std::uint16_t> fixedBounds_;
  // The summary-only estimate's: per block of polygon ids, and per block of one mesh
  // (FlatErrorBoundOfMesh.h), in the same fixed point.
  std::vector<std::uint16_t> blockBounds_, localBounds_;
  std::vector<detail::EstimateSums> rowSums_;         // per pixel row: the fused estimate's
  std::vector<const detail::BoundTerms*> meshTerms_;  // per mesh: terms_'s, for the hook
  std::vector<std::uint8_t> reshade_;    // per polygon id: shaded again (visible ones only)
  std::vector<Color> cornerColors_;      // Gouraud: per corner of every mesh
  std::vector<Color> cornerBright_;      // Gouraud with a scalarTexture: the corners lit white
  const std::uint8_t* shown_ = nullptr;  // per polygon id: this render lit it (Renderer)
};

}  // namespace facet
