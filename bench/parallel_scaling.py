#!/usr/bin/env python3
"""vtkFacetRenderFilter on MPI ranks: render time, composite time and bytes exchanged at
1920x1080, strong scaling (one mesh of 2M or 8M triangles split over the ranks) and weak
scaling (2M or 8M triangles on every rank), for 1, 2 and 4 ranks.

    PYTHONPATH=build/lib/python3.11/dist-packages /usr/bin/python3 bench/parallel_scaling.py

It runs `mpirun -np N` on itself (--worker) for each case and prints one table. The mesh is
a UV sphere (vtkSphereSource), each rank generating its piece (a band of longitudes); every
rank renders with cores/N threads, and N x threads above the machine's cores is flagged
"oversubscribed": the ranks then share cores and the times say little about a cluster.
Closed-surface culling is off in every case (one rank's whole sphere would otherwise cull
its back half, which pieces cannot), so ranks split the same work.

Times are per frame, the median of --frames frames after a first one that converts the
mesh; each frame turns the camera. Of every frame the slowest rank counts (a composite
waits for it): wall (Update, from a barrier), CPU (the process's CPU time in Update, all
its threads: the work, whatever else shares the cores; Open MPI's waiting spins count too)
and render (FacetRenderSeconds minus the composite); the composite (FacetCompositeSeconds: packing, IceT, unpacking) and IceT's part
are the slowest renderer's, since the others' include waiting for it.
Bytes are what IceT sent (FacetCompositeBytes), the most any rank sent and all ranks'.
"""
import argparse
import json
import math
import os
import statistics
import subprocess
import sys
import time

WIDTH, HEIGHT = 1920, 1080
HERE = os.path.abspath(__file__)


# --- One case, on every rank ---------------------------------------------------------------
def sphere_piece(triangles, rank, ranks):
    """Piece `rank` of `ranks` of a UV sphere of about `triangles` triangles
    (vtkSphereSource: 2 * theta * (phi - 1) triangles)."""
    from vtkmodules.vtkFiltersSources import vtkSphereSource

    theta = max(8, round(math.sqrt(triangles / 2)))
    sphere = vtkSphereSource()
    sphere.SetThetaResolution(theta)
    sphere.SetPhiResolution(theta + 1)
    sphere.UpdatePiece(rank, ranks, 0)
    return sphere.GetOutput()


def component(field_data, array_name, component_name):
    array = field_data.GetArray(array_name)
    if array is None:
        return 0.0
    names = [array.GetComponentName(c) for c in range(array.GetNumberOfComponents())]
    return array.GetComponent(0, names.index(component_name))


def slowest(ranks):
    """One frame of every rank: the longest wall and render; the composite of the rank that
    rendered longest (the others' composites include waiting for it); the most bytes."""
    last = max(ranks, key=lambda r: r["render"])
    return {"wall": max(r["wall"] for r in ranks), "cpu": max(r["cpu"] for r in ranks),
            "render": last["render"],
            "composite": last["composite"], "icet": last["icet"],
            "bytes_max": max(r["bytes"] for r in ranks), "bytes_all": ranks[0]["bytes_all"]}


