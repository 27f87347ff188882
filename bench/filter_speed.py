#!/usr/bin/env python3
"""vtkFacetRenderFilter.Update() per 1920x1080 frame from Python vs VTK's OpenGL pipeline.

Each frame turns the camera (the interactive case: the converted mesh is reused) and runs
Update(), which includes the render and the output arrays (RGBA, Depth, CellId). VTK renders
the same spheres offscreen (llvmpipe under Xvfb) with one positional light and reads every
frame back, as bench/compare_vtk.py does, in the same run: like for like (multisampling
off) and with VTK's default multisampling.

    PYTHONPATH=build/lib/python3.11/dist-packages \\
        xvfb-run -a -s "-noreset -screen 0 1920x1080x24" /usr/bin/python3 bench/filter_speed.py

--overhead (no VTK renderer, no Xvfb): what Update() costs beyond the core's frame, and what
the error estimate adds, per size; two filters on the same input (EstimateError off and on)
render alternately, so their ratio is of one run:

    PYTHONPATH=build/lib/python3.11/dist-packages /usr/bin/python3 bench/filter_speed.py --overhead
"""
import argparse
import os
import statistics
import sys
import time

from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.vtkRenderingCore import vtkLight, vtkRenderer

from facet import vtkFacetRenderFilter

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from compare_vtk import SIZES  # noqa: E402

WIDTH, HEIGHT = 1920, 1080


def sphere_of(theta):
    sphere = vtkSphereSource()
    sphere.SetThetaResolution(theta)
    sphere.SetPhiResolution(theta + 2)
    sphere.Update()
    return sphere


def facet_filter(sphere, threads, detect_closed):
    """The filter on the sphere, its camera fitted, one positional light at the camera."""
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
    # The renderer's own speed: the error estimate (on by default) is timed apart, --overhead.
    render.SetEstimateError(False)
    return render, camera


def timed_update(render):
    """(wall seconds, CPU seconds of all threads) of one Update()."""
    wall, cpu = time.perf_counter(), time.process_time()
    render.Update()
    return time.perf_counter() - wall, time.process_time() - cpu


def facet_frame_timer(theta, threads, detect_closed, turn_degrees=0.5):
    """(a function that turns the camera turn_degrees, runs one Update() and returns its
    seconds; the first Update()'s seconds, which converted the mesh)."""
    render, camera = facet_filter(sphere_of(theta), threads, detect_closed)
    render.Update()  # first frame: converts the mesh (and checks closedness once)
    first = render.GetOutput().GetFieldData().GetArray("FacetRenderSeconds").GetValue(0)

    def frame():
        camera.Azimuth(turn_degrees)
        start = time.perf_counter()
        render.Update()
        seconds = time.perf_counter() - start
        converted = render.GetOutput().GetFieldData().GetArray("FacetMeshConverted").GetValue(0)
        assert converted == 0, "a camera change must not convert the mesh again"
        return seconds
    return frame, first


def facet_seconds_per_frame(theta, frames, threads, detect_closed, turn_degrees=0.5):
    """(median seconds of `frames` Update()s, the camera turning turn_degrees before each;
    the first Update()'s seconds)."""
    frame, first = facet_frame_timer(theta, threads, detect_closed, turn_degrees)
    return statistics.median(frame() for _ in range(frames)), first


def core_seconds(render):
    """The core renderer's own phases in the last Update (field data FacetPhaseSeconds)."""
    phases = render.GetOutput().GetFieldData().GetArray("FacetPhaseSeconds")
    names = {"Validate", "Transform", "Setup", "Raster", "Shade"}
    return sum(phases.GetComponent(0, i) for i in range(phases.GetNumberOfComponents())
               if phases.GetComponentName(i) in names)


