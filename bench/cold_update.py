#!/usr/bin/env python3
"""The filter's Update() (closed check on, 500k) after different neighbours, in one process.

bench/peers.py's paired_ratios times VTK 1x's frame, then Update closed, then Update every
face, frame after frame: the Update that runs right after VTK's frame seemed ~20 % slower than
one timed in a row. This times Update closed after each of

  vtk      one VTK 1x frame (llvmpipe, LP_NUM_THREADS = --threads, read back), as in peers.py
  update   another Update closed (the caches as warm as Update leaves them)
  sweep    a plain --sweep-mb MB memory sweep on this thread (numpy: read and write), which
           evicts the last-level cache but wakes no other thread
  sleep    --sleep-ms ms asleep (VTK's frame time, idle: the threads and the core cool down)
  every    one Update every face (the filter paired_ratios runs after closed)

the conditions rotating frame by frame (each sees the same camera angles in turn), and prints
per condition the median Update wall and CPU time (all threads), the time its threads waited
runnable for a CPU (Waited, /proc schedstat), Xvfb's CPU time meanwhile, its phases inside Update (FacetPhaseSeconds: the
conversion, the core's Validate/Transform/Setup/Raster/Shade, the filter's Output), the rest
(wall - FacetRenderSeconds: the pipeline), minor page faults, and the ratio to 'update'.

    XVFB_SCREEN=1920x1080x24 tests/plugin/xvfb_run.sh env \
        PYTHONPATH=build/lib/python3.11/dist-packages /usr/bin/python3 bench/cold_update.py
"""
import argparse
import os
import resource
import statistics
import sys
import time

import numpy

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

PHASES = ("Conversion", "Validate", "Transform", "Setup", "Raster", "Shade", "Output")


def xvfb_schedstat_path():
    """/proc/PID/schedstat of the Xvfb serving $DISPLAY (None if not found)."""
    display = os.environ.get("DISPLAY", "")
    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            with open(f"/proc/{pid}/cmdline", "rb") as f:
                words = f.read().split(b"\0")
        except OSError:
            continue
        if words and words[0].endswith(b"Xvfb") and display.encode() in words:
            return f"/proc/{pid}/schedstat"
    return None


def schedstat(path, field):
    """Nanoseconds: field 0 = on a CPU, 1 = runnable but waiting for one."""
    with open(path) as f:
        return int(f.read().split()[field])


def threads_waiting_ns():
    """Nanoseconds this process's threads have waited, runnable, for a CPU (all threads)."""
    total = 0
    for task in os.listdir("/proc/self/task"):
        try:
            total += schedstat(f"/proc/self/task/{task}/schedstat", 1)
        except OSError:
            pass
    return total


def phase_seconds(render):
    output = render.GetOutput().GetFieldData()
    phases = output.GetArray("FacetPhaseSeconds")
    named = {phases.GetComponentName(i): phases.GetComponent(0, i)
             for i in range(phases.GetNumberOfComponents())}
    named["Total"] = output.GetArray("FacetRenderSeconds").GetValue(0)
    return named


