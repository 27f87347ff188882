"""examples/paraview/render_parallel.py run as a user runs it: on 2 MPI ranks
(`mpirun -np 2 pvbatch --mpi`) and in one process (`pvbatch`); the two images must be the
same, pixel for pixel.

Run by Debian's python3 (VTK 9.1 reads what ParaView wrote); the pvbatch runs get ParaView's
Python modules through $FACET_PARAVIEW_PYTHONPATH. Each run has a time limit: a rank that
waits forever fails the test instead of hanging it.
"""
import os
import subprocess
import sys
import tempfile
import unittest

import numpy
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader
from vtkmodules.vtkIOXML import vtkXMLPImageDataReader

EXAMPLE = os.path.join(os.environ["FACET_EXAMPLES_DIR"], "paraview", "render_parallel.py")
MESH = os.path.join(os.environ["FACET_SHARED_DATA_DIR"], "meshes", "spot.obj")
W, H = 320, 240
SECONDS = 150  # per run; a run takes about 5 s (one process) and 12 s (two ranks)


def run(command, folder):
    environment = dict(os.environ, PYTHONPATH=os.environ["FACET_PARAVIEW_PYTHONPATH"])
    try:
        done = subprocess.run(command, cwd=folder, env=environment, timeout=SECONDS,
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    except subprocess.TimeoutExpired as expired:
        raise AssertionError("%s did not finish in %d s (a rank waits for another?):\n%s"
                             % (" ".join(command), SECONDS, expired.output)) from None
    if done.returncode != 0:
        raise AssertionError("%s failed (%d):\n%s" % (" ".join(command), done.returncode,
                                                      done.stdout))
    return done.stdout


def planes(pvti):
    reader = vtkXMLPImageDataReader()
    reader.SetFileName(pvti)
    reader.Update()
    image = reader.GetOutput()
    assert image.GetDimensions() == (W, H, 1), image.GetDimensions()
    point_data = image.GetPointData()
    return {point_data.GetArrayName(i): vtk_to_numpy(point_data.GetArray(i)).copy()
            for i in range(point_data.GetNumberOfArrays())}, image.GetFieldData()


def png_pixels(path):
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    return vtk_to_numpy(reader.GetOutput().GetPointData().GetScalars()).copy()


class RenderParallelExample(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.folder = tempfile.TemporaryDirectory()
        example = [EXAMPLE, MESH, "--plugin", os.environ["FACET_PLUGIN"],
                   "--size", str(W), str(H)]
        cls.output = {}
        for ranks in (2, 1):
            name = "ranks%d" % ranks
            files = [name + ".png", "--data", name + ".pvti"]
            if ranks == 1:
                command = [os.environ["FACET_PVBATCH"]] + example + files
            else:
                command = [os.environ["FACET_MPIRUN"], "--allow-run-as-root", "--oversubscribe",
                           "-np", str(ranks), os.environ["FACET_PVBATCH"], "--mpi"] + \
                    example + files
            cls.output[ranks] = run(command, cls.folder.name)
        cls.serial, cls.serial_fields = planes(os.path.join(cls.folder.name, "ranks1.pvti"))
        cls.parallel, cls.parallel_fields = planes(os.path.join(cls.folder.name, "ranks2.pvti"))

    @classmethod
    def tearDownClass(cls):
        cls.folder.cleanup()

    def test_runs_say_how_many_ranks(self):
        self.assertIn("from 2 ranks", self.output[2])
        self.assertIn("from 1 rank", self.output[1])

    def assert_same(self, name):
        got, expected = self.parallel[name], self.serial[name]
        differ = numpy.nonzero(numpy.any((got != expected).reshape(W * H, -1), axis=1))[0]
        self.assertEqual(len(differ), 0, "%s differs at %d pixels, first (x %d, y %d): %s "
                         "instead of %s" % (name, len(differ), differ[0] % W, differ[0] // W,
                                            got[differ[0]], expected[differ[0]])
                         if len(differ) else "")

    def test_same_image_as_one_process(self):
        for name in ("RGBA", "Depth", "CellId"):  # CellId: global ids, the serial cell ids
            self.assert_same(name)
        covered = numpy.count_nonzero(self.serial["CellId"] >= 0)
        self.assertTrue(0.08 * W * H < covered < 0.8 * W * H, "the mesh covers %d pixels"
                        % covered)

    def test_png_is_the_rgba_array(self):
        for ranks in (1, 2):
            pixels = png_pixels(os.path.join(self.folder.name, "ranks%d.png" % ranks))
            numpy.testing.assert_array_equal(pixels, self.serial["RGBA"])

    def test_both_ranks_show_and_composite(self):
        self.assertNotIn("RankId", self.serial)
        rank_id = self.parallel["RankId"]
        numpy.testing.assert_array_equal(rank_id < 0, self.serial["CellId"] < 0)
        shown = set(numpy.unique(rank_id)) - {-1}
        self.assertEqual(shown, {0, 1})
        strategy = self.parallel_fields.GetAbstractArray("FacetCompositeStrategy")
        self.assertIsNotNone(strategy, "no FacetCompositeStrategy in the field data")
        self.assertIn("2 ranks onto rank 0", strategy.GetValue(0))
        self.assertIsNone(self.serial_fields.GetAbstractArray("FacetCompositeStrategy"))


if __name__ == "__main__":
    unittest.main(argv=[sys.argv[0], "-v"])
