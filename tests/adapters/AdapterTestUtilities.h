#pragma once

// Helpers shared by the adapter tests.

#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkFacetRenderFilter.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkImageAlgorithm.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"

#include <array>
#include <functional>
#include <gtest/gtest.h>
#include <string>

namespace facet_test {

inline vtkIdType PixelIndex(vtkImageData* image, int x, int y)
{
  return static_cast<vtkIdType>(y) * image->GetDimensions()[0] + x;
}

inline vtkIdType CellIdAt(vtkImageData* image, int x, int y)
{
  return vtkIdTypeArray::SafeDownCast(image->GetPointData()->GetArray("CellId"))
    ->GetValue(PixelIndex(image, x, y));
}

inline int ActorIdAt(vtkImageData* image, int x, int y)
{
  return vtkIntArray::SafeDownCast(image->GetPointData()->GetArray("ActorId"))
    ->GetValue(PixelIndex(image, x, y));
}

inline std::array<int, 4> RgbaAt(vtkImageData* image, int x, int y)
{
  auto* rgba = vtkUnsignedCharArray::SafeDownCast(image->GetPointData()->GetArray("RGBA"));
  const unsigned char* p = rgba->GetPointer(4 * PixelIndex(image, x, y));
  return { p[0], p[1], p[2], p[3] };
}

inline double FieldValue(vtkImageData* image, const char* array, const char* component)
{
  vtkDataArray* values = image->GetFieldData()->GetArray(array);
  for (int c = 0; values && c < values->GetNumberOfComponents(); ++c)
  {
    if (std::string(values->GetComponentName(c)) == component)
    {
      return values->GetComponent(0, c);
    }
  }
  return -1.0;
}

// A parallel camera for which world x, y are window pixels of a width × height image.
inline vtkSmartPointer<vtkCamera> PixelCamera(int width, int height)
{
  auto camera = vtkSmartPointer<vtkCamera>::New();
  camera->ParallelProjectionOn();
  camera->SetParallelScale(0.5 * height);
  camera->SetFocalPoint(0.5 * width, 0.5 * height, 0.0);
  camera->SetPosition(0.5 * width, 0.5 * height, 100.0);
  camera->SetViewUp(0.0, 1.0, 0.0);
  camera->SetClippingRange(1.0, 300.0);
  return camera;
}

// Counts the executions of an algorithm (its StartEvents).
struct ExecutionCounter
{
  explicit ExecutionCounter(vtkObject* algorithm)
  {
    this->Callback->SetClientData(this);
    this->Callback->SetCallback([](vtkObject*, unsigned long, void* self, void*) {
      ++static_cast<ExecutionCounter*>(self)->Count;
    });
    algorithm->AddObserver(vtkCommand::StartEvent, this->Callback);
  }
  int Count = 0;
  vtkNew<vtkCallbackCommand> Callback;
};

// A square in the z = 0 plane, [x0, x1] × [y0, y1], counter-clockwise seen from +z.
inline vtkIdType AddSquare(vtkPoints* points,
  vtkCellArray* polys,
  double x0,
  double y0,
  double x1,
  double y1,
  double z = 0.0)
{
  const vtkIdType first = points->InsertNextPoint(x0, y0, z);
  points->InsertNextPoint(x1, y0, z);
  points->InsertNextPoint(x1, y1, z);
  points->InsertNextPoint(x0, y1, z);
  const vtkIdType ids[4] = { first, first + 1, first + 2, first + 3 };
  return polys->InsertNextCell(4, ids);
}

// A vtkPolyData of these points and polygons.
inline vtkSmartPointer<vtkPolyData> PolyData(vtkPoints* points, vtkCellArray* polys)
{
  auto data = vtkSmartPointer<vtkPolyData>::New();
  data->SetPoints(points);
  data->SetPolys(polys);
  return data;
}

// A columns × rows grid of side × side squares from the origin (square (i, j) is polygon
// j·columns + i) after `verts` vertex cells and one line cell: its polys' cell ids start at
// verts + 1.
inline vtkSmartPointer<vtkPolyData> SquareGridAfterVertsAndALine(int columns,
  int rows,
  int side,
  int verts)
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> vertCells, lines, polys;
  const vtkIdType vertex = points->InsertNextPoint(1.0, 1.0, 0.0);
  for (int v = 0; v < verts; ++v)
  {
    vertCells->InsertNextCell(1, &vertex);
  }
  const vtkIdType line[2] = { vertex, vertex };
  lines->InsertNextCell(2, line);
  for (int j = 0; j < rows; ++j)
  {
    for (int i = 0; i < columns; ++i)
    {
      AddSquare(points, polys, i * side, j * side, (i + 1) * side, (j + 1) * side);
    }
  }
  vtkSmartPointer<vtkPolyData> data = PolyData(points, polys);
  data->SetVerts(vertCells);
  data->SetLines(lines);
  return data;
}

