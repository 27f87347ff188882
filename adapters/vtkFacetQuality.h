/**
 * @class   vtkFacetQuality
 * @brief   Private: vtkFacetRenderFilter's quality modes and error reports (facet's
 *          QualityRenderer.h and MeshReference.h), kept out of the filter.
 *
 * The property's Interpolation picks the shading (VTK_FLAT flat, VTK_GOURAUD Gouraud,
 * VTK_PHONG Phong; per mesh for vtkFacetRendererToImageFilter, each actor's own); SamplesPerPixel
 * supersamples; a MaximumError above 0 shades adaptively. Shading beyond flat and ComputeError
 * need the ShadingMesh of every scene mesh (triangles, vertex normals: the data's point normals
 * when it has them, else vtkPolyDataNormals' meaning; the range of each polygon's corner colors),
 * kept per mesh while its points, polygons, normals and point colors are unchanged. Flat shading
 * with the estimate needs no ShadingMesh: the quality renderer keeps, per mesh version, each
 * polygon's radius and normal spread (8 bytes); the render's shade phase bounds the polygons
 * it lights and, at one sample per pixel, its resolve takes the per-pixel estimate (a new
 * background alone keeps the last estimate). AddOutputs puts the estimate in the field data
 * (`FacetErrorEstimate`: PredictedRMSE, PredictedMax, 8-bit units, and Seconds, its time outside
 * the render: inside it, at one sample, only its summing) and, on request, as the point-data
 * array `ErrorEstimate`; with
 * ShadingMeshes, how many the render built and how many it kept (`FacetShadingMeshes`: Built,
 * Kept). With ComputeError it renders the converged Phong mesh reference and adds `FacetError`
 * (RMSE, Max, PSNR, SSIM, SilhouetteFraction, ReferenceSeconds, RenderSeconds) and the per-pixel
 * `Error` array (ImageMetrics.h).
 */

#ifndef vtkFacetQuality_h
#define vtkFacetQuality_h

#include "vtkDoubleArray.h"
#include "vtkFacetFieldArray.h"
#include "vtkType.h"

#include "facet/QualityRenderer.h"

#include <functional>
#include <memory>
#include <vector>

class vtkFacetMessages;
class vtkImageData;

class vtkFacetQuality
{
public:
  struct Settings
  {
    int Interpolation = 0;   ///< vtkProperty's: VTK_FLAT, VTK_GOURAUD, VTK_PHONG
    int SamplesPerPixel = 1; ///< 1, 4 or 16
    double MaximumError = 0; ///< 8-bit units; 0: off
    bool ComputeError = false;
    bool EstimateError = true;
    bool ErrorEstimateArray = false;
    /// One Interpolation per scene mesh (a VTK scene's actors); empty: Interpolation for all.
    std::vector<int> MeshInterpolation;
  };

  /// The renderer call vtkFacetImageRenderer makes: the scene in the settings' mode.
  using RenderFunction = std::function<facet::RenderStats(facet::Renderer&,
    const facet::Scene&,
    const facet::Camera&,
    const facet::FramebufferView&)>;

  /**
   * Prepares a render: checks the settings (an error in `messages` for samples other than 1, 4
   * or 16 or a negative maximum error). Returns the function that renders a scene (meshes
   * from vtkFacetActorConverter, whose versions cover their point normals), first building
   * the ShadingMesh of every mesh whose points, polygons, normals or corner colors changed;
   * or an empty one after an error or when the plain Renderer does all that is asked (flat,
   * one sample, no estimate, no error measurement).
   */
  RenderFunction Prepare(const Settings& settings, vtkFacetMessages& messages);

  /**
   * After the render: the estimate and, with ComputeError, the measured error (the mesh
   * reference is rendered here) into `output`'s field and point data. `polygonIds` is the
   * rendered id plane.
   */
  void AddOutputs(const facet::Scene& scene,
    const facet::Camera& camera,
    const std::int32_t* polygonIds,
    const double background[3],
    bool twoSidedLighting,
    int threads,
    vtkImageData* output,
    vtkFacetMessages& messages);

  /**
   * Makes `output`'s FacetErrorEstimate (PredictedRMSE, PredictedMax) summarize its
   * ErrorEstimate array as the core summarizes its estimate (over the pixels with one): after
   * compositing, the whole image's rather than this process's piece's. Nothing without both.
   */
  static void SummarizeEstimateArray(vtkImageData* output);

private:
  // What a mesh's ShadingMesh is made of: its arrays (points, offsets, connectivity and their
  // sizes: two inputs may share their points and their version, the latest MTime of both),
  // its version (points, polygons and point normals) and, with point colors or a scalar
  // texture, its color version (the polygons' corner color ranges). The core's own caches key
  // a mesh the same way (MeshIdentity).
  struct Key
  {
    const void* Points = nullptr;
    const void* Offsets = nullptr;
    const void* Connectivity = nullptr;
    std::size_t PointCount = 0, PolygonCount = 0, ConnectivitySize = 0;
    std::uint64_t Version = 0, ColorVersion = 0;
    bool operator==(const Key&) const = default;
  };
  static Key KeyOf(const facet::MeshView& mesh);
  // The ShadingMesh of every mesh whose key changed (every render for an unversioned mesh).
  void UpdateShading(const facet::Scene& scene, facet::Renderer& renderer);

  Settings Current;
  std::unique_ptr<facet::QualityRenderer> Quality; // its buffers kept between renders
  const facet::Renderer* QualityOf = nullptr;      // the renderer it renders through
  std::vector<facet::ShadingMesh> Shading;         // only for shading beyond flat and ComputeError
  std::vector<Key> Keys;                           // what each of Shading was made of
  std::size_t Built = 0;                           // by the last render
  facet::QualityStats Stats;
  double RenderSeconds = 0.0;
  // FacetShadingMeshes, FacetErrorEstimate and FacetError, refilled in place while nobody else
  // holds them (vtkFacetFieldArray).
  vtkFacetFieldArray<vtkDoubleArray> ShadingMeshesField, EstimateField, ErrorField;
};

#endif
