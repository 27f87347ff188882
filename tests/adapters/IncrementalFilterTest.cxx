// vtkFacetRenderFilter leaves out work: incremental rendering judged by MTimes (each change
// alone gives the bytes of a fresh filter with the same settings, and the field data names
// the path that ran), outputs nobody asked for, and the plan in the field data.

#include "AdapterTestUtilities.h"

#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkElevationFilter.h"
#include "vtkFloatArray.h"
#include "vtkIdList.h"
#include "vtkIdTypeArray.h"
#include "vtkLight.h"
#include "vtkLookupTable.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkProperty.h"
#include "vtkSphereSource.h"
#include "vtkStringArray.h"
#include "vtkWeakPointer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <ostream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

using namespace facet_test;

namespace {
constexpr int Width = 160, Height = 120;
enum Path
{
  Full = 0,
  Reshade = 1,
  Resolve = 2
};

// Everything a test changes, one thing at a time.
struct Settings
{
  double LightColor[3] = { 1.0, 0.9, 0.8 };
  double LightIntensity = 1.0;
  double Color[3] = { 0.8, 0.7, 0.6 };
  double Hue[2] = { 0.0, 0.667 };
  double Background[3] = { 0.1, 0.2, 0.3 };
  double Azimuth = 20.0;
  double Distance = 3.0;        ///< of the camera from the focal point (FitCameraToInput off)
  double Pan[2] = { 0.0, 0.0 }; ///< the camera and its focal point moved by (x, y)
  bool ColorByScalars = true;
  int Interpolation = VTK_FLAT;
};

// A filter and the objects it renders with, changed in place as a user would.
struct Rig
{
  vtkNew<vtkFacetRenderFilter> Filter;
  vtkNew<vtkCamera> Camera;
  vtkNew<vtkLight> Light;
  vtkNew<vtkLookupTable> Table;

  explicit Rig(vtkPolyData* input)
  {
    this->Filter->SetInputData(input);
    this->Filter->SetSize(Width, Height);
    this->Filter->SetNumberOfThreads(2);
    this->Camera->SetPosition(0.0, 0.5, 3.0);
    this->Filter->SetCamera(this->Camera);
    this->Filter->FitCameraToInputOn();
    this->Light->SetPosition(1.0, 2.0, 3.0);
    this->Light->SetPositional(true);
    this->Light->SetConeAngle(180.0);
    this->Filter->AddLight(this->Light);
    this->Filter->SetLookupTable(this->Table);
    this->Filter->SetScalarRange(-0.5, 0.5);
  }

  vtkImageData* Render(const Settings& s)
  {
    this->Light->SetDiffuseColor(s.LightColor[0], s.LightColor[1], s.LightColor[2]);
    this->Light->SetIntensity(s.LightIntensity);
    this->Filter->GetProperty()->SetColor(s.Color[0], s.Color[1], s.Color[2]);
    this->Filter->GetProperty()->SetInterpolation(s.Interpolation);
    this->Table->SetHueRange(s.Hue[0], s.Hue[1]);
    this->Filter->SetBackground(s.Background[0], s.Background[1], s.Background[2]);
    const double scale = s.Distance / 3.0;
    this->Camera->SetPosition(s.Pan[0], s.Pan[1] + 0.5 * scale, 3.0 * scale);
    this->Camera->SetFocalPoint(s.Pan[0], s.Pan[1], 0.0);
    this->Camera->Azimuth(s.Azimuth);
    this->Filter->SetScalarVisibility(s.ColorByScalars);
    this->Filter->Update();
    return this->Filter->GetOutput();
  }
};

// The bytes of one point-data array, or empty if the image has none by that name.
std::string Bytes(vtkImageData* image, const char* name)
{
  vtkDataArray* array = image->GetPointData()->GetArray(name);
  if (!array)
  {
    return {};
  }
  const auto* begin = static_cast<const char*>(array->GetVoidPointer(0));
  return { begin, begin + array->GetNumberOfValues() * array->GetDataTypeSize() };
}

// Where two images' arrays differ, for the failure message.
std::string FirstDifference(const std::string& got, const std::string& expected, int itemSize)
{
  if (got.size() != expected.size())
  {
    return std::to_string(got.size()) + " bytes instead of " + std::to_string(expected.size());
  }
  const auto at = std::mismatch(got.begin(), got.end(), expected.begin()).first - got.begin();
  const long pixel = static_cast<long>(at) / itemSize;
  return "first at pixel (" + std::to_string(pixel % Width) + ", " + std::to_string(pixel / Width) +
    ")";
}

void ExpectSameImage(vtkImageData* got, vtkImageData* expected)
{
  for (const auto& [name, size] : { std::pair{ "RGBA", 4 }, { "Depth", 4 }, { "CellId", 8 } })
  {
    const std::string a = Bytes(got, name), b = Bytes(expected, name);
    EXPECT_FALSE(b.empty()) << name;
    EXPECT_TRUE(a == b) << name << " differs: " << FirstDifference(a, b, size);
  }
}

int PathOf(vtkImageData* image)
{
  return static_cast<int>(FieldValue(image, "FacetRenderPath", "Path"));
}

class Incremental : public ::testing::Test
{
protected:
  void SetUp() override
  {
    vtkNew<vtkSphereSource> sphere;
    sphere->SetThetaResolution(48);
    sphere->SetPhiResolution(24);
    vtkNew<vtkElevationFilter> elevation; // point scalars from -0.5 to 0.5
    elevation->SetInputConnection(sphere->GetOutputPort());
    elevation->SetLowPoint(0.0, -0.5, 0.0);
    elevation->SetHighPoint(0.0, 0.5, 0.0);
    elevation->SetScalarRange(-0.5, 0.5);
    elevation->Update();
    this->Input->DeepCopy(elevation->GetOutput());
  }

