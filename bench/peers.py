#!/usr/bin/env python3
"""Facet and its peers per 1920x1080 frame, measured in one run (`make bench-peers`).

Every column draws the same vtkSphereSource-topology sphere (20k, 500k, 2M, 8M triangles)
from the same camera (vtkRenderer::ResetCamera's, looking down -Z), lit by one positional
light at the camera, at 1920x1080 with one sample per pixel (except "VTK default"), on
--threads threads wherever the program can use them:

  VTK 1x       VTK 9.1 + llvmpipe under Xvfb, multisampling off, flat interpolation, every
               frame read back (RGB) with vtkWindowToImageFilter (bench/compare_vtk.py)
  VTK default  the same with VTK's default multisampling (asks for 8 samples, llvmpipe grants 4)
  OSMesa       llvmpipe through OSMesa without VTK: the mesh in buffer objects once, flat
               shading from the face normal, RGBA + depth read back (build/bin/osmesa_peer)
  Embree       an Embree 3 packet ray caster, one primary ray per pixel, flat shading from
               the geometric normal, RGBA + depth + primitive id (build/bin/embree_peer);
               its BVH build, done once per mesh, is a column of its own
  core         Facet's core, facet_bench's BM_Sphere (Google Benchmark mean; every face drawn
               / closed-surface hint): a versioned mesh and the camera turning a degree per
               frame (bench/TurningView.h), in a process of its own after the others. Not
               quite the filter's frame: its sphere lists the triangles ring by ring (the
               filter's vtkSphereSource meridian by meridian), its light is unattenuated;
               the Update/core section at the end compares the two in one process
               (bench/filter_overhead.md, id24)
  Update       vtkFacetRenderFilter.Update() from Python, the camera turning 360/--frames
               degrees before each (the median frame of a whole turn), RGBA + Depth + CellId
               output (bench/filter_speed.py; every face / closed check)
  limit        the memory-bound limit: bytes a frame must move over the measured bandwidth

llvmpipe (VTK, OSMesa) rasterizes on LP_NUM_THREADS = --threads threads; it transforms
vertices and sets up triangles on the calling thread alone. Peer times are the median of
--frames frames after a warm-up frame.

The whole set is measured --rounds times, one round after another; the tables show each
column's median over the rounds and each target's ratio is taken within a round (the two
times it divides were measured minutes apart, not hours), its median and range printed. The
host under these VMs changes speed in steps (bench/core-frame-issue11.md, section 9): every
round starts with a speed check (a fixed pure-Python loop, best of 5), printed beside it,
so a round measured on a slow host shows as one. The targets against VTK 1x and between
every face and closed are then measured frame by frame in turn (--paired-frames of VTK 1x,
Update closed and Update every face, one after the other, in one process, each frame starting
with the next of the three: --paired-order): each ratio is of two frames a second apart, and
the verdict is on the median of those ratios.

    make bench-peers
    XVFB_SCREEN=1920x1080x24 tests/plugin/xvfb_run.sh /usr/bin/python3 bench/peers.py --sizes 500000
"""
import argparse
import glob
import os
import re
import statistics
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from check_peers import coverage_disagreement, run_program  # noqa: E402
from compare_vtk import (SIZES, WIDTH, HEIGHT, facet_seconds_per_frame, vtk_frame_timer,  # noqa: E402
                         vtk_seconds_per_frame)

PEER_SIZES = {**SIZES, 8000000: 2000}  # triangles: theta = phi - 2 resolution

FRAMEBUFFER_BYTES_PER_PIXEL = 4 + 4 + 4  # RGBA8, float depth, int32 polygon id
LIMIT_FORMULA = (
    "limit = mesh bytes / read bandwidth + framebuffer bytes / write bandwidth, where\n"
    "  mesh bytes        = 12 B x points (float xyz) + 8 B x (triangles + 1) (offsets)\n"
    "                      + 8 B x 3 x triangles (connectivity): VTK's 64-bit cell array, read once\n"
    f"  framebuffer bytes = {FRAMEBUFFER_BYTES_PER_PIXEL} B x {WIDTH} x {HEIGHT} "
    "(RGBA8 + float depth + int32 id), written once")


