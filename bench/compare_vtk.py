#!/usr/bin/env python3
"""Facet vs VTK 9.1's own OpenGL pipeline, per 1920x1080 frame, measured in one run.

VTK renders the same vtkSphereSource spheres offscreen (Mesa llvmpipe under Xvfb, on
LP_NUM_THREADS = --threads rasterizer threads), with flat interpolation and one positional
light, and reads every frame back with vtkWindowToImageFilter, twice: like for like with
Facet (multisampling off: one sample per pixel) and with VTK's defaults (the window asks for
8 samples; llvmpipe grants 4, and the table says what it granted). Facet's numbers come from
the build tree's facet_bench (2 threads, full frame including the clear) run by this script
in the same session. Prints a table and the ratios.

    xvfb-run -a -s "-noreset -screen 0 1920x1080x24" /usr/bin/python3 bench/compare_vtk.py

(-noreset: every measurement deletes its window, and so its X connection, and the next one
connects milliseconds later; a server that resets when its last client leaves may drop that
connection: VTK's "bad X server connection". tests/plugin/xvfb_run.sh passes it.)

Give --facet-bench twice (a build before a change, then one after) for both tables against
the same VTK frames, in one run.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import time
from collections import namedtuple
from pathlib import Path

import vtk

SIZES = {20000: 100, 500000: 500, 2000000: 1000}  # triangles: theta = phi - 2 resolution
WIDTH, HEIGHT = 1920, 1080
# The build tree's programs (bench/CMakeLists.txt puts them in bin/).
BUILD_BIN = Path(__file__).resolve().parent.parent / "build" / "bin"

VtkFrame = namedtuple("VtkFrame", "triangles seconds renderer requested samples")


def vtk_frame_timer(theta, multisamples=None):
    """(a function that renders one frame, reads it back and returns its seconds; a
    VtkFrame whose seconds are those of the first frame). multisamples: None keeps VTK's
    default request, 0 turns MSAA off."""
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
    if multisamples is not None:
        window.SetMultiSamples(multisamples)
    requested = window.GetMultiSamples()
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

    start = time.perf_counter()
    frame()  # first frame uploads the mesh and compiles shaders
    first = time.perf_counter() - start
    samples = max(1, window.GetRenderFramebuffer().GetMultiSamples())  # 0 = single-sampled
    renderer_info = window.ReportCapabilities().splitlines()
    gl_renderer = next((l for l in renderer_info if "OpenGL renderer" in l), "OpenGL renderer: ?")

    def timed_frame():
        actor.Modified()
        start = time.perf_counter()
        frame()
        return time.perf_counter() - start
    return timed_frame, VtkFrame(triangles, first, gl_renderer.split(":")[-1].strip(), requested,
                                 samples)


def vtk_seconds_per_frame(theta, frames, multisamples=None):
    """VtkFrame: the median seconds per frame of `frames` frames, and the samples per pixel
    the window requested and llvmpipe granted. multisamples: None keeps VTK's default
    request, 0 turns MSAA off."""
    timed_frame, info = vtk_frame_timer(theta, multisamples)
    return info._replace(seconds=statistics.median(timed_frame() for _ in range(frames)))


FacetFrame = namedtuple("FacetFrame", "seconds peak pixels")


def facet_seconds_per_frame(bench, threads, sizes=tuple(SIZES)):
    """{(triangles, closed): FacetFrame(seconds per frame, heap peak / (mesh + framebuffer),
    pixels covered)} from facet_bench's BM_Sphere cases with `sizes` triangles."""
    if not sizes:
        return {}
    if not Path(bench).is_file():
        sys.exit(f"{bench} does not exist: build it (make bench) or pass --facet-bench")
    triangles = "|".join(str(size) for size in sizes)
    result = subprocess.run(
        [bench, f"--benchmark_filter=BM_Sphere/triangles:({triangles})/threads:{threads}/",
         "--benchmark_format=json", "--benchmark_min_time=1"],
        check=True, capture_output=True, text=True)
    rows = json.loads(result.stdout)["benchmarks"]
    out = {}
    for row in rows:
        name = row["name"]
        triangles = int(name.split("triangles:")[1].split("/")[0])
        closed = int(name.split("closed:")[1].split("/")[0])
        out[(triangles, closed)] = FacetFrame(row["real_time"] / 1000.0, row["peak/(mesh+fb)"],
                                              int(row["pixels"]))
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--facet-bench", action="append",
                        help="facet_bench to measure (default: the build tree's); give it twice, "
                        "e.g. a build before a change and one after, for a table each against "
                        "the same VTK frames")
    parser.add_argument("--frames", type=int, default=5)
    parser.add_argument("--threads", type=int, default=2)
    args = parser.parse_args()
    os.environ["LP_NUM_THREADS"] = str(args.threads)  # read when llvmpipe's screen is created

    vtk_off, vtk_default = {}, {}
    for triangles, theta in SIZES.items():
        vtk_off[triangles] = vtk_seconds_per_frame(theta, args.frames, 0)
        vtk_default[triangles] = vtk_seconds_per_frame(theta, args.frames)
    benches = args.facet_bench or [str(BUILD_BIN / "facet_bench")]
    facets = [facet_seconds_per_frame(bench, args.threads) for bench in benches]
    for triangles, theta in SIZES.items():  # VTK again after Facet: both see the same machine
        for rows, samples in ((vtk_off, 0), (vtk_default, None)):
            again = vtk_seconds_per_frame(theta, args.frames, samples)
            rows[triangles] = min(rows[triangles], again, key=lambda frame: frame.seconds)

    default = vtk_default[next(iter(SIZES))]
    granted = default.samples
    print(f"VTK 1x: multisampling off, one sample per pixel as Facet (like for like); VTK "
          f"{granted}x: VTK's default (asks for {default.requested} samples, llvmpipe granted "
          f"{granted})")
    print("Facet: every face drawn (as VTK does) | with the closed-surface hint (hidden back "
          "faces skipped); ratio = VTK time / Facet time")
    for bench, facet in zip(benches, facets):
        if len(benches) > 1:
            print(f"Facet: {bench}")
        print(f"{'triangles':>10} {'VTK 1x s':>9} {f'VTK {granted}x s':>9} | {'Facet s':>8} "
              f"{'vs 1x':>6} {f'vs {granted}x':>6} {'peak':>5} | {'Facet s':>8} {'vs 1x':>6} "
              f"{f'vs {granted}x':>6} {'peak':>5}")
        for triangles in SIZES:
            off, default = vtk_off[triangles], vtk_default[triangles]
            cells = []
            for closed in (0, 1):
                f = facet[(triangles, closed)]
                cells.append(f"{f.seconds:>8.4f} {off.seconds / f.seconds:>5.1f}x "
                             f"{default.seconds / f.seconds:>5.1f}x {f.peak:>5.2f}")
            print(f"{off.triangles:>10} {off.seconds:>9.3f} {default.seconds:>9.3f} | "
                  f"{cells[0]} | {cells[1]}")
    print(f"VTK {vtk.vtkVersion.GetVTKVersion()} ({off.renderer}, LP_NUM_THREADS={args.threads}), "
          f"best of two passes of {args.frames} frames (median); Facet: {args.threads} threads, "
          f"Google Benchmark mean; peak = heap peak / (mesh + framebuffer bytes)")


if __name__ == "__main__":
    sys.exit(main())
