"""Facet Render's output in a ParaView render view (pvbatch under Xvfb): shown with the
"Facet Image" representation, its RGBA bytes are the colors on screen, not a color map.

The filter renders an unlit pure red sphere on a pure blue background; a screenshot of the
view must contain those exact colors in quantity. Through a color map (Map Scalars on), the
magnitude of (255, 0, 0, 255) or (0, 0, 255, 255) maps to neither.
"""
import os
import sys
import tempfile
import unittest

import numpy
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import facet_paraview_testing as testing  # noqa: E402
from paraview.simple import *  # noqa: E402,F401,F403

testing.load_plugin(globals())


class FacetImageRepresentation(unittest.TestCase):
    def test_rgba_shown_as_colors(self):
        render = FacetRender(Input=Sphere(ThetaResolution=32, PhiResolution=16))
        render.Size = [200, 150]
        render.Background = [0.0, 0.0, 1.0]
        render.Light1Switch = 0
        render.AmbientLightColor = [0.0, 0.0, 0.0]
        render.Ambient = 1.0
        render.AmbientColor = [1.0, 0.0, 0.0]
        view = CreateView("RenderView")
        view.OrientationAxesVisibility = 0
        view.Background = [0.5, 0.5, 0.5]
        display = Show(render, view)
        self.assertEqual(display.Representation, "Facet Image")

        view.InteractionMode = "2D"
        ResetCamera(view)
        with tempfile.TemporaryDirectory() as folder:
            path = os.path.join(folder, "view.png")
            SaveScreenshot(path, view, ImageResolution=[400, 300])
            reader = vtkPNGReader()
            reader.SetFileName(path)
            reader.Update()
            shot = vtk_to_numpy(reader.GetOutput().GetPointData().GetScalars())[:, :3]
        Delete(view)  # before pvbatch's teardown, which fails on a live view under Xvfb
        red = numpy.all(shot == (255, 0, 0), axis=1).sum()
        blue = numpy.all(shot == (0, 0, 255), axis=1).sum()
        # The 200 x 150 image fills about half the 400 x 300 view: a sphere covering ~ 1/4
        # of it, and its blue background the rest.
        self.assertGreater(red, 2000, "pure red pixels: %d, pure blue: %d" % (red, blue))
        self.assertGreater(blue, 5000, "pure red pixels: %d, pure blue: %d" % (red, blue))


if __name__ == "__main__":
    unittest.main(argv=[sys.argv[0], "-v"])
