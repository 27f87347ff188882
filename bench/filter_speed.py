#!/usr/bin/env python3
"""vtkFacetRenderFilter.Update() per 1920x1080 frame from Python vs VTK's OpenGL pipeline.

Each frame turns the camera (the interactive case: the converted mesh is reused) and runs
Update(), which includes the render and the output arrays (RGBA, Depth, CellId). VTK renders
the same spheres offscreen (llvmpipe under Xvfb) with one positional light and reads every
frame back, as bench/compare_vtk.py does, in the same run.

    PYTHONPATH=build/lib/python3.11/dist-packages xvfb-run -a -s "-screen 0 1920x1080x24" \\
        /usr/bin/python3 bench/filter_speed.py
"""
import argparse
import os
import statistics
import sys
import time

from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.vtkRenderingCore import vtkCamera, vtkLight, vtkRenderer

from facet import vtkFacetRenderFilter

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from compare_vtk import SIZES, vtk_seconds_per_frame  # noqa: E402

WIDTH, HEIGHT = 1920, 1080


def facet_seconds_per_frame(theta, frames, threads, detect_closed):
    sphere = vtkSphereSource()
    sphere.SetThetaResolution(theta)
    sphere.SetPhiResolution(theta + 2)
    sphere.Update()
    fit = vtkRenderer()
    fit.SetAspect(WIDTH / HEIGHT, 1.0)
    camera = fit.GetActiveCamera()
    fit.ResetCamera(sphere.GetOutput().GetBounds())
    light = vtkLight()
    light.SetPositional(True)
    light.SetConeAngle(180)
    light.SetPosition(camera.GetPosition())
    light.SetFocalPoint(camera.GetFocalPoint())

    render = vtkFacetRenderFilter()
    render.SetInputConnection(sphere.GetOutputPort())
    render.SetSize(WIDTH, HEIGHT)
    render.SetCamera(camera)
    render.AddLight(light)
    render.SetAmbientLightColor(0, 0, 0)
    render.SetNumberOfThreads(threads)
    render.SetDetectClosedSurfaces(detect_closed)
    render.Update()  # first frame: converts the mesh (and checks closedness once)
    first = render.GetOutput().GetFieldData().GetArray("FacetRenderSeconds").GetValue(0)
    times = []
    for _ in range(frames):
        camera.Azimuth(0.5)
        start = time.perf_counter()
        render.Update()
        times.append(time.perf_counter() - start)
    converted = render.GetOutput().GetFieldData().GetArray("FacetMeshConverted").GetValue(0)
    assert converted == 0, "a camera change must not convert the mesh again"
    return statistics.median(times), first


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--frames", type=int, default=10)
    parser.add_argument("--threads", type=int, default=2)
    args = parser.parse_args()

    rows = []
    for triangles, theta in SIZES.items():
        if triangles < 500000:
            continue
        vtk_count, vtk_seconds, gl = vtk_seconds_per_frame(theta, 5)
        every_face, first = facet_seconds_per_frame(theta, args.frames, args.threads, False)
        closed, first_closed = facet_seconds_per_frame(theta, args.frames, args.threads, True)
        vtk_seconds = min(vtk_seconds, vtk_seconds_per_frame(theta, 5)[1])
        rows.append((vtk_count, vtk_seconds, every_face, closed, first, first_closed))

    print("vtkFacetRenderFilter.Update() from Python, 1920x1080, camera turning every frame")
    print(f"{'triangles':>10} {'VTK s':>8} | {'Update s':>9} {'ratio':>7} | {'closed s':>9} "
          f"{'ratio':>7} | {'first Update s (closed check)':>30}")
    for count, vtk_seconds, every_face, closed, first, first_closed in rows:
        print(f"{count:>10} {vtk_seconds:>8.3f} | {every_face:>9.4f} "
              f"{vtk_seconds / every_face:>6.1f}x | {closed:>9.4f} {vtk_seconds / closed:>6.1f}x | "
              f"{first:>13.3f} ({first_closed:.3f})")
    print(f"VTK {gl.split(':')[-1].strip()}; Facet: {args.threads} threads, median of "
          f"{args.frames} frames; 'closed': DetectClosedSurfaces on (the default)")


if __name__ == "__main__":
    main()