def memory_bound_seconds(triangles, theta, bandwidth):
    points = theta * theta + 2  # theta * (phi - 2) ring points and two poles
    mesh = 12 * points + 8 * (triangles + 1) + 8 * 3 * triangles
    framebuffer = FRAMEBUFFER_BYTES_PER_PIXEL * WIDTH * HEIGHT
    return (mesh / bandwidth["read_bytes_per_second"]
            + framebuffer / bandwidth["write_bytes_per_second"])


def uptime():
    return subprocess.run(["uptime"], check=True, capture_output=True, text=True).stdout.strip()


def measure_size(triangles, theta, args, bin_dir, update_seconds):
    """{column: seconds or None} for one sphere, plus the peers' reports."""
    peer_args = ("--triangles", triangles, "--frames", args.frames, "--threads", args.threads)
    osmesa = run_program(bin_dir / "osmesa_peer", *peer_args)
    embree = run_program(bin_dir / "embree_peer", *peer_args)
    vtk_off = vtk_seconds_per_frame(theta, args.vtk_frames, 0)
    vtk_default = vtk_seconds_per_frame(theta, args.vtk_frames)
    if vtk_off.samples != 1:
        sys.exit(f"VTK with multisampling off still drew {vtk_off.samples} samples per pixel")
    # Around the whole sphere: drawn every face, the mesh's order puts the back faces first
    # from some sides and last from others (bench/core-frame-issue11.md, section 9).
    turn = 360.0 / args.frames
    every_face, _ = update_seconds(theta, args.frames, args.threads, False, turn)
    closed, _ = update_seconds(theta, args.frames, args.threads, True, turn)
    return {
        "VTK 1x": vtk_off.seconds,
        "VTK default": vtk_default.seconds,
        "OSMesa": osmesa and osmesa["seconds_per_frame"],
        "Embree trace": embree and embree["seconds_per_frame"],
        "Embree BVH": embree and embree["build_seconds"],
        "Update every": every_face,
        "Update closed": closed,
    }, {"vtk": vtk_default, "osmesa": osmesa, "embree": embree}


def milliseconds(seconds):
    return "n/a" if seconds is None else f"{1000 * seconds:.1f}"


def ratio(facet, peer):
    return "n/a" if facet is None or peer is None else f"{facet / peer:.3f}"


def print_tables(rows):
    columns = ["VTK 1x", "VTK default", "OSMesa", "Embree trace", "Embree BVH", "core every",
               "core closed", "Update every", "Update closed", "limit"]
    print("\nMilliseconds per 1920x1080 frame, median over the rounds (Embree BVH: the build, "
          "once per mesh)")
    print(f"{'triangles':>10}" + "".join(f"{name:>14}" for name in columns))
    for triangles, row in rows.items():
        print(f"{triangles:>10}" + "".join(f"{milliseconds(row.get(name)):>14}" for name in columns))

    peers = ["VTK 1x", "VTK default", "OSMesa", "Embree trace", "limit"]
    print("\nFacet time / peer time (below 1: Facet is faster)")
    print(f"{'triangles':>10} {'Facet':>14}" + "".join(f"{'/ ' + name:>16}" for name in peers))
    for triangles, row in rows.items():
        for facet in ("core every", "core closed", "Update every", "Update closed"):
            if row.get(facet) is None:
                continue
            print(f"{triangles:>10} {facet:>14}"
                  + "".join(f"{ratio(row[facet], row.get(name)):>16}" for name in peers))


