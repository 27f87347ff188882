#include "vtkFacetRendererToImageFilterInternals.h"

#include "vtkIdTypeArray.h"
#include "vtkIntArray.h"
#include "vtkRenderer.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>

namespace {
// The byte VTK's gradient background quad gives row y of `height`: its corner colors are
// truncated to bytes, interpolated at the pixel center and rounded to the framebuffer's.
unsigned char GradientByte(double bottom, double top, int y, int height)
{
  const double b = std::floor(bottom * 255.0), t = std::floor(top * 255.0);
  return static_cast<unsigned char>(std::lround(b + (t - b) * (y + 0.5) / height));
}
}

//------------------------------------------------------------------------------
void vtkFacetRendererToImageFilter::vtkInternals::MapIds(vtkRenderer* renderer,
  const std::int32_t* polygonIds,
  vtkIdType begin,
  vtkIdType end)
{
  vtkIdType* cellIds = this->Image.GetCellIds()->GetPointer(0);
  int* actorIds = this->Image.GetActorIds()->GetPointer(0);
  unsigned char* rgba = this->Image.GetRgba()->GetPointer(0);
  int size[2];
  this->Image.GetSize(size);
  const bool gradient = renderer->GetGradientBackground();
  const double *bottom = renderer->GetBackground(), *top = renderer->GetBackground2();
  // One actor: its cell ids straight from its converter (for one part, in SIMD lanes,
  // streamed: vtkFacetActorConverter::CellIdsOf), then its actor id where it shows.
  const bool oneActor = this->Leaves.size() == 1;
  if (oneActor)
  {
    this->Leaves[0]->Converter.CellIdsOf(
      polygonIds, cellIds, begin, end, this->Image.StreamsIdPlanes());
  }
  for (vtkIdType i = begin; i < end; ++i)
  {
    const std::int32_t id = polygonIds[i];
    if (id < 0)
    {
      actorIds[i] = -1;
      if (!oneActor)
      {
        cellIds[i] = -1;
      }
      const int y = static_cast<int>(i / size[0]);
      for (int c = 0; gradient && c < 3; ++c)
      {
        rgba[4 * i + c] = GradientByte(bottom[c], top[c], y, size[1]);
      }
      continue;
    }
    if (oneActor)
    {
      actorIds[i] = this->Leaves[0]->PropIndex;
      continue;
    }
    const std::size_t k = static_cast<std::size_t>(
      std::upper_bound(this->LeafStarts.begin(), this->LeafStarts.end(), id) -
      this->LeafStarts.begin() - 1);
    const Leaf& leaf = *this->Leaves[k];
    actorIds[i] = leaf.PropIndex;
    cellIds[i] = leaf.Converter.CellIdOf(id - leaf.FirstPolygon);
  }
}
