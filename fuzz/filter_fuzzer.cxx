// libFuzzer target over vtkFacetRenderFilter: random vtkPolyData (polys and strips, some
// verts and lines, float or double points with special values, 32- or 64-bit cell arrays,
// bad ids), point and cell scalars (unsigned char colors and float values, sometimes with
// the wrong tuple count), and random settings: size, camera or none, lights, property,
// coloring, visibility mode. Each input renders on 1 thread, then on 2.
//
// Checks: nothing but VTK's error mechanism reports a problem (no exception, no sanitizer
// report); a failed execution leaves the output empty; a successful one has RGBA, Depth and
// CellId arrays of W × H tuples with CellId −1 or a polygon or strip cell, Depth finite in
// [0, 1], background pixels in the background color and alpha, polygon pixels opaque; and
// both thread counts give the same bytes.

#include <cstdint>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "FuzzInput.h"
#include "facet/Color.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkColorTransferFunction.h"
#include "vtkCommand.h"
#include "vtkDoubleArray.h"
#include "vtkFacetLight.h"
#include "vtkFacetRenderFilter.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkLogger.h"
#include "vtkLookupTable.h"
#include "vtkNew.h"
#include "vtkOutputWindow.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkSmartPointer.h"
#include "vtkTransform.h"
#include "vtkUnsignedCharArray.h"

