"""facet-render and facet-vtk-pipeline: help, renders to PNG (coloring by data, spot lights),
and one-line errors with the right exit codes."""
import os
import subprocess
import sys
import tempfile
import unittest

from vtkmodules.vtkFiltersCore import vtkElevationFilter
from vtkmodules.vtkFiltersSources import vtkPlaneSource, vtkSphereSource
from vtkmodules.vtkIOImage import vtkPNGReader
from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter

from facet import vtkFacetLight, vtkFacetRenderFilter

TOOL = os.environ["FACET_RENDER"]
PIPELINE = os.environ["FACET_VTK_PIPELINE"]
MESHES = os.environ["FACET_SHARED_DATA_DIR"] + "/meshes"


def run(*args, tool=TOOL):
    return subprocess.run([tool, *args], capture_output=True, text=True, timeout=120)


def write_vtp(source, path):
    writer = vtkXMLPolyDataWriter()
    writer.SetInputConnection(source.GetOutputPort())
    writer.SetFileName(path)
    writer.Write()
    return path


def read_png(path):
    """Pixels as {(x, y): (r, g, b)}, row 0 at the bottom (as vtkImageData)."""
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    width, height, _ = image.GetDimensions()
    scalars = image.GetPointData().GetScalars()
    return {(x, y): tuple(int(scalars.GetComponent(y * width + x, c)) for c in range(3))
            for y in range(height) for x in range(width)}


def formatted(values):
    return ",".join("%.3g" % v for v in values)