  // Renders `changed` after `before` with one filter, and `changed` with a fresh one: the
  // same bytes, and the kept filter took `path`.
  void ExpectPath(const Settings& before, const Settings& changed, int path)
  {
    Rig kept(this->Input);
    ASSERT_EQ(PathOf(kept.Render(before)), Full);
    vtkImageData* again = kept.Render(changed);
    EXPECT_EQ(PathOf(again), path) << kept.Filter->GetRenderPlan();
    Rig fresh(this->Input);
    ExpectSameImage(again, fresh.Render(changed));
  }

  vtkNew<vtkPolyData> Input;
};
}

//------------------------------------------------------------------------------
TEST_F(Incremental, OnlyALightReshades)
{
  Settings changed;
  changed.LightColor[1] = 0.3;
  changed.LightIntensity = 0.7;
  this->ExpectPath(Settings(), changed, Reshade);
}

TEST_F(Incremental, OnlyThePropertysColorReshades)
{
  Settings before;
  before.ColorByScalars = false;
  Settings changed = before;
  changed.Color[2] = 0.1;
  this->ExpectPath(before, changed, Reshade);
}

TEST_F(Incremental, OnlyTheLookupTableReshades)
{
  Settings changed;
  changed.Hue[0] = 0.3;
  this->ExpectPath(Settings(), changed, Reshade);
}

TEST_F(Incremental, OnlyTheBackgroundResolves)
{
  Settings changed;
  changed.Background[0] = 0.9;
  this->ExpectPath(Settings(), changed, Resolve);
}

TEST_F(Incremental, NothingChangedResolves)
{
  Rig kept(this->Input);
  kept.Render(Settings());
  kept.Filter->Modified();
  vtkImageData* again = kept.Render(Settings());
  EXPECT_EQ(PathOf(again), Resolve);
  Rig fresh(this->Input);
  ExpectSameImage(again, fresh.Render(Settings()));
}

TEST_F(Incremental, ANewCameraRendersInFull)
{
  Settings changed;
  changed.Azimuth = 50.0;
  this->ExpectPath(Settings(), changed, Full);
}

TEST_F(Incremental, GouraudShadingReshadesToo)
{
  Settings before;
  before.Interpolation = VTK_GOURAUD;
  Settings changed = before;
  changed.LightColor[0] = 0.2;
  this->ExpectPath(before, changed, Reshade);
}

// The usual VTK edit: points moved, the data marked modified.
TEST_F(Incremental, MovedPointsRenderInFull)
{
  Rig kept(this->Input);
  kept.Render(Settings());
  double p[3];
  for (vtkIdType i = 0; i < this->Input->GetNumberOfPoints(); ++i)
  {
    this->Input->GetPoint(i, p);
    this->Input->GetPoints()->SetPoint(i, 1.2 * p[0], p[1], p[2]);
  }
  this->Input->Modified();
  vtkImageData* again = kept.Render(Settings());
  EXPECT_EQ(PathOf(again), Full) << kept.Filter->GetRenderPlan();
  Rig fresh(this->Input);
  ExpectSameImage(again, fresh.Render(Settings()));
}

// New scalar values in the same array: new colors on the same geometry.
TEST_F(Incremental, NewScalarsReshade)
{
  Rig kept(this->Input);
  kept.Render(Settings());
  vtkDataArray* scalars = this->Input->GetPointData()->GetScalars();
  for (vtkIdType i = 0; i < scalars->GetNumberOfTuples(); ++i)
  {
    scalars->SetComponent(i, 0, -scalars->GetComponent(i, 0));
  }
  scalars->Modified();
  vtkImageData* again = kept.Render(Settings());
  EXPECT_EQ(PathOf(again), Reshade) << kept.Filter->GetRenderPlan();
  Rig fresh(this->Input);
  ExpectSameImage(again, fresh.Render(Settings()));
}

