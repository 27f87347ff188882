"""The Facet Render filter in ParaView (run with pvbatch): its proxy and Python names, the
camera, lights, coloring and quality its properties set, progress and abort.

Most checks are closed forms on small images: what a parallel camera covers, a light's
inverse-square falloff, the exact bytes of the lookup table.
"""
import math
import os
import sys
import unittest

import numpy
from vtkmodules.vtkCommonCore import VTK_COLOR_MODE_DEFAULT, VTK_RGBA, vtkDoubleArray

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import facet_paraview_testing as testing  # noqa: E402
from facet_paraview_testing import Image  # noqa: E402
from paraview import servermanager  # noqa: E402
from paraview.simple import *  # noqa: E402,F401,F403

testing.load_plugin(globals())

W, H = 160, 120


def sphere(resolution=32):
    return Sphere(ThetaResolution=resolution, PhiResolution=resolution // 2)


def unlit(render):
    """Shows the surface colors as they are: no lights, Ka = 1, Kd = 0."""
    render.Light1Switch = 0
    render.AmbientLightColor = [0.0, 0.0, 0.0]
    render.Ambient = 1.0
    render.Diffuse = 0.0
    return render


def mapped(lookup_table, values):
    """RGB bytes of values through a lookup table proxy, as VTK's mappers map them."""
    array = vtkDoubleArray()
    for value in values:
        array.InsertNextValue(value)
    table = lookup_table.GetClientSideObject()
    colors = table.MapScalars(array, VTK_COLOR_MODE_DEFAULT, -1, VTK_RGBA)
    return [colors.GetTuple(i)[:3] for i in range(colors.GetNumberOfTuples())]


class Proxy(unittest.TestCase):
    def test_menu_label_and_python_names(self):
        render = FacetRender(Input=sphere())
        self.assertEqual(render.SMProxy.GetXMLLabel(), "Facet Render")
        menu = render.SMProxy.GetHints().FindNestedElementByName("ShowInMenu")
        self.assertEqual(menu.GetAttribute("category"), "Facet")
        names = set(render.ListProperties())
        for name in ["Size", "Background", "FitCameraToInput", "CameraPosition",
                     "CameraFocalPoint", "CameraViewUp", "CameraViewAngle",
                     "CameraParallelProjection", "CameraParallelScale", "AmbientLightColor",
                     "ColorByArray", "ColorArrayName", "LookupTable", "BackfaceCulling",
                     "NumberOfThreads", "VisibilityMode"]:
            self.assertIn(name, names)
        for light in range(1, 5):
            for setting in ["Switch", "Type", "Positional", "Position", "FocalPoint", "Color",
                            "Intensity", "ConeAngle", "Exponent", "AttenuationValues",
                            "SpotModel", "FullIntensityAngle", "FalloffAngle",
                            "AttenuationModel", "FalloffDistance"]:
                self.assertIn("Light%d%s" % (light, setting), names)

    def test_defaults_fit_a_sphere_with_a_headlight(self):
        render = FacetRender(Input=sphere(), Size=[W, H])
        image = Image(render)
        self.assertEqual((image.width, image.height), (W, H))
        self.assertEqual(image.scalars, "RGBA")
        self.assertEqual(image.arrays["RGBA"].GetNumberOfComponents(), 4)
        self.assertEqual(image.arrays["RGBA"].GetDataTypeAsString(), "unsigned char")
        self.assertEqual(image.arrays["Depth"].GetDataTypeAsString(), "float")
        self.assertEqual(image.arrays["CellId"].GetDataTypeAsString(), "idtype")
        for y, x in image.corners():
            self.assertEqual(tuple(image.rgba[y, x]), (0, 0, 0, 255))
            self.assertEqual(image.depth[y, x], 1.0)
            self.assertEqual(image.cell_id[y, x], -1)
        center = image.rgba[H // 2, W // 2]
        self.assertGreaterEqual(image.cell_id[H // 2, W // 2], 0)
        self.assertGreater(int(center[0]), 230, "the headlight faces the center: %s" % center)
        fraction = image.covered().mean()
        self.assertTrue(0.15 < fraction < 0.6, "the sphere covers %.3f of the view" % fraction)


class Camera(unittest.TestCase):
    def test_parallel_camera_as_given_covers_the_closed_form_area(self):
        # A unit-diameter sphere, a parallel scale of 0.5: the disk's radius is H / 2 pixels.
        render = FacetRender(Input=sphere(64), Size=[W, H], FitCameraToInput=0)
        render.CameraPosition = [0.0, 0.0, 5.0]
        render.CameraParallelProjection = 1
        render.CameraParallelScale = 0.5
        image = Image(render)
        disk = math.pi * (H / 2) ** 2
        # The polygonal sphere's silhouette is inscribed in the circle.
        self.assertTrue(0.98 * disk < image.covered().sum() <= disk,
                        "covered %d pixels, the disk has %.0f" % (image.covered().sum(), disk))

    def test_fit_camera_keeps_the_direction_and_off_uses_the_camera_as_is(self):
        render = FacetRender(Input=sphere(), Size=[W, H], FitCameraToInput=0)
        render.CameraPosition = [10.0, 0.0, 0.0]
        render.CameraFocalPoint = [20.0, 0.0, 0.0]  # looking away from the sphere
        self.assertEqual(Image(render).covered().sum(), 0)
        render.FitCameraToInput = 1
        image = Image(render)
        self.assertGreater(image.covered().mean(), 0.15)
        self.assertGreaterEqual(image.cell_id[H // 2, W // 2], 0)


class Lights(unittest.TestCase):
    def setUp(self):
        self.render = FacetRender(Input=sphere(), Size=[W, H], AmbientLightColor=[0, 0, 0])
        self.render.Light1Switch = 0

    def center(self):
        return Image(self.render).rgba[H // 2, W // 2]

    def test_no_light_leaves_the_ambient_light(self):
        self.render.AmbientLightColor = [50 / 255, 50 / 255, 50 / 255]
        self.assertEqual(tuple(self.center()), (50, 50, 50, 255))

    def test_colored_scene_light(self):
        self.render.Light2Switch = 1
        self.render.Light2Type = "Scene Light"
        self.render.Light2Position = [0.0, 0.0, 1.0]
        self.render.Light2FocalPoint = [0.0, 0.0, 0.0]
        self.render.Light2Color = [1.0, 0.0, 0.0]
        red, green, blue, alpha = self.center()
        self.assertGreater(red, 230)
        self.assertEqual((green, blue, alpha), (0, 0, 255))

    def positional_light_at(self, z):
        self.render.Light2Switch = 1
        self.render.Light2Type = "Scene Light"
        self.render.Light2Positional = "Positional"
        self.render.Light2ConeAngle = 180.0  # a point light
        self.render.Light2Position = [0.0, 0.0, z]
        self.render.Light2FocalPoint = [0.0, 0.0, 0.0]

    def test_quadratic_attenuation_falls_with_the_square_of_the_distance(self):
        # The polygon at the center faces the light 2.5 units away: 1 / 2.5^2 of full light.
        self.positional_light_at(3.0)
        full = int(self.center()[0])
        self.render.Light2AttenuationValues = [0.0, 0.0, 1.0]
        attenuated = int(self.center()[0])
        self.assertAlmostEqual(attenuated, full / 2.5**2, delta=2.0,
                               msg="full %d, attenuated %d" % (full, attenuated))

    def test_linear_falloff_spot_lights_a_disk(self):
        self.positional_light_at(3.0)
        self.render.Light2SpotModel = "Linear Falloff"
        self.render.Light2FullIntensityAngle = 3.0
        self.render.Light2FalloffAngle = 0.0
        image = Image(self.render)
        lit = image.rgba[..., 0] > 0
        # tan(3 degrees) * 2.5 = 0.13 units of the 0.5 radius: a small disk in the middle.
        self.assertTrue(lit[H // 2, W // 2])
        self.assertLess(lit.sum(), 0.2 * image.covered().sum())
        self.assertGreater(lit.sum(), 0)


class Coloring(unittest.TestCase):
    def test_point_array_through_a_preset_gives_its_exact_colors(self):
        elevation = Elevation(Input=sphere(), LowPoint=[0, -0.5, 0], HighPoint=[0, 0.5, 0])
        render = unlit(FacetRender(Input=elevation, Size=[W, H]))
        render.ColorByArray = 1
        render.ColorArrayName = ["POINTS", "Elevation"]
        render.LookupTable.ApplyPreset("Viridis (matplotlib)", True)
        image = Image(render)
        mesh = servermanager.Fetch(elevation)
        values = mesh.GetPointData().GetArray("Elevation")
        for y in (H // 4, H // 2, 3 * H // 4):
            cell = image.cell_id[y, W // 2]
            self.assertGreaterEqual(cell, 0)
            ids = mesh.GetCell(cell).GetPointIds()
            # Flat shading: the colors of the polygon's points, averaged.
            colors = mapped(render.LookupTable,
                            [values.GetValue(ids.GetId(i)) for i in range(ids.GetNumberOfIds())])
            expected = numpy.rint(numpy.mean(colors, axis=0))
            numpy.testing.assert_allclose(image.rgba[y, W // 2, :3], expected, atol=1)

    def test_cell_array(self):
        ids = GenerateIds(Input=sphere())
        render = unlit(FacetRender(Input=ids, Size=[W, H]))
        render.ColorByArray = 1
        render.ColorArrayName = ["CELLS", "CellIds"]
        cells = servermanager.Fetch(ids).GetNumberOfCells()
        render.LookupTable.RescaleTransferFunction(0.0, cells - 1.0)
        image = Image(render)
        for y in (H // 4, H // 2, 3 * H // 4):
            cell = image.cell_id[y, W // 2]
            numpy.testing.assert_array_equal(image.rgba[y, W // 2, :3],
                                             mapped(render.LookupTable, [cell])[0])

    def test_solid_color_when_not_colored_by_array(self):
        render = unlit(FacetRender(Input=sphere(), Size=[W, H]))
        render.AmbientColor = [0.2, 0.4, 0.6]
        self.assertEqual(tuple(Image(render).rgba[H // 2, W // 2]), (51, 102, 153, 255))


class Rendering(unittest.TestCase):
    def test_backface_culling_hides_a_plane_seen_from_behind(self):
        # Plane's polygons face +z; the fitted camera looks at them from -z.
        render = FacetRender(Input=Plane(), Size=[W, H], CameraPosition=[0.0, 0.0, -1.0])
        self.assertGreater(Image(render).covered().mean(), 0.3)
        render.BackfaceCulling = 1
        self.assertEqual(Image(render).covered().sum(), 0)

    def test_same_bytes_for_any_number_of_threads(self):
        render = FacetRender(Input=sphere(), Size=[W, H], NumberOfThreads=1)
        one = Image(render).rgba.copy()
        render.NumberOfThreads = 2
        numpy.testing.assert_array_equal(Image(render).rgba, one)


class Quality(unittest.TestCase):
    """Shading, Samples Per Pixel, Maximum Error and Compute Error, as the panel sets them."""

    def render(self, **settings):
        return FacetRender(Input=sphere(16), Size=[W, H], **settings)

    @staticmethod
    def colors(image):
        covered = image.rgba[image.covered()][:, :3]
        return len({tuple(c) for c in covered})

    def test_names_and_shading_entries(self):
        render = self.render()
        for name in ["Shading", "SamplesPerPixel", "MaximumError", "ComputeError",
                     "InterpolateScalarsBeforeMapping"]:
            self.assertIn(name, render.ListProperties())
        self.assertEqual(render.GetProperty("Shading").Available, ["Flat", "Gouraud", "Phong"])
        self.assertEqual(render.Shading, "Flat")
        self.assertEqual(render.SamplesPerPixel, "1")  # an enumeration: its entry text

    def test_shading_changes_the_image(self):
        render = self.render()
        flat = Image(render)
        flat_rgba, flat_colors = flat.rgba.copy(), self.colors(flat)
        render.Shading = "Gouraud"
        gouraud = Image(render)
        gouraud_rgba, gouraud_colors = gouraud.rgba.copy(), self.colors(gouraud)
        render.Shading = "Phong"
        phong = Image(render)
        # Flat shows one color per visible facet of the 16 x 8 sphere; smooth shading many.
        self.assertLess(flat_colors, 16 * 8)
        self.assertGreater(gouraud_colors, 3 * flat_colors)
        self.assertGreater(self.colors(phong), 3 * flat_colors)
        self.assertFalse(numpy.array_equal(gouraud_rgba, flat_rgba))
        self.assertFalse(numpy.array_equal(phong.rgba, gouraud_rgba))
        # Same silhouette: only the colors change.
        numpy.testing.assert_array_equal(phong.covered(), flat.covered())

    def test_samples_per_pixel_blend_the_silhouette(self):
        # One sample: a pixel the sphere does not own is the black background. Sixteen: the
        # pixels its edge crosses mix in some of it.
        for samples, blended in ((1, False), (16, True)):
            image = Image(self.render(SamplesPerPixel=samples))
            background = image.rgba[~image.covered()][:, :3]
            self.assertEqual(bool((background > 0).any()), blended, samples)

    def test_maximum_error_stays_within_its_budget_of_phong(self):
        phong = Image(self.render(Shading="Phong")).rgba.astype(int)
        flat = Image(self.render()).rgba.astype(int)
        adaptive = Image(self.render(MaximumError=2.0)).rgba.astype(int)
        self.assertGreater(numpy.abs(flat - phong).max(), 10)
        self.assertLessEqual(numpy.abs(adaptive - phong).max(), 2)
        # A budget above any polygon's bound keeps everything flat.
        numpy.testing.assert_array_equal(Image(self.render(MaximumError=255.0)).rgba, flat)

    def test_every_render_estimates_its_error(self):
        image = Image(self.render())
        estimate = image.data.GetFieldData().GetArray("FacetErrorEstimate")
        self.assertIsNotNone(estimate, "EstimateError is on by default")
        names = [estimate.GetComponentName(c) for c in range(estimate.GetNumberOfComponents())]
        rmse, largest = (estimate.GetComponent(0, names.index(n))
                         for n in ("PredictedRMSE", "PredictedMax"))
        self.assertGreater(rmse, 0.5)
        self.assertGreaterEqual(largest, rmse)
        self.assertNotIn("ErrorEstimate", image.arrays)
        per_pixel = Image(self.render(ErrorEstimateArray=1))
        self.assertIn("ErrorEstimate", per_pixel.arrays)
        off = Image(self.render(EstimateError=0))
        self.assertIsNone(off.data.GetFieldData().GetArray("FacetErrorEstimate"))
        numpy.testing.assert_array_equal(off.rgba, image.rgba)

    def test_compute_error_reports_phong_closer_to_the_reference_than_flat(self):
        rmse = {}
        for shading in ("Flat", "Phong"):
            image = Image(self.render(Shading=shading, ComputeError=1))
            error = image.data.GetFieldData().GetArray("FacetError")
            names = [error.GetComponentName(c) for c in range(error.GetNumberOfComponents())]
            self.assertIn("Error", image.arrays)
            rmse[shading] = error.GetComponent(0, names.index("RMSE"))
        self.assertLess(rmse["Phong"], rmse["Flat"] / 2, rmse)


class LeavingOutWork(unittest.TestCase):
    def test_outputs_not_asked_for_are_left_out(self):
        every = Image(FacetRender(Input=sphere(), Size=[W, H]))
        image = Image(FacetRender(Input=sphere(), Size=[W, H], OutputDepth=0, OutputCellIds=0))
        self.assertEqual(sorted(image.arrays), ["RGBA"])
        numpy.testing.assert_array_equal(image.rgba, every.rgba)

    def test_each_change_gives_a_fresh_filters_bytes(self):
        """ParaView executes the filter again for each change. Its executive modifies the
        input vtkPolyData before every execution (not its points or cells), which the filter
        must take for new geometry: here every execution renders in full (FacetRenderPath
        0); the bytes are a fresh filter's either way."""
        render = FacetRender(Input=sphere(), Size=[W, H], LightCullingTolerance=0.0)
        Image(render)
        for settings in ({"Light1Intensity": 0.5}, {"Background": [0.5, 0.25, 0.0]}):
            for name, value in settings.items():
                setattr(render, name, value)
            image = Image(render)
            fresh = Image(FacetRender(Input=sphere(), Size=[W, H], Light1Intensity=0.5,
                                      Background=render.Background))
            numpy.testing.assert_array_equal(image.rgba, fresh.rgba)
            numpy.testing.assert_array_equal(image.depth, fresh.depth)
            numpy.testing.assert_array_equal(image.cell_id, fresh.cell_id)
        render.IncrementalRendering = 0
        self.assertEqual(Image(render).path(), 0)


class ProgressAndAbort(unittest.TestCase):
    def big_render(self):
        # About two million triangles: a render long enough to report progress many times.
        return FacetRender(Input=sphere(1024), Size=[1024, 1024], NumberOfThreads=2)

    def test_progress_reaches_paraviews_progress_handler(self):
        handler = servermanager.ActiveConnection.Session.GetProgressHandler()
        handler.SetProgressInterval(0.01)  # the default forwards at most once a second
        reports = []

        def on_progress(caller, event):
            reports.append((caller.GetLastProgressText(), caller.GetLastProgress()))

        observer = handler.AddObserver("ProgressEvent", on_progress)
        try:
            self.big_render().UpdatePipeline()
        finally:
            handler.RemoveObserver(observer)
        ours = [percent for text, percent in reports if "Facet" in (text or "")]
        self.assertGreaterEqual(len([p for p in ours if 0 < p < 100]), 2,
                                "progress reports: %s" % reports)
        self.assertEqual(ours, sorted(ours), "progress never goes back")

    def test_abort_stops_the_render(self):
        render = self.big_render()
        algorithm = render.GetClientSideObject()

        def abort_once_started(caller, event):
            if caller.GetProgress() > 0.1:
                caller.SetAbortExecute(1)

        observer = algorithm.AddObserver("ProgressEvent", abort_once_started)
        aborted = Image(render)
        algorithm.RemoveObserver(observer)
        self.assertEqual(aborted.count("PixelsCovered"), 0, "the aborted render is background")
        algorithm.SetAbortExecute(0)  # VTK 9.2 leaves resetting the flag to its setter
        render.Size = [1024, 1023]  # anything, to render again
        self.assertGreater(Image(render).count("PixelsCovered"), 0)


if __name__ == "__main__":
    unittest.main(argv=[sys.argv[0], "-v"])