namespace facet::fuzz {
namespace {

// `count` cells of minSize..maxSize points each (sometimes empty ones).
vtkSmartPointer<vtkCellArray> anyCells(FuzzedDataProvider& in, vtkIdType pointCount, int count,
                                       int minSize, int maxSize, bool storage64) {
  auto cells = vtkSmartPointer<vtkCellArray>::New();
  if (storage64) {
    cells->Use64BitStorage();
  } else {
    cells->Use32BitStorage();
  }
  for (int c = 0; c < count; ++c) {
    const int size = in.ConsumeIntegralInRange(0, 15) == 0
                         ? in.ConsumeIntegralInRange(0, 40)
                         : in.ConsumeIntegralInRange(minSize, maxSize);
    std::vector<std::int64_t> ids;
    for (int k = 0; k < size; ++k) {
      ids.push_back(anyPointId(in, pointCount, ids));
    }
    const std::vector<vtkIdType> cell(ids.begin(), ids.end());
    cells->InsertNextCell(static_cast<vtkIdType>(cell.size()), cell.data());
  }
  return cells;
}

// Scalars for `tuples` points or cells (sometimes one too many or too few): colors as
// unsigned char (1 to 4 components) or values as float or double (1 to 3 components).
vtkSmartPointer<vtkDataArray> anyScalars(FuzzedDataProvider& in, vtkIdType tuples) {
  if (in.ConsumeIntegralInRange(0, 15) == 0) {
    tuples = std::max<vtkIdType>(0, tuples + in.ConsumeIntegralInRange(-1, 1));
  }
  vtkSmartPointer<vtkDataArray> array;
  switch (in.ConsumeIntegralInRange(0, 2)) {
    case 0: {
      auto colors = vtkSmartPointer<vtkUnsignedCharArray>::New();
      colors->SetNumberOfComponents(in.ConsumeIntegralInRange(1, 4));
      colors->SetNumberOfTuples(tuples);
      for (vtkIdType i = 0; i < colors->GetNumberOfValues(); ++i)
        colors->SetValue(i, in.ConsumeIntegral<std::uint8_t>());
      array = colors;
      break;
    }
    case 1: {
      auto values = vtkSmartPointer<vtkFloatArray>::New();
      values->SetNumberOfComponents(in.ConsumeIntegralInRange(1, 3));
      values->SetNumberOfTuples(tuples);
      for (vtkIdType i = 0; i < values->GetNumberOfValues(); ++i)
        values->SetValue(i, toFloat(anyDouble(in, -1.0, 2.0)));
      array = values;
      break;
    }
    default: {
      auto values = vtkSmartPointer<vtkDoubleArray>::New();
      values->SetNumberOfComponents(in.ConsumeIntegralInRange(1, 3));
      values->SetNumberOfTuples(tuples);
      for (vtkIdType i = 0; i < values->GetNumberOfValues(); ++i)
        values->SetValue(i, anyDouble(in, -1.0, 2.0));
      array = values;
      break;
    }
  }
  const char* names[] = {"colors", "values", "other"};
  array->SetName(in.PickValueInArray(names));
  return array;
}

void addScalars(FuzzedDataProvider& in, vtkDataSetAttributes* attributes, vtkIdType tuples) {
  const int arrays = in.ConsumeIntegralInRange(0, 2);
  for (int i = 0; i < arrays; ++i) {
    vtkSmartPointer<vtkDataArray> array = anyScalars(in, tuples);
    if (in.ConsumeBool()) {
      attributes->SetScalars(array);
    } else {
      attributes->AddArray(array);
    }
  }
}

vtkSmartPointer<vtkPolyData> anyPolyData(FuzzedDataProvider& in, const Placement& placement) {
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataType(in.ConsumeBool() ? VTK_FLOAT : VTK_DOUBLE);
  const int pointCount = in.ConsumeIntegralInRange(0, 40);
  for (int i = 0; i < pointCount; ++i) {
    const glm::dvec3 p = placement.place(anyVector(in, -1.0, 1.0));
    const double xyz[3] = {p.x, p.y, p.z};
    if (points->GetDataType() == VTK_FLOAT) {
      const float f[3] = {toFloat(xyz[0]), toFloat(xyz[1]), toFloat(xyz[2])};
      points->InsertNextPoint(f);
    } else {
      points->InsertNextPoint(xyz);
    }
  }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(points);
  const bool storage64 = in.ConsumeBool();
  const int verts = in.ConsumeIntegralInRange(0, 7) == 0 ? in.ConsumeIntegralInRange(1, 3) : 0;
  const int lines = in.ConsumeIntegralInRange(0, 7) == 0 ? in.ConsumeIntegralInRange(1, 3) : 0;
  poly->SetVerts(anyCells(in, pointCount, verts, 1, 2, storage64));
  poly->SetLines(anyCells(in, pointCount, lines, 2, 3, storage64));
  poly->SetPolys(anyCells(in, pointCount, in.ConsumeIntegralInRange(0, 16), 3, 6, storage64));
  poly->SetStrips(anyCells(in, pointCount, in.ConsumeIntegralInRange(0, 6), 3, 8, storage64));
  addScalars(in, poly->GetPointData(), pointCount);
  addScalars(in, poly->GetCellData(), poly->GetNumberOfCells());
  return poly;
}

vtkSmartPointer<vtkCamera> anyCamera(FuzzedDataProvider& in, const Placement& placement) {
  auto camera = vtkSmartPointer<vtkCamera>::New();
  const glm::dvec3 position = placement.place(glm::dvec3(0.0, 0.0, 3.0) + anyVector(in, -3.0, 3.0));
  camera->SetPosition(position.x, position.y, position.z);
  const glm::dvec3 focal = placement.place(anyVector(in, -0.5, 0.5));
  camera->SetFocalPoint(focal.x, focal.y, focal.z);
  const glm::dvec3 up = anyVector(in, -1.0, 1.0);
  camera->SetViewUp(up.x, up.y, up.z);
  camera->SetViewAngle(anyDouble(in, 1.0, 179.0));
  camera->SetUseHorizontalViewAngle(in.ConsumeIntegralInRange(0, 7) == 0);
  camera->SetParallelProjection(in.ConsumeBool());
  camera->SetParallelScale(placement.scale * anyDouble(in, 0.0, 3.0));
  const double nearClip = placement.scale * anyDouble(in, 0.0, 2.0);
  camera->SetClippingRange(nearClip, nearClip + placement.scale * anyDouble(in, 0.0, 10.0));
  if (in.ConsumeIntegralInRange(0, 7) == 0) {
    camera->SetWindowCenter(anyDouble(in, -1.0, 1.0), anyDouble(in, -1.0, 1.0));
  }
  if (in.ConsumeIntegralInRange(0, 15) == 0) {  // what Facet renders without: said, not drawn
    vtkNew<vtkTransform> transform;
    transform->Scale(1.0, anyDouble(in, 0.5, 2.0), 1.0);
    camera->SetModelTransformMatrix(transform->GetMatrix());
  }
  return camera;
}

void anyColor(FuzzedDataProvider& in, double out[3]) {
  const glm::dvec3 c = anyVector(in, 0.0, 1.0);
  out[0] = c.r, out[1] = c.g, out[2] = c.b;
}

vtkSmartPointer<vtkLight> anyLight(FuzzedDataProvider& in, const Placement& placement) {
  vtkSmartPointer<vtkLight> light;
  if (in.ConsumeBool()) {
    auto facetLight = vtkSmartPointer<vtkFacetLight>::New();
    facetLight->SetSpotModel(in.ConsumeIntegralInRange(0, 1));
    facetLight->SetFullIntensityAngle(anyDouble(in, 0.0, 180.0));
    facetLight->SetFalloffAngle(anyDouble(in, 0.0, 90.0));
    facetLight->SetAttenuationModel(in.ConsumeIntegralInRange(0, 1));
    facetLight->SetFalloffDistance(anyDouble(in, 0.0, 10.0));
    light = facetLight;
  } else {
    light = vtkSmartPointer<vtkLight>::New();
  }
  light->SetLightType(in.ConsumeIntegralInRange(1, 3));  // headlight, camera, scene light
  const glm::dvec3 position = placement.place(anyVector(in, -3.0, 3.0));
  light->SetPosition(position.x, position.y, position.z);
  const glm::dvec3 focal = placement.place(anyVector(in, -1.0, 1.0));
  light->SetFocalPoint(focal.x, focal.y, focal.z);
  light->SetPositional(in.ConsumeBool());
  light->SetConeAngle(anyDouble(in, 0.0, 180.0));
  light->SetExponent(anyDouble(in, 0.0, 16.0));
  light->SetAttenuationValues(anyDouble(in, 0.0, 2.0), anyDouble(in, 0.0, 1.0),
                              anyDouble(in, 0.0, 1e-2));
  light->SetIntensity(anyDouble(in, 0.0, 2.0));
  double color[3];
  anyColor(in, color);
  light->SetDiffuseColor(color);
  light->SetSwitch(in.ConsumeIntegralInRange(0, 7) != 0);
  return light;
}

void setProperty(FuzzedDataProvider& in, vtkProperty* property) {
  if (in.ConsumeBool()) return;  // the filter's default
  double c[3];
  anyColor(in, c);
  property->SetDiffuseColor(c);
  anyColor(in, c);
  property->SetAmbientColor(c);
  anyColor(in, c);
  property->SetSpecularColor(c);
  property->SetAmbient(anyDouble(in, 0.0, 1.0));
  property->SetDiffuse(anyDouble(in, 0.0, 1.0));
  property->SetSpecular(anyDouble(in, 0.0, 1.0));
  property->SetSpecularPower(anyDouble(in, 0.0, 128.0));
  property->SetBackfaceCulling(in.ConsumeBool());
  if (in.ConsumeIntegralInRange(0, 7) == 0) {
    property->SetInterpolation(in.ConsumeIntegralInRange(0, 2));
    property->SetOpacity(anyDouble(in, 0.0, 1.0));
    property->SetRepresentation(in.ConsumeIntegralInRange(0, 2));
  }
}

vtkSmartPointer<vtkScalarsToColors> anyLookupTable(FuzzedDataProvider& in) {
  switch (in.ConsumeIntegralInRange(0, 3)) {
    case 0: {
      auto table = vtkSmartPointer<vtkLookupTable>::New();
      table->SetNumberOfTableValues(in.ConsumeIntegralInRange(1, 300));
      table->SetRange(anyDouble(in, -1.0, 1.0), anyDouble(in, 0.0, 2.0));
      table->SetScale(in.ConsumeIntegralInRange(0, 3) == 0 ? VTK_SCALE_LOG10 : VTK_SCALE_LINEAR);
      if (in.ConsumeBool()) table->Build();  // else unbuilt, as users leave it
      return table;
    }
    case 1: {
      auto function = vtkSmartPointer<vtkColorTransferFunction>::New();
      function->AddRGBPoint(anyDouble(in, -1.0, 1.0), 1.0, 0.0, 0.0);
      function->AddRGBPoint(anyDouble(in, 0.0, 2.0), 0.0, 0.0, 1.0);
      return function;
    }
    default:
      return nullptr;  // the filter's default table
  }
}

void setColoring(FuzzedDataProvider& in, vtkFacetRenderFilter* filter) {
  filter->SetScalarVisibility(in.ConsumeIntegralInRange(0, 3) != 0);
  filter->SetScalarMode(in.ConsumeIntegralInRange(-1, 6));
  filter->SetColorMode(in.ConsumeIntegralInRange(-1, 3));
  switch (in.ConsumeIntegralInRange(0, 3)) {
    case 0: {
      const char* names[] = {"colors", "values", "missing", ""};
      filter->SelectColorArray(in.PickValueInArray(names));
      break;
    }
    case 1:
      filter->SelectColorArray(in.ConsumeIntegralInRange(-1, 3));
      break;
    default:
      break;
  }
  filter->SetArrayComponent(in.ConsumeIntegralInRange(-2, 3));
  filter->SetLookupTable(anyLookupTable(in));
  filter->SetScalarRange(anyDouble(in, -1.0, 1.0), anyDouble(in, 0.0, 2.0));
  filter->SetUseLookupTableScalarRange(in.ConsumeBool());
}

void setScene(FuzzedDataProvider& in, const Placement& placement, vtkFacetRenderFilter* filter) {
  filter->SetSize(anySide(in), anySide(in));
  if (in.ConsumeBool()) filter->SetCamera(anyCamera(in, placement));
  const int lights = in.ConsumeIntegralInRange(0, 3);
  for (int i = 0; i < lights; ++i)
    filter->AddLight(anyLight(in, placement));
  filter->SetAutomaticLightCreation(in.ConsumeBool());
  double c[3];
  anyColor(in, c);
  filter->SetAmbientLightColor(c);
  filter->SetTwoSidedLighting(in.ConsumeBool());
  anyColor(in, c);
  filter->SetBackground(c);
  filter->SetBackgroundAlpha(anyDouble(in, 0.0, 1.0));
  setProperty(in, filter->GetProperty());
  setColoring(in, filter);
  filter->SetVisibilityMode(in.ConsumeIntegralInRange(0, 1));
  filter->SetDetectClosedSurfaces(in.ConsumeBool());
}

// Counts the filter's error and warning events while it lives (and keeps VTK from printing
// them).
class Messages {
 public:
  explicit Messages(vtkObject* object) : object_(object) {
    callback_->SetClientData(this);
    callback_->SetCallback([](vtkObject*, unsigned long event, void* self, void*) {
      auto* messages = static_cast<Messages*>(self);
      ++(event == vtkCommand::ErrorEvent ? messages->errors : messages->warnings);
    });
    errorTag_ = object->AddObserver(vtkCommand::ErrorEvent, callback_);
    warningTag_ = object->AddObserver(vtkCommand::WarningEvent, callback_);
  }
  ~Messages() {
    object_->RemoveObserver(errorTag_);
    object_->RemoveObserver(warningTag_);
  }
  Messages(const Messages&) = delete;
  Messages& operator=(const Messages&) = delete;

