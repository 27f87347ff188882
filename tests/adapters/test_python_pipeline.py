"""Python pipeline: vtkOBJReader -> vtkFacetRenderFilter -> vtkPNGWriter, in /usr/bin/python3.

Checks the output's array names, types, extent and a few pixel values, and that the PNG
written reads back as the same image.
"""
import math
import os
import sys
import tempfile
import unittest

from vtkmodules.vtkCommonCore import VTK_FLOAT, VTK_ID_TYPE, VTK_UNSIGNED_CHAR
from vtkmodules.vtkIOGeometry import vtkOBJReader
from vtkmodules.vtkIOImage import vtkPNGReader, vtkPNGWriter
from vtkmodules.vtkRenderingCore import vtkCamera

from facet import vtkFacetLight, vtkFacetRenderFilter
from readme_blocks import readme_python_block

MESHES = os.environ["FACET_SHARED_DATA_DIR"] + "/meshes"


class PythonPipeline(unittest.TestCase):
    def setUp(self):
        self.reader = vtkOBJReader()
        self.reader.SetFileName(MESHES + "/spot.obj")
        self.render = vtkFacetRenderFilter()
        self.render.SetInputConnection(self.reader.GetOutputPort())
        self.render.SetSize(320, 240)
        self.render.SetBackground(0.0, 0.0, 0.25)

    def test_arrays_extent_and_pixels(self):
        self.render.Update()
        image = self.render.GetOutput()
        self.assertEqual(image.GetExtent(), (0, 319, 0, 239, 0, 0))
        point_data = image.GetPointData()
        self.assertEqual(point_data.GetScalars().GetName(), "RGBA")
        rgba, depth, cell_id = (point_data.GetArray(n) for n in ("RGBA", "Depth", "CellId"))
        self.assertEqual(rgba.GetDataType(), VTK_UNSIGNED_CHAR)
        self.assertEqual(rgba.GetNumberOfComponents(), 4)
        self.assertEqual(depth.GetDataType(), VTK_FLOAT)
        self.assertEqual(cell_id.GetDataType(), VTK_ID_TYPE)
        corner = 0  # bottom-left pixel: background
        self.assertEqual(rgba.GetTuple(corner), (0.0, 0.0, 64.0, 255.0))
        self.assertEqual(depth.GetValue(corner), 1.0)
        self.assertEqual(cell_id.GetValue(corner), -1)
        center = 120 * 320 + 160  # the cow fills the middle
        self.assertGreaterEqual(cell_id.GetValue(center), 0)
        self.assertLess(cell_id.GetValue(center), self.reader.GetOutput().GetNumberOfCells())
        self.assertLess(depth.GetValue(center), 1.0)
        self.assertNotEqual(rgba.GetTuple(center)[:3], (0.0, 0.0, 64.0))
        counts = image.GetFieldData().GetArray("FacetCounts")
        names = [counts.GetComponentName(i) for i in range(counts.GetNumberOfComponents())]
        covered = counts.GetComponent(0, names.index("PixelsCovered"))
        self.assertGreater(covered, 5000)
        self.assertIn("z-buffer", self.render.GetRenderPlan())

    def test_png_round_trip(self):
        with tempfile.TemporaryDirectory() as folder:
            path = os.path.join(folder, "spot.png")
            writer = vtkPNGWriter()
            writer.SetInputConnection(self.render.GetOutputPort())
            writer.SetFileName(path)
            writer.Write()
            back = vtkPNGReader()
            back.SetFileName(path)
            back.Update()
            written = back.GetOutput().GetPointData().GetScalars()
            rendered = self.render.GetOutput().GetPointData().GetArray("RGBA")
            self.assertEqual(back.GetOutput().GetDimensions(), (320, 240, 1))
            for index in (0, 120 * 320 + 160, 200 * 320 + 100):
                self.assertEqual(written.GetTuple(index), rendered.GetTuple(index))

    def test_arrays_kept_by_the_user_are_not_overwritten(self):
        self.render.Update()
        kept = self.render.GetOutput().GetPointData().GetArray("RGBA")
        before = [kept.GetTuple(i) for i in range(0, 320 * 240, 997)]
        self.render.SetBackground(1.0, 0.0, 0.0)
        self.render.Update()
        after = [kept.GetTuple(i) for i in range(0, 320 * 240, 997)]
        self.assertEqual(before, after)
        fresh = self.render.GetOutput().GetPointData().GetArray("RGBA")
        self.assertEqual(fresh.GetTuple(0), (255.0, 0.0, 0.0, 255.0))

    def test_facet_light_from_python(self):
        light = vtkFacetLight()
        light.SetLightTypeToHeadlight()
        light.SetColor(1.0, 0.0, 0.0)
        self.render.AddLight(light)
        self.render.SetAmbientLightColor(0.0, 0.0, 0.0)
        self.render.Update()
        red, green, blue, _ = self.render.GetOutput().GetPointData().GetArray("RGBA").GetTuple(
            120 * 320 + 160)
        self.assertGreater(red, 50)
        self.assertEqual((green, blue), (0.0, 0.0))

    def test_orbit_from_the_fitted_camera_as_the_readme_says(self):
        self.render.Update()
        fitted = vtkCamera()
        fitted.DeepCopy(self.render.GetActiveCamera())
        self.assertIsNone(self.render.GetCamera())
        namespace = {"render": self.render, "reader": self.reader, "vtkCamera": vtkCamera,
                     "vtkFacetRenderFilter": vtkFacetRenderFilter}
        exec(readme_python_block("GetActiveCamera"), namespace)
        self.render.SetSize(800, 600)  # the size the snippet fitted for
        self.render.Update()
        camera = self.render.GetActiveCamera()
        self.assertIs(camera, self.render.GetCamera())
        self.assertEqual(camera.GetFocalPoint(), fitted.GetFocalPoint())
        turned = sum(a * b for a, b in zip(camera.GetDirectionOfProjection(),
                                           fitted.GetDirectionOfProjection()))
        self.assertAlmostEqual(turned, math.cos(math.radians(30)), places=9)
        center = 300 * 800 + 400
        self.assertGreaterEqual(
            self.render.GetOutput().GetPointData().GetArray("CellId").GetValue(center), 0)


if __name__ == "__main__":
    sys.exit(unittest.main())
