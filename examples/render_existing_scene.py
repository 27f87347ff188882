"""A scene built for VTK's renderer, rendered by Facet: no window, no OpenGL context, no GPU.

    PYTHONPATH=build/lib/python3.11/dist-packages /usr/bin/python3 \
        examples/render_existing_scene.py scene.png

vtkFacetRendererToImageFilter takes the place of vtkWindowToImageFilter: it reads the
renderer's actors, lights, camera and background and renders them on the CPU.
"""
import sys

import vtkmodules.vtkRenderingOpenGL2  # noqa: F401  VTK's mapper classes; no window opens
from vtkmodules.vtkFiltersCore import vtkElevationFilter
from vtkmodules.vtkFiltersSources import vtkConeSource, vtkSphereSource
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingCore import vtkActor, vtkLightKit, vtkPolyDataMapper, vtkRenderer

from facet import vtkFacetRendererToImageFilter

# The scene, as any VTK program builds it.
sphere = vtkSphereSource()
sphere.SetThetaResolution(64)
sphere.SetPhiResolution(48)
elevation = vtkElevationFilter()          # point scalars, colored through the default table
elevation.SetInputConnection(sphere.GetOutputPort())
elevation.SetLowPoint(0, -0.5, 0)
elevation.SetHighPoint(0, 0.5, 0)
ball_mapper = vtkPolyDataMapper()
ball_mapper.SetInputConnection(elevation.GetOutputPort())
ball = vtkActor()
ball.SetMapper(ball_mapper)
ball.SetScale(1.0, 1.3, 1.0)

cone = vtkConeSource()
cone.SetResolution(48)
cone_mapper = vtkPolyDataMapper()
cone_mapper.SetInputConnection(cone.GetOutputPort())
spike = vtkActor()
spike.SetMapper(cone_mapper)
spike.SetPosition(1.2, 0.0, 0.0)
spike.SetOrientation(0.0, 0.0, 30.0)
spike.GetProperty().SetColor(0.9, 0.6, 0.3)

renderer = vtkRenderer()
renderer.AddActor(ball)
renderer.AddActor(spike)
renderer.GradientBackgroundOn()
renderer.SetBackground(0.1, 0.1, 0.15)
renderer.SetBackground2(0.4, 0.45, 0.6)
vtkLightKit().AddLightsToRenderer(renderer)
for actor in (ball, spike):
    actor.GetProperty().SetInterpolationToFlat()  # what Facet renders (else it says so)
renderer.GetActiveCamera().Azimuth(20)
renderer.GetActiveCamera().Elevation(15)
renderer.ResetCamera()

# Facet in place of a render window and vtkWindowToImageFilter.
grab = vtkFacetRendererToImageFilter()
grab.SetRenderer(renderer)
grab.SetSize(800, 600)
writer = vtkPNGWriter()
writer.SetInputConnection(grab.GetOutputPort())
writer.SetFileName(sys.argv[1] if len(sys.argv) > 1 else "scene.png")
writer.Write()
print(grab.GetRenderPlan())