// New scalars are no new geometry: the mesh is not converted again (nor validated, nor
// checked for closedness), only colored again.
TEST_F(Incremental, NewScalarsAreNoNewConversion)
{
  Rig kept(this->Input);
  kept.Render(Settings());
  vtkDataArray* scalars = this->Input->GetPointData()->GetScalars();
  for (vtkIdType i = 0; i < scalars->GetNumberOfTuples(); ++i)
  {
    scalars->SetComponent(i, 0, 0.5 * scalars->GetComponent(i, 0));
  }
  scalars->Modified();
  vtkImageData* again = kept.Render(Settings());
  EXPECT_EQ(FieldValue(again, "FacetMeshConverted", "Converted"), 0.0);
  EXPECT_EQ(PathOf(again), Reshade) << kept.Filter->GetRenderPlan();
  Rig fresh(this->Input);
  ExpectSameImage(again, fresh.Render(Settings()));
}

// The estimate's camera-independent part is kept per mesh version; new point normals (an
// attribute, no new conversion) still reach it, and a new background keeps it.
TEST_F(Incremental, TheEstimateFollowsNewPointNormals)
{
  const auto predicted = [](vtkImageData* image) {
    return FieldValue(image, "FacetErrorEstimate", "PredictedRMSE");
  };
  Rig kept(this->Input);
  kept.Filter->EstimateErrorOn();
  const double before = predicted(kept.Render(Settings()));
  TiltPointNormals(this->Input, 0.3);
  vtkImageData* again = kept.Render(Settings());
  EXPECT_EQ(FieldValue(again, "FacetMeshConverted", "Converted"), 0.0);
  const double after = predicted(again);
  Rig fresh(this->Input);
  fresh.Filter->EstimateErrorOn();
  EXPECT_EQ(after, predicted(fresh.Render(Settings())));
  EXPECT_GT(after, before) << "tilted normals are further from the faces'";

  Settings background;
  background.Background[0] = 0.9;
  vtkImageData* recolored = kept.Render(background);
  EXPECT_EQ(PathOf(recolored), Resolve);
  EXPECT_EQ(predicted(recolored), after);
}

TEST_F(Incremental, OffRendersInFull)
{
  Rig kept(this->Input);
  kept.Filter->IncrementalRenderingOff();
  kept.Render(Settings());
  Settings changed;
  changed.LightColor[1] = 0.3;
  EXPECT_EQ(PathOf(kept.Render(changed)), Full);
}

// Output arrays somebody holds (ParaView's representations hold every output) are not
// written again: they keep their image. The execution that finds Depth held renders in full
// into a depth plane of the filter's own, and from then on changes re-shade as before.
TEST_F(Incremental, HeldOutputArraysAreLeftAlone)
{
  Rig kept(this->Input);
  std::vector<vtkSmartPointer<vtkImageData>> held; // as a representation would
  const auto hold = [&](vtkImageData* image) {
    held.emplace_back(vtkSmartPointer<vtkImageData>::New())->ShallowCopy(image);
    return image;
  };
  const std::string first = Bytes(hold(kept.Render(Settings())), "Depth");
  Settings changed;
  for (int change = 0; change < 3; ++change)
  {
    changed.LightColor[1] = 0.1 * change;
    vtkImageData* again = hold(kept.Render(changed));
    EXPECT_EQ(PathOf(again), change == 0 ? Full : Reshade) << kept.Filter->GetRenderPlan();
    Rig fresh(this->Input);
    ExpectSameImage(again, fresh.Render(changed));
  }
  EXPECT_TRUE(Bytes(held[0], "Depth") == first);
  EXPECT_NE(held[0]->GetPointData()->GetArray("RGBA"), held[1]->GetPointData()->GetArray("RGBA"));
}

