#!/usr/bin/env python3
"""The error estimate's composite cost across MPI ranks: the bytes IceT sent and the
composite's seconds (total, and its pack, IceT and unpack parts; the total also waits for
the slowest rank's render) without the estimate, with it in the image's payload, and with it
in a second composite (the pieces' global cell ids from 2^48, which the payload cannot
carry), in turn (two rounds), for a 1M-triangle UV sphere split in halves of longitude (one
per rank) at 1920x1080, the camera turning a degree a frame; the median of frames 2 to 6.

    PYTHONPATH=build/lib/python3.11/dist-packages mpirun --allow-run-as-root --oversubscribe \\
        -np 2 /usr/bin/python3 bench/mpi_estimate_cost.py
"""
import statistics

import numpy

from mpi4py import MPI  # noqa: F401 (initializes MPI before VTK's controller takes it over)
from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.vtkParallelCore import vtkMultiProcessController
from vtkmodules.vtkParallelMPI import vtkMPIController
from vtkmodules.vtkRenderingCore import vtkCamera
from vtkmodules.util.numpy_support import numpy_to_vtkIdTypeArray

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


def with_global_ids(data, first):
    """A shallow copy of `data` whose cells have global ids first, first + 1, ..."""
    copy = type(data)()
    copy.ShallowCopy(data)
    ids = numpy_to_vtkIdTypeArray(first + numpy.arange(data.GetNumberOfCells(), dtype=numpy.int64),
                                  deep=1)
    copy.GetCellData().SetGlobalIds(ids)
    return copy


def measure(data, estimate):
    """(bytes sent by all ranks, [total, pack, IceT, unpack] composite ms) of one filter's
    frames."""
    render = vtkFacetRenderFilter()
    render.SetInputData(data)
    render.SetSize(1920, 1080)
    render.SetDetectClosedSurfaces(0)  # no piece is closed: the ranks split the same work
    render.SetEstimateError(estimate)
    camera = vtkCamera()
    camera.SetPosition(0.0, 0.3, 3.0)
    render.SetCamera(camera)
    render.FitCameraToInputOn()
    parts = []
    for _ in range(FRAMES):
        camera.Azimuth(1.0)
        render.Modified()
        render.Update()
        seconds = render.GetOutput().GetFieldData().GetArray("FacetCompositeSeconds")
        parts.append([seconds.GetComponent(0, c) for c in range(4)])
    sent = render.GetOutput().GetFieldData().GetArray("FacetCompositeBytes").GetComponent(0, 1)
    return sent, [1e3 * statistics.median(frame[c] for frame in parts[1:]) for c in range(4)]


def main():
    controller = vtkMPIController()
    controller.Initialize()
    vtkMultiProcessController.SetGlobalController(controller)
    rank, ranks = controller.GetLocalProcessId(), controller.GetNumberOfProcesses()
    data = piece(rank, ranks)
    wide = with_global_ids(data, 2**48 + rank * data.GetNumberOfCells())
    modes = (("no estimate", data, 0), ("estimate in the payload", data, 1),
             ("estimate in a second composite", wide, 1))
    for _ in range(2):
        for name, piece_data, estimate in modes:
            sent, (total, pack, icet, unpack) = measure(piece_data, estimate)
            if rank == 0:
                print("%-31s IceT sent %d bytes (all ranks), composite %.1f ms (pack %.1f, "
                      "IceT %.1f, unpack %.1f)" % (name, sent, total, pack, icet, unpack),
                      flush=True)


if __name__ == "__main__":
    main()