def peers_order(args, vtk_frame, closed_update, every, every_camera, turn):
    """paired_ratios' order, every time printed: VTK's frame, Update closed, Update every face
    each frame, with a second Update closed right after the first; then as many in a row (as a round's Update column)."""
    load = os.getloadavg()[0]
    vtks, closeds, agains, everys, ratios = [], [], [], [], []
    for _ in range(args.frames):
        vtks.append(vtk_frame())
        closeds.append(closed_update())
        agains.append(closed_update())
        every_camera.Azimuth(turn)
        start = time.perf_counter()
        every.Update()
        everys.append(time.perf_counter() - start)
        ratios.append(closeds[-1]["Wall"] / vtks[-1])
    in_a_row = [closed_update() for _ in range(args.frames)]
    med = statistics.median
    print(f"paired order, {args.frames} frames, load {load:.1f} -> {os.getloadavg()[0]:.1f}; "
          f"median ms: VTK {1000 * med(vtks):.2f}, closed {1000 * med(c['Wall'] for c in closeds):.2f} "
          f"(CPU {1000 * med(c['CPU'] for c in closeds):.2f}), every {1000 * med(everys):.2f}; "
          f"closed / VTK median of ratios {med(ratios):.4f}; closed in a row "
          f"{1000 * med(c['Wall'] for c in in_a_row):.2f} (CPU "
          f"{1000 * med(c['CPU'] for c in in_a_row):.2f}); in a row / median VTK "
          f"{med(c['Wall'] for c in in_a_row) / med(vtks):.4f}")
    print(f"  the second Update closed of each frame, right after the first: "
          f"{1000 * med(c['Wall'] for c in agains):.2f}, first / second median of ratios "
          f"{med(a['Wall'] / b['Wall'] for a, b in zip(closeds, agains)):.4f}; CPU "
          f"{med(a['CPU'] / b['CPU'] for a, b in zip(closeds, agains)):.4f}")
    for name in ("Wall", "CPU", "Transform", "Setup", "Raster", "Shade", "Rest", "Waited", "Xvfb"):
        print(f"  {name:<10} paired {1000 * med(c[name] for c in closeds):7.3f} second "
              f"{1000 * med(c[name] for c in agains):7.3f} in a row "
              f"{1000 * med(c[name] for c in in_a_row):7.3f}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--theta", type=int, default=500, help="500: 500k triangles")
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--frames", type=int, default=20, help="frames of each condition")
    parser.add_argument("--sweep-mb", type=int, default=64)
    parser.add_argument("--sleep-ms", type=float, default=75.0)
    parser.add_argument("--conditions", default="vtk,update,sweep,sleep,every")
    parser.add_argument("--peers-order", action="store_true",
                        help="peers.py's paired order (VTK, closed, every each frame), then "
                        "--frames closed Updates in a row; absolute medians")
    args = parser.parse_args()
    os.environ["LP_NUM_THREADS"] = str(args.threads)
    conditions = args.conditions.split(",")

    from compare_vtk import vtk_frame_timer
    from filter_speed import facet_filter, sphere_of

    sphere = sphere_of(args.theta)
    closed, camera = facet_filter(sphere, args.threads, True)
    every, every_camera = facet_filter(sphere_of(args.theta), args.threads, False)
    closed.Update()
    every.Update()
    vtk_frame = vtk_frame_timer(args.theta, 0)[0] if "vtk" in conditions else None
    sweep = numpy.ones(args.sweep_mb << 17)  # float64: MB * 2^20 / 8
    turn = 360.0 / args.frames
    xvfb = xvfb_schedstat_path()

    def closed_update():
        camera.Azimuth(turn / len(conditions))
        faults = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
        waited = threads_waiting_ns()
        xvfb_before = schedstat(xvfb, 0) if xvfb else 0
        start, cpu = time.perf_counter(), time.process_time()
        closed.Update()
        wall, cpu = time.perf_counter() - start, time.process_time() - cpu
        xvfb_after = schedstat(xvfb, 0) if xvfb else 0
        waited = threads_waiting_ns() - waited
        faults = resource.getrusage(resource.RUSAGE_SELF).ru_minflt - faults
        named = phase_seconds(closed)
        named["Wall"] = wall
        named["CPU"] = cpu
        named["Rest"] = wall - named["Total"]
        named["Faults"] = faults
        named["Waited"] = waited * 1e-9
        named["Xvfb"] = (xvfb_after - xvfb_before) * 1e-9
        return named

    if args.peers_order:
        peers_order(args, vtk_frame, closed_update, every, every_camera, turn)
        return
    before = {
        "vtk": lambda: vtk_frame(),
        "update": closed_update,
        "sweep": lambda: sweep.__iadd__(1.0),
        "sleep": lambda: time.sleep(args.sleep_ms / 1000.0),
        "every": lambda: (every_camera.Azimuth(turn), every.Update()),
    }
    samples = {name: [] for name in conditions}
    load = os.getloadavg()[0]
    for frame in range(args.frames):
        for k in range(len(conditions)):
            name = conditions[(frame + k) % len(conditions)]  # rotate: no fixed neighbour
            before[name]()
            samples[name].append(closed_update())

    columns = ("Wall", "CPU", "Waited", "Xvfb", "Total", "Rest") + PHASES + ("Faults",)
    print(f"Update closed, theta {args.theta}, {args.threads} threads, {args.frames} frames per "
          f"condition, rotating; medians, ms (Faults: minor page faults in Update); load "
          f"{load:.1f} -> {os.getloadavg()[0]:.1f}")
    print(f"{'after':<8}" + "".join(f"{c:>11}" for c in columns) + f"{'wall/update':>12}"
          f"{'CPU/update':>11}")
    reference = samples.get("update", samples[conditions[0]])
    base = statistics.median(s["Wall"] for s in reference)
    base_cpu = statistics.median(s["CPU"] for s in reference)
    for name in conditions:
        rows = samples[name]
        med = {c: statistics.median(r.get(c, 0.0) for r in rows) for c in columns}
        cells = "".join(f"{med[c]:>11.0f}" if c == "Faults" else f"{1000 * med[c]:>11.2f}"
                        for c in columns)
        print(f"{name:<8}{cells}{med['Wall'] / base:>12.3f}{med['CPU'] / base_cpu:>11.3f}")


if __name__ == "__main__":
    main()