// Output arrays nobody else holds are written again in place: a turning camera allocates no
// new plane (vtkImageData keeps its scalars across the executive's PrepareForNewData; that
// reference is the output's own, not somebody else's). One held array alone is replaced.
TEST_F(Incremental, OutputArraysNobodyHoldsAreReused)
{
  Rig kept(this->Input);
  const auto arrays = [](vtkImageData* image) {
    std::vector<vtkDataArray*> found;
    for (const char* name : { "RGBA", "Depth", "CellId" })
    {
      found.push_back(image->GetPointData()->GetArray(name));
    }
    return found;
  };
  const std::vector<vtkDataArray*> first = arrays(kept.Render(Settings()));
  Settings turned;
  turned.Azimuth = 35.0;
  vtkImageData* again = kept.Render(turned);
  EXPECT_EQ(PathOf(again), Full);
  EXPECT_EQ(arrays(again), first) << "RGBA, Depth and CellId written in place";
  Rig fresh(this->Input);
  ExpectSameImage(again, fresh.Render(turned));

  const vtkSmartPointer<vtkDataArray> heldRgba = again->GetPointData()->GetArray("RGBA");
  const std::string heldBytes = Bytes(again, "RGBA");
  turned.Azimuth = 50.0;
  const std::vector<vtkDataArray*> third = arrays(kept.Render(turned));
  EXPECT_NE(third[0], heldRgba.Get()) << "the held RGBA is not written again";
  EXPECT_EQ(third[1], first[1]);
  EXPECT_EQ(third[2], first[2]);
  EXPECT_TRUE(std::memcmp(heldRgba->GetVoidPointer(0), heldBytes.data(), heldBytes.size()) == 0);
}

// The field data arrays too are refilled in place when nobody else holds them (the executive
// empties the output's field data before every execution; the filter keeps its own
// references), with new values, a later MTime and their component names; an array somebody
// holds keeps the values it had, and the execution adds a new one.
TEST_F(Incremental, FieldArraysNobodyHoldsAreRefilledAndHeldOnesKept)
{
  Rig kept(this->Input);
  kept.Filter->FitCameraToInputOff();
  kept.Filter->EstimateErrorOn(); // FacetErrorEstimate, vtkFacetQuality's
  const char* names[] = { "FacetRenderSeconds",
    "FacetPhaseSeconds",
    "FacetCounts",
    "FacetMeshConverted",
    "FacetRenderPlan",
    "FacetRenderPath",
    "FacetRenderPlanRulesAllowed",
    "FacetRenderPlanRulesFired",
    "FacetRenderPlanRulesSkipped",
    "FacetRenderPlanLightCulling",
    "FacetErrorEstimate" };
  // Weak: an array the executive released is gone, not mistaken for a new one at its address.
  using Arrays = std::vector<vtkWeakPointer<vtkAbstractArray>>;
  const auto arrays = [&](vtkImageData* image) {
    Arrays found;
    for (const char* name : names)
    {
      found.push_back(image->GetFieldData()->GetAbstractArray(name));
      EXPECT_NE(found.back(), nullptr) << name;
    }
    return found;
  };
  Settings view;
  vtkImageData* image = kept.Render(view);
  const Arrays first = arrays(image);
  const double firstCovered = FieldValue(image, "FacetCounts", "PixelsCovered");
  const vtkMTimeType firstTime = first[2]->GetMTime();
  EXPECT_EQ(FieldValue(image, "FacetMeshConverted", "Converted"), 1.0);

  view.Distance = 1.5; // nearer: more pixels covered
  image = kept.Render(view);
  EXPECT_EQ(arrays(image), first) << "every field array refilled in place";
  Rig fresh(this->Input);
  fresh.Filter->FitCameraToInputOff();
  fresh.Filter->EstimateErrorOn();
  vtkImageData* expected = fresh.Render(view);
  for (const char* component : { "Polygons", "PolygonsDrawn", "PixelsCovered" })
  {
    EXPECT_EQ(
      FieldValue(image, "FacetCounts", component), FieldValue(expected, "FacetCounts", component))
      << component;
  }
  EXPECT_GT(FieldValue(image, "FacetCounts", "PixelsCovered"), firstCovered);
  EXPECT_EQ(FieldValue(image, "FacetMeshConverted", "Converted"), 0.0);
  EXPECT_EQ(FieldValue(image, "FacetErrorEstimate", "PredictedRMSE"),
    FieldValue(expected, "FacetErrorEstimate", "PredictedRMSE"));
  ASSERT_NE(first[2], nullptr);
  EXPECT_GT(first[2]->GetMTime(), firstTime) << "refilled arrays are Modified()";
  EXPECT_EQ(vtkStringArray::SafeDownCast(first[4])->GetValue(0), kept.Filter->GetRenderPlan());

  // Held (as a ShallowCopy of the output holds them): kept as they are.
  vtkNew<vtkImageData> held;
  held->ShallowCopy(image);
  const double heldCovered = FieldValue(held, "FacetCounts", "PixelsCovered");
  const std::string heldPlan = kept.Filter->GetRenderPlan();
  view.Distance = 6.0;
  image = kept.Render(view);
  const Arrays third = arrays(image);
  for (std::size_t i = 0; i < third.size(); ++i)
  {
    EXPECT_NE(third[i], first[i]) << names[i] << ": a held array is not written again";
  }
  EXPECT_EQ(FieldValue(held, "FacetCounts", "PixelsCovered"), heldCovered);
  EXPECT_LT(FieldValue(image, "FacetCounts", "PixelsCovered"), heldCovered);
  EXPECT_EQ(vtkStringArray::SafeDownCast(held->GetFieldData()->GetAbstractArray("FacetRenderPlan"))
              ->GetValue(0),
    heldPlan);
  auto* counts = vtkDataArray::SafeDownCast(third[2]);
  ASSERT_NE(counts, nullptr);
  EXPECT_STREQ(counts->GetComponentName(11), "PixelsCovered") << "a new array is named again";
}

