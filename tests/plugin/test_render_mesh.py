"""examples/paraview/render_mesh.py run as a user runs it (in pvbatch), then its image:
the PNG's size and pixels, the filter's arrays, and what its two lights must do.

Expectations, from the example's settings: the four corners are the background
(0.12, 0.13, 0.16) -> (31, 33, 41, 255); the middle of the image shows the mesh; the key light
(warm, intensity 1) comes from the upper right in the camera's frame and the fill light
(cool, 0.3) from the left, so the mesh is brighter on its right than on its left.
"""
import os
import runpy
import sys
import tempfile
import unittest

import numpy
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import facet_paraview_testing as testing  # noqa: E402
from facet_paraview_testing import Image, luminance  # noqa: E402
from paraview.simple import GetSources  # noqa: E402

W, H = 320, 240


class RenderMeshExample(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.folder = tempfile.TemporaryDirectory()
        cls.png = os.path.join(cls.folder.name, "spot.png")
        sys.argv = [os.path.join(testing.EXAMPLES, "paraview", "render_mesh.py"),
                    os.path.join(testing.MESHES, "spot.obj"), cls.png,
                    "--plugin", testing.PLUGIN, "--size", str(W), str(H),
                    "--view", "-0.7", "0.4", "-1.0"]
        runpy.run_path(sys.argv[0], run_name="__main__")
        renders = [p for p in GetSources().values() if p.GetXMLName() == "FacetRender"]
        cls.image = Image(renders[0])
        reader = vtkPNGReader()
        reader.SetFileName(cls.png)
        reader.Update()
        cls.written = reader.GetOutput()

    @classmethod
    def tearDownClass(cls):
        cls.folder.cleanup()

    def test_png_is_the_rgba_array(self):
        self.assertEqual(self.written.GetDimensions(), (W, H, 1))
        scalars = self.written.GetPointData().GetScalars()
        self.assertEqual(scalars.GetNumberOfComponents(), 4)
        pixels = vtk_to_numpy(scalars).reshape(H, W, 4)
        numpy.testing.assert_array_equal(pixels, self.image.rgba)

    def test_arrays(self):
        self.assertEqual((self.image.width, self.image.height), (W, H))
        self.assertEqual(sorted(self.image.arrays), ["CellId", "Depth", "RGBA"])
        self.assertEqual(self.image.scalars, "RGBA")

    def test_background_corners(self):
        for y, x in self.image.corners():
            self.assertEqual(tuple(self.image.rgba[y, x]), (31, 33, 41, 255))
            self.assertEqual(self.image.cell_id[y, x], -1)
            self.assertEqual(self.image.depth[y, x], 1.0)

    def test_mesh_in_the_middle(self):
        self.assertGreaterEqual(self.image.cell_id[H // 2, W // 2], 0)
        self.assertLess(self.image.depth[H // 2, W // 2], 1.0)
        fraction = self.image.covered().mean()
        self.assertTrue(0.08 < fraction < 0.8, "the mesh covers %.3f of the image" % fraction)

    def test_key_light_side_is_brighter(self):
        covered = self.image.covered()
        columns = numpy.nonzero(covered.any(axis=0))[0]
        middle = (columns[0] + columns[-1]) // 2
        light = luminance(self.image.rgba)
        left = light[:, :middle][covered[:, :middle]].mean()
        right = light[:, middle:][covered[:, middle:]].mean()
        self.assertGreater(right, 1.2 * left, "mean luma: left %.1f, right %.1f" % (left, right))


if __name__ == "__main__":
    unittest.main(argv=[sys.argv[0], "-v"])
