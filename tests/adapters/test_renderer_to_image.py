"""vtkFacetRendererToImageFilter from Python (/usr/bin/python3, VTK 9.1): a renderer built as a
VTK user builds one, rendered without a window; the README's snippet and
examples/render_existing_scene.py run as a user runs them.
"""
import os
import subprocess
import sys
import tempfile
import unittest

import vtkmodules.vtkRenderingOpenGL2  # noqa: F401  the mappers' factory; no window opens
from vtkmodules.vtkCommonCore import VTK_FLOAT, VTK_ID_TYPE, VTK_INT, VTK_UNSIGNED_CHAR
from vtkmodules.vtkFiltersSources import vtkConeSource, vtkSphereSource
from vtkmodules.vtkIOImage import vtkPNGReader
from vtkmodules.vtkRenderingCore import vtkActor, vtkPolyDataMapper, vtkRenderer, vtkVolume

from facet import vtkFacetRendererToImageFilter
from readme_blocks import readme_python_block

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..", "..")
EXAMPLE = os.path.join(ROOT, "examples", "render_existing_scene.py")


def actor_of(source, position):
    mapper = vtkPolyDataMapper()
    mapper.SetInputConnection(source.GetOutputPort())
    actor = vtkActor()
    actor.SetMapper(mapper)
    actor.SetPosition(*position)
    actor.GetProperty().SetInterpolationToFlat()
    return actor


def png_pixels(path):
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


class RendererToImage(unittest.TestCase):
    def setUp(self):
        self.renderer = vtkRenderer()
        self.renderer.AddActor(actor_of(vtkSphereSource(), (-0.8, 0.0, 0.0)))  # prop 0
        self.renderer.AddVolume(vtkVolume())                                      # prop 1
        self.renderer.AddActor(actor_of(vtkConeSource(), (0.8, 0.0, 0.0)))      # prop 2
        self.renderer.SetBackground(0.0, 0.0, 0.25)
        self.grab = vtkFacetRendererToImageFilter()
        self.grab.SetRenderer(self.renderer)
        self.grab.SetSize(320, 240)
        self.warnings = []
        self.grab.AddObserver("WarningEvent", lambda caller, event: self.warnings.append(event))

    def test_arrays_ids_and_the_one_warning(self):
        self.grab.Update()
        image = self.grab.GetOutput()
        self.assertEqual(image.GetExtent(), (0, 319, 0, 239, 0, 0))
        point_data = image.GetPointData()
        self.assertEqual(point_data.GetScalars().GetName(), "RGBA")
        types = {name: point_data.GetArray(name).GetDataType()
                 for name in ("RGBA", "Depth", "CellId", "ActorId")}
        self.assertEqual(types, {"RGBA": VTK_UNSIGNED_CHAR, "Depth": VTK_FLOAT,
                                 "CellId": VTK_ID_TYPE, "ActorId": VTK_INT})
        actor_ids = point_data.GetArray("ActorId")
        seen = {actor_ids.GetValue(i) for i in range(actor_ids.GetNumberOfTuples())}
        self.assertEqual(seen, {-1, 0, 2}, "the sphere, the cone (after the volume), background")
        self.assertEqual(point_data.GetArray("RGBA").GetTuple(0), (0.0, 0.0, 64.0, 255.0))
        self.assertEqual(len(self.warnings), 1)
        self.assertTrue(self.renderer.IsActiveCameraCreated(), "as Render would make it")

    def test_renders_again_only_when_the_scene_changed(self):
        executions = []
        self.grab.AddObserver("StartEvent", lambda caller, event: executions.append(event))
        self.grab.Update()
        self.grab.Update()
        self.assertEqual(len(executions), 1)
        self.renderer.GetActiveCamera().Azimuth(30)
        self.grab.Update()
        self.assertEqual(len(executions), 2)

    def test_readme_snippet(self):
        with tempfile.TemporaryDirectory() as folder:
            cwd = os.getcwd()
            os.chdir(folder)
            try:
                exec(readme_python_block("vtkFacetRendererToImageFilter"), {})
            finally:
                os.chdir(cwd)
            image = png_pixels(os.path.join(folder, "scene.png"))
            self.assertEqual(image.GetDimensions(), (800, 600, 1))
            center = image.GetPointData().GetScalars().GetTuple(300 * 800 + 400)
            self.assertNotEqual(center[:3], (0.0, 0.0, 0.0), "the sphere fills the middle")

    def test_example_writes_the_scene(self):
        with tempfile.TemporaryDirectory() as folder:
            path = os.path.join(folder, "scene.png")
            run = subprocess.run([sys.executable, EXAMPLE, path], capture_output=True, text=True,
                                 env=dict(os.environ), check=False)
            self.assertEqual(run.returncode, 0, run.stderr)
            self.assertIn("render plan", run.stdout)
            self.assertNotIn("Warning", run.stderr)
            image = png_pixels(path)
            self.assertEqual(image.GetDimensions(), (800, 600, 1))
            rgb = image.GetPointData().GetScalars()
            top, bottom = rgb.GetTuple(599 * 800), rgb.GetTuple(0)
            self.assertGreater(top[2], bottom[2], "the gradient: lighter at the top")
            distinct = {rgb.GetTuple(i)[:3] for i in range(0, 800 * 600, 101)}
            self.assertGreater(len(distinct), 100, "shaded, colored surfaces")


if __name__ == "__main__":
    sys.exit(unittest.main())