// A kept CellId plane is written only where this frame's or the last frame's ids are not
// background (vtkFacetBackgroundSpans): frame after frame the sphere turns, grows, shrinks,
// moves out of rows and columns and leaves the image, at 160 x 120 (plain stores) and at
// 1031 x 1030 (a plane streamed past the caches, rows not a multiple of the SIMD width), and
// every frame has the bytes of a fresh filter's.
TEST_F(Incremental, KeptCellIdsEqualAFreshFiltersAsTheViewMoves)
{
  for (const auto& [width, height] : { std::pair{ Width, Height }, { 1031, 1030 } })
  {
    Rig kept(this->Input);
    kept.Filter->FitCameraToInputOff();
    kept.Filter->SetSize(width, height);
    const vtkDataArray* plane = nullptr;
    Settings view;
    for (const auto& [azimuth, distance, panX, panY] :
      std::vector<std::tuple<double, double, double, double>>{ { 20, 3, 0, 0 },
        { 35, 3, 0, 0 },
        { 35, 1.5, 0, 0 },
        { 50, 6, 0, 0 },
        { 50, 6, 0.6, 0 },
        { 60, 6, -0.8, 0.3 },
        { 70, 1.2, 0, 0 },
        { 70, 3, 0, -0.9 },
        { 70, 3, 9, 9 },
        { 80, 3, 0, 0 } })
    {
      view.Azimuth = azimuth;
      view.Distance = distance;
      view.Pan[0] = panX;
      view.Pan[1] = panY;
      vtkImageData* image = kept.Render(view);
      const vtkDataArray* cellIds = image->GetPointData()->GetArray("CellId");
      EXPECT_TRUE(plane == nullptr || cellIds == plane) << "the plane is kept";
      plane = cellIds;
      Rig fresh(this->Input);
      fresh.Filter->FitCameraToInputOff();
      fresh.Filter->SetSize(width, height);
      vtkImageData* expected = fresh.Render(view);
      SCOPED_TRACE(std::to_string(width) + " x " + std::to_string(height) + ", azimuth " +
        std::to_string(azimuth) + ", distance " + std::to_string(distance) + ", pan " +
        std::to_string(panX) + ", " + std::to_string(panY));
      const std::string got = Bytes(image, "CellId"), want = Bytes(expected, "CellId");
      ASSERT_FALSE(want.empty());
      EXPECT_TRUE(got == want) << "CellId differs: " << FirstDifference(got, want, 8);
    }
  }
}

// review25: a kept CellId plane meets what may change between two executions: the image's
// shape (the same pixel count, so the same plane), a quality mode that renders a sample grid
// and back, and a user who wrote into the plane and said so (Modified()). Every frame has the
// bytes of a fresh filter's.
TEST_F(Incremental, KeptCellIdsEqualAFreshFiltersAfterShapeModeAndUserChanges)
{
  Rig kept(this->Input);
  kept.Filter->FitCameraToInputOff();
  Settings view;
  const auto expectFresh = [&](vtkImageData* image, const std::string& step) {
    SCOPED_TRACE(step);
    Rig fresh(this->Input);
    fresh.Filter->FitCameraToInputOff();
    fresh.Filter->SetSize(kept.Filter->GetSize());
    fresh.Filter->SetSamplesPerPixel(kept.Filter->GetSamplesPerPixel());
    const std::string got = Bytes(image, "CellId"), want = Bytes(fresh.Render(view), "CellId");
    ASSERT_FALSE(want.empty());
    EXPECT_TRUE(got == want) << "CellId differs: " << FirstDifference(got, want, 8);
  };
  view.Distance = 1.5; // the sphere fills most rows
  expectFresh(kept.Render(view), "first");
  kept.Filter->SetSize(Height, Width); // the same pixels, rows of another length
  view.Azimuth = 30.0;
  view.Distance = 6.0;
  expectFresh(kept.Render(view), "transposed");
  kept.Filter->SetSamplesPerPixel(4);
  view.Azimuth = 40.0;
  view.Distance = 1.5;
  expectFresh(kept.Render(view), "4 samples");
  kept.Filter->SetSamplesPerPixel(1);
  view.Azimuth = 50.0;
  view.Distance = 6.0;
  expectFresh(kept.Render(view), "1 sample again");
  vtkIdTypeArray* plane =
    vtkIdTypeArray::SafeDownCast(kept.Filter->GetOutput()->GetPointData()->GetArray("CellId"));
  ASSERT_NE(plane, nullptr);
  plane->Fill(7); // every pixel, the background too
  plane->Modified();
  plane = nullptr;
  view.Azimuth = 60.0;
  expectFresh(kept.Render(view), "after the user's change");
}

