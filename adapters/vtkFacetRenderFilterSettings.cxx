// The settings of the pieces an execution of vtkFacetRenderFilter uses (the actor converter,
// the image renderer, the quality modes, the compositor), each from the filter's.
#include "vtkFacetRenderFilterInternals.h"

#include "vtkLightCollection.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"

#include <algorithm>

//------------------------------------------------------------------------------
vtkFacetSceneConverter::LightOptions vtkFacetRenderFilter::vtkInternals::LightOptionsOf(
  vtkFacetRenderFilter* filter)
{
  vtkFacetSceneConverter::LightOptions lights;
  lights.AddHeadlight = filter->AutomaticLightCreation && filter->Lights->GetNumberOfItems() == 0;
  std::copy_n(filter->AmbientLightColor, 3, lights.AmbientColor);
  return lights;
}

//------------------------------------------------------------------------------
vtkFacetActorConverter::Actor vtkFacetRenderFilter::vtkInternals::ActorOf(
  vtkFacetRenderFilter* filter,
  vtkPolyData* input)
{
  vtkFacetActorConverter::Actor actor;
  actor.Data = input;
  actor.Coloring = this->ColoringOf(filter);
  actor.Property = filter->GetProperty();
  actor.Lighting = vtkFacetSceneConverter::LightingOf(filter->Lights, LightOptionsOf(filter));
  // Without a light the filter's surfaces are lit by nothing but the ambient light, as they
  // always have been, not shown unlit.
  if (actor.Lighting == vtkFacetSceneConverter::Lighting::Unlit)
  {
    actor.Lighting = vtkFacetSceneConverter::Lighting::Lights;
  }
  return actor;
}

//------------------------------------------------------------------------------
vtkFacetImageRenderer::Settings vtkFacetRenderFilter::vtkInternals::SettingsOf(
  vtkFacetRenderFilter* filter,
  bool parallel)
{
  vtkFacetImageRenderer::Settings settings;
  settings.Width = filter->Size[0];
  settings.Height = filter->Size[1];
  settings.Threads = filter->NumberOfThreads;
  settings.Visibility = filter->VisibilityMode == PainterSort ? facet::Visibility::PainterSort
                                                              : facet::Visibility::ZBuffer;
  settings.TwoSidedLighting = filter->TwoSidedLighting != 0;
  std::copy_n(filter->Background, 3, settings.Background);
  settings.BackgroundAlpha = filter->BackgroundAlpha;
  settings.Depth = filter->OutputDepth || parallel;
  settings.CellIds = filter->OutputCellIds || parallel;
  settings.RankIds = settings.Composited = parallel;
  settings.CellIdsOnly = !parallel; // CellLabels: RankId too when parallel
  settings.Rules.lightTolerance = filter->LightCullingTolerance;
  settings.Rules.incremental = filter->IncrementalRendering != 0;
  return settings;
}

//------------------------------------------------------------------------------
vtkFacetQuality::Settings vtkFacetRenderFilter::vtkInternals::QualityOf(
  vtkFacetRenderFilter* filter,
  bool composited)
{
  return { filter->GetProperty()->GetInterpolation(),
    filter->SamplesPerPixel,
    filter->MaximumError,
    filter->ComputeError != 0,
    filter->EstimateError != 0,
    filter->ErrorEstimateArray || (composited && Estimates(filter)) };
}

//------------------------------------------------------------------------------
vtkFacetCompositor::Settings vtkFacetRenderFilter::vtkInternals::CompositeSettingsOf(
  vtkFacetRenderFilter* filter,
  vtkDataArray* globalIds)
{
  vtkFacetCompositor::Settings composite;
  composite.Width = filter->Size[0];
  composite.Height = filter->Size[1];
  composite.Target = filter->CompositeRank;
  composite.ToAllRanks = filter->CompositeToAllRanks != 0;
  composite.Method = static_cast<vtkFacetCompositor::Strategy>(filter->CompositeStrategy);
  composite.WithEstimate = Estimates(filter);
  composite.CellIdsFit48Bits = vtkFacetCompositor::CellIdsFit48Bits(globalIds);
  return composite;
}