def print_targets(rounds):
    """Issue 11's targets, on the filter's Update() (closed check on: the filter's default):
    each ratio taken within a round; the verdict on the median over the rounds."""
    def check(text, facet, peer, bound, triangles):
        values = [row[triangles][facet] / row[triangles][peer] for row in rounds
                  if row.get(triangles, {}).get(facet) and row[triangles].get(peer)]
        if not values:
            print(f"  {text:<50} n/a")
            return
        median = statistics.median(values)
        verdict = "met" if median <= bound else "NOT met"
        spread = f"{min(values):.3f}-{max(values):.3f}" if len(values) > 1 else ""
        print(f"  {text:<50} {median:>7.3f} {spread:>13} (target <= {bound}) {verdict}")

    print(f"\nIssue 11's targets (Update = the filter's Update(), turning camera; median and "
          f"range of the ratio over {len(rounds)} round(s))")
    sizes = rounds[0].keys()
    for triangles in (500000, 2000000):
        if triangles in sizes:
            check(f"{triangles}: Update closed / VTK 1x", "Update closed", "VTK 1x", 0.1, triangles)
            check(f"{triangles}: Update closed / Embree frame", "Update closed", "Embree trace",
                  1.0, triangles)
    for triangles in sizes:
        check(f"{triangles}: Update every face / Update closed", "Update every", "Update closed",
              1.5, triangles)
    if 8000000 in sizes:
        check("8000000: Update closed / Embree frame", "Update closed", "Embree trace", 1.5,
              8000000)
    if 2000000 in sizes:
        check("2000000: Update closed / memory-bound limit", "Update closed", "limit", 8.0,
              2000000)


def paired_ratios(args, update_timer):
    """({(triangles, name): [ratio per frame]}, {(triangles, column): [seconds per frame]}):
    VTK 1x (at 500k and 2M), Update closed and Update every face rendered in turn, frame after
    frame, the filters turning once around. --paired-order rotate (the default) starts each
    frame with the next of the three (V C E | C E V | E V C: closed follows VTK's frame in two
    frames of three, every face in one, neither always; a frame right after VTK's finds none
    of its bytes in cache, ~3 % slower: bench/core-frame-issue11.md, section 51); fixed keeps
    the order VTK, closed, every face of the runs before it."""
    ratios, seconds = {}, {}
    turn = 360.0 / args.paired_frames
    for triangles in args.sizes:
        theta = PEER_SIZES[triangles]
        timers = {}
        if triangles in (500000, 2000000):
            timers["VTK 1x"] = vtk_frame_timer(theta, 0)[0]
        timers["Update closed"] = update_timer(theta, args.threads, True, turn)[0]
        timers["Update every face"] = update_timer(theta, args.threads, False, turn)[0]
        names = list(timers)
        for frame in range(args.paired_frames):
            start = frame % len(names) if args.paired_order == "rotate" else 0
            frame_seconds = {name: timers[name]() for name in names[start:] + names[:start]}
            for name, value in frame_seconds.items():
                seconds.setdefault((triangles, name), []).append(value)
            closed_seconds = frame_seconds["Update closed"]
            if "VTK 1x" in frame_seconds:
                ratios.setdefault((triangles, "Update closed / VTK 1x"), []).append(
                    closed_seconds / frame_seconds["VTK 1x"])
            ratios.setdefault((triangles, "Update every face / Update closed"), []).append(
                frame_seconds["Update every face"] / closed_seconds)
    return ratios, seconds


def print_paired_targets(ratios, seconds, frames, order):
    print(f"\nThe same targets frame by frame in turn ({frames} frames of each, one after the "
          f"other, order {order}; median and range of the ratios of neighbouring frames)")
    bounds = {"Update closed / VTK 1x": 0.1, "Update every face / Update closed": 1.5}
    for (triangles, name), values in ratios.items():
        median = statistics.median(values)
        verdict = "met" if median <= bounds[name] else "NOT met"
        spread = f"{min(values):.3f}-{max(values):.3f}"
        print(f"  {f'{triangles}: {name}':<50} {median:>7.3f} {spread:>13} "
              f"(target <= {bounds[name]}) {verdict}")
    print("  their frames, median ms: " + "; ".join(
        f"{triangles} {name} {milliseconds(statistics.median(values))}"
        for (triangles, name), values in seconds.items()))