//------------------------------------------------------------------------------
TEST_F(Incremental, OutputsNobodyAskedForAreLeftOut)
{
  Rig all(this->Input);
  const std::string rgba = Bytes(all.Render(Settings()), "RGBA");
  Rig some(this->Input);
  some.Filter->OutputDepthOff();
  vtkImageData* image = some.Render(Settings());
  EXPECT_EQ(image->GetPointData()->GetArray("Depth"), nullptr);
  EXPECT_NE(image->GetPointData()->GetArray("CellId"), nullptr);
  EXPECT_TRUE(Bytes(image, "RGBA") == rgba);
  EXPECT_NE(std::string(some.Filter->GetRenderPlan()).find("depth output off"), std::string::npos)
    << some.Filter->GetRenderPlan();
  some.Filter->OutputCellIdsOff();
  image = some.Render(Settings());
  EXPECT_EQ(image->GetPointData()->GetArray("Depth"), nullptr);
  EXPECT_EQ(image->GetPointData()->GetArray("CellId"), nullptr);
  EXPECT_TRUE(Bytes(image, "RGBA") == rgba);
  some.Filter->OutputDepthOn();
  some.Filter->OutputCellIdsOn();
  ExpectSameImage(some.Render(Settings()), all.Filter->GetOutput());
}

//------------------------------------------------------------------------------
TEST_F(Incremental, ThePlanInNumbers)
{
  Rig rig(this->Input);
  vtkNew<vtkLight> black; // reaches nothing
  black->SetDiffuseColor(0.0, 0.0, 0.0);
  rig.Filter->AddLight(black);
  vtkImageData* image = rig.Render(Settings());
  auto* plan =
    vtkStringArray::SafeDownCast(image->GetFieldData()->GetAbstractArray("FacetRenderPlan"));
  ASSERT_NE(plan, nullptr);
  EXPECT_EQ(plan->GetValue(0), rig.Filter->GetRenderPlan());
  EXPECT_NE(plan->GetValue(0).find("seconds:"), std::string::npos) << plan->GetValue(0);
  EXPECT_EQ(FieldValue(image, "FacetRenderPlanRulesAllowed", "LightsThatReachNothing"), 1.0);
  EXPECT_EQ(FieldValue(image, "FacetRenderPlanRulesFired", "LightsThatReachNothing"), 1.0);
  EXPECT_EQ(FieldValue(image, "FacetRenderPlanRulesSkipped", "LightsThatReachNothing"), 1.0);
  EXPECT_EQ(FieldValue(image, "FacetRenderPlanRulesFired", "AmbientOnly"), 0.0);
  EXPECT_EQ(FieldValue(image, "FacetRenderPlanLightCulling", "Lights"), 2.0);
  EXPECT_EQ(FieldValue(image, "FacetRenderPlanLightCulling", "Dark"), 1.0);
  EXPECT_EQ(FieldValue(image, "FacetRenderPlanLightCulling", "ErrorBound8Bit"), 0.0);
  for (const char* phase : { "Validate", "Transform", "Setup", "Raster", "Shade", "Output" })
  {
    EXPECT_GE(FieldValue(image, "FacetPhaseSeconds", phase), 0.0) << phase;
  }
  EXPECT_GT(FieldValue(image, "FacetPhaseSeconds", "Raster"), 0.0);
}

