/**
 * @class   vtkFacetIceT
 * @brief   Private, vtkFacetCompositor's (built with IceT only): an IceT context on a
 *          controller's MPI communicator, the pixels handed to it, and one composite.
 *
 * A composite goes in four steps, each a method: Pack puts this rank's image (its RGBA,
 * depth, rank and cell ids, and the error estimate) into the buffers IceT reads; Run
 * composites them by depth onto the target, in place; Broadcast hands the result from the
 * target to every rank (CompositeToAllRanks); Unpack writes it back into the image's arrays.
 *
 * What IceT carries for a pixel is its RGBA_FLOAT "color", 16 bytes IceT copies and never
 * interprets (Payload), at the window depth halved (vtkFacetCompositor.h says why). The
 * estimate either rides in the payload (EstimateLayout::Packed: 16-bit rank, 48-bit CellId,
 * the estimate's float) or has a composite of its own with the same depths
 * (EstimateLayout::SecondComposite).
 */

#ifndef vtkFacetIceT_h
#define vtkFacetIceT_h

#include "vtkFacetCompositor.h"

#include "vtkMPI.h"

#include <IceT.h>

#include "facet/HugePageAllocator.h"

#include <cstdint>

class vtkFacetImageRenderer;
class vtkFacetMessages;
class vtkMultiProcessController;

class vtkFacetIceT
{
public:
  /// A pixel's RGBA_FLOAT "color" in IceT: Label and Extra hold the rank and the CellId's
  /// high half, or, packed, the rank and the CellId's bits 32-47 in Label and the estimate's
  /// float in Extra.
  struct Payload
  {
    std::uint32_t Rgba;    // the RGBA bytes, in memory order
    std::uint32_t Label;   // the rank (packed: rank << 16 | CellId bits 32-47)
    std::uint32_t CellLow; // the CellId's bits 0-31
    std::uint32_t Extra;   // the CellId's bits 32-63 (packed: the estimate's float bits)
  };
  static_assert(sizeof(Payload) == 4 * sizeof(IceTFloat), "a payload is one RGBA_FLOAT color");

  /// A packed Label that names no rank: the pixel carries an estimate but shows no polygon
  /// (a supersampled silhouette whose center sample is background). So 65535 ranks at most.
  static constexpr std::uint32_t EstimateOnly = 0xFFFFu;
  static constexpr int MaxPackedRanks = static_cast<int>(EstimateOnly);

  /// What one composite sends a covered pixel, with the depth; the estimate's second one adds
  /// its float (the bits of an RGBA_UBYTE color, which IceT copies as it copies the payload).
  static constexpr int BytesPerPixel = sizeof(Payload) + sizeof(float);
  static constexpr int EstimateBytesPerPixel = sizeof(float) + sizeof(float);

  /// How the per-pixel error estimate travels, if at all.
  enum class EstimateLayout
  {
    None,
    Packed,
    SecondComposite
  };

  /// What a composite carries: the image (colors and depths, both back on the target), or
  /// the estimate (in a context of its own; its values alone come back).
  enum class Layer
  {
    Image,
    Estimate
  };

  vtkFacetIceT() = default;
  ~vtkFacetIceT() { this->Destroy(); }
  vtkFacetIceT(const vtkFacetIceT&) = delete;
  vtkFacetIceT& operator=(const vtkFacetIceT&) = delete;

  /// A context on `controller`'s MPI communicator; false, with an error, without MPI.
  bool Bind(vtkMultiProcessController* controller, vtkFacetMessages& messages);

  /**
   * This rank's pixels (`pixels` of them) into the buffers: a covered one at half its
   * window depth, the others as background (depth 1), or behind every surface when they
   * carry an estimate. `rendered` false: background only. `ownEstimates`: this rank's
   * per-pixel estimate, or null (zeros).
   */
  void Pack(vtkFacetImageRenderer& image,
    std::size_t pixels,
    bool rendered,
    const float* ownEstimates,
    EstimateLayout layout);

  /// Composites a layer in place on the target; adds its time and bytes to `cost`.
  bool Run(const vtkFacetCompositor::Settings& settings,
    int ranks,
    Layer layer,
    vtkFacetCompositor::Cost& cost,
    vtkFacetMessages& messages);

  /// The target's composited buffers to every rank (collective).
  void Broadcast(vtkMultiProcessController* controller, int target, EstimateLayout layout);

  /**
   * The composited pixels into `image`'s arrays; a pixel that no rank covers keeps this
   * rank's values. `estimates` (or null) becomes the estimate of the piece each pixel shows.
   */
  void Unpack(vtkFacetImageRenderer& image, float* estimates, EstimateLayout layout);

private:
  void PackPixels(vtkFacetImageRenderer& image, const float* ownEstimates, bool packed);
  void PackSecondEstimate(vtkFacetImageRenderer& image, const float* ownEstimates);
  void Destroy();

  facet::HugePageVector<Payload> Colors;
  facet::HugePageVector<float> Depths;
  // The second composite's: the estimate's float per pixel, and a copy of the depths sent
  // (the first composite overwrites Depths on the target).
  facet::HugePageVector<float> Estimates;
  facet::HugePageVector<float> EstimateDepths;

  IceTContext Context = nullptr;
  IceTContext EstimateContext = nullptr;
  MPI_Comm Communicator = MPI_COMM_NULL;
};

#endif
