// vtkFacetRenderFilter across the processes of its controller: one camera fitted to the
// union of all pieces, and the pieces' images composited into one.
#include "vtkFacetRenderFilterInternals.h"

#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMath.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

//------------------------------------------------------------------------------
void vtkFacetRenderFilter::vtkInternals::BoundsOf(vtkFacetRenderFilter* filter,
  vtkPolyData* input,
  bool parallel,
  double bounds[6])
{
  this->Actor.GetFiniteBounds(bounds);
  this->GlobalIds = nullptr;
  if (!parallel)
  {
    return;
  }
  this->GlobalIds = vtkFacetCompositor::GlobalIdsOf(input, this->Messages);
  if (this->Messages.HasErrors())
  {
    vtkMath::UninitializeBounds(bounds); // this piece adds nothing
  }
  this->Compositor.Prepare(
    filter->Controller, CompositeSettingsOf(filter, this->GlobalIds), bounds, this->Messages);
}

//------------------------------------------------------------------------------
void vtkFacetRenderFilter::vtkInternals::Composite(vtkFacetRenderFilter* filter,
  vtkImageData* output,
  bool rendered)
{
  this->Compositor.Composite(this->Image,
    output,
    rendered,
    this->Messages,
    vtkFloatArray::SafeDownCast(output->GetPointData()->GetArray("ErrorEstimate")));
  if (vtkFacetCompositor::IsAvailable() && output->GetNumberOfPoints() > 0)
  {
    vtkFacetQuality::SummarizeEstimateArray(output); // the composited image's, not the piece's
  }
  RemoveArraysNotAsked(filter, output);
  if (filter->ComputeError)
  {
    // Each rank's measurement is of its own piece, not of the composited pixels.
    this->Messages.AddWarningOnce("ComputeError across processes measures each process's piece "
                                  "against that piece's reference: FacetError describes this "
                                  "rank's piece, and the composited image has no Error array");
    output->GetPointData()->RemoveArray("Error");
  }
}

//------------------------------------------------------------------------------
void vtkFacetRenderFilter::vtkInternals::RemoveArraysNotAsked(vtkFacetRenderFilter* filter,
  vtkImageData* output)
{
  if (!filter->OutputDepth)
  {
    output->GetPointData()->RemoveArray("Depth");
  }
  if (!filter->OutputCellIds)
  {
    output->GetPointData()->RemoveArray("CellId");
  }
  if (!filter->ErrorEstimateArray)
  {
    output->GetPointData()->RemoveArray("ErrorEstimate");
  }
}