// A dim light far away left out by a tolerance: the image stays within the bound the plan
// reports.
TEST_F(Incremental, LightCullingToleranceStaysWithinItsBound)
{
  Rig exact(this->Input), tolerant(this->Input);
  for (Rig* rig : { &exact, &tolerant })
  {
    vtkNew<vtkLight> far;
    far->SetPositional(true);
    far->SetConeAngle(180.0);
    far->SetPosition(0.0, 0.0, 40.0);
    far->SetAttenuationValues(0.0, 0.0, 1.0); // 1/d²: at most 1/39² ≈ 6.6e-4
    rig->Filter->AddLight(far);
  }
  tolerant.Filter->SetLightCullingTolerance(0.01);
  const std::string expected = Bytes(exact.Render(Settings()), "RGBA");
  vtkImageData* image = tolerant.Render(Settings());
  EXPECT_EQ(FieldValue(image, "FacetRenderPlanLightCulling", "BelowTolerance"), 1.0);
  const double bound = FieldValue(image, "FacetRenderPlanLightCulling", "ErrorBound");
  const int bound8 =
    static_cast<int>(FieldValue(image, "FacetRenderPlanLightCulling", "ErrorBound8Bit"));
  EXPECT_GT(bound, 0.0);
  EXPECT_LE(bound, 0.01);
  const std::string got = Bytes(image, "RGBA");
  ASSERT_EQ(got.size(), expected.size());
  int largest = 0;
  for (std::size_t i = 0; i < got.size(); ++i)
  {
    largest = std::max(largest,
      std::abs(static_cast<unsigned char>(got[i]) - static_cast<unsigned char>(expected[i])));
  }
  EXPECT_LE(largest, bound8) << "bound " << bound;
}

//------------------------------------------------------------------------------
// The quality modes keep per mesh what they derive from it between renders (vertex normals,
// each polygon's shape and the range of its corners' colors, which the estimate and the
// error budget bound by). A change of an attribute alone — the scalars' values, the lookup
// table's range, the point normals — must reach them: the image, the estimate and the
// measured error are a fresh filter's.
namespace {
struct QualityMode
{
  const char* Name;
  int Interpolation;
  double MaximumError;
};

struct AttributeChange
{
  const char* Name;
  void (*Input)(vtkPolyData* input);            // made to the shared input once
  void (*Filter)(vtkFacetRenderFilter* filter); // made to each filter
};

void NegateScalars(vtkPolyData* input)
{
  vtkDataArray* scalars = input->GetPointData()->GetScalars();
  for (vtkIdType i = 0; i < scalars->GetNumberOfTuples(); ++i)
  {
    scalars->SetComponent(i, 0, -0.7 * scalars->GetComponent(i, 0) + 0.1);
  }
  scalars->Modified();
}

void TiltNormals(vtkPolyData* input)
{
  TiltPointNormals(input, 0.3);
}

const QualityMode QualityModes[] = { { "FlatWithinTwo", VTK_FLAT, 2.0 },
  { "Gouraud", VTK_GOURAUD, 0.0 },
  { "Phong", VTK_PHONG, 0.0 } };
const AttributeChange AttributeChanges[] = {
  { "Scalars", NegateScalars, [](vtkFacetRenderFilter*) {} },
  { "TableRange",
    [](vtkPolyData*) {},
    [](vtkFacetRenderFilter* filter) { filter->SetScalarRange(-0.2, 0.9); } },
  { "PointNormals", TiltNormals, [](vtkFacetRenderFilter*) {} },
};

void PrintTo(const QualityMode& mode, std::ostream* out)
{
  *out << mode.Name;
}

void PrintTo(const AttributeChange& change, std::ostream* out)
{
  *out << change.Name;
}

class IncrementalQuality
  : public Incremental
  , public ::testing::WithParamInterface<std::tuple<QualityMode, AttributeChange>>
{
};

std::vector<double> Estimates(vtkImageData* image)
{
  std::vector<double> values;
  for (const char* name : { "PredictedRMSE", "PredictedMax" })
  {
    values.push_back(FieldValue(image, "FacetErrorEstimate", name));
  }
  if (image->GetFieldData()->GetArray("FacetError"))
  {
    for (const char* name : { "RMSE", "Max", "SSIM", "SilhouetteFraction" })
    {
      values.push_back(FieldValue(image, "FacetError", name));
    }
  }
  return values;
}
}