def worker(args):
    from mpi4py import MPI  # initializes MPI before VTK's controller wraps it
    from vtkmodules.vtkParallelCore import vtkMultiProcessController
    from vtkmodules.vtkParallelMPI import vtkMPIController
    from vtkmodules.vtkRenderingCore import vtkCamera

    from facet import vtkFacetRenderFilter

    controller = vtkMPIController()
    controller.Initialize()
    vtkMultiProcessController.SetGlobalController(controller)
    comm = MPI.COMM_WORLD
    rank, ranks = comm.Get_rank(), comm.Get_size()
    total = args.triangles * (ranks if args.scaling == "weak" else 1)
    piece = sphere_piece(total, rank, ranks)

    camera = vtkCamera()
    camera.SetPosition(0.4, 0.7, 3.0)
    render = vtkFacetRenderFilter()
    render.SetInputData(piece)
    render.SetSize(WIDTH, HEIGHT)
    render.SetCamera(camera)
    render.FitCameraToInputOn()
    render.SetDetectClosedSurfaces(False)
    render.SetNumberOfThreads(args.threads)
    render.Update()  # converts the piece
    frames = []
    for _ in range(args.frames):
        camera.Azimuth(3.0)
        render.Modified()
        comm.Barrier()
        start, cpu_start = time.perf_counter(), time.process_time()
        render.Update()
        wall, cpu = time.perf_counter() - start, time.process_time() - cpu_start
        fields = render.GetOutput().GetFieldData()
        composite = component(fields, "FacetCompositeSeconds", "Total")
        mine = {"wall": wall, "cpu": cpu,
                "render": component(fields, "FacetRenderSeconds", "Total") - composite,
                "composite": composite,
                "icet": component(fields, "FacetCompositeSeconds", "IceT"),
                "bytes": component(fields, "FacetCompositeBytes", "SentByThisRank"),
                "bytes_all": component(fields, "FacetCompositeBytes", "SentByAllRanks")}
        frames.append(slowest(comm.allgather(mine)))
    triangles = comm.allreduce(piece.GetNumberOfCells())
    if rank == 0:
        median = {key: statistics.median(f[key] for f in frames) for key in frames[0]}
        strategy = render.GetOutput().GetFieldData().GetAbstractArray("FacetCompositeStrategy")
        print(json.dumps({"ranks": ranks, "threads": args.threads, "scaling": args.scaling,
                          "triangles": triangles, "per_rank": triangles // ranks,
                          **median, "strategy": strategy.GetValue(0) if strategy else ""}), flush=True)


# --- The driver: one mpirun per case, one table ----------------------------------------------
def run_case(args, ranks, scaling, millions):
    cores = os.cpu_count()
    threads = max(1, cores // ranks)
    command = [args.mpirun, "--allow-run-as-root", "--oversubscribe", "-np", str(ranks),
               sys.executable, HERE, "--worker", "--scaling", scaling,
               "--triangles", str(millions * 1_000_000), "--threads", str(threads),
               "--frames", str(args.frames)]
    done = subprocess.run(command, stdout=subprocess.PIPE, text=True, timeout=1800, check=True)
    result = json.loads(done.stdout.strip().splitlines()[-1])
    result["oversubscribed"] = ranks * threads > cores
    return result


def table(results):
    lines = ["| mesh | scaling | ranks x threads | triangles per rank | wall ms | CPU ms | "
             "render ms | composite ms (IceT) | MB sent, most by a rank / all |",
             "|---|---|---|---|---:|---:|---:|---:|---:|"]
    for r in results:
        flag = " (oversubscribed)" if r["oversubscribed"] else ""
        lines.append("| %.0fM | %s | %d x %d%s | %.2fM | %.0f | %.0f | %.0f | %.1f (%.1f) | "
                     "%.1f / %.1f |"
                     % (r["mesh"], r["scaling"], r["ranks"], r["threads"], flag,
                        r["per_rank"] / 1e6, 1e3 * r["wall"], 1e3 * r["cpu"], 1e3 * r["render"],
                        1e3 * r["composite"], 1e3 * r["icet"], r["bytes_max"] / 1e6,
                        r["bytes_all"] / 1e6))
    return "\n".join(lines)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--ranks", type=int, nargs="+", default=[1, 2, 4])
    parser.add_argument("--millions", type=int, nargs="+", default=[2, 8],
                        help="mesh sizes, millions of triangles (default: 2 8)")
    parser.add_argument("--frames", type=int, default=5)
    parser.add_argument("--mpirun", default="mpirun")
    parser.add_argument("--worker", action="store_true", help=argparse.SUPPRESS)
    parser.add_argument("--scaling", choices=["strong", "weak"], help=argparse.SUPPRESS)
    parser.add_argument("--triangles", type=int, help=argparse.SUPPRESS)
    parser.add_argument("--threads", type=int, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.worker:
        worker(args)
        return
    print("load average before: %s" % os.getloadavg()[0], flush=True)
    results = []
    for millions in args.millions:
        for scaling in ("strong", "weak"):
            for ranks in args.ranks:
                if scaling == "weak" and ranks == 1:
                    continue  # the same case as strong on one rank
                result = run_case(args, ranks, scaling, millions)
                result["mesh"] = millions
                results.append(result)
                print(json.dumps(result), flush=True)
    print("load average after: %s" % os.getloadavg()[0])
    print(results[-1]["strategy"])
    print(table(results))


if __name__ == "__main__":
    main()
