/**
 * @class   vtkFacetColoringMapper
 * @brief   Private: vtkFacetRenderFilter's coloring by data, held in a vtkMapper so that it
 *          reaches vtkFacetScalarColors by the path an actor's mapper takes.
 *
 * The filter's ScalarVisibility, ScalarMode, ColorMode, color array, ArrayComponent,
 * LookupTable, ScalarRange, UseLookupTableScalarRange and InterpolateScalarsBeforeMapping
 * are this mapper's, with vtkMapper's defaults. It never renders and has no input.
 */

#ifndef vtkFacetColoringMapper_h
#define vtkFacetColoringMapper_h

#include "vtkMapper.h"

class vtkFacetColoringMapper : public vtkMapper
{
public:
  static vtkFacetColoringMapper* New();
  vtkTypeMacro(vtkFacetColoringMapper, vtkMapper);

  /// Does nothing: Facet renders, not this mapper.
  void Render(vtkRenderer*, vtkActor*) override {}
  /// Uninitialized bounds: there is no input.
  double* GetBounds() override;

  /// The lookup table set, without creating the default one as GetLookupTable does.
  vtkScalarsToColors* GetLookupTableIfSet() const { return this->LookupTable; }

protected:
  vtkFacetColoringMapper() = default;
  ~vtkFacetColoringMapper() override = default;

private:
  vtkFacetColoringMapper(const vtkFacetColoringMapper&) = delete;
  void operator=(const vtkFacetColoringMapper&) = delete;
};

#endif
