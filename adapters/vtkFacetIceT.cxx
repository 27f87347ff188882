// VTK-HeaderTest-Exclude: vtkFacetIceT.h
#if FACET_HAVE_ICET
#include "vtkFacetIceT.h"

#include "vtkFacetImageRenderer.h"
#include "vtkFacetMessages.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkIntArray.h"
#include "vtkMPICommunicator.h"
#include "vtkMultiProcessController.h"
#include "vtkUnsignedCharArray.h"

#include <IceTMPI.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

namespace {
/// A pixel whose center sample shows no polygon may still have an estimate (with
/// supersampling, a silhouette's other samples): it goes at this depth, behind every surface
/// (their depths are halved, at most 0.5) and before the background (1).
constexpr float kEstimateOnlyDepth = 0.75f;

std::uint32_t PackedLabel(int rank, std::uint64_t cell)
{
  return static_cast<std::uint32_t>(rank) << 16 | static_cast<std::uint32_t>(cell >> 32 & 0xFFFFu);
}

// IceT has one current context per process, which ParaView's own compositing also sets:
// ours is current only while we composite.
class CurrentContext
{
public:
  explicit CurrentContext(IceTContext context)
    : Previous(icetGetContext())
  {
    icetSetContext(context);
  }
  ~CurrentContext()
  {
    if (this->Previous)
    {
      icetSetContext(this->Previous);
    }
  }
  CurrentContext(const CurrentContext&) = delete;
  CurrentContext& operator=(const CurrentContext&) = delete;

private:
  IceTContext Previous;
};
}

//------------------------------------------------------------------------------
bool vtkFacetIceT::Bind(vtkMultiProcessController* controller, vtkFacetMessages& messages)
{
  auto* communicator = vtkMPICommunicator::SafeDownCast(controller->GetCommunicator());
  if (!communicator || !communicator->GetMPIComm() || !communicator->GetMPIComm()->GetHandle())
  {
    vtkCommunicator* other = controller->GetCommunicator();
    messages.AddError(std::string("cannot composite: IceT needs an MPI communicator "
                                  "(a vtkMPIController), the controller has ") +
      (other ? other->GetClassName() : "none"));
    return false;
  }
  const MPI_Comm handle = *communicator->GetMPIComm()->GetHandle();
  if (this->Context && handle == this->Communicator)
  {
    return true;
  }
  this->Destroy();
  const IceTContext previous = icetGetContext();
  // A context duplicates the communicator (a collective call on every rank). The estimate
  // has a context of its own: switching one context's color format every frame costs IceT
  // more than the estimate's bytes (bench/mpi_estimate_cost.py).
  IceTCommunicator icetCommunicator = icetCreateMPICommunicator(handle);
  this->Context = icetCreateContext(icetCommunicator);
  this->EstimateContext = icetCreateContext(icetCommunicator);
  icetDestroyMPICommunicator(icetCommunicator);
  this->Communicator = handle;
  if (previous)
  {
    icetSetContext(previous);
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkFacetIceT::Destroy()
{
  if (!this->Context)
  {
    return;
  }
  // Freeing the context frees its MPI communicator, which is an error once MPI is finalized
  // (Python may collect the filter after mpi4py finalized MPI): then it is left to the exit.
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (!finalized)
  {
    // Each restores the current context unless it was itself.
    icetDestroyContext(this->EstimateContext);
    icetDestroyContext(this->Context);
  }
  this->Context = this->EstimateContext = nullptr;
  this->Communicator = MPI_COMM_NULL;
}

//------------------------------------------------------------------------------
void vtkFacetIceT::Pack(vtkFacetImageRenderer& image,
  std::size_t pixels,
  bool rendered,
  const float* ownEstimates,
  EstimateLayout layout)
{
  this->Colors.resize(pixels);
  this->Depths.resize(pixels);
  if (rendered)
  {
    this->PackPixels(image, ownEstimates, layout == EstimateLayout::Packed);
  }
  else
  {
    std::fill(this->Depths.begin(), this->Depths.end(), 1.0f);
  }
  if (layout == EstimateLayout::SecondComposite)
  {
    this->PackSecondEstimate(image, ownEstimates);
  }
}

//------------------------------------------------------------------------------
// A covered pixel (RankId set) carries its payload at half its window depth; the others are
// background (depth 1), whose payload IceT never reads, unless the packed estimate rides on
// them.
void vtkFacetIceT::PackPixels(vtkFacetImageRenderer& image, const float* ownEstimates, bool packed)
{
  Payload* colors = this->Colors.data();
  float* depths = this->Depths.data();
  const unsigned char* rgba = image.GetRgba()->GetPointer(0);
  const float* depth = image.GetDepth()->GetPointer(0);
  const vtkIdType* cellIds = image.GetCellIds()->GetPointer(0);
  const int* rankIds = image.GetRankIds()->GetPointer(0);
  image.ForEachPixelBlock([&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType i = begin; i < end; ++i)
    {
      const float own = packed && ownEstimates ? ownEstimates[i] : 0.0f;
      std::memcpy(&colors[i].Extra, &own, sizeof own);
      if (rankIds[i] < 0)
      {
        depths[i] = own != 0.0f ? kEstimateOnlyDepth : 1.0f;
        colors[i].Label = EstimateOnly;
        continue;
      }
      const auto cell = static_cast<std::uint64_t>(cellIds[i]);
      std::memcpy(&colors[i].Rgba, rgba + 4 * i, 4);
      colors[i].CellLow = static_cast<std::uint32_t>(cell);
      if (packed)
      {
        colors[i].Label = PackedLabel(rankIds[i], cell);
      }
      else
      {
        colors[i].Label = static_cast<std::uint32_t>(rankIds[i]);
        colors[i].Extra = static_cast<std::uint32_t>(cell >> 32);
      }
      depths[i] = 0.5f * depth[i]; // exact: a power of two
    }
  });
}

//------------------------------------------------------------------------------
void vtkFacetIceT::PackSecondEstimate(vtkFacetImageRenderer& image, const float* ownEstimates)
{
  this->EstimateDepths.assign(this->Depths.begin(), this->Depths.end());
  this->Estimates.assign(this->Depths.size(), 0.0f);
  if (!ownEstimates)
  {
    return;
  }
  image.ForEachPixelBlock([&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType i = begin; i < end; ++i)
    {
      this->Estimates[i] = ownEstimates[i];
      if (ownEstimates[i] != 0.0f && this->EstimateDepths[i] == 1.0f)
      {
        this->EstimateDepths[i] = kEstimateOnlyDepth;
      }
    }
  });
}

