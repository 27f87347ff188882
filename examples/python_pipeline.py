"""A VTK pipeline with Facet as a stage, in Python: OBJ file -> vtkFacetRenderFilter -> PNG.

    PYTHONPATH=build/lib/python3.11/dist-packages /usr/bin/python3 \
        examples/python_pipeline.py ../shared/data/meshes/spot.obj spot.png
"""
import sys

from vtkmodules.vtkIOGeometry import vtkOBJReader
from vtkmodules.vtkIOImage import vtkPNGWriter

from facet import vtkFacetRenderFilter

reader = vtkOBJReader()
reader.SetFileName(sys.argv[1])
render = vtkFacetRenderFilter()  # camera fitted to the mesh, one headlight
render.SetInputConnection(reader.GetOutputPort())
render.SetSize(800, 600)
writer = vtkPNGWriter()
writer.SetInputConnection(render.GetOutputPort())
writer.SetFileName(sys.argv[2])
writer.Write()
print(render.GetRenderPlan())
