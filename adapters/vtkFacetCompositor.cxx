// VTK-HeaderTest-Exclude: vtkFacetCompositor.h
#include "vtkFacetCompositor.h"

#include "vtkCellData.h"
#include "vtkCommunicator.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFacetImageRenderer.h"
#include "vtkFacetMessages.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkMath.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"
#include "vtkUnsignedCharArray.h"

#if FACET_HAVE_ICET
#include "vtkMPI.h"
#include "vtkMPICommunicator.h"

#include <IceT.h>
#include <IceTMPI.h>

#include "facet/HugePageAllocator.h"
#endif

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <iterator>
#include <limits>
#include <sstream>
#include <vector>

namespace {
using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

std::string RankList(const std::vector<int>& ranks)
{
  std::vector<std::string> names;
  for (int rank : ranks)
  {
    names.push_back(std::to_string(rank));
  }
  return vtkFacetMessages::List(names);
}
}

#if FACET_HAVE_ICET
//------------------------------------------------------------------------------
// IceT: a context on the controller's MPI communicator (kept while the communicator is the
// same), the pixels handed to it, and one composite.
class vtkFacetCompositor::vtkIceT
{
public:
  /// What IceT carries for a pixel as its RGBA_FLOAT "color": copied, never interpreted.
  /// Label and Extra hold the rank and the CellId's high half, or, with the estimate packed
  /// (vtkFacetCompositor::PackEstimate), the rank and the CellId's bits 32-47 in Label and
  /// the estimate's float in Extra.
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
  static std::uint32_t PackedLabel(int rank, std::uint64_t cell)
  {
    return static_cast<std::uint32_t>(rank) << 16 |
      static_cast<std::uint32_t>(cell >> 32 & 0xFFFFu);
  }

  /// What one composite sends a covered pixel, with the depth; the estimate's second one adds
  /// its float (the bits of an RGBA_UBYTE color, which IceT copies as it copies the payload).
  static constexpr int BytesPerPixel = sizeof(Payload) + sizeof(float);
  static constexpr int EstimateBytesPerPixel = sizeof(float) + sizeof(float);

  ~vtkIceT() { this->Destroy(); }

  /// A context on `controller`'s MPI communicator; false, with an error, without MPI.
  bool Bind(vtkMultiProcessController* controller, vtkFacetMessages& messages);

  /// What a composite carries: the image (Colors at Depths, both back on the target), or the
  /// estimate (Estimates at EstimateDepths, in a context of its own; the colors alone come
  /// back, the background's as zeros).
  enum class Layer
  {
    Image,
    Estimate
  };
  /// Composites a layer in place on the target; adds its time and bytes to `cost`.
  bool Run(const vtkFacetCompositor::Settings& settings,
    int ranks,
    Layer layer,
    vtkFacetCompositor::Cost& cost,
    vtkFacetMessages& messages);

  facet::HugePageVector<Payload> Colors;
  facet::HugePageVector<float> Depths;
  // With the estimate: its float per pixel, and a copy of the depths sent (the first
  // composite overwrites Depths on the target).
  facet::HugePageVector<float> Estimates;
  facet::HugePageVector<float> EstimateDepths;

private:
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

  void Destroy();

  IceTContext Context = nullptr;
  IceTContext EstimateContext = nullptr;
  MPI_Comm Communicator = MPI_COMM_NULL;
};

