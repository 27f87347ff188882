"""Helpers shared by the plugin's tests, which run inside pvbatch (ParaView's Python)."""
import os

import numpy
from paraview import servermanager
from paraview.simple import LoadPlugin
from vtkmodules.util.numpy_support import vtk_to_numpy

PLUGIN = os.environ["FACET_PLUGIN"]
MESHES = os.path.join(os.environ["FACET_SHARED_DATA_DIR"], "meshes")
EXAMPLES = os.environ["FACET_EXAMPLES_DIR"]


def load_plugin(namespace):
    """Loads FacetRender.so into this process and its filter into `namespace`."""
    LoadPlugin(PLUGIN, remote=False, ns=namespace)


class Image:
    """A Facet Render output fetched from the pipeline, as numpy planes indexed [y, x]
    (row 0 at the bottom, as VTK stores images)."""

    def __init__(self, proxy):
        proxy.UpdatePipeline()
        self.data = servermanager.Fetch(proxy)
        width, height, depth = self.data.GetDimensions()
        assert depth == 1, "an image is one slice, got %d" % depth
        self.width, self.height = width, height
        point_data = self.data.GetPointData()
        self.arrays = {point_data.GetArrayName(i): point_data.GetArray(i)
                       for i in range(point_data.GetNumberOfArrays())}
        self.scalars = point_data.GetScalars().GetName() if point_data.GetScalars() else None
        shape = (height, width)
        self.rgba = vtk_to_numpy(self.arrays["RGBA"]).reshape(shape + (4,))
        # None when left out (OutputDepth, OutputCellIds off).
        self.depth, self.cell_id = (vtk_to_numpy(self.arrays[name]).reshape(shape)
                                    if name in self.arrays else None
                                    for name in ("Depth", "CellId"))

    def path(self):
        """The path the render took: 0 full, 1 re-shade, 2 resolve (FacetRenderPath)."""
        return int(self.data.GetFieldData().GetArray("FacetRenderPath").GetValue(0))

    def count(self, name):
        """A named component of the FacetCounts field-data array."""
        counts = self.data.GetFieldData().GetArray("FacetCounts")
        names = [counts.GetComponentName(c) for c in range(counts.GetNumberOfComponents())]
        return counts.GetComponent(0, names.index(name))

    def covered(self):
        return self.cell_id >= 0

    def corners(self):
        h, w = self.height - 1, self.width - 1
        return [(0, 0), (0, w), (h, 0), (h, w)]


def luminance(rgba):
    """Rec. 709 luma of RGB(A) pixels in [0, 255]."""
    rgb = numpy.asarray(rgba, dtype=float)[..., :3]
    return rgb @ numpy.array([0.2126, 0.7152, 0.0722])
