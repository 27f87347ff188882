// A VTK pipeline with Facet as a stage: OBJ file -> vtkFacetRenderFilter -> PNG.
//   build/bin/facet-vtk-pipeline mesh.obj out.png
#include "vtkFacetRenderFilter.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkOBJReader.h"
#include "vtkPNGWriter.h"

#include <cstdio>

int main(int argc, char** argv)
{
  if (argc != 3)
  {
    std::fprintf(stderr,
      "usage: facet-vtk-pipeline MESH.obj OUT.png\n"
      "Renders MESH.obj with vtkFacetRenderFilter (800 x 600, the camera fitted to the mesh,\n"
      "one headlight) and writes OUT.png.\n");
    return 2;
  }
  vtkNew<vtkOBJReader> reader;
  reader->SetFileName(argv[1]);
  vtkNew<vtkFacetRenderFilter> render; // camera fitted to the mesh, one headlight
  render->SetInputConnection(reader->GetOutputPort());
  render->SetSize(800, 600);
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputConnection(render->GetOutputPort());
  writer->SetFileName(argv[2]);
  writer->Write();
  return render->GetOutput()->GetNumberOfPoints() > 0 ? 0 : 1;
}
