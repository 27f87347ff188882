// VTK-HeaderTest-Exclude: vtkFacetColoringMapper.h
#include "vtkFacetColoringMapper.h"

#include "vtkMath.h"
#include "vtkObjectFactory.h"

vtkStandardNewMacro(vtkFacetColoringMapper);

//------------------------------------------------------------------------------
double* vtkFacetColoringMapper::GetBounds()
{
  vtkMath::UninitializeBounds(this->Bounds);
  return this->Bounds;
}
