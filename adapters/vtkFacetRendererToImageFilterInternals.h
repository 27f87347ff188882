/**
 * @class   vtkFacetRendererToImageFilter::vtkInternals
 * @brief   Private: what vtkFacetRendererToImageFilter keeps between executions, and the
 *          steps of an execution, kept out of the filter's public header.
 *
 * An execution converts the renderer's actors into a scene (each kept while unchanged), its
 * camera and lights, renders (vtkFacetFrame) and maps the polygon ids to actor and cell ids.
 * Each concept has its file:
 * - vtkFacetRendererToImageFilterActors.cxx: which props Facet renders, and their conversion;
 * - vtkFacetRendererToImageFilterScene.cxx: what the image depends on (GetMTime), the camera,
 *   the lights and what the renderer asks for that Facet does not render;
 * - vtkFacetRendererToImageFilterIds.cxx: ActorId and CellId from the polygon ids (and the
 *   gradient background's rows);
 * - vtkFacetRendererToImageFilter.cxx: the filter itself.
 */

#ifndef vtkFacetRendererToImageFilterInternals_h
#define vtkFacetRendererToImageFilterInternals_h

#include "vtkFacetRendererToImageFilter.h"

#include "vtkFacetActorConverter.h"
#include "vtkFacetImageRenderer.h"
#include "vtkFacetMessages.h"
#include "vtkFacetQuality.h"
#include "vtkFacetSceneConverter.h"

#include "facet/Scene.h"

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

class vtkActor;
class vtkCamera;
class vtkDataObject;
class vtkMapper;
class vtkMatrix4x4;
class vtkObject;
class vtkRenderer;

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

  // The actors (Actors.cxx).
  using ActorVisit = std::function<void(int propIndex, vtkActor* actor, vtkMatrix4x4* matrix)>;
  // Calls visit(propIndex, actor, matrix) for every visible vtkActor leaf Facet renders;
  // the classes of the other visible props go to `skipped`.
  static void ForEachActor(vtkRenderer* renderer,
    const ActorVisit& visit,
    std::set<std::string>& skipped);
  // The mapper's input, brought up to date as rendering would bring it (unless Static).
  static vtkDataObject* InputOf(vtkMapper* mapper);
  // Converts the actors Facet renders (kept while unchanged) into `scene`, with a warning for
  // the props it skips.
  void AddActors(vtkRenderer* renderer,
    vtkFacetSceneConverter::Lighting lighting,
    bool detectClosedSurfaces,
    facet::Scene& scene);
  int NumberOfConversions() const;

  // The renderer's scene (Scene.cxx).
  using ObjectVisit = std::function<void(vtkObject* object)>;
  // Calls see(object) for every object whose change changes the image (null ones too).
  static void ForEachSceneObject(vtkRenderer* renderer, const ObjectVisit& see);
  // Remembers the MTime of everything ForEachSceneObject sees, for GetMTime.
  void RememberScene(vtkRenderer* renderer);
  // The renderer's active camera; one it creates (fitted as vtkRenderer::Render fits it,
  // for this image's aspect) when it has none.
  static vtkCamera* CameraOf(vtkRenderer* renderer, int width, int height);
  // The renderer's lights: with none on, the headlight vtkRenderer would create, or none.
  static vtkFacetSceneConverter::LightOptions LightOptionsOf(vtkRenderer* renderer);
  // What the renderer asks for that Facet does not render yet.
  static void WarnAboutUnrendered(vtkRenderer* renderer, vtkFacetMessages& messages);

  // ActorId and CellId of pixels [begin, end), and the gradient background's colors on the
  // pixels that show it (Ids.cxx).
  void MapIds(vtkRenderer* renderer,
    const std::int32_t* polygonIds,
    vtkIdType begin,
    vtkIdType end);
};

#endif
// VTK-HeaderTest-Exclude: vtkFacetRendererToImageFilterInternals.h