class FacetRenderCli(unittest.TestCase):
    def test_help(self):
        result = run("--help")
        self.assertEqual(result.returncode, 0)
        self.assertIn("usage: facet-render MESH", result.stdout)
        for option in ("--size", "--azimuth", "--light", "--color-by", "--threads"):
            self.assertIn(option, result.stdout)

    def test_help_states_the_real_defaults(self):
        """Issue 7: the help said 0.2 for the ambient default; it is the filter's 50/255."""
        text = run("--help").stdout
        render, light = vtkFacetRenderFilter(), vtkFacetLight()
        lines = {line.split()[0]: line for line in text.splitlines() if line.strip()}
        self.assertIn("(default: %s)" % formatted(render.GetAmbientLightColor()),
                      lines["--ambient"])
        self.assertIn("(default: %d)" % render.GetNumberOfThreads(), lines["-t,"])
        self.assertIn("(default: %s)" % formatted((light.GetConeAngle(), light.GetExponent())),
                      text)
        self.assertIn("(default: %s)" % formatted((light.GetFullIntensityAngle(),
                                                   light.GetFalloffAngle())), text)

    def test_color_by_varies_across_the_image_and_is_deterministic(self):
        """Issue 7, defect 1: --color-by read an unbuilt lookup table and never worked."""
        sphere = vtkSphereSource()
        sphere.SetThetaResolution(32)
        sphere.SetPhiResolution(24)
        elevation = vtkElevationFilter()
        elevation.SetInputConnection(sphere.GetOutputPort())
        elevation.SetLowPoint(0, -0.5, 0)
        elevation.SetHighPoint(0, 0.5, 0)
        with tempfile.TemporaryDirectory() as folder:
            mesh = write_vtp(elevation, os.path.join(folder, "elevation.vtp"))
            images = []
            for name in ("one.png", "two.png"):
                out = os.path.join(folder, name)
                result = run(mesh, "-o", out, "--size", "120x90", "--background", "0,0,0",
                             "--color-by", "Elevation", "-q")
                self.assertEqual(result.returncode, 0, result.stderr)
                with open(out, "rb") as png:
                    images.append(png.read())
            self.assertEqual(images[0], images[1], "two runs, two images")
            pixels = read_png(os.path.join(folder, "one.png"))
        surface = [rgb for rgb in pixels.values() if rgb != (0, 0, 0)]
        self.assertGreater(len(surface), 1000)
        self.assertGreater(len(set(surface)), 20, "colors vary across the sphere")
        self.assertGreater(max(r for r, g, b in surface), 200, "red at one end")
        self.assertGreater(max(b for r, g, b in surface), 200, "blue at the other")

    def test_spot_lights(self):
        """A plane lit from 2 above its center: VTK's cone (10 degrees, exponent 1) and
        vtkFacetLight's linear falloff (full within 5 degrees, none beyond 10)."""
        plane = vtkPlaneSource()  # [-0.5, 0.5]^2, facing +z
        plane.SetResolution(60, 60)
        with tempfile.TemporaryDirectory() as folder:
            mesh = write_vtp(plane, os.path.join(folder, "plane.vtp"))
            images = {}
            for spec in ("spot:0,0,2:0,0,0:10", "linear-spot:0,0,2:0,0,0:5,5"):
                out = os.path.join(folder, spec.split(":")[0] + ".png")
                result = run(mesh, "-o", out, "--size", "200x150", "--ambient", "0,0,0",
                             "--color", "1,1,1", "--light", spec, "-q")
                self.assertEqual(result.returncode, 0, result.stderr)
                images[spec.split(":")[0]] = read_png(out)
        # The fitted camera shows the plane's bounding circle (radius 0.707) in the image's
        # height: world (x, 0) is near pixel (100 + 102.4 x, 75).
        def at(image, x):
            return images[image][(int(100 + 102.4 * x), 75)][0]
        # Spot: cos(angle)^1 from the cone times Lambert's cos(angle), up to 10 degrees.
        self.assertGreaterEqual(at("spot", 0.0), 254)
        self.assertGreaterEqual(at("spot", 0.25), 240)       # 7 degrees: 0.985
        self.assertEqual(at("spot", 0.45), 0)                # 12.7 degrees: outside
        # Linear: full within 5 degrees, (10 - angle) / 5 up to 10.
        self.assertGreaterEqual(at("linear-spot", 0.1), 250)  # 2.9 degrees
        self.assertTrue(120 <= at("linear-spot", 0.25) <= 190, at("linear-spot", 0.25))
        self.assertEqual(at("linear-spot", 0.45), 0)

    def test_renders_every_format_to_png(self):
        with tempfile.TemporaryDirectory() as folder:
            for mesh in ("suzanne.obj", "igea-strips.vtp"):
                out = os.path.join(folder, mesh + ".png")
                result = run(os.path.join(MESHES, mesh), "-o", out, "--size", "200x150",
                             "--azimuth", "30", "--elevation", "15", "--zoom", "1.2",
                             "--light", "point:1,2,3@1,0.9,0.8", "--threads", "2")
                self.assertEqual(result.returncode, 0, result.stderr)
                self.assertIn("wrote " + out, result.stdout)
                with open(out, "rb") as png:
                    self.assertEqual(png.read(8), b"\x89PNG\r\n\x1a\n")
            # STL, PLY and legacy VTK written with VTK from an OBJ.
            from vtkmodules.vtkIOGeometry import vtkOBJReader, vtkSTLWriter
            from vtkmodules.vtkIOLegacy import vtkPolyDataWriter
            from vtkmodules.vtkIOPLY import vtkPLYWriter
            reader = vtkOBJReader()
            reader.SetFileName(os.path.join(MESHES, "spot.obj"))
            for writer_class, extension in ((vtkSTLWriter, ".stl"), (vtkPLYWriter, ".ply"),
                                            (vtkPolyDataWriter, ".vtk")):
                path = os.path.join(folder, "spot" + extension)
                writer = writer_class()
                writer.SetInputConnection(reader.GetOutputPort())
                writer.SetFileName(path)
                writer.Write()
                result = run(path, "-o", path + ".png", "--size", "64x48", "-q")
                self.assertEqual(result.returncode, 0, result.stderr)
                self.assertTrue(os.path.getsize(path + ".png") > 100)

    def test_shading_modes_samples_and_budget(self):
        mesh = os.path.join(MESHES, "suzanne.obj")
        with tempfile.TemporaryDirectory() as folder:
            images = {}
            for name, args in (("flat", ()), ("phong", ("--shading", "phong", "--samples", "4")),
                               ("adaptive", ("--max-error", "3"))):
                out = os.path.join(folder, name + ".png")
                result = run(mesh, "-o", out, "--size", "96x72", *args)
                self.assertEqual(result.returncode, 0, result.stderr)
                self.assertIn("flat shading's error here is at most", result.stdout)
                images[name] = read_png(out)
            differing = sum(images["flat"][p] != images["phong"][p] for p in images["flat"])
            self.assertGreater(differing, 500)

    def test_explain_prints_the_plan_after_the_render(self):
        mesh = os.path.join(MESHES, "suzanne.obj")
        with tempfile.TemporaryDirectory() as folder:
            out = os.path.join(folder, "explained.png")
            # A black light reaches nothing: the plan says it left it out.
            result = run(mesh, "-o", out, "--size", "96x72", "--explain", "-q",
                         "--light", "headlight", "--light", "directional:0,0,-1@0,0,0")
            self.assertEqual(result.returncode, 0, result.stderr)
            self.assertTrue(os.path.getsize(out) > 100)
            text = result.stdout
            self.assertIn("Facet render plan: 96x72 pixels", text)
            self.assertIn("path: full render (no previous frame to reuse)", text)
            self.assertIn("fired lights that reach nothing: 1 lights of 2 (1 dark", text)
            self.assertIn("seconds: validate", text)
            self.assertEqual(run(mesh, "-o", out, "--size", "96x72", "-q").stdout, "")

    def test_report_table_csv_and_plot(self):
        with tempfile.TemporaryDirectory() as folder:
            prefix = os.path.join(folder, "report")
            result = run("--report", "--sweep", "8,24", "--no-builtin",
                         os.path.join(MESHES, "suzanne.obj"), "--size", "96x72",
                         "--repeats", "1", "--reference-samples", "8", "-o", prefix, "-q")
            self.assertEqual(result.returncode, 0, result.stderr)
            self.assertIn("| mesh | mode | samples | time ms | RMSE |", result.stdout)
            with open(prefix + ".csv") as csv:
                rows = [line.split(",") for line in csv.read().splitlines()[1:]]
            self.assertEqual(len(rows), 3 * 12)  # 3 meshes x (4 modes x 3 sample counts)
            flat = {row[1]: float(row[5]) for row in rows if row[2] == "flat" and row[3] == "1"}
            self.assertLess(flat["sphere 24"], flat["sphere 8"])  # finer: closer to the sphere
            with open(prefix + ".png", "rb") as png:
                self.assertEqual(png.read(8), b"\x89PNG\r\n\x1a\n")

    def test_missing_file_is_one_line_and_exit_1(self):
        result = run("no-such-mesh.obj")
        self.assertEqual(result.returncode, 1)
        self.assertEqual(result.stderr.strip(),
                         "facet-render: cannot read 'no-such-mesh.obj': no such file")

    def test_bad_options_are_one_line_and_exit_2(self):
        mesh = os.path.join(MESHES, "suzanne.obj")
        for args, expected in ((("--size", "12"), "--size expects"),
                               (("--bogus",), "unknown option '--bogus'"),
                               (("--light", "laser:1"), "--light expects"),
                               (("--color", "2,0,0"), "must be in [0, 1]"),
                               (("--shading", "toon"), "flat, gouraud or phong"),
                               (("--samples", "2"), "--samples expects 1, 4 or 16"),
                               (("--max-error", "-1"), "--max-error expects"),
                               (("--color-by", "nothing"), "no point or cell array 'nothing'"),
                               # Issue 7: NaN and infinities were render errors (exit 1).
                               (("--azimuth", "nan"), "finite numbers"),
                               (("--zoom", "inf"), "finite numbers"),
                               (("--range", "0,-inf"), "finite numbers"),
                               (("--light", "point:1,nan,2"), "finite numbers"),
                               (("--background", "nan,0,0"), "finite numbers"),
                               (("--light", "spot:0,0,1"), "--light expects"),
                               (("--light", "spot:0,0,1:0,0,1"), "points nowhere"),
                               (("--light", "spot:0,0,2:0,0,0:95"), "ANGLE in [0, 90]"),
                               (("--light", "linear-spot:0,0,2:0,0,0:5"), "FULL,FALLOFF")):
            result = run(mesh, *args)
            self.assertEqual(result.returncode, 2, args)
            lines = result.stderr.strip().splitlines()
            self.assertEqual(len(lines), 1, result.stderr)
            self.assertIn(expected, lines[0])

    def test_unreadable_file_is_one_line(self):
        with tempfile.NamedTemporaryFile(suffix=".vtp") as bad:
            bad.write(b"not xml")
            bad.flush()
            result = run(bad.name)
        self.assertEqual(result.returncode, 1)
        self.assertEqual(len(result.stderr.strip().splitlines()), 1, result.stderr)
        self.assertIn("cannot read", result.stderr)


class VtkPipelineExample(unittest.TestCase):
    def test_without_arguments_prints_usage_and_exits_2(self):
        result = run(tool=PIPELINE)
        self.assertEqual(result.returncode, 2)
        self.assertIn("usage: facet-vtk-pipeline MESH.obj OUT.png", result.stderr)

    def test_renders_an_obj_to_png(self):
        with tempfile.TemporaryDirectory() as folder:
            out = os.path.join(folder, "spot.png")
            result = run(os.path.join(MESHES, "spot.obj"), out, tool=PIPELINE)
            self.assertEqual(result.returncode, 0, result.stderr)
            pixels = read_png(out)
        self.assertEqual(len(pixels), 800 * 600)
        self.assertGreater(sum(rgb != (0, 0, 0) for rgb in pixels.values()), 800 * 600 // 10)


if __name__ == "__main__":
    sys.exit(unittest.main())