def filter_overhead_ratios(args, bin_dir):
    """{(triangles, closed): (Update/core wall, CPU, core/bench mesh wall, CPU)}: the filter's
    Update() and the core's frame on the same arrays at the same camera, frame by frame in turn
    in one process (build/bin/facet_filter_overhead, the camera turning as Update's above),
    with facet_bench's BM_Sphere mesh as a third side. The table's "core" and "Update" columns
    are of separate processes minutes apart; these are not."""
    program = bin_dir / "facet_filter_overhead"
    if not program.is_file():
        return {}
    ratios = {}
    for triangles in args.sizes:
        if triangles not in SIZES:
            continue
        for closed in (1, 0):
            result = subprocess.run(
                [str(program), str(PEER_SIZES[triangles]), str(closed), str(args.threads),
                 str(args.frames), "--no-estimate", f"--turn={360.0 / args.frames}"],
                check=False, capture_output=True, text=True).stdout  # no figures: left out
            found = re.search(r"Update/core ([\d.]+) / ([\d.]+), core/bench mesh ([\d.]+) / "
                              r"([\d.]+)", result)
            if found:
                ratios[(triangles, closed)] = tuple(float(v) for v in found.groups())
    return ratios


def print_filter_overhead(ratios, frames):
    print(f"\nUpdate() against the core's frame in one process, frame by frame in turn "
          f"(build/bin/facet_filter_overhead, {frames} frames, the camera turning as Update's; "
          "median of the per-frame ratios, wall / CPU). 'core' here renders the filter's own "
          "arrays (vtkSphereSource's triangle order, the filter's light); 'bench mesh' is "
          "facet_bench's BM_Sphere mesh (rings in place of meridians, an unattenuated light) at "
          "the same camera:")
    for (triangles, closed), (update_wall, update_cpu, core_wall, core_cpu) in ratios.items():
        name = "closed" if closed else "every face"
        print(f"  {triangles:>8} {name:<10}  Update / core {update_wall:.3f} / {update_cpu:.3f}"
              f"   core / bench mesh {core_wall:.3f} / {core_cpu:.3f}")


def median_rows(rounds):
    """{triangles: row}: each column's median over the rounds (None where never measured);
    the first round's reports and covered pixels."""
    rows = {}
    for triangles, first in rounds[0].items():
        row = dict(first)
        for column in first:
            measured = [r[triangles][column] for r in rounds
                        if isinstance(r[triangles].get(column), float)]
            if measured:  # a peer may fail in one round and not another
                row[column] = statistics.median(measured)
        rows[triangles] = row
    return rows


def speed_check_seconds():
    """A fixed, memory-free amount of interpreter work, best of 5: the host's speed now."""
    def once():
        start = time.perf_counter()
        total = 0
        for i in range(300000):
            total += i * i % 7
        return time.perf_counter() - start
    return min(once() for _ in range(5))


def print_coverage(rows):
    """The programs must have drawn the same sphere: their covered pixel counts agree."""
    for triangles, row in rows.items():
        problem = coverage_disagreement(row["pixels"])
        if problem:
            print(f"WARNING: {triangles} triangles: {problem}")
    print("Covered pixels (OSMesa, Embree, Facet core): " + "; ".join(
        f"{triangles}: " + ", ".join(str(n or "n/a") for n in row["pixels"].values())
        for triangles, row in rows.items()))


def print_notes(args, rows, bandwidth):
    reports = [row["reports"] for row in rows.values()]
    vtk = reports[0]["vtk"]
    osmesa = next((r["osmesa"] for r in reports if r["osmesa"]), None)
    embree = next((r["embree"] for r in reports if r["embree"]), None)
    print(f"VTK default: asks for {vtk.requested} samples per pixel, llvmpipe granted "
          f"{vtk.samples}; VTK 1x: 1. {vtk.renderer}, LP_NUM_THREADS={args.threads}.")
    print("OSMesa: " + (osmesa["renderer"] if osmesa else
                        "osmesa_peer not built (Debian: libosmesa6-dev, then re-run cmake)"))
    print("Embree: " + (f"{embree['renderer']}, {embree['packet']}-ray packets" if embree else
                        "embree_peer not built (Debian: libembree-dev, then re-run cmake)"))
    if any(t not in SIZES for t in rows):
        print("core: n/a at 8000000 triangles (facet_bench's BM_Sphere has no 8M case)")
    print(f"Bandwidth ({args.threads} threads, best of {bandwidth['passes']} sweeps of "
          f"{bandwidth['bytes'] >> 20} MiB): read {bandwidth['read_bytes_per_second'] / 1e9:.1f} "
          f"GB/s, write {bandwidth['write_bytes_per_second'] / 1e9:.1f} GB/s")
    print(LIMIT_FORMULA)
    print(f"Threads: {args.threads} for Facet, Embree (BVH build and trace), llvmpipe's "
          "rasterizer and the bandwidth sweep; llvmpipe's vertex and set-up work uses one.")