//------------------------------------------------------------------------------
bool vtkFacetIceT::Run(const vtkFacetCompositor::Settings& settings,
  int ranks,
  Layer layer,
  vtkFacetCompositor::Cost& cost,
  vtkFacetMessages& messages)
{
  static constexpr IceTEnum strategies[] = { ICET_SINGLE_IMAGE_STRATEGY_AUTOMATIC,
    ICET_SINGLE_IMAGE_STRATEGY_BSWAP,
    ICET_SINGLE_IMAGE_STRATEGY_TREE,
    ICET_SINGLE_IMAGE_STRATEGY_RADIXK };
  const bool image = layer == Layer::Image;
  void* colors = image ? static_cast<void*>(this->Colors.data()) : this->Estimates.data();
  float* depths = image ? this->Depths.data() : this->EstimateDepths.data();
  CurrentContext current(image ? this->Context : this->EstimateContext);
  icetResetTiles();
  icetAddTile(0, 0, settings.Width, settings.Height, settings.Target);
  icetPhysicalRenderSize(settings.Width, settings.Height);
  icetSetColorFormat(image ? ICET_IMAGE_COLOR_RGBA_FLOAT : ICET_IMAGE_COLOR_RGBA_UBYTE);
  icetSetDepthFormat(ICET_IMAGE_DEPTH_FLOAT);
  icetCompositeMode(ICET_COMPOSITE_MODE_Z_BUFFER);
  if (image)
  {
    icetDisable(ICET_COMPOSITE_ONE_BUFFER); // the depth comes back too
  }
  else
  {
    icetEnable(ICET_COMPOSITE_ONE_BUFFER);
  }
  // One tile: the sequential strategy is one single-image composite over every rank.
  icetStrategy(ICET_STRATEGY_SEQUENTIAL);
  icetSingleImageStrategy(strategies[static_cast<int>(settings.Method)]);
  // Ties go to the image later in the compose order: ranks P-1, ..., 0 gives them to the
  // lowest rank.
  std::vector<IceTInt> order(static_cast<std::size_t>(ranks));
  for (int i = 0; i < ranks; ++i)
  {
    order[static_cast<std::size_t>(i)] = ranks - 1 - i;
  }
  icetEnable(ICET_ORDERED_COMPOSITE);
  icetCompositeOrder(order.data());

  // No bounds: IceT takes every rank to cover the whole tile; the projection is unused.
  static constexpr IceTDouble identity[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
  static constexpr IceTFloat background[4] = { 0.0f, 0.0f, 0.0f, 0.0f };
  const auto start = std::chrono::steady_clock::now();
  IceTImage result = icetCompositeImage(colors, depths, nullptr, identity, identity, background);
  cost.IceTSeconds +=
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  IceTInt bytes = 0;
  icetGetIntegerv(ICET_BYTES_SENT, &bytes);
  cost.BytesSent += bytes;
  cost.Strategy =
    std::string("(") + icetGetStrategyName() + ", " + icetGetSingleImageStrategyName() + ")";
  const IceTEnum error = icetGetError();
  if (error != ICET_NO_ERROR)
  {
    std::ostringstream text;
    text << "IceT could not composite the image (error 0x" << std::hex << error << ")";
    messages.AddError(text.str());
    return false;
  }
  const std::size_t pixels = this->Depths.size();
  if (!icetImageIsNull(result))
  {
    if (static_cast<std::size_t>(icetImageGetNumPixels(result)) != pixels)
    {
      messages.AddError("IceT returned an image of " +
        std::to_string(icetImageGetNumPixels(result)) + " pixels for " + std::to_string(pixels));
      return false;
    }
    if (image)
    {
      std::memcpy(colors, icetImageGetColorcf(result), pixels * sizeof(Payload));
      std::memcpy(depths, icetImageGetDepthcf(result), pixels * sizeof(float));
    }
    else
    {
      std::memcpy(colors, icetImageGetColorcui(result), pixels * sizeof(float));
    }
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkFacetIceT::Broadcast(vtkMultiProcessController* controller,
  int target,
  EstimateLayout layout)
{
  const auto pixels = static_cast<vtkIdType>(this->Depths.size());
  controller->Broadcast(reinterpret_cast<int*>(this->Colors.data()),
    pixels * static_cast<vtkIdType>(sizeof(Payload) / sizeof(int)),
    target);
  controller->Broadcast(this->Depths.data(), pixels, target);
  if (layout == EstimateLayout::SecondComposite)
  {
    controller->Broadcast(this->Estimates.data(), pixels, target);
  }
}

//------------------------------------------------------------------------------
void vtkFacetIceT::Unpack(vtkFacetImageRenderer& image, float* estimates, EstimateLayout layout)
{
  const bool packed = layout == EstimateLayout::Packed;
  const Payload* colors = this->Colors.data();
  const float* depths = this->Depths.data();
  unsigned char* rgba = image.GetRgba()->GetPointer(0);
  float* depth = image.GetDepth()->GetPointer(0);
  vtkIdType* cellIds = image.GetCellIds()->GetPointer(0);
  int* rankIds = image.GetRankIds()->GetPointer(0);
  image.ForEachPixelBlock([&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType i = begin; i < end; ++i)
    {
      if (estimates)
      {
        // Packed: no rank's estimate reached a pixel left at depth 1, so it keeps its own 0.
        if (!packed)
        {
          estimates[i] = this->Estimates[i];
        }
        else if (depths[i] < 1.0f)
        {
          std::memcpy(estimates + i, &colors[i].Extra, sizeof(float));
        }
      }
      if (depths[i] >= 1.0f || (packed && colors[i].Label == EstimateOnly))
      {
        continue;
      }
      std::memcpy(rgba + 4 * i, &colors[i].Rgba, 4);
      depth[i] = 2.0f * depths[i];
      const std::uint32_t label = colors[i].Label;
      rankIds[i] = static_cast<int>(packed ? label >> 16 : label);
      const std::uint64_t high = packed ? label & 0xFFFFu : colors[i].Extra;
      cellIds[i] = static_cast<vtkIdType>(high << 32 | colors[i].CellLow);
    }
  });
}
#endif