TEST_P(IncrementalQuality, AnAttributeChangeReachesWhatTheModesKeep)
{
  // Named, not bound: clang 14 does not capture structured bindings in lambdas (C++20 P1091).
  const QualityMode& mode = std::get<0>(this->GetParam());
  const AttributeChange& change = std::get<1>(this->GetParam());
  const auto configure = [&](Rig& rig) {
    rig.Filter->SetMaximumError(mode.MaximumError);
    rig.Filter->EstimateErrorOn();
    rig.Filter->ErrorEstimateArrayOn();
    // The measured error reads the kept vertex normals (the mesh reference shades by them);
    // once is enough (it renders a 128-sample reference).
    rig.Filter->SetComputeError(change.Input == TiltNormals && mode.Interpolation == VTK_PHONG);
  };
  Settings settings;
  settings.Interpolation = mode.Interpolation;
  Rig kept(this->Input);
  configure(kept);
  vtkNew<vtkImageData> before;
  before->DeepCopy(kept.Render(settings));
  change.Input(this->Input);
  change.Filter(kept.Filter);
  vtkImageData* again = kept.Render(settings);
  EXPECT_EQ(FieldValue(again, "FacetMeshConverted", "Converted"), 0.0);
  EXPECT_EQ(FieldValue(again, "FacetShadingMeshes", "Built"), 1.0) << "the sphere's one mesh";
  EXPECT_TRUE(Bytes(again, "ErrorEstimate") != Bytes(before, "ErrorEstimate"))
    << "the change shows in the estimate";

  Rig fresh(this->Input);
  configure(fresh);
  change.Filter(fresh.Filter);
  vtkImageData* expected = fresh.Render(settings);
  ExpectSameImage(again, expected);
  const std::string estimate = Bytes(again, "ErrorEstimate");
  EXPECT_TRUE(estimate == Bytes(expected, "ErrorEstimate"))
    << "ErrorEstimate differs: " << FirstDifference(estimate, Bytes(expected, "ErrorEstimate"), 4);
  EXPECT_EQ(Estimates(again), Estimates(expected));
}

INSTANTIATE_TEST_SUITE_P(Modes,
  IncrementalQuality,
  ::testing::Combine(::testing::ValuesIn(QualityModes), ::testing::ValuesIn(AttributeChanges)),
  [](const auto& info) {
    return std::string(std::get<0>(info.param).Name) + "_" + std::get<1>(info.param).Name;
  });

// What the quality modes keep is built again only for what changed: a new camera, light or
// background builds nothing, nor do new scalars where they give no point colors.
TEST_F(Incremental, TheShadingMeshIsBuiltOnlyWhenItsMeshChanged)
{
  Settings settings;
  settings.Interpolation = VTK_PHONG;
  Rig kept(this->Input);
  kept.Filter->EstimateErrorOn();
  const auto built = [](vtkImageData* image) {
    return std::pair{ FieldValue(image, "FacetShadingMeshes", "Built"),
      FieldValue(image, "FacetShadingMeshes", "Kept") };
  };
  EXPECT_EQ(built(kept.Render(settings)), std::pair(1.0, 0.0));
  Settings changed = settings;
  changed.Azimuth = 50.0;
  changed.LightIntensity = 0.6;
  changed.Background[0] = 0.7;
  EXPECT_EQ(built(kept.Render(changed)), std::pair(0.0, 1.0)) << "camera, light, background";
  changed.ColorByScalars = false;
  EXPECT_EQ(built(kept.Render(changed)), std::pair(1.0, 0.0)) << "the point colors gone";
  NegateScalars(this->Input);
  vtkImageData* again = kept.Render(changed);
  EXPECT_EQ(built(again), std::pair(0.0, 1.0)) << "scalars that color nothing";
  Rig fresh(this->Input);
  fresh.Filter->EstimateErrorOn();
  vtkImageData* expected = fresh.Render(changed);
  ExpectSameImage(again, expected);
  EXPECT_EQ(FieldValue(again, "FacetErrorEstimate", "PredictedRMSE"),
    FieldValue(expected, "FacetErrorEstimate", "PredictedRMSE"));
}

//------------------------------------------------------------------------------
// Two inputs sharing one vtkPoints, modified after both were built, have the same points,
// polygon count and version (their latest MTime): what the quality keeps for one must not
// shade the other.
TEST_F(Incremental, InputsSharingTheirPointsKeepTheirOwnShading)
{
  vtkNew<vtkCellArray> twisted; // the same cells, each corner moved to the next point
  const vtkIdType points = this->Input->GetNumberOfPoints();
  vtkCellArray* polys = this->Input->GetPolys();
  vtkNew<vtkIdList> cell;
  for (vtkIdType c = 0; c < polys->GetNumberOfCells(); ++c)
  {
    polys->GetCellAtId(c, cell);
    for (vtkIdType k = 0; k < cell->GetNumberOfIds(); ++k)
      cell->SetId(k, (cell->GetId(k) + 1) % points);
    twisted->InsertNextCell(cell);
  }
  vtkNew<vtkPolyData> other;
  other->SetPoints(this->Input->GetPoints());
  other->SetPolys(twisted);
  other->GetPointData()->ShallowCopy(this->Input->GetPointData());
  this->Input->GetPoints()->Modified();

  Settings settings;
  settings.Interpolation = VTK_PHONG;
  settings.ColorByScalars = false; // no point colors, so no color version tells them apart
  Rig kept(this->Input);
  kept.Render(settings);
  kept.Filter->SetInputData(other);
  vtkImageData* again = kept.Render(settings);
  Rig fresh(other);
  ExpectSameImage(again, fresh.Render(settings));
}