//------------------------------------------------------------------------------
bool vtkFacetCompositor::vtkIceT::Bind(vtkMultiProcessController* controller,
  vtkFacetMessages& messages)
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
void vtkFacetCompositor::vtkIceT::Destroy()
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
bool vtkFacetCompositor::vtkIceT::Run(const vtkFacetCompositor::Settings& settings,
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
  const Clock::time_point start = Clock::now();
  IceTImage result = icetCompositeImage(colors, depths, nullptr, identity, identity, background);
  cost.IceTSeconds += SecondsSince(start);
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
#else
class vtkFacetCompositor::vtkIceT
{
};
#endif

//------------------------------------------------------------------------------
vtkFacetCompositor::vtkFacetCompositor()
  : IceT(new vtkIceT)
{}

vtkFacetCompositor::~vtkFacetCompositor() = default;

//------------------------------------------------------------------------------
bool vtkFacetCompositor::IsParallel(vtkMultiProcessController* controller)
{
  return controller && controller->GetNumberOfProcesses() > 1;
}

bool vtkFacetCompositor::IsAvailable()
{
#if FACET_HAVE_ICET
  return true;
#else
  return false;
#endif
}

//------------------------------------------------------------------------------
void vtkFacetCompositor::Prepare(vtkMultiProcessController* controller,
  const Settings& settings,
  double bounds[6],
  vtkFacetMessages& messages)
{
  this->Controller = controller;
  this->Current = settings;
  this->Rank = controller->GetLocalProcessId();
  this->Ranks = controller->GetNumberOfProcesses();

  // One reduction by minimum does both: min(x) and -min(-x) = max(x), for the bounds (an
  // empty piece gives +inf, which changes nothing) and for the settings (equal everywhere
  // when every minimum is minus the maximum).
  const bool hasBounds = vtkMath::AreBoundsInitialized(bounds);
  const double none = std::numeric_limits<double>::infinity();
  const double agreed[] = { static_cast<double>(settings.Width),
    static_cast<double>(settings.Height),
    static_cast<double>(settings.Target),
    settings.ToAllRanks ? 1.0 : 0.0,
    static_cast<double>(settings.Method),
    settings.WithEstimate ? 1.0 : 0.0 };
  constexpr int settingCount = static_cast<int>(std::size(agreed));
  constexpr int fitsAt = 6 + 2 * settingCount; // CellIdsFit48Bits: all ranks' minimum
  double local[fitsAt + 1], global[fitsAt + 1];
  for (int axis = 0; axis < 3; ++axis)
  {
    local[axis] = hasBounds ? bounds[2 * axis] : none;
    local[3 + axis] = hasBounds ? -bounds[2 * axis + 1] : none;
  }
  for (int i = 0; i < settingCount; ++i)
  {
    local[6 + i] = agreed[i];
    local[6 + settingCount + i] = -agreed[i];
  }
  local[fitsAt] = settings.CellIdsFit48Bits ? 1.0 : 0.0;
  controller->AllReduce(local, global, fitsAt + 1, vtkCommunicator::MIN_OP);

  for (int axis = 0; axis < 3; ++axis)
  {
    bounds[2 * axis] = global[axis];
    bounds[2 * axis + 1] = -global[3 + axis];
  }
  if (!(bounds[0] <= bounds[1]))
  {
    vtkMath::UninitializeBounds(bounds);
  }
#if FACET_HAVE_ICET
  this->PackEstimate =
    settings.WithEstimate && global[fitsAt] == 1.0 && this->Ranks <= vtkIceT::MaxPackedRanks;
#endif
  this->Agreed = true;
  for (int i = 0; i < settingCount; ++i)
  {
    this->Agreed = this->Agreed && global[6 + i] == -global[6 + settingCount + i];
  }
  if (!this->Agreed)
  {
    messages.AddError("the processes disagree on Size, CompositeRank, CompositeToAllRanks, "
                      "CompositeStrategy or EstimateError (here " +
      std::to_string(settings.Width) + " x " + std::to_string(settings.Height) + ", rank " +
      std::to_string(settings.Target) + (settings.ToAllRanks ? ", to all ranks" : "") +
      ", strategy " + std::to_string(static_cast<int>(settings.Method)) +
      (settings.WithEstimate ? ", estimating" : ", not estimating") +
      "): set them alike on every process");
  }
  else if (settings.Target < 0 || settings.Target >= this->Ranks)
  {
    messages.AddError("CompositeRank is " + std::to_string(settings.Target) + ", but the " +
      std::to_string(this->Ranks) + " processes are ranks 0 to " + std::to_string(this->Ranks - 1));
    this->Agreed = false;
  }
}

//------------------------------------------------------------------------------
vtkDataArray* vtkFacetCompositor::GlobalIdsOf(vtkPolyData* input, vtkFacetMessages& messages)
{
  vtkDataArray* ids = input ? input->GetCellData()->GetGlobalIds() : nullptr;
  if (!ids)
  {
    return nullptr;
  }
  const int type = ids->GetDataType();
  if (ids->GetNumberOfComponents() != 1 || ids->GetNumberOfTuples() < input->GetNumberOfCells() ||
    type == VTK_FLOAT || type == VTK_DOUBLE)
  {
    messages.AddWarning(std::string("the global cell ids '") +
      (ids->GetName() ? ids->GetName() : "") + "' (" + ids->GetDataTypeAsString() + ", " +
      std::to_string(ids->GetNumberOfTuples()) + " tuples of " +
      std::to_string(ids->GetNumberOfComponents()) + " components for " +
      std::to_string(input->GetNumberOfCells()) +
      " cells) are not one integer a cell: CellId keeps the piece's cell ids");
    return nullptr;
  }
  return ids;
}

//------------------------------------------------------------------------------
bool vtkFacetCompositor::CellIdsFit48Bits(vtkDataArray* globalIds)
{
  if (!globalIds || globalIds->GetNumberOfTuples() == 0)
  {
    return true; // a piece's own cell ids: fewer than 2^48 cells fit in memory
  }
  double range[2];
  globalIds->GetRange(range, 0); // cached by VTK until the array changes
  return range[0] >= 0.0 && range[1] < 0x1p48;
}

//------------------------------------------------------------------------------
void vtkFacetCompositor::LabelPixels(vtkDataArray* globalIds,
  vtkIdType* cellIds,
  int* rankIds,
  vtkIdType begin,
  vtkIdType end) const
{
  vtkIdTypeArray* ids = vtkIdTypeArray::FastDownCast(globalIds);
  for (vtkIdType i = begin; i < end; ++i)
  {
    const vtkIdType cell = cellIds[i];
    rankIds[i] = cell < 0 ? -1 : this->Rank;
    if (cell >= 0 && globalIds)
    {
      cellIds[i] = ids ? ids->GetValue(cell) : static_cast<vtkIdType>(globalIds->GetTuple1(cell));
    }
  }
}

//------------------------------------------------------------------------------
// Every rank learns which ranks rendered; the target names the others. Returns whether the
// target rendered (there is an image to hand out).
bool vtkFacetCompositor::Gather(bool rendered, vtkFacetMessages& messages)
{
  const int mine = rendered ? 1 : 0;
  std::vector<int> all(static_cast<std::size_t>(this->Ranks));
  this->Controller->AllGather(&mine, all.data(), 1);
  std::vector<int> failed;
  for (int rank = 0; rank < this->Ranks; ++rank)
  {
    if (!all[static_cast<std::size_t>(rank)])
    {
      failed.push_back(rank);
    }
  }
  this->FailedRanks = RankList(failed);
  const int target = this->Current.Target;
  const bool targetRendered = target >= 0 && target < this->Ranks && all[target];
  if (this->Agreed && IsAvailable() && rendered && this->Receives() && !failed.empty())
  {
    messages.AddWarning(std::string("the image lacks the piece") +
      (failed.size() > 1 ? "s of ranks " : " of rank ") + this->FailedRanks +
      ", which could not render it (see the error there)");
  }
  return targetRendered;
}

//------------------------------------------------------------------------------
void vtkFacetCompositor::MakeEmpty(vtkImageData* output) const
{
  // No pixels: an image piece of no extent, as ParaView's parallel pipeline expects of a
  // process that holds no part of an image; the field data (this rank's costs) stays.
  output->GetPointData()->Initialize();
  output->SetExtent(0, -1, 0, -1, 0, -1);
}

//------------------------------------------------------------------------------
void vtkFacetCompositor::KeepOwnPieces(vtkFacetImageRenderer& image,
  vtkImageData* output,
  vtkFacetMessages& messages)
{
  messages.AddWarningOnce("this build cannot composite (it has no IceT): each of the " +
    std::to_string(this->Ranks) + " processes shows its own piece of the input only");
  image.AddToReport(output,
    "  composite: none (built without IceT); rank " + std::to_string(this->Rank) + " of " +
      std::to_string(this->Ranks) + " shows its piece\n");
}

//------------------------------------------------------------------------------
void vtkFacetCompositor::Composite(vtkFacetImageRenderer& image,
  vtkImageData* output,
  bool rendered,
  vtkFacetMessages& messages,
  vtkFloatArray* estimate)
{
  const Clock::time_point start = Clock::now();
  const bool targetRendered = this->Gather(rendered, messages);
  if (!this->Agreed)
  {
    this->MakeEmpty(output);
    return;
  }
  if (!IsAvailable())
  {
    if (rendered)
    {
      this->KeepOwnPieces(image, output, messages);
    }
    return;
  }
  if (!targetRendered)
  {
    if (rendered && this->Receives())
    {
      messages.AddError("rank " + std::to_string(this->Current.Target) +
        ", which composites the image, could not render its piece (see the error there)");
    }
    this->MakeEmpty(output);
    return;
  }
#if FACET_HAVE_ICET
  vtkIceT& icet = *this->IceT;
  if (!icet.Bind(this->Controller, messages))
  {
    this->MakeEmpty(output);
    return;
  }
  Cost cost;
  const bool composited = this->RunIceT(image, rendered, estimate, cost, messages);
  if (!rendered)
  {
    return; // this rank's output is emptied with its error
  }
  if (!composited || !this->Receives())
  {
    this->MakeEmpty(output);
  }
  if (composited)
  {
    this->Report(image, output, cost, SecondsSince(start));
  }
#else
  (void)start;
#endif
}

#if FACET_HAVE_ICET
//------------------------------------------------------------------------------
bool vtkFacetCompositor::RunIceT(vtkFacetImageRenderer& image,
  bool rendered,
  vtkFloatArray* estimate,
  Cost& cost,
  vtkFacetMessages& messages)
{
  vtkIceT& icet = *this->IceT;
  using Payload = vtkIceT::Payload;
  const std::size_t pixels =
    static_cast<std::size_t>(this->Current.Width) * static_cast<std::size_t>(this->Current.Height);
  icet.Colors.resize(pixels);
  icet.Depths.resize(pixels);
  Payload* colors = icet.Colors.data();
  float* depths = icet.Depths.data();

  // This rank's pixels: a covered one (RankId set) carries its payload at half its window
  // depth; the others are background (depth 1), whose payload IceT never reads. A pixel
  // whose center sample shows no polygon may still have an estimate (with supersampling, a
  // silhouette's other samples): it goes at kEdgeDepth, behind every surface (their depths
  // are halved, at most 0.5) and before the background.
  constexpr float kEdgeDepth = 0.75f;
  const bool withEstimate = this->Current.WithEstimate;
  const std::size_t estimateValues =
    estimate ? static_cast<std::size_t>(estimate->GetNumberOfValues()) : 0;
  const float* ownEstimates =
    rendered && withEstimate && estimateValues == pixels ? estimate->GetPointer(0) : nullptr;
  const bool packed = this->PackEstimate;
  Clock::time_point start = Clock::now();
  if (rendered)
  {
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
          depths[i] = own != 0.0f ? kEdgeDepth : 1.0f;
          colors[i].Label = vtkIceT::EstimateOnly;
          continue;
        }
        const auto cell = static_cast<std::uint64_t>(cellIds[i]);
        std::memcpy(&colors[i].Rgba, rgba + 4 * i, 4);
        colors[i].CellLow = static_cast<std::uint32_t>(cell);
        if (packed)
        {
          colors[i].Label = vtkIceT::PackedLabel(rankIds[i], cell);
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
  else
  {
    std::fill(icet.Depths.begin(), icet.Depths.end(), 1.0f);
  }
  if (withEstimate && !packed)
  {
    icet.EstimateDepths.assign(icet.Depths.begin(), icet.Depths.end());
    icet.Estimates.assign(pixels, 0.0f);
    if (ownEstimates)
    {
      const float* values = ownEstimates;
      image.ForEachPixelBlock([&](vtkIdType begin, vtkIdType end) {
        for (vtkIdType i = begin; i < end; ++i)
        {
          icet.Estimates[i] = values[i];
          if (values[i] != 0.0f && icet.EstimateDepths[i] == 1.0f)
          {
            icet.EstimateDepths[i] = kEdgeDepth;
          }
        }
      });
    }
  }
  cost.PackSeconds = SecondsSince(start);

  // Every rank learns whether every rank composited, and the bytes they sent, before any
  // rank gives up: the broadcast below is collective too.
  bool ranHere = icet.Run(this->Current, this->Ranks, vtkIceT::Layer::Image, cost, messages);
  if (withEstimate && !packed)
  {
    // Run even when the first failed here: the others are in it.
    ranHere =
      icet.Run(this->Current, this->Ranks, vtkIceT::Layer::Estimate, cost, messages) && ranHere;
  }
  const long long local[2] = { cost.BytesSent, ranHere ? 0 : 1 };
  long long global[2] = { 0, 0 };
  this->Controller->AllReduce(local, global, 2, vtkCommunicator::SUM_OP);
  cost.BytesSentByAll = global[0];
  if (global[1] > 0)
  {
    if (ranHere)
    {
      messages.AddError("IceT could not composite on " + std::to_string(global[1]) + " ranks");
    }
    return false;
  }

  start = Clock::now();
  if (this->Current.ToAllRanks)
  {
    const int target = this->Current.Target;
    this->Controller->Broadcast(reinterpret_cast<int*>(colors),
      static_cast<vtkIdType>(pixels * sizeof(Payload) / sizeof(int)),
      target);
    this->Controller->Broadcast(depths, static_cast<vtkIdType>(pixels), target);
    if (withEstimate && !packed)
    {
      this->Controller->Broadcast(icet.Estimates.data(), static_cast<vtkIdType>(pixels), target);
    }
  }
  if (rendered && this->Receives())
  {
    // A pixel that no rank covers was background here too: it keeps this rank's values.
    unsigned char* rgba = image.GetRgba()->GetPointer(0);
    float* depth = image.GetDepth()->GetPointer(0);
    vtkIdType* cellIds = image.GetCellIds()->GetPointer(0);
    int* rankIds = image.GetRankIds()->GetPointer(0);
    float* estimates = withEstimate && estimateValues == pixels ? estimate->GetPointer(0) : nullptr;
    image.ForEachPixelBlock([&](vtkIdType begin, vtkIdType end) {
      for (vtkIdType i = begin; i < end; ++i)
      {
        if (estimates)
        {
          // Packed: no rank's estimate reached a pixel left at depth 1, so it keeps its own 0.
          if (!packed)
          {
            estimates[i] = icet.Estimates[i];
          }
          else if (depths[i] < 1.0f)
          {
            std::memcpy(estimates + i, &colors[i].Extra, sizeof(float));
          }
        }
        if (depths[i] >= 1.0f || (packed && colors[i].Label == vtkIceT::EstimateOnly))
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
  cost.UnpackSeconds = SecondsSince(start);
  return true;
}

//------------------------------------------------------------------------------
void vtkFacetCompositor::Report(vtkFacetImageRenderer& image,
  vtkImageData* output,
  const Cost& cost,
  double seconds) const
{
  vtkFieldData* fieldData = output->GetFieldData();
  vtkNew<vtkDoubleArray> times;
  times->SetName("FacetCompositeSeconds");
  times->SetNumberOfComponents(4);
  const char* timeNames[] = { "Total", "Pack", "IceT", "Unpack" };
  const double timeValues[] = { seconds, cost.PackSeconds, cost.IceTSeconds, cost.UnpackSeconds };
  for (int i = 0; i < 4; ++i)
  {
    times->SetComponentName(i, timeNames[i]);
  }
  times->InsertNextTuple(timeValues);
  fieldData->AddArray(times);

  vtkNew<vtkIdTypeArray> bytes;
  bytes->SetName("FacetCompositeBytes");
  bytes->SetNumberOfComponents(2);
  bytes->SetComponentName(0, "SentByThisRank");
  bytes->SetComponentName(1, "SentByAllRanks");
  const vtkIdType counts[] = { static_cast<vtkIdType>(cost.BytesSent),
    static_cast<vtkIdType>(cost.BytesSentByAll) };
  bytes->InsertNextTypedTuple(counts);
  fieldData->AddArray(bytes);

  std::ostringstream strategy;
  strategy << "IceT " << ICET_VERSION << " " << cost.Strategy << ", z-buffer, " << this->Ranks
           << " ranks onto " << (this->Current.ToAllRanks ? "every rank from rank " : "rank ")
           << this->Current.Target << ", ties to the lower rank";
  vtkNew<vtkStringArray> name;
  name->SetName("FacetCompositeStrategy");
  name->InsertNextValue(strategy.str());
  fieldData->AddArray(name);

  std::ostringstream plan;
  const bool secondComposite = this->Current.WithEstimate && !this->PackEstimate;
  plan << "  composite: " << strategy.str() << "; "
       << vtkIceT::BytesPerPixel + (secondComposite ? vtkIceT::EstimateBytesPerPixel : 0)
       << " bytes a covered pixel"
       << (this->PackEstimate   ? " (the error estimate in the payload), "
              : secondComposite ? " (the error estimate's 8 in a second composite), "
                                : ", ")
       << cost.BytesSentByAll << " sent by all ranks (" << cost.BytesSent << " by rank "
       << this->Rank << "), " << seconds << " s\n";
  image.AddToReport(output, plan.str());
}
#endif