// Turns every point normal of `data` toward +x (x += dx, normalized) in place and marks the
// normals modified: new normals on the same points, as a user edits them.
inline void TiltPointNormals(vtkPolyData* data, double dx)
{
  vtkDataArray* normals = data->GetPointData()->GetNormals();
  ASSERT_NE(normals, nullptr);
  for (vtkIdType i = 0; i < normals->GetNumberOfTuples(); ++i)
  {
    double n[3];
    normals->GetTuple(i, n);
    n[0] += dx;
    vtkMath::Normalize(n);
    normals->SetTuple(i, n);
  }
  normals->Modified();
}

// Counts the messages of one kind (vtkCommand::ErrorEvent or WarningEvent) and keeps the
// last, instead of letting VTK print them.
struct MessageCounter
{
  explicit MessageCounter(vtkObject* object, unsigned long event)
  {
    this->Callback->SetClientData(this);
    this->Callback->SetCallback([](vtkObject*, unsigned long, void* self, void* data) {
      auto* counter = static_cast<MessageCounter*>(self);
      ++counter->Count;
      counter->Last = data ? static_cast<const char*>(data) : "";
    });
    object->AddObserver(event, this->Callback);
  }
  int Count = 0;
  std::string Last;
  vtkNew<vtkCallbackCommand> Callback;
};

// An algorithm that renders a width × height image of something covering over 1000 pixels
// reports progress, and when aborted past 10 % stops early with a valid background image.
// `renderAgain` makes the next execution a full render (one with nothing changed would
// only resolve the last frame, facet/Renderer.h: the abort must stop a whole render).
inline void ExpectProgressReportedAndAbortable(vtkImageAlgorithm* algorithm,
  int width,
  int height,
  const std::function<void()>& renderAgain)
{
  struct Progress
  {
    int Calls = 0;
    bool Abort = false;
  } progress;
  vtkNew<vtkCallbackCommand> observer;
  observer->SetClientData(&progress);
  observer->SetCallback([](vtkObject* caller, unsigned long, void* data, void* fraction) {
    auto* p = static_cast<Progress*>(data);
    ++p->Calls;
    if (p->Abort && *static_cast<double*>(fraction) > 0.1)
    {
      vtkAlgorithm::SafeDownCast(caller)->SetAbortExecute(1);
    }
  });
  const unsigned long tag = algorithm->AddObserver(vtkCommand::ProgressEvent, observer);
  algorithm->Update();
  EXPECT_GT(progress.Calls, 3);
  vtkImageData* image = vtkImageData::SafeDownCast(algorithm->GetOutputDataObject(0));
  EXPECT_GT(FieldValue(image, "FacetCounts", "PixelsCovered"), 1000.0);

  progress.Abort = true;
  renderAgain();
  algorithm->Update();
  algorithm->SetAbortExecute(0);
  algorithm->RemoveObserver(tag);
  image = vtkImageData::SafeDownCast(algorithm->GetOutputDataObject(0));
  EXPECT_EQ(FieldValue(image, "FacetCounts", "PixelsCovered"), 0.0)
    << "stopped early: a valid background image";
  EXPECT_EQ(image->GetNumberOfPoints(), static_cast<vtkIdType>(width) * height);
}

} // namespace facet_test
