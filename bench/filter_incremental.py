#!/usr/bin/env python3
"""vtkFacetRenderFilter.Update() after one change, against a full Update, in one run.

The 2M-triangle sphere (colored by elevation through a lookup table, one positional light)
at 1920x1080, 2 threads. Each round changes one thing at a time, in turn: the camera (a
full render), only the light's color (re-shade), only the lookup table (new colors:
re-shade), only the scalars' values (new colors of the same geometry: re-shade, no new
conversion) and only the background (resolve). Every Update is timed around Update() (so it
includes the outputs RGBA, Depth and CellId and the field data) and its path is checked in
the field data (FacetRenderPath). The table gives the median of each kind and its ratio
against the full Update, with EstimateError on (flat shading's error estimated at every
render: vtkFacetQuality) and off (the default). Each rig renders its own copy of the data.

    PYTHONPATH=build/lib/python3.11/dist-packages /usr/bin/python3 bench/filter_incremental.py
"""
import argparse
import os
import statistics
import time

from vtkmodules.vtkCommonCore import vtkLookupTable
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkFiltersCore import vtkElevationFilter
from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.vtkRenderingCore import vtkCamera, vtkLight
from vtkmodules.util.numpy_support import vtk_to_numpy

from facet import vtkFacetRenderFilter

WIDTH, HEIGHT = 1920, 1080
THETA = 1000  # 2,000,000 triangles (compare_vtk.SIZES)
PATHS = {0: "full", 1: "re-shade", 2: "resolve"}


def sphere():
    source = vtkSphereSource()
    source.SetThetaResolution(THETA)
    source.SetPhiResolution(THETA + 2)
    elevation = vtkElevationFilter()
    elevation.SetInputConnection(source.GetOutputPort())
    elevation.SetLowPoint(0, -0.5, 0)
    elevation.SetHighPoint(0, 0.5, 0)
    elevation.Update()
    return elevation.GetOutput()


class Rig:
    """A filter and the objects a user changes."""

    def __init__(self, data, threads, estimate_error):
        self.data = vtkPolyData()  # its own: the scalars change per rig
        self.data.DeepCopy(data)
        self.filter = vtkFacetRenderFilter()
        self.filter.SetInputData(self.data)
        self.filter.SetSize(WIDTH, HEIGHT)
        self.filter.SetNumberOfThreads(threads)
        self.filter.SetEstimateError(estimate_error)
        self.camera = vtkCamera()
        self.camera.SetPosition(0, 0.3, 3)
        self.filter.SetCamera(self.camera)
        self.filter.FitCameraToInputOn()
        self.light = vtkLight()
        self.light.SetPositional(True)
        self.light.SetConeAngle(180)
        self.light.SetPosition(1, 2, 3)
        self.filter.AddLight(self.light)
        self.table = vtkLookupTable()
        self.filter.SetLookupTable(self.table)
        self.filter.SetScalarRange(0, 1)
        self.steps = {}
        self.filter.Update()  # converts the mesh, checks closedness, computes normals once

    def change(self, kind):
        self.steps[kind] = self.steps.get(kind, 0) + 1
        wiggle = 0.1 * (self.steps[kind] % 2)  # each kind alternates between two values
        if kind == "full":
            self.camera.Azimuth(0.5)
        elif kind == "re-light":
            self.light.SetDiffuseColor(1.0, 0.8 + wiggle, 0.7)
        elif kind == "recolor":
            self.table.SetHueRange(0.0 + wiggle, 0.667)
        elif kind == "scalars":
            scalars = self.data.GetPointData().GetScalars()
            values = vtk_to_numpy(scalars)
            values[:] = 1.0 - values
            scalars.Modified()
        elif kind == "background":
            self.filter.SetBackground(0.1 + wiggle, 0.1, 0.2)

    def update(self):
        start = time.perf_counter()
        self.filter.Update()
        seconds = time.perf_counter() - start
        path = self.filter.GetOutput().GetFieldData().GetArray("FacetRenderPath").GetValue(0)
        return seconds, PATHS[int(path)]


KINDS = {"full": "full", "re-light": "re-shade", "recolor": "re-shade", "scalars": "re-shade",
         "background": "resolve"}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=10)
    parser.add_argument("--threads", type=int, default=2)
    args = parser.parse_args()
    data = sphere()
    rigs = {"EstimateError on": Rig(data, args.threads, True),
            "EstimateError off": Rig(data, args.threads, False)}
    times = {(setup, kind): [] for setup in rigs for kind in KINDS}
    for _ in range(args.rounds):
        for kind, expected in KINDS.items():
            for setup, rig in rigs.items():
                rig.change(kind)
                seconds, path = rig.update()
                assert path == expected, f"{setup}, {kind}: the {path} path ran, not {expected}"
                times[setup, kind].append(seconds)

    load = os.getloadavg()[0]
    print(f"vtkFacetRenderFilter.Update() after one change, {data.GetNumberOfCells():,} "
          f"triangles at {WIDTH}x{HEIGHT}, {args.threads} threads, median of {args.rounds}; "
          f"load average {load:.1f}")
    header = "| change | path |" + "".join(f" {setup} | ratio |" for setup in rigs)
    print(header)
    print("|---|---|" + "---:|---:|" * len(rigs))
    for kind, path in KINDS.items():
        row = f"| {kind} | {path} |"
        for setup in rigs:
            median = statistics.median(times[setup, kind])
            full = statistics.median(times[setup, "full"])
            row += f" {median * 1e3:.1f} ms | {full / median:.1f}x |"
        print(row)


if __name__ == "__main__":
    main()
