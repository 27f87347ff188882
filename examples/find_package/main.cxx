// facet-turntable: eight views around a mesh, from the camera Facet fits to it. Built against
// the installed Facet by the CMakeLists.txt beside it.
//   facet-turntable MESH.obj PREFIX   writes PREFIX-0.png ... PREFIX-7.png
#include "vtkCamera.h"
#include "vtkFacetRenderFilter.h"
#include "vtkNew.h"
#include "vtkOBJReader.h"
#include "vtkPNGWriter.h"
#include "vtkPolyData.h"

#include <cstdio>
#include <string>

int main(int argc, char** argv)
{
  if (argc != 3)
  {
    std::fprintf(stderr, "usage: facet-turntable MESH.obj PREFIX\n");
    return 2;
  }
  constexpr int width = 640, height = 480;
  vtkNew<vtkOBJReader> reader;
  reader->SetFileName(argv[1]);
  reader->Update();
  vtkNew<vtkFacetRenderFilter> render;
  render->SetInputConnection(reader->GetOutputPort());
  render->SetSize(width, height);
  vtkNew<vtkCamera> camera; // VTK's default view, turned and fitted to the mesh per frame
  render->SetCamera(camera);
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputConnection(render->GetOutputPort());
  for (int frame = 0; frame < 8; ++frame)
  {
    if (frame > 0)
    {
      camera->Azimuth(45.0);
    }
    // Fitted as the filter fits its automatic camera; the clipping range follows the turn.
    vtkFacetRenderFilter::ResetCamera(camera, reader->GetOutput(), width, height);
    const std::string path = std::string(argv[2]) + "-" + std::to_string(frame) + ".png";
    writer->SetFileName(path.c_str());
    writer->Write(); // renders again; the mesh was converted once
    std::printf("wrote %s\n", path.c_str());
  }
  return 0;
}
