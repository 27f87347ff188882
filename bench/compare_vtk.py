#!/usr/bin/env python3
"""Facet vs VTK 9.1's own OpenGL pipeline, per 1920x1080 frame, measured in one run.

VTK renders the same vtkSphereSource spheres offscreen (Mesa llvmpipe under Xvfb), with flat
interpolation and one positional light, and reads every frame back with
vtkWindowToImageFilter. Facet's numbers come from build/bench/facet_bench (2 threads, full
frame including the clear) run by this script in the same session. Prints a table and the
ratios.

    xvfb-run -a -s "-screen 0 1920x1080x24" /usr/bin/python3 bench/compare_vtk.py \
        --facet-bench build/bench/facet_bench
"""
import argparse
import json
import statistics
import subprocess
import sys
import time

import vtk

SIZES = {20000: 100, 500000: 500, 2000000: 1000}  # triangles: theta = phi - 2 resolution
WIDTH, HEIGHT = 1920, 1080


def vtk_seconds_per_frame(theta, frames):
    sphere = vtk.vtkSphereSource()
    sphere.SetThetaResolution(theta)
    sphere.SetPhiResolution(theta + 2)
    sphere.Update()
    triangles = sphere.GetOutput().GetNumberOfPolys()

    mapper = vtk.vtkPolyDataMapper()
    mapper.SetInputConnection(sphere.GetOutputPort())
    mapper.ScalarVisibilityOff()
    actor = vtk.vtkActor()
    actor.SetMapper(mapper)
    actor.GetProperty().SetInterpolationToFlat()

    renderer = vtk.vtkRenderer()
    renderer.AddActor(actor)
    renderer.SetBackground(0, 0, 0)
    window = vtk.vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(WIDTH, HEIGHT)
    window.AddRenderer(renderer)
    renderer.ResetCamera()
    light = vtk.vtkLight()
    light.SetPositional(True)
    light.SetConeAngle(180)
    light.SetPosition(renderer.GetActiveCamera().GetPosition())
    light.SetFocalPoint(renderer.GetActiveCamera().GetFocalPoint())
    renderer.AddLight(light)

    grab = vtk.vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.ReadFrontBufferOff()
    grab.ShouldRerenderOff()

    def frame():
        window.Render()
        grab.Modified()
        grab.Update()

    frame()  # first frame uploads the mesh and compiles shaders
    times = []
    for _ in range(frames):
        actor.Modified()
        start = time.perf_counter()
        frame()
        times.append(time.perf_counter() - start)
    renderer_info = window.ReportCapabilities().splitlines()
    gl_renderer = next((l for l in renderer_info if "OpenGL renderer" in l), "OpenGL renderer: ?")
    return triangles, statistics.median(times), gl_renderer.strip()


def facet_seconds_per_frame(bench, threads):
    """{(triangles, closed): (seconds per frame, peak heap / (mesh + framebuffer))}"""
    result = subprocess.run(
        [bench, f"--benchmark_filter=BM_Sphere/.*/threads:{threads}/",
         "--benchmark_format=json", "--benchmark_min_time=1"],
        check=True, capture_output=True, text=True)
    rows = json.loads(result.stdout)["benchmarks"]
    out = {}
    for row in rows:
        name = row["name"]
        triangles = int(name.split("triangles:")[1].split("/")[0])
        closed = int(name.split("closed:")[1].split("/")[0])
        out[(triangles, closed)] = (row["real_time"] / 1000.0, row["peak/(mesh+fb)"])
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--facet-bench", default="build/bench/facet_bench")
    parser.add_argument("--frames", type=int, default=5)
    parser.add_argument("--threads", type=int, default=2)
    args = parser.parse_args()

    vtk_rows = {}
    gl = ""
    for triangles, theta in SIZES.items():
        count, seconds, gl = vtk_seconds_per_frame(theta, args.frames)
        vtk_rows[triangles] = (count, seconds)
    facet = facet_seconds_per_frame(args.facet_bench, args.threads)
    for triangles, theta in SIZES.items():  # VTK again after Facet: both see the same machine
        vtk_rows[triangles] = (vtk_rows[triangles][0],
                               min(vtk_rows[triangles][1], vtk_seconds_per_frame(theta, args.frames)[1]))

    print("Facet: every face drawn (as VTK does) | with the closed-surface hint (hidden back "
          "faces skipped)")
    print(f"{'triangles':>10} {'VTK s':>8} {'Facet s':>9} {'ratio':>7} {'peak':>6} | "
          f"{'Facet s':>9} {'ratio':>7} {'peak':>6}")
    for triangles in SIZES:
        count, vtk_seconds = vtk_rows[triangles]
        all_faces, all_peak = facet[(triangles, 0)]
        closed, closed_peak = facet[(triangles, 1)]
        print(f"{count:>10} {vtk_seconds:>8.3f} {all_faces:>9.4f} {vtk_seconds / all_faces:>6.1f}x "
              f"{all_peak:>6.2f} | {closed:>9.4f} {vtk_seconds / closed:>6.1f}x {closed_peak:>6.2f}")
    print(f"VTK {vtk.vtkVersion.GetVTKVersion()} ({gl}), best of two passes of {args.frames} "
          f"frames; Facet: {args.threads} threads, Google Benchmark mean; peak = heap peak / "
          f"(mesh + framebuffer bytes)")


if __name__ == "__main__":
    sys.exit(main())
