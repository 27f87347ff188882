// vtkFacetRenderFilter's coloring by data: vtkMapper's settings, held by the coloring mapper,
// and the array ParaView's array selection names.
#include "vtkFacetRenderFilterInternals.h"

#include "vtkDataObject.h"
#include "vtkInformation.h"
#include "vtkScalarsToColors.h"

//------------------------------------------------------------------------------
#define vtkFacetColoringSetting(name, type)                                                        \
  void vtkFacetRenderFilter::Set##name(type value)                                                 \
  {                                                                                                \
    this->Internals->Coloring->Set##name(value);                                                   \
  }                                                                                                \
  type vtkFacetRenderFilter::Get##name()                                                           \
  {                                                                                                \
    return this->Internals->Coloring->Get##name();                                                 \
  }
vtkFacetColoringSetting(ScalarVisibility, vtkTypeBool);
vtkFacetColoringSetting(ScalarMode, int);
vtkFacetColoringSetting(ColorMode, int);
vtkFacetColoringSetting(ArrayComponent, int);
vtkFacetColoringSetting(LookupTable, vtkScalarsToColors*);
vtkFacetColoringSetting(UseLookupTableScalarRange, vtkTypeBool);
vtkFacetColoringSetting(InterpolateScalarsBeforeMapping, vtkTypeBool);
#undef vtkFacetColoringSetting

void vtkFacetRenderFilter::SetScalarModeToDefault()
{
  this->SetScalarMode(VTK_SCALAR_MODE_DEFAULT);
}
void vtkFacetRenderFilter::SetScalarModeToUsePointData()
{
  this->SetScalarMode(VTK_SCALAR_MODE_USE_POINT_DATA);
}
void vtkFacetRenderFilter::SetScalarModeToUseCellData()
{
  this->SetScalarMode(VTK_SCALAR_MODE_USE_CELL_DATA);
}
void vtkFacetRenderFilter::SetScalarModeToUsePointFieldData()
{
  this->SetScalarMode(VTK_SCALAR_MODE_USE_POINT_FIELD_DATA);
}
void vtkFacetRenderFilter::SetScalarModeToUseCellFieldData()
{
  this->SetScalarMode(VTK_SCALAR_MODE_USE_CELL_FIELD_DATA);
}
void vtkFacetRenderFilter::SetColorModeToDefault()
{
  this->SetColorMode(VTK_COLOR_MODE_DEFAULT);
}
void vtkFacetRenderFilter::SetColorModeToMapScalars()
{
  this->SetColorMode(VTK_COLOR_MODE_MAP_SCALARS);
}
void vtkFacetRenderFilter::SetColorModeToDirectScalars()
{
  this->SetColorMode(VTK_COLOR_MODE_DIRECT_SCALARS);
}

void vtkFacetRenderFilter::SetScalarRange(double minimum, double maximum)
{
  this->Internals->Coloring->SetScalarRange(minimum, maximum);
}
void vtkFacetRenderFilter::SetScalarRange(const double range[2])
{
  this->SetScalarRange(range[0], range[1]);
}
double* vtkFacetRenderFilter::GetScalarRange()
{
  return this->Internals->Coloring->GetScalarRange();
}

// vtkMapper::SelectColorArray also sets ArrayComponent to -1 (the magnitude); the filter
// has always kept it.
void vtkFacetRenderFilter::SelectColorArray(int arrayId)
{
  this->Internals->Coloring->SetArrayId(arrayId);
  this->Internals->Coloring->SetArrayAccessMode(VTK_GET_ARRAY_BY_ID);
}
void vtkFacetRenderFilter::SelectColorArray(const char* arrayName)
{
  this->Internals->Coloring->SetArrayName(arrayName);
  this->Internals->Coloring->SetArrayAccessMode(VTK_GET_ARRAY_BY_NAME);
}
const char* vtkFacetRenderFilter::GetArrayName()
{
  const char* name = this->Internals->Coloring->GetArrayName();
  return name && *name ? name : nullptr;
}
int vtkFacetRenderFilter::GetArrayId()
{
  return this->Internals->Coloring->GetArrayId();
}
int vtkFacetRenderFilter::GetArrayAccessMode()
{
  return this->Internals->Coloring->GetArrayAccessMode();
}

//------------------------------------------------------------------------------
vtkFacetScalarColors::Settings vtkFacetRenderFilter::vtkInternals::ColoringOf(
  vtkFacetRenderFilter* filter)
{
  vtkFacetScalarColors::Settings coloring = vtkFacetScalarColors::Settings::Of(this->Coloring);
  vtkInformation* array = filter->GetInputArrayInformation(0);
  const char* name = array->Get(vtkDataObject::FIELD_NAME());
  const int association = array->Has(vtkDataObject::FIELD_ASSOCIATION())
    ? array->Get(vtkDataObject::FIELD_ASSOCIATION())
    : -1;
  if (name && *name &&
    (association == vtkDataObject::FIELD_ASSOCIATION_POINTS ||
      association == vtkDataObject::FIELD_ASSOCIATION_CELLS))
  {
    coloring.ScalarMode = association == vtkDataObject::FIELD_ASSOCIATION_POINTS
      ? VTK_SCALAR_MODE_USE_POINT_FIELD_DATA
      : VTK_SCALAR_MODE_USE_CELL_FIELD_DATA;
    coloring.ArrayAccessMode = VTK_GET_ARRAY_BY_NAME;
    coloring.ArrayName = name;
  }
  return coloring;
}

//------------------------------------------------------------------------------
void vtkFacetRenderFilter::vtkInternals::PrintColoring(vtkFacetRenderFilter* filter,
  ostream& os,
  vtkIndent indent)
{
  vtkFacetColoringMapper* coloring = this->Coloring;
  os << indent << "ScalarVisibility: " << coloring->GetScalarVisibility() << "\n";
  os << indent << "ScalarMode: " << coloring->GetScalarModeAsString() << "\n";
  os << indent << "ColorMode: " << coloring->GetColorModeAsString() << "\n";
  const char* name = filter->GetArrayName();
  os << indent << "ArrayName: " << (name ? name : "(none)") << "\n";
  os << indent << "ArrayId: " << coloring->GetArrayId() << "\n";
  os << indent << "ArrayComponent: " << coloring->GetArrayComponent() << "\n";
  os << indent << "LookupTable: " << coloring->GetLookupTableIfSet() << "\n";
  os << indent << "ScalarRange: (" << coloring->GetScalarRange()[0] << ", "
     << coloring->GetScalarRange()[1] << ")\n";
  os << indent << "UseLookupTableScalarRange: " << coloring->GetUseLookupTableScalarRange() << "\n";
  os << indent
     << "InterpolateScalarsBeforeMapping: " << coloring->GetInterpolateScalarsBeforeMapping()
     << "\n";
}
