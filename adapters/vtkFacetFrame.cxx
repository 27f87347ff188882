#include "vtkFacetFrame.h"

//------------------------------------------------------------------------------
bool vtkFacetFrame::Render(vtkImageData* output,
  vtkFacetImageRenderer& image,
  vtkFacetQuality& quality,
  vtkFacetMessages& messages)
{
  this->Image.RenderWith = quality.Prepare(this->Quality, messages);
  if (!image.Render(
        this->Scene, this->Camera, this->Image, output, this->MapIds, this->Conversions, messages))
  {
    return false;
  }
  quality.AddOutputs(this->Scene,
    this->Camera,
    image.GetPolygonIds(),
    this->Image.Background,
    this->Image.TwoSidedLighting,
    this->Image.Threads,
    output,
    messages);
  return true;
}
