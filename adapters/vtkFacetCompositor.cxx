// VTK-HeaderTest-Exclude: vtkFacetCompositor.h
#include "vtkFacetCompositor.h"

#include "vtkCellData.h"
#include "vtkCommunicator.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFacetImageRenderer.h"
#include "vtkFacetMessages.h"
#include "vtkFacetSeconds.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkMath.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"

#if FACET_HAVE_ICET
#include "vtkFacetIceT.h"
#endif

#include <chrono>
#include <iterator>
#include <limits>
#include <sstream>
#include <vector>

namespace {
using Clock = std::chrono::steady_clock;

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

#if !FACET_HAVE_ICET
class vtkFacetIceT
{
};
#endif

//------------------------------------------------------------------------------
vtkFacetCompositor::vtkFacetCompositor()
  : IceT(new vtkFacetIceT)
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
    settings.WithEstimate && global[fitsAt] == 1.0 && this->Ranks <= vtkFacetIceT::MaxPackedRanks;
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
  if (!this->IceT->Bind(this->Controller, messages))
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
    this->Report(image, output, cost, vtkFacetSecondsSince(start));
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
  vtkFacetIceT& icet = *this->IceT;
  using Layout = vtkFacetIceT::EstimateLayout;
  const Layout layout = !this->Current.WithEstimate ? Layout::None
    : this->PackEstimate                            ? Layout::Packed
                                                    : Layout::SecondComposite;
  const std::size_t pixels =
    static_cast<std::size_t>(this->Current.Width) * static_cast<std::size_t>(this->Current.Height);
  float* estimates = layout != Layout::None && estimate &&
      static_cast<std::size_t>(estimate->GetNumberOfValues()) == pixels
    ? estimate->GetPointer(0)
    : nullptr;

  Clock::time_point start = Clock::now();
  icet.Pack(image, pixels, rendered, rendered ? estimates : nullptr, layout);
  cost.PackSeconds = vtkFacetSecondsSince(start);

  // Every rank learns whether every rank composited, and the bytes they sent, before any
  // rank gives up: the broadcast below is collective too.
  bool ranHere = icet.Run(this->Current, this->Ranks, vtkFacetIceT::Layer::Image, cost, messages);
  if (layout == Layout::SecondComposite)
  {
    // Run even when the first failed here: the others are in it.
    ranHere = icet.Run(this->Current, this->Ranks, vtkFacetIceT::Layer::Estimate, cost, messages) &&
      ranHere;
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
    icet.Broadcast(this->Controller, this->Current.Target, layout);
  }
  if (rendered && this->Receives())
  {
    icet.Unpack(image, estimates, layout);
  }
  cost.UnpackSeconds = vtkFacetSecondsSince(start);
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
       << vtkFacetIceT::BytesPerPixel + (secondComposite ? vtkFacetIceT::EstimateBytesPerPixel : 0)
       << " bytes a covered pixel"
       << (this->PackEstimate   ? " (the error estimate in the payload), "
              : secondComposite ? " (the error estimate's 8 in a second composite), "
                                : ", ")
       << cost.BytesSentByAll << " sent by all ranks (" << cost.BytesSent << " by rank "
       << this->Rank << "), " << seconds << " s\n";
  image.AddToReport(output, plan.str());
}
#endif
