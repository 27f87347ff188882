#include "vtkFacetRendererToImageFilter.h"

#include "vtkActor.h"
#include "vtkAssemblyNode.h"
#include "vtkAssemblyPath.h"
#include "vtkCamera.h"
#include "vtkCompositePolyDataMapper.h"
#include "vtkDataSetMapper.h"
#include "vtkFacetActorConverter.h"
#include "vtkFacetImageRenderer.h"
#include "vtkFacetMessages.h"
#include "vtkFacetQuality.h"
#include "vtkFacetSceneConverter.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkPolyDataMapper.h"
#include "vtkPropCollection.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkScalarsToColors.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

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

// The mapper's input, brought up to date as rendering would bring it (unless Static).
vtkDataObject* InputOf(vtkMapper* mapper)
{
  if (!mapper->GetStatic())
  {
    mapper->GetInputAlgorithm()->Update();
  }
  return mapper->GetInputDataObject(0, 0);
}

bool AnyLightOn(vtkRenderer* renderer)
{
  vtkCollectionSimpleIterator iterator;
  renderer->GetLights()->InitTraversal(iterator);
  while (vtkLight* light = renderer->GetLights()->GetNextLight(iterator))
  {
    if (light->GetSwitch())
    {
      return true;
    }
  }
  return false;
}

// What the renderer asks for that Facet does not render yet.
void WarnAboutUnrendered(vtkRenderer* renderer, vtkFacetMessages& messages)
{
  std::vector<std::string> asks;
  if (renderer->GetUseShadows())
  {
    asks.push_back("shadows (UseShadows)");
  }
  if (renderer->GetTexturedBackground())
  {
    asks.push_back("a textured background");
  }
  if (renderer->GetUseSSAO())
  {
    asks.push_back("ambient occlusion (UseSSAO)");
  }
  if (renderer->GetUseImageBasedLighting())
  {
    asks.push_back("image-based lighting");
  }
  if (!asks.empty())
  {
    messages.AddWarningOnce("the renderer asks for " + vtkFacetMessages::List(asks) +
      ", which Facet does not render yet (said once)");
  }
}

// What the actor asks for that Facet does not render yet (its property: the actor converter).
void WarnAboutUnrendered(vtkActor* actor, vtkFacetMessages& messages)
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

// The byte VTK's gradient background quad gives row y of `height`: its corner colors are
// truncated to bytes, interpolated at the pixel center and rounded to the framebuffer's.
unsigned char GradientByte(double bottom, double top, int y, int height)
{
  const double b = std::floor(bottom * 255.0), t = std::floor(top * 255.0);
  return static_cast<unsigned char>(std::lround(b + (t - b) * (y + 0.5) / height));
}
}

//------------------------------------------------------------------------------
class vtkFacetRendererToImageFilter::vtkInternals
{
public:
  // A rendered vtkActor (or a part of an assembly) and its prop's index in the renderer.
  struct Leaf
  {
    int PropIndex = -1;
    vtkFacetActorConverter Converter;
    std::int64_t FirstPolygon = 0; // in the scene
  };

  vtkFacetImageRenderer Image;
  vtkFacetQuality Quality;            // shading modes and supersampling
  std::vector<int> MeshInterpolation; // per scene mesh, its actor's property's
  vtkFacetMessages Messages;
  std::vector<std::unique_ptr<Leaf>> Leaves; // kept between executions, by position
  std::vector<std::int64_t> LeafStarts;      // their first polygons, for the id lookup
  std::map<vtkObject*, vtkMTimeType> Seen;   // what the last execution saw, and when

  // Calls visit(propIndex, actor, matrix) for every visible vtkActor leaf Facet renders;
  // the classes of the other visible props go to `skipped`.
  template<class Visit>
  static void ForEachActor(vtkRenderer* renderer,
    const Visit& visit,
    std::set<std::string>& skipped);
  // Calls see(object) for every object whose change changes the image (null ones too).
  template<class See>
  static void ForEachSceneObject(vtkRenderer* renderer, const See& see);
  vtkCamera* CameraOf(vtkRenderer* renderer, int width, int height);
  void AddActors(vtkRenderer* renderer,
    vtkFacetSceneConverter::Lighting lighting,
    bool detectClosedSurfaces,
    facet::Scene& scene);
  int NumberOfConversions() const;
  // Remembers the MTime of everything ForEachSceneObject sees, for GetMTime.
  void RememberScene(vtkRenderer* renderer);
  void MapIds(vtkRenderer* renderer,
    const std::int32_t* polygonIds,
    vtkIdType begin,
    vtkIdType end);
};

