#!/usr/bin/env python3
"""The error estimate's composite cost across MPI ranks: the bytes IceT sent and the
composite's seconds with EstimateError off and on, alternately (two rounds each), for a
1M-triangle UV sphere split in halves of longitude (one per rank) at 1920x1080, the camera
turning a degree a frame; the median of frames 2 to 6.

    PYTHONPATH=build/lib/python3.11/dist-packages mpirun --allow-run-as-root --oversubscribe \\
        -np 2 /usr/bin/python3 bench/mpi_estimate_cost.py
"""
import statistics

from mpi4py import MPI  # noqa: F401 (initializes MPI before VTK's controller takes it over)
from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.vtkParallelCore import vtkMultiProcessController
from vtkmodules.vtkParallelMPI import vtkMPIController
from vtkmodules.vtkRenderingCore import vtkCamera

from facet import vtkFacetRenderFilter

FRAMES = 6


def piece(rank, ranks):
    sphere = vtkSphereSource()
    sphere.SetThetaResolution(1000)
    sphere.SetPhiResolution(500)
    sphere.SetStartTheta(360.0 * rank / ranks)
    sphere.SetEndTheta(360.0 * (rank + 1) / ranks)
    sphere.Update()
    return sphere.GetOutput()


def measure(data, estimate):
    """(bytes sent by all ranks, composite ms, IceT ms) of one filter's frames."""
    render = vtkFacetRenderFilter()
    render.SetInputData(data)
    render.SetSize(1920, 1080)
    render.SetDetectClosedSurfaces(0)  # no piece is closed: the ranks split the same work
    render.SetEstimateError(estimate)
    camera = vtkCamera()
    camera.SetPosition(0.0, 0.3, 3.0)
    render.SetCamera(camera)
    render.FitCameraToInputOn()
    total, icet = [], []
    for _ in range(FRAMES):
        camera.Azimuth(1.0)
        render.Modified()
        render.Update()
        seconds = render.GetOutput().GetFieldData().GetArray("FacetCompositeSeconds")
        total.append(seconds.GetComponent(0, 0))
        icet.append(seconds.GetComponent(0, 2))
    sent = render.GetOutput().GetFieldData().GetArray("FacetCompositeBytes").GetComponent(0, 1)
    return sent, 1e3 * statistics.median(total[1:]), 1e3 * statistics.median(icet[1:])


def main():
    controller = vtkMPIController()
    controller.Initialize()
    vtkMultiProcessController.SetGlobalController(controller)
    rank, ranks = controller.GetLocalProcessId(), controller.GetNumberOfProcesses()
    data = piece(rank, ranks)
    for estimate in (0, 1, 0, 1):
        sent, total, icet = measure(data, estimate)
        if rank == 0:
            print("EstimateError %d: IceT sent %d bytes (all ranks), composite %.1f ms (IceT %.1f)"
                  % (estimate, sent, total, icet), flush=True)


if __name__ == "__main__":
    main()
