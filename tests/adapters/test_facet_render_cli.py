"""facet-render: help, a render to PNG, and one-line errors with the right exit codes."""
import os
import subprocess
import sys
import tempfile
import unittest

TOOL = os.environ["FACET_RENDER"]
MESHES = os.environ["FACET_SHARED_DATA_DIR"] + "/meshes"


def run(*args):
    return subprocess.run([TOOL, *args], capture_output=True, text=True, timeout=120)


class FacetRenderCli(unittest.TestCase):
    def test_help(self):
        result = run("--help")
        self.assertEqual(result.returncode, 0)
        self.assertIn("usage: facet-render MESH", result.stdout)
        for option in ("--size", "--azimuth", "--light", "--color-by", "--threads"):
            self.assertIn(option, result.stdout)

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
                               (("--interpolation", "gouraud"), "not supported yet"),
                               (("--color-by", "nothing"), "no point or cell array 'nothing'")):
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


if __name__ == "__main__":
    sys.exit(unittest.main())