  int errors = 0;
  int warnings = 0;

 private:
  vtkObject* object_;
  vtkNew<vtkCallbackCommand> callback_;
  unsigned long errorTag_ = 0, warningTag_ = 0;
};

// The output of one execution, kept (the filter reuses its arrays on the next one).
struct Result {
  bool failed = false;
  int dimensions[3] = {0, 0, 0};
  std::vector<std::uint8_t> rgba;
  std::vector<float> depth;
  std::vector<vtkIdType> cellIds;
};

template <class ArrayType>
ArrayType* requireArray(vtkImageData* image, const char* name, int components) {
  vtkAbstractArray* array = image->GetPointData()->GetAbstractArray(name);
  auto* typed = ArrayType::SafeDownCast(array);
  const vtkIdType pixels = image->GetNumberOfPoints();
  FUZZ_CHECK(typed, "the output has no %s array of the documented type", name);
  FUZZ_CHECK(typed->GetNumberOfComponents() == components && typed->GetNumberOfTuples() == pixels,
             "%s has %d components and %lld tuples for %lld pixels", name,
             typed->GetNumberOfComponents(), static_cast<long long>(typed->GetNumberOfTuples()),
             static_cast<long long>(pixels));
  return typed;
}

Result execute(vtkFacetRenderFilter* filter, vtkPolyData* input) {
  Messages messages(filter);
  try {
    filter->Update();
  } catch (const std::exception& e) {
    FUZZ_CHECK(false, "Update() threw: %s", e.what());
  } catch (...) {
    FUZZ_CHECK(false, "Update() threw something");
  }
  Result result;
  vtkImageData* output = filter->GetOutput();
  const int* size = filter->GetSize();
  const bool validSize = size[0] >= 1 && size[1] >= 1 && size[0] <= 16384 && size[1] <= 16384;
  FUZZ_CHECK(validSize || messages.errors > 0, "Size %d x %d accepted without an error", size[0],
             size[1]);
  if (messages.errors > 0) {
    result.failed = true;
    FUZZ_CHECK(output->GetNumberOfPoints() == 0 && output->GetPointData()->GetNumberOfArrays() == 0,
               "after an error the output has %lld points and %d arrays, expected none",
               static_cast<long long>(output->GetNumberOfPoints()),
               output->GetPointData()->GetNumberOfArrays());
    return result;
  }
  output->GetDimensions(result.dimensions);
  FUZZ_CHECK(result.dimensions[0] == size[0] && result.dimensions[1] == size[1] &&
                 result.dimensions[2] == 1,
             "output dimensions %d x %d x %d for Size %d x %d", result.dimensions[0],
             result.dimensions[1], result.dimensions[2], size[0], size[1]);
  auto* rgba = requireArray<vtkUnsignedCharArray>(output, "RGBA", 4);
  auto* depth = requireArray<vtkFloatArray>(output, "Depth", 1);
  auto* cellIds = requireArray<vtkIdTypeArray>(output, "CellId", 1);
  FUZZ_CHECK(output->GetPointData()->GetScalars() == rgba, "RGBA is not the active scalars");

  const double* bg = filter->GetBackground();
  const Rgba8 background = toRgba8(Color(toFloat(bg[0]), toFloat(bg[1]), toFloat(bg[2])),
                                   toFloat(filter->GetBackgroundAlpha()));
  const vtkIdType firstSurface = input->GetNumberOfVerts() + input->GetNumberOfLines();
  const vtkIdType cells = input->GetNumberOfCells();
  const vtkIdType pixels = output->GetNumberOfPoints();
  for (vtkIdType i = 0; i < pixels; ++i) {
    const vtkIdType id = cellIds->GetValue(i);
    const float d = depth->GetValue(i);
    const unsigned char* c = rgba->GetPointer(4 * i);
    FUZZ_CHECK(d >= 0.0f && d <= 1.0f, "pixel %lld: Depth %.9g outside [0, 1]",
               static_cast<long long>(i), d);
    FUZZ_CHECK(id == -1 || (id >= firstSurface && id < cells),
               "pixel %lld: CellId %lld, polygons and strips are cells %lld to %lld",
               static_cast<long long>(i), static_cast<long long>(id),
               static_cast<long long>(firstSurface), static_cast<long long>(cells - 1));
    if (id == -1) {
      FUZZ_CHECK(d == 1.0f && c[0] == background.r && c[1] == background.g &&
                     c[2] == background.b && c[3] == background.a,
                 "pixel %lld: background RGBA (%d %d %d %d) depth %.9g, expected (%d %d %d %d) "
                 "depth 1",
                 static_cast<long long>(i), c[0], c[1], c[2], c[3], d, background.r, background.g,
                 background.b, background.a);
    } else {
      FUZZ_CHECK(c[3] == 255, "pixel %lld: cell %lld has alpha %d, surfaces are opaque",
                 static_cast<long long>(i), static_cast<long long>(id), c[3]);
    }
  }
  result.rgba.assign(rgba->GetPointer(0), rgba->GetPointer(0) + 4 * pixels);
  result.depth.assign(depth->GetPointer(0), depth->GetPointer(0) + pixels);
  result.cellIds.assign(cellIds->GetPointer(0), cellIds->GetPointer(0) + pixels);
  return result;
}

void checkSame(const Result& one, const Result& two) {
  FUZZ_CHECK(one.failed == two.failed, "1 thread %s, 2 threads %s", one.failed ? "failed" : "ok",
             two.failed ? "failed" : "ok");
  if (one.failed) return;
  FUZZ_CHECK(one.rgba == two.rgba, "RGBA differs between 1 and 2 threads");
  FUZZ_CHECK(std::memcmp(one.depth.data(), two.depth.data(), one.depth.size() * sizeof(float)) == 0,
             "Depth differs between 1 and 2 threads");
  FUZZ_CHECK(one.cellIds == two.cellIds, "CellId differs between 1 and 2 threads");
}

void fuzzOne(FuzzedDataProvider& in) {
  const Placement placement = anyPlacement(in);
  vtkSmartPointer<vtkPolyData> input = anyPolyData(in, placement);
  vtkNew<vtkFacetRenderFilter> filter;
  filter->SetInputData(input);
  setScene(in, placement, filter);
  filter->SetNumberOfThreads(1);
  const Result one = execute(filter, input);
  // Again on two threads: the kept conversion and colors are reused.
  filter->SetNumberOfThreads(2);
  const Result two = execute(filter, input);
  checkSame(one, two);
  // Then with new settings (a new size, camera, lights, coloring) on the same filter.
  if (in.ConsumeBool()) {
    filter->RemoveAllLights();
    filter->SetCamera(nullptr);
    setScene(in, placement, filter);
    execute(filter, input);
  }
}

}  // namespace
}  // namespace facet::fuzz

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  // VTK's own messages (the executive's "returned failure", ...) are noise here. Errors still
  // reach observers (GlobalWarningDisplayOff would silence the macros themselves).
  vtkOutputWindow::GetInstance()->SetDisplayModeToNever();
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider in(data, size);
  facet::fuzz::fuzzOne(in);
  return 0;
}