//------------------------------------------------------------------------------
template<class Visit>
void vtkFacetRendererToImageFilter::vtkInternals::ForEachActor(vtkRenderer* renderer,
  const Visit& visit,
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
template<class See>
void vtkFacetRendererToImageFilter::vtkInternals::ForEachSceneObject(vtkRenderer* renderer,
  const See& see)
{
  see(renderer);
  see(renderer->GetRenderWindow()); // its size, when it sets the image's
  see(renderer->IsActiveCameraCreated() ? renderer->GetActiveCamera() : nullptr);
  see(renderer->GetLights());
  vtkCollectionSimpleIterator lights;
  renderer->GetLights()->InitTraversal(lights);
  while (vtkLight* light = renderer->GetLights()->GetNextLight(lights))
  {
    see(light);
  }
  see(renderer->GetViewProps());
  vtkCollectionSimpleIterator props;
  renderer->GetViewProps()->InitTraversal(props);
  while (vtkProp* prop = renderer->GetViewProps()->GetNextProp(props))
  {
    see(prop); // also an invisible one: its visibility may change
  }
  // Each rendered actor (with its property), its mapper (with its lookup table) and the
  // mapper's input, brought up to date, as vtkActor::GetRedrawMTime looks at them.
  std::set<std::string> skipped;
  ForEachActor(
    renderer,
    [&](int, vtkActor* actor, vtkMatrix4x4*) {
      see(actor); // its matrix is its own and its assembly's (the top prop's) MTime
      see(actor->GetMapper());
      see(InputOf(actor->GetMapper()));
    },
    skipped);
}

//------------------------------------------------------------------------------
vtkCamera* vtkFacetRendererToImageFilter::vtkInternals::CameraOf(vtkRenderer* renderer,
  int width,
  int height)
{
  if (renderer->IsActiveCameraCreated())
  {
    return renderer->GetActiveCamera();
  }
  // What vtkRenderer::Render does to a renderer without a camera, for this image's aspect.
  vtkCamera* camera = renderer->GetActiveCamera();
  double bounds[6];
  renderer->ComputeVisiblePropBounds(bounds);
  vtkFacetSceneConverter::FitCamera(camera, bounds, width, height);
  return camera;
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
      WarnAboutUnrendered(prop, this->Messages);
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
void vtkFacetRendererToImageFilter::vtkInternals::RememberScene(vtkRenderer* renderer)
{
  this->Seen.clear();
  ForEachSceneObject(renderer, [&](vtkObject* object) {
    if (object)
    {
      this->Seen[object] = object->GetMTime();
    }
  });
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
  for (vtkIdType i = begin; i < end; ++i)
  {
    const std::int32_t id = polygonIds[i];
    if (id < 0)
    {
      cellIds[i] = actorIds[i] = -1;
      const int y = static_cast<int>(i / size[0]);
      for (int c = 0; gradient && c < 3; ++c)
      {
        rgba[4 * i + c] = GradientByte(bottom[c], top[c], y, size[1]);
      }
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

//------------------------------------------------------------------------------
vtkStandardNewMacro(vtkFacetRendererToImageFilter);
vtkCxxSetObjectMacro(vtkFacetRendererToImageFilter, Renderer, vtkRenderer);

//------------------------------------------------------------------------------
vtkFacetRendererToImageFilter::vtkFacetRendererToImageFilter()
  : Internals(new vtkInternals)
{
  this->SetNumberOfInputPorts(0);
  this->SetNumberOfOutputPorts(1);
}

//------------------------------------------------------------------------------
vtkFacetRendererToImageFilter::~vtkFacetRendererToImageFilter()
{
  this->SetRenderer(nullptr);
  delete this->Internals;
}

//------------------------------------------------------------------------------
void vtkFacetRendererToImageFilter::GetEffectiveSize(int size[2])
{
  size[0] = this->Size[0];
  size[1] = this->Size[1];
  if (size[0] != 0 || size[1] != 0)
  {
    return;
  }
  vtkRenderWindow* window = this->Renderer ? this->Renderer->GetRenderWindow() : nullptr;
  const int* windowSize = window ? window->GetSize() : nullptr;
  if (windowSize && windowSize[0] > 0 && windowSize[1] > 0)
  {
    const int* rendererSize = this->Renderer->GetSize(); // its viewport, in pixels
    size[0] = rendererSize[0];
    size[1] = rendererSize[1];
    return;
  }
  size[0] = 640;
  size[1] = 480;
}

//------------------------------------------------------------------------------
void vtkFacetRendererToImageFilter::SetNumberOfThreads(int threads)
{
  if (vtkFacetImageRenderer::CheckThreadCount(this, threads, this->NumberOfThreads) &&
    threads != this->NumberOfThreads)
  {
    this->NumberOfThreads = threads;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
const char* vtkFacetRendererToImageFilter::GetRenderPlan()
{
  return this->Internals->Image.GetPlan().c_str();
}

//------------------------------------------------------------------------------
vtkMTimeType vtkFacetRendererToImageFilter::GetMTime()
{
  // What changed since the last execution saw it: changes made during an execution, by the
  // user or by the execution itself (a lookup table built, a camera created), are in its
  // image and must not make the next Update render again.
  vtkMTimeType time = this->Superclass::GetMTime();
  if (this->Renderer)
  {
    const std::map<vtkObject*, vtkMTimeType>& seen = this->Internals->Seen;
    vtkInternals::ForEachSceneObject(this->Renderer, [&](vtkObject* object) {
      const auto found = object ? seen.find(object) : seen.end();
      if (object && (found == seen.end() || found->second != object->GetMTime()))
      {
        time = std::max(time, object->GetMTime());
      }
    });
  }
  return time;
}

//------------------------------------------------------------------------------
int vtkFacetRendererToImageFilter::RequestInformation(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  int size[2];
  this->GetEffectiveSize(size);
  return vtkFacetImageRenderer::RequestInformation(
    this, outputVector->GetInformationObject(0), size[0], size[1]);
}

//------------------------------------------------------------------------------
int vtkFacetRendererToImageFilter::RequestData(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkImageData* output = vtkImageData::GetData(outputVector);
  vtkInternals& internals = *this->Internals;
  vtkFacetMessages& messages = internals.Messages;
  vtkRenderer* renderer = this->Renderer;
  if (!renderer)
  {
    messages.AddError("no renderer to render: call SetRenderer");
    return messages.Report(this, output);
  }
  int size[2];
  this->GetEffectiveSize(size);
  internals.Image.Start(this);

  // The renderer's lights: with none on, the headlight vtkRenderer would create, or none.
  vtkFacetSceneConverter::LightOptions lights;
  lights.AddHeadlight = !AnyLightOn(renderer) && renderer->GetAutomaticLightCreation();
  lights.FollowCamera = renderer->GetLightFollowCamera() || lights.AddHeadlight;
  const vtkFacetSceneConverter::Lighting lighting =
    vtkFacetSceneConverter::LightingOf(renderer->GetLights(), lights);

  // The actors, then the camera (fitted to them if the renderer has none) and the lights.
  facet::Scene scene;
  internals.AddActors(renderer, lighting, this->DetectClosedSurfaces != 0, scene);
  internals.Image.ConversionDone();
  vtkCamera* camera = internals.CameraOf(renderer, size[0], size[1]);
  const facet::Camera facetCamera =
    vtkFacetSceneConverter::ConvertCamera(camera, size[0], size[1], messages);
  scene.lights =
    vtkFacetSceneConverter::ConvertLights(renderer->GetLights(), camera, lights, messages);
  WarnAboutUnrendered(renderer, messages);
  vtkFacetImageRenderer::Settings settings;
  settings.Width = size[0];
  settings.Height = size[1];
  settings.ActorIds = true;
  settings.Threads = this->NumberOfThreads;
  settings.TwoSidedLighting = renderer->GetTwoSidedLighting() != 0;
  renderer->GetBackground(settings.Background);
  // A window without alpha bit planes (VTK's default) reads back opaque.
  vtkRenderWindow* window = renderer->GetRenderWindow();
  settings.BackgroundAlpha =
    window && window->GetAlphaBitPlanes() ? renderer->GetBackgroundAlpha() : 1.0;

  // Each actor's interpolation, the samples and the budget (vtkFacetQuality).
  vtkFacetQuality::Settings quality;
  quality.SamplesPerPixel = this->SamplesPerPixel;
  quality.MaximumError = this->MaximumError;
  quality.EstimateError = this->EstimateError != 0;
  quality.ErrorEstimateArray = this->ErrorEstimateArray != 0;
  quality.MeshInterpolation = internals.MeshInterpolation;
  settings.RenderWith = internals.Quality.Prepare(quality, messages);

  // Render straight into the output's arrays; polygon ids become actor and cell ids.
  if (internals.Image.Render(
        scene,
        facetCamera,
        settings,
        output,
        [&](const std::int32_t* polygonIds, vtkIdType begin, vtkIdType end) {
          internals.MapIds(renderer, polygonIds, begin, end);
        },
        internals.NumberOfConversions(),
        messages))
  {
    internals.Quality.AddOutputs(scene,
      facetCamera,
      internals.Image.GetPolygonIds(),
      settings.Background,
      settings.TwoSidedLighting,
      this->NumberOfThreads,
      output,
      messages);
  }
  internals.RememberScene(renderer);
  return messages.Report(this, output);
}

//------------------------------------------------------------------------------
void vtkFacetRendererToImageFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Renderer: " << this->Renderer << "\n";
  int size[2];
  this->GetEffectiveSize(size);
  os << indent << "Size: " << this->Size[0] << " x " << this->Size[1] << " (renders at " << size[0]
     << " x " << size[1] << ")\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
  os << indent << "DetectClosedSurfaces: " << this->DetectClosedSurfaces << "\n";
  os << indent << "SamplesPerPixel: " << this->SamplesPerPixel << "\n";
  os << indent << "MaximumError: " << this->MaximumError << "\n";
  os << indent << "EstimateError: " << this->EstimateError << "\n";
  os << indent << "ErrorEstimateArray: " << this->ErrorEstimateArray << "\n";
}