def overhead(frames, threads):
    """Update() with a turning camera against the core's frame, estimate off and on."""
    print("vtkFacetRenderFilter.Update(), 1920x1080, camera turning every frame (every face "
          f"drawn), {threads} threads, median of {frames} frames; 'core' = the core renderer's "
          "phases inside the same Update(); estimate off and on render alternately; CPU = "
          f"seconds of all threads (steadier than wall time on a shared machine); load average "
          f"{os.getloadavg()[0]:.1f} at the start")
    print(f"{'triangles':>10} | {'Update s':>9} {'core s':>8} {'Update/core':>11} | "
          f"{'+estimate':>9} {'CPU':>6} | {'first Update s':>14} {'+estimate':>9} {'CPU':>7}")
    for triangles, theta in SIZES.items():
        if triangles < 500000:
            continue
        sphere = sphere_of(theta)
        plain, camera = facet_filter(sphere, threads, False)
        plain.SetEstimateError(False)
        estimating, _ = facet_filter(sphere, threads, False)
        estimating.SetCamera(camera)
        estimating.SetEstimateError(True)
        first = timed_update(plain)
        first_estimating = timed_update(estimating)
        times = {id(plain): [], id(estimating): []}
        cores = []
        for _ in range(frames):
            camera.Azimuth(0.5)
            for render in (plain, estimating):
                times[id(render)].append(timed_update(render))
            cores.append(core_seconds(plain))

        def median(render, which):
            return statistics.median(t[which] for t in times[id(render)])

        update = median(plain, 0)
        core = statistics.median(cores)
        wall_cost = median(estimating, 0) / update - 1
        cpu_cost = median(estimating, 1) / median(plain, 1) - 1
        print(f"{triangles:>10} | {update:>9.4f} {core:>8.4f} {update / core:>10.2f}x | "
              f"{100 * wall_cost:>+8.0f}% {100 * cpu_cost:>+5.0f}% | {first[0]:>14.3f} "
              f"{first_estimating[0] - first[0]:>+9.3f} {first_estimating[1] - first[1]:>+7.3f}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--frames", type=int, default=10)
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--overhead", action="store_true",
                        help="Update() against the core's frame, and the estimate's cost")
    args = parser.parse_args()
    if args.overhead:
        overhead(args.frames, args.threads)
        return
    os.environ["LP_NUM_THREADS"] = str(args.threads)  # read when llvmpipe's screen is created
    from compare_vtk import vtk_seconds_per_frame

    def best_vtk(theta, multisamples):
        return min((vtk_seconds_per_frame(theta, 5, multisamples) for _ in range(2)),
                   key=lambda frame: frame.seconds)

    rows = []
    for triangles, theta in SIZES.items():
        if triangles < 500000:
            continue
        every_face, first = facet_seconds_per_frame(theta, args.frames, args.threads, False)
        closed, first_closed = facet_seconds_per_frame(theta, args.frames, args.threads, True)
        rows.append((best_vtk(theta, 0), best_vtk(theta, None), every_face, closed, first,
                     first_closed))

    granted = rows[0][1].samples
    print("vtkFacetRenderFilter.Update() from Python, 1920x1080, camera turning every frame; "
          f"ratio = VTK time / Update() time, VTK 1x = multisampling off, VTK {granted}x = VTK's "
          "default")
    print(f"{'triangles':>10} {'VTK 1x s':>9} {f'VTK {granted}x s':>9} | {'Update s':>9} "
          f"{'vs 1x':>6} {f'vs {granted}x':>6} | {'closed s':>9} {'vs 1x':>6} "
          f"{f'vs {granted}x':>6} | {'first Update s (closed check)':>30}")
    for off, default, every_face, closed, first, first_closed in rows:
        print(f"{off.triangles:>10} {off.seconds:>9.3f} {default.seconds:>9.3f} | "
              f"{every_face:>9.4f} {off.seconds / every_face:>5.1f}x "
              f"{default.seconds / every_face:>5.1f}x | {closed:>9.4f} "
              f"{off.seconds / closed:>5.1f}x {default.seconds / closed:>5.1f}x | "
              f"{first:>13.3f} ({first_closed:.3f})")
    print(f"VTK {rows[0][0].renderer}, best of two runs of 5 frames (median); Facet: "
          f"{args.threads} threads, median of {args.frames} frames; 'closed': "
          "DetectClosedSurfaces on (the default)")


if __name__ == "__main__":
    main()
