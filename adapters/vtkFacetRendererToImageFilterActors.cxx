#include "vtkFacetRendererToImageFilterInternals.h"

#include "vtkActor.h"
#include "vtkAssemblyNode.h"
#include "vtkAssemblyPath.h"
#include "vtkCompositePolyDataMapper.h"
#include "vtkDataSetMapper.h"
#include "vtkMatrix4x4.h"
#include "vtkPolyDataMapper.h"
#include "vtkPropCollection.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"

#include <algorithm>

namespace {
// Mappers that are vtkPolyDataMappers but draw their points as something else.
constexpr const char* PointMappers[] = { "vtkPointGaussianMapper",
  "vtkOpenGLSphereMapper",
  "vtkOpenGLStickMapper" };

// Whether Facet renders what this mapper draws: the polygons of its polydata.
bool DrawsPolygons(vtkMapper* mapper)
{
  if (vtkCompositePolyDataMapper::SafeDownCast(mapper) || vtkDataSetMapper::SafeDownCast(mapper))
  {
    return true;
  }
  return vtkPolyDataMapper::SafeDownCast(mapper) &&
    std::none_of(std::begin(PointMappers), std::end(PointMappers), [&](const char* name) {
      return mapper->IsA(name);
    });
}

// What keeps a visible actor from being rendered, for the warning; empty when nothing.
std::string WhyNotRendered(vtkActor* actor)
{
  vtkMapper* mapper = actor->GetMapper();
  const std::string name = actor->GetClassName();
  if (!mapper)
  {
    return name + " without a mapper";
  }
  if (!DrawsPolygons(mapper))
  {
    return name + " with " + mapper->GetClassName();
  }
  if (mapper->GetNumberOfInputConnections(0) == 0)
  {
    return name + " whose " + mapper->GetClassName() + " has no input";
  }
  return {};
}

// What the actor asks for that Facet does not render yet (its property: the actor converter).
void WarnAboutUnrenderedActor(vtkActor* actor, vtkFacetMessages& messages)
{
  std::vector<std::string> asks;
  if (actor->GetTexture())
  {
    asks.push_back("a texture");
  }
  if (actor->GetBackfaceProperty())
  {
    asks.push_back("a backface property");
  }
  if (!asks.empty())
  {
    messages.AddWarningOnce("the actor has " + vtkFacetMessages::List(asks) +
      ", which Facet does not render yet (said once)");
  }
}

// How VTK's OpenGL mapper shades an actor's polygons: as its property's Interpolation says
// when its data has point normals; without them with the face normal (the shaders take it
// from the screen-space derivatives of the position), flat whatever the interpolation.
int InterpolationOf(vtkProperty* property, const facet::SceneMesh& mesh)
{
  return mesh.mesh.pointNormals.count > 0 ? property->GetInterpolation() : VTK_FLAT;
}
}

//------------------------------------------------------------------------------
void vtkFacetRendererToImageFilter::vtkInternals::ForEachActor(vtkRenderer* renderer,
  const ActorVisit& visit,
  std::set<std::string>& skipped)
{
  vtkCollectionSimpleIterator props;
  renderer->GetViewProps()->InitTraversal(props);
  int index = 0;
  for (vtkProp* prop; (prop = renderer->GetViewProps()->GetNextProp(props)); ++index)
  {
    if (!prop->GetVisibility())
    {
      continue;
    }
    prop->InitPathTraversal();
    while (vtkAssemblyPath* path = prop->GetNextPath())
    {
      vtkAssemblyNode* node = path->GetLastNode();
      auto* actor = vtkActor::SafeDownCast(node->GetViewProp());
      if (!actor)
      {
        skipped.insert(node->GetViewProp()->GetClassName());
        continue;
      }
      if (!actor->GetVisibility())
      {
        continue;
      }
      const std::string why = WhyNotRendered(actor);
      if (!why.empty())
      {
        skipped.insert(why);
        continue;
      }
      // A part of an assembly carries its full matrix in its path; an actor alone, none.
      visit(index, actor, node->GetMatrix() ? node->GetMatrix() : actor->GetMatrix());
    }
  }
}

//------------------------------------------------------------------------------
vtkDataObject* vtkFacetRendererToImageFilter::vtkInternals::InputOf(vtkMapper* mapper)
{
  if (!mapper->GetStatic())
  {
    mapper->GetInputAlgorithm()->Update();
  }
  return mapper->GetInputDataObject(0, 0);
}

//------------------------------------------------------------------------------
void vtkFacetRendererToImageFilter::vtkInternals::AddActors(vtkRenderer* renderer,
  vtkFacetSceneConverter::Lighting lighting,
  bool detectClosedSurfaces,
  facet::Scene& scene)
{
  std::set<std::string> skipped;
  std::size_t count = 0;
  std::int64_t polygons = 0;
  this->MeshInterpolation.clear();
  ForEachActor(
    renderer,
    [&](int propIndex, vtkActor* prop, vtkMatrix4x4* matrix) {
      if (count == this->Leaves.size())
      {
        this->Leaves.push_back(std::make_unique<Leaf>());
      }
      Leaf& leaf = *this->Leaves[count++];
      vtkMapper* mapper = prop->GetMapper();
      vtkFacetActorConverter::Actor actor;
      actor.Data = InputOf(mapper);
      actor.Coloring = vtkFacetScalarColors::Settings::Of(mapper);
      actor.Property = prop->GetProperty();
      actor.Matrix = matrix;
      actor.Lighting = lighting;
      this->Messages.SetContext(
        "actor " + std::to_string(propIndex) + " (" + prop->GetClassName() + "): ");
      WarnAboutUnrenderedActor(prop, this->Messages);
      leaf.PropIndex = propIndex;
      leaf.FirstPolygon = polygons;
      if (leaf.Converter.Update(actor, detectClosedSurfaces, this->Messages))
      {
        const std::size_t first = scene.meshes.size();
        leaf.Converter.AddTo(scene);
        for (std::size_t m = first; m < scene.meshes.size(); ++m)
        {
          this->MeshInterpolation.push_back(InterpolationOf(actor.Property, scene.meshes[m]));
        }
        polygons += leaf.Converter.GetNumberOfPolygons();
      }
    },
    skipped);
  this->Messages.SetContext("");
  this->Leaves.resize(count);
  this->LeafStarts.resize(count);
  std::transform(this->Leaves.begin(),
    this->Leaves.end(),
    this->LeafStarts.begin(),
    [](const std::unique_ptr<Leaf>& leaf) { return leaf->FirstPolygon; });
  if (!skipped.empty())
  {
    this->Messages.AddWarningOnce("skipped props that Facet does not render: " +
      vtkFacetMessages::List({ skipped.begin(), skipped.end() }) + " (said once)");
  }
}

//------------------------------------------------------------------------------
int vtkFacetRendererToImageFilter::vtkInternals::NumberOfConversions() const
{
  int conversions = 0;
  for (const auto& leaf : this->Leaves)
  {
    conversions += leaf->Converter.GetNumberOfConversions();
  }
  return conversions;
}