def measure(args, bin_dir):
    """({triangles: row}, bandwidth): a row holds every column's seconds (None where a
    program was not built), the peers' reports and the covered pixels."""
    sys.path[:0] = glob.glob(str(args.build_dir / "lib" / "python3*" / "dist-packages"))
    from filter_speed import facet_seconds_per_frame as update_seconds

    bandwidth = run_program(bin_dir / "bandwidth_bench", "--threads", args.threads)
    if bandwidth is None:
        sys.exit(f"{bin_dir / 'bandwidth_bench'} does not exist: build it (make build)")
    rows = {}
    for triangles in args.sizes:
        theta = PEER_SIZES[triangles]
        row, reports = measure_size(triangles, theta, args, bin_dir, update_seconds)
        row["limit"] = memory_bound_seconds(triangles, theta, bandwidth)
        row["reports"] = reports
        rows[triangles] = row
    core = facet_seconds_per_frame(bin_dir / "facet_bench", args.threads,
                                   [t for t in args.sizes if t in SIZES])
    for triangles, row in rows.items():
        every, closed = core.get((triangles, 0)), core.get((triangles, 1))
        row["core every"] = every and every.seconds
        row["core closed"] = closed and closed.seconds
        row["pixels"] = {name: row["reports"][name] and row["reports"][name]["pixels_covered"]
                         for name in ("osmesa", "embree")}
        row["pixels"]["facet_bench"] = every and every.pixels
    return rows, bandwidth


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--build-dir", type=Path, default=HERE.parent / "build")
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--frames", type=int, default=10, help="frames per peer and Update()")
    parser.add_argument("--vtk-frames", type=int, default=5)
    parser.add_argument("--rounds", type=int, default=3, help="times the whole set is measured")
    parser.add_argument("--paired-frames", type=int, default=20,
                        help="frames of each in the frame-by-frame comparison (0: none)")
    parser.add_argument("--paired-order", choices=("rotate", "fixed"), default="rotate",
                        help="the frame-by-frame comparison's order: rotate (each frame starts "
                        "with the next of VTK 1x, closed, every face) or fixed (always that "
                        "order, as before session 16)")
    parser.add_argument("--sizes", type=int, nargs="+", default=list(PEER_SIZES),
                        choices=list(PEER_SIZES), help="triangle counts (default: all)")
    args = parser.parse_args()
    os.environ["LP_NUM_THREADS"] = str(args.threads)  # read when llvmpipe's screen is created

    load_start = uptime()
    rounds, speeds = [], []
    for number in range(1, args.rounds + 1):
        speeds.append(speed_check_seconds())
        print(f"round {number} of {args.rounds}: speed check {1000 * speeds[-1]:.1f} ms, "
              f"{uptime()}", flush=True)
        rows, bandwidth = measure(args, args.build_dir / "bin")
        rounds.append(rows)

    from filter_speed import facet_frame_timer
    ratios, paired_seconds = (paired_ratios(args, facet_frame_timer) if args.paired_frames > 0
                              else ({}, {}))
    overhead = filter_overhead_ratios(args, args.build_dir / "bin")
    load_end = uptime()

    rows = median_rows(rounds)
    print_tables(rows)
    print_targets(rounds)
    if ratios:
        print_paired_targets(ratios, paired_seconds, args.paired_frames, args.paired_order)
    if overhead:
        print_filter_overhead(overhead, args.frames)
    print("Speed check per round (ms; a slower host shows larger): "
          + ", ".join(f"{1000 * s:.1f}" for s in speeds))
    print()
    print_coverage(rows)
    print_notes(args, rows, bandwidth)
    print(f"Load at start: {load_start}")
    print(f"Load at end:   {load_end}")


if __name__ == "__main__":
    sys.exit(main())
