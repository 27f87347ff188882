"""vtkFacetRenderFilter on MPI ranks (vtkMPIController from mpi4py), composited with IceT.

Run on N ranks:  mpirun -np N /usr/bin/python3 test_parallel_render.py
Every rank runs every case in the same order (the filter's calls are collective). Rank 0
compares the composited image with the image one process renders of the whole input
(SetController(None)): the same RGBA bytes and Depth, and CellId/RankId naming the cell the
serial render shows. A failed check on any rank prints why and aborts every rank (a hang
would be the other failure; ctest's timeout catches it).
"""
import os
import sys
import time
import traceback

from mpi4py import MPI  # initializes MPI before VTK's controller takes it over

import numpy
from vtkmodules.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray, vtk_to_numpy
from vtkmodules.util.misc import calldata_type
from vtkmodules.vtkCommonCore import VTK_STRING, vtkCommand, vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
from vtkmodules.vtkCommonTransforms import vtkTransform
from vtkmodules.vtkFiltersCore import vtkAppendPolyData, vtkTriangleFilter
from vtkmodules.vtkFiltersGeneral import vtkTransformPolyDataFilter
from vtkmodules.vtkFiltersGeometry import vtkGeometryFilter
from vtkmodules.vtkFiltersParallelGeometry import vtkPDistributedDataFilter
from vtkmodules.vtkFiltersSources import vtkPlaneSource, vtkSphereSource
from vtkmodules.vtkIOGeometry import vtkOBJReader
from vtkmodules.vtkParallelCore import vtkMultiProcessController
from vtkmodules.vtkParallelMPI import vtkMPIController
from vtkmodules.vtkRenderingCore import vtkCamera, vtkLight

from facet import vtkFacetRenderFilter

CONTROLLER = vtkMPIController()
CONTROLLER.Initialize()  # MPI is already initialized (mpi4py): this only wraps it
vtkMultiProcessController.SetGlobalController(CONTROLLER)
RANK = CONTROLLER.GetLocalProcessId()
RANKS = CONTROLLER.GetNumberOfProcesses()
MESHES = os.path.join(os.environ["FACET_SHARED_DATA_DIR"], "meshes")
WIDTH, HEIGHT = 320, 240


def fail(message):
    raise AssertionError("rank %d of %d: %s" % (RANK, RANKS, message))


def check(condition, message):
    if not condition:
        fail(message)


# --- Meshes -------------------------------------------------------------------------------
def polydata(points, triangles, cell_ids=None):
    """A vtkPolyData of triangles (numpy arrays) colored by height (point scalars), with
    global cell ids if given."""
    data = vtkPolyData()
    vtk_points = vtkPoints()
    points = numpy.ascontiguousarray(points, dtype=numpy.float32)
    vtk_points.SetData(numpy_to_vtk(points, deep=1))
    data.SetPoints(vtk_points)
    height = numpy_to_vtk(numpy.ascontiguousarray(points[:, 1]), deep=1)
    height.SetName("Height")
    data.GetPointData().SetScalars(height)
    cells = vtkCellArray()
    offsets = numpy.arange(0, 3 * len(triangles) + 1, 3, dtype=numpy.int64)
    cells.SetData(numpy_to_vtkIdTypeArray(offsets, deep=1),
                  numpy_to_vtkIdTypeArray(numpy.ascontiguousarray(triangles, dtype=numpy.int64).ravel(), deep=1))
    data.SetPolys(cells)
    if cell_ids is not None:
        ids = numpy_to_vtkIdTypeArray(numpy.ascontiguousarray(cell_ids, dtype=numpy.int64), deep=1)
        ids.SetName("OriginalCellId")
        data.GetCellData().SetGlobalIds(ids)
    return data


def arrays_of(data):
    points = vtk_to_numpy(data.GetPoints().GetData()).astype(numpy.float32)
    connectivity = vtk_to_numpy(data.GetPolys().GetConnectivityArray()).reshape(-1, 3)
    return points, connectivity


def moved(source_port, center, translate, scale, rotate_y):
    """The source moved from `center` to `translate`, turned and scaled about it."""
    transform = vtkTransform()
    transform.Translate(*translate)
    transform.RotateY(rotate_y)
    transform.Scale(scale, scale, scale)
    transform.Translate(*(-c for c in center))
    mover = vtkTransformPolyDataFilter()
    mover.SetTransform(transform)
    mover.SetInputConnection(source_port)
    return mover


def scene_mesh():
    """Triangles that hide each other: a closed cow, an open monkey head cutting into it,
    a plane through both and a sphere behind (9k triangles)."""
    append = vtkAppendPolyData()
    cow = vtkOBJReader()
    cow.SetFileName(os.path.join(MESHES, "spot.obj"))
    append.AddInputConnection(cow.GetOutputPort())
    monkey = vtkOBJReader()
    monkey.SetFileName(os.path.join(MESHES, "suzanne.obj"))
    monkey_moved = moved(monkey.GetOutputPort(), (-2.49, 1.25, 4.10), (0.25, 0.55, 0.55),
                         0.3, 30.0)
    append.AddInputConnection(monkey_moved.GetOutputPort())
    plane = vtkPlaneSource()
    plane.SetOrigin(-1.2, -0.9, -0.2)
    plane.SetPoint1(1.2, -0.5, 0.1)
    plane.SetPoint2(-1.0, 0.9, -0.4)
    plane.SetResolution(23, 17)
    append.AddInputConnection(plane.GetOutputPort())
    sphere = vtkSphereSource()
    sphere.SetCenter(-0.5, 0.3, -0.6)
    sphere.SetRadius(0.35)
    sphere.SetThetaResolution(40)
    sphere.SetPhiResolution(20)
    append.AddInputConnection(sphere.GetOutputPort())
    triangles = vtkTriangleFilter()
    triangles.SetInputConnection(append.GetOutputPort())
    triangles.Update()
    return arrays_of(triangles.GetOutput())


def piece_of(points, triangles, first, last, with_global_ids, first_global_id=0):
    """Cells [first, last) with only the points they use, as one rank's piece; cell i's
    global id is first_global_id + i."""
    cells = triangles[first:last]
    used, local = numpy.unique(cells.ravel(), return_inverse=True)
    ids = first_global_id + numpy.arange(first, last) if with_global_ids else None
    return polydata(points[used], local.reshape(-1, 3), ids)


# How the compositor carries the error estimate, and global ids that make it: in the image's
# payload while every CellId fits 48 bits (these reach 2^48 - 1), else in a second composite
# (the last rank's ids from 2^48: one rank decides for all).
ESTIMATE_LAYOUTS = {
    "the error estimate in the payload": lambda rank, count: 2**48 - count,
    "the error estimate's 8 in a second composite":
        lambda rank, count: 2**48 if rank == RANKS - 1 else 0,
}


def cell_range(count, rank, ranks):
    return count * rank // ranks, count * (rank + 1) // ranks


# --- Rendering ----------------------------------------------------------------------------
class Render:
    """One execution of the filter: its output planes (numpy, [y, x]) and its messages."""

    def __init__(self, data, controller=CONTROLLER, camera=None, closed=True, lights=(),
                 **settings):
        self.filter = vtkFacetRenderFilter()
        self.filter.SetController(controller)
        self.filter.SetInputData(data)
        self.filter.SetSize(WIDTH, HEIGHT)
        self.filter.SetBackground(0.1, 0.2, 0.3)
        self.filter.SetDetectClosedSurfaces(closed)
        self.filter.SetScalarRange(-0.9, 1.3)
        if camera is None:  # a view from the side, fitted to the data
            camera = vtkCamera()
            camera.SetPosition(2.5, 1.2, 2.0)
            self.filter.FitCameraToInputOn()
        self.filter.SetCamera(camera)
        for name, value in settings.items():
            getattr(self.filter, "Set" + name)(value)
        for light in lights:
            self.filter.AddLight(light)
        # Observers collect the filter's messages (and keep them off stderr).
        self.errors, self.warnings = [], []

        @calldata_type(VTK_STRING)
        def error(caller, event, message):
            self.errors.append(message)

        @calldata_type(VTK_STRING)
        def warning(caller, event, message):
            self.warnings.append(message)

        self.filter.AddObserver(vtkCommand.ErrorEvent, error)
        self.filter.AddObserver(vtkCommand.WarningEvent, warning)
        self.update()

    def update(self):
        self.filter.Update()
        self.image = self.filter.GetOutput()
        point_data = self.image.GetPointData()
        self.planes = {}
        if self.image.GetNumberOfPoints() > 0:
            for name in ("RGBA", "Depth", "CellId", "RankId", "ErrorEstimate"):
                array = point_data.GetArray(name)
                if array is not None:
                    plane = vtk_to_numpy(array).copy()
                    width, height = self.image.GetDimensions()[:2]
                    self.planes[name] = plane.reshape((height, width) + plane.shape[1:])

    def field(self, name):
        return self.image.GetFieldData().GetAbstractArray(name)

    def named(self, array_name, component):
        array = self.image.GetFieldData().GetArray(array_name)
        names = [array.GetComponentName(c) for c in range(array.GetNumberOfComponents())]
        return array.GetComponent(0, names.index(component))


def serial(data, camera=None, closed=True, **settings):
    return Render(data, controller=None, camera=camera, closed=closed, **settings)


def describe_difference(name, got, expected):
    differ = numpy.argwhere(numpy.any((got != expected).reshape(HEIGHT, WIDTH, -1), axis=2))
    y, x = differ[0]
    return "%s differs at %d pixels, first (x %d, y %d): %s instead of %s" % (
        name, len(differ), x, y, got[y, x], expected[y, x])


def check_plane(name, composited, reference):
    """A plane of the composited image equal to the one-process render's."""
    got, expected = composited.planes[name], reference.planes[name]
    if not numpy.array_equal(got, expected):
        fail(describe_difference(name, got, expected))


def check_same_image(composited, reference, depth_reference=None):
    """RGBA bytes and Depth equal to the one-process render. A closed surface split into
    pieces is closed on no rank, so the ranks draw its back faces where one process culls
    them; the colors agree, but culling changes the core's depth of a few front pixels in
    the last bits (see the README): Depth is then compared with `depth_reference`, the
    one-process render without closed-surface detection."""
    check_plane("RGBA", composited, reference)
    check_plane("Depth", composited, depth_reference or reference)


def check_receives_nothing(render):
    check(render.image.GetNumberOfPoints() == 0,
          "a rank that does not receive the image has %d pixels" % render.image.GetNumberOfPoints())
    check(render.field("FacetRenderSeconds") is not None, "its field data is missing")


# --- Cases --------------------------------------------------------------------------------
CASES = []


def case(function):
    CASES.append(function)
    return function


MESH = scene_mesh()


@case
def cell_ranges_compose_to_the_serial_image():
    """Consecutive cell ranges, no global ids: the image is the serial one, and
    first cell of RankId's range + CellId is the serial CellId."""
    points, triangles = MESH
    first, last = cell_range(len(triangles), RANK, RANKS)
    render = Render(piece_of(points, triangles, first, last, with_global_ids=False))
    if RANK != 0:
        check_receives_nothing(render)
        return
    whole = polydata(points, triangles)
    reference = serial(whole)
    check_same_image(render, reference)
    rank_id, cell_id = render.planes["RankId"], render.planes["CellId"]
    expected = reference.planes["CellId"]
    check(numpy.array_equal(rank_id < 0, expected < 0), "RankId -1 where the serial CellId is not")
    starts = numpy.array([cell_range(len(triangles), r, RANKS)[0] for r in range(RANKS)])
    covered = rank_id >= 0
    global_id = starts[rank_id[covered]] + cell_id[covered]
    check(numpy.array_equal(global_id, expected[covered]),
          "range start + CellId differs from the serial CellId at %d pixels"
          % numpy.count_nonzero(global_id != expected[covered]))
    check(len(numpy.unique(rank_id[covered])) == RANKS, "every rank's piece shows")
    check(covered.sum() > 8000, "the scene covers %d pixels" % covered.sum())


@case
def a_closed_surface_split():
    """A closed sphere in cell ranges: one process culls its back faces, the ranks cannot
    (no piece is closed), and the front faces hide them: the same colors."""
    source = vtkSphereSource()
    source.SetThetaResolution(60)
    source.SetPhiResolution(30)
    source.Update()
    points, triangles = arrays_of(source.GetOutput())
    first, last = cell_range(len(triangles), RANK, RANKS)
    render = Render(piece_of(points, triangles, first, last, with_global_ids=True))
    if RANK == 0:
        whole = polydata(points, triangles)
        reference = serial(whole)
        check("closed surfaces skipped" in reference.filter.GetRenderPlan(),
              "the sphere is not culled as closed: " + reference.filter.GetRenderPlan())
        check_same_image(render, reference, serial(whole, closed=False))
        check_plane("CellId", render, reference)


def colored_light():
    light = vtkLight()
    light.SetPosition(2.0, 3.0, 4.0)
    light.SetDiffuseColor(1.0, 0.6, 0.3)
    return light


@case
def each_rank_reshades_and_the_composite_still_runs():
    """Only the lights, then only the background change: every rank reuses its last frame
    (FacetRenderPath), and the composited image is the one a fresh one-process render of
    the whole input gives."""
    points, triangles = MESH
    first, last = cell_range(len(triangles), RANK, RANKS)
    render = Render(piece_of(points, triangles, first, last, with_global_ids=True))
    render.filter.AddLight(colored_light())
    render.update()
    check(render.named("FacetRenderPath", "Path") == 1, render.filter.GetRenderPlan())
    if RANK == 0:
        reference = serial(polydata(points, triangles), lights=[colored_light()])
        check_same_image(render, reference)
        check_plane("CellId", render, reference)
    render.filter.SetBackground(0.5, 0.5, 0.5)
    render.update()
    check(render.named("FacetRenderPath", "Path") == 2, render.filter.GetRenderPlan())
    if RANK == 0:
        reference = serial(polydata(points, triangles), lights=[colored_light()],
                           Background=(0.5, 0.5, 0.5))
        check_same_image(render, reference)
        check_plane("CellId", render, reference)


@case
def depth_and_cell_ids_composite_but_are_left_out_when_not_asked_for():
    points, triangles = MESH
    first, last = cell_range(len(triangles), RANK, RANKS)
    render = Render(piece_of(points, triangles, first, last, with_global_ids=True),
                    OutputDepth=False, OutputCellIds=False)
    if RANK == 0:
        check(sorted(render.planes) == ["RGBA", "RankId"], "arrays: %s" % sorted(render.planes))
        check_plane("RGBA", render, serial(polydata(points, triangles)))


@case
def global_ids_become_cell_ids():
    points, triangles = MESH
    first, last = cell_range(len(triangles), RANK, RANKS)
    render = Render(piece_of(points, triangles, first, last, with_global_ids=True),
                    CompositeToAllRanks=True)
    reference = serial(polydata(points, triangles))
    # Every rank receives the image: each compares.
    check_plane("RGBA", render, reference)
    check_plane("CellId", render, reference)


@case
def unusable_global_ids_are_ignored():
    """Global ids that are not one integer a cell: a warning, and CellId stays the piece's."""
    points, triangles = MESH
    first, last = cell_range(len(triangles), RANK, RANKS)
    piece = piece_of(points, triangles, first, last, with_global_ids=False)
    ids = numpy_to_vtk(numpy.arange(first, last, dtype=numpy.float64) + 0.5, deep=1)
    ids.SetName("FloatIds")
    piece.GetCellData().SetGlobalIds(ids)
    render = Render(piece)
    check(any("not one integer a cell" in w for w in render.warnings),
          "no warning of the float global ids: %s" % render.warnings)
    if RANK == 0:
        mine = render.planes["RankId"] == 0
        expected = serial(polydata(points, triangles)).planes["CellId"][mine]
        check(numpy.array_equal(render.planes["CellId"][mine], expected),
              "rank 0's CellId is not its piece's cell id")


@case
def distributed_data_filter_pieces():
    """The mesh handed to vtkPDistributedDataFilter (D3) from rank 0: spatial pieces whose
    cells are in another order, with the original ids as global cell ids."""
    points, triangles = MESH
    data = (polydata(points, triangles, numpy.arange(len(triangles))) if RANK == 0
            else polydata(numpy.zeros((0, 3)), numpy.zeros((0, 3), dtype=numpy.int64),
                          numpy.zeros(0)))
    distribute = vtkPDistributedDataFilter()
    distribute.SetController(CONTROLLER)
    distribute.SetInputData(data)
    surface = vtkGeometryFilter()
    surface.SetInputConnection(distribute.GetOutputPort())
    surface.Update()
    piece = vtkPolyData()
    piece.ShallowCopy(surface.GetOutput())
    ids = piece.GetCellData().GetArray("OriginalCellId")
    check(ids is not None, "D3 dropped the OriginalCellId array")
    piece.GetCellData().SetGlobalIds(ids)
    check(0 < piece.GetNumberOfCells() < len(triangles),
          "D3 gave this rank %d of %d cells" % (piece.GetNumberOfCells(), len(triangles)))
    render = Render(piece)
    if RANK != 0:
        check_receives_nothing(render)
        return
    whole = polydata(points, triangles)
    reference = serial(whole)
    check_same_image(render, reference)
    check_plane("CellId", render, reference)


@case
def an_empty_piece():
    """The middle rank (rank 1 of 2) holds nothing; the image is the others'."""
    points, triangles = MESH
    empty_rank = RANKS // 2
    owners = [r for r in range(RANKS) if r != empty_rank]
    if RANK == empty_rank:
        piece = vtkPolyData()
    else:
        first, last = cell_range(len(triangles), owners.index(RANK), len(owners))
        piece = piece_of(points, triangles, first, last, with_global_ids=True)
    render = Render(piece)
    check(not render.errors and not render.warnings,
          "an empty piece is not a problem: %s" % (render.errors + render.warnings))
    if RANK == 0:
        whole = polydata(points, triangles)
        check_same_image(render, serial(whole))
        check(empty_rank not in render.planes["RankId"], "the empty rank shows")


@case
def disjoint_bounds():
    """Each rank holds a sphere far from the others': the automatic camera frames all."""
    def sphere(rank):
        source = vtkSphereSource()
        source.SetCenter(4.0 * rank, 1.5 * (rank % 2), -2.0 * rank)
        source.SetThetaResolution(24)
        source.SetPhiResolution(12)
        source.Update()
        return arrays_of(source.GetOutput())

    points, triangles = sphere(RANK)
    render = Render(polydata(points, triangles))
    if RANK != 0:
        return
    spheres = [sphere(r) for r in range(RANKS)]
    offsets = numpy.cumsum([0] + [len(p) for p, _ in spheres])
    whole = polydata(numpy.concatenate([p for p, _ in spheres]),
                     numpy.concatenate([t + o for (_, t), o in zip(spheres, offsets)]))
    check_same_image(render, serial(whole))  # every piece is a closed sphere here
    shown = set(numpy.unique(render.planes["RankId"])) - {-1}
    check(shown == set(range(RANKS)), "the ranks shown are %s" % sorted(shown))


@case
def an_invalid_piece():
    """Rank 1's cells use a point it does not have: rank 1 reports the error, the others
    finish, and rank 0's image is the others' pieces, with a warning naming rank 1."""
    points, triangles = MESH
    first, last = cell_range(len(triangles), RANK, RANKS)
    piece = piece_of(points, triangles, first, last, with_global_ids=True)
    if RANK == 1:
        broken = vtk_to_numpy(piece.GetPolys().GetConnectivityArray())
        broken[5] = piece.GetNumberOfPoints() + 100
    render = Render(piece)
    if RANK == 1:
        check(any("outside" in e for e in render.errors),
              "the invalid piece's rank reports no error: %s" % render.errors)
        check(render.image.GetNumberOfPoints() == 0, "an output after an error")
        return
    check(not render.errors, "rank %d reports errors: %s" % (RANK, render.errors))
    if RANK != 0:
        return
    check(any("lacks the piece of rank 1" in w for w in render.warnings),
          "no warning of the missing piece: %s" % render.warnings)
    valid = [cell_range(len(triangles), r, RANKS) for r in range(RANKS) if r != 1]
    kept = numpy.concatenate([numpy.arange(a, b) for a, b in valid])
    reference = serial(polydata(points, triangles[kept]),
                       camera=render.filter.GetActiveCamera())
    check_same_image(render, reference)


@case
def an_invalid_piece_on_the_composite_rank():
    """Rank 0, which composites, cannot render: every rank finishes, and the ranks that
    were to receive the image (all of them here) say why they have none."""
    points, triangles = MESH
    first, last = cell_range(len(triangles), RANK, RANKS)
    piece = piece_of(points, triangles, first, last, with_global_ids=True)
    if RANK == 0:
        vtk_to_numpy(piece.GetPolys().GetConnectivityArray())[0] = -7
    render = Render(piece, CompositeToAllRanks=True)
    check(render.image.GetNumberOfPoints() == 0,
          "an image of %d pixels without rank 0's" % render.image.GetNumberOfPoints())
    expected = "outside" if RANK == 0 else "rank 0, which composites the image, could not"
    check(any(expected in e for e in render.errors),
          "no error with '%s': %s" % (expected, render.errors))


@case
def ties_go_to_the_lowest_rank():
    """Every rank renders the same mesh: every depth ties, and rank 0 wins them all, with
    every IceT strategy."""
    points, triangles = MESH
    for strategy in ("Automatic", "BinarySwap", "Tree", "RadixK"):
        render = Render(polydata(points, triangles), CompositeStrategy=getattr(
            vtkFacetRenderFilter, "Composite" + strategy))
        if RANK != 0:
            continue
        rank_id = render.planes["RankId"]
        shown = set(numpy.unique(rank_id)) - {-1}
        check(shown == {0}, "%s: ties went to ranks %s" % (strategy, sorted(shown)))
        reference = serial(polydata(points, triangles))
        check_same_image(render, reference)
        check(strategy.replace("BinarySwap", "Binary Swap").replace("RadixK", "Radix-k")
              .replace("Tree", "Binary Tree") in render.field("FacetCompositeStrategy").GetValue(0),
              "%s: %s" % (strategy, render.field("FacetCompositeStrategy").GetValue(0)))


@case
def another_composite_rank_and_the_report():
    points, triangles = MESH
    target = RANKS - 1
    first, last = cell_range(len(triangles), RANK, RANKS)
    render = Render(piece_of(points, triangles, first, last, with_global_ids=True),
                    CompositeRank=target)
    sent = render.named("FacetCompositeBytes", "SentByThisRank")
    total = render.named("FacetCompositeBytes", "SentByAllRanks")
    sums = MPI.COMM_WORLD.allreduce(sent)
    check(total == sums > 0, "bytes sent by all ranks: %s, the sum of each rank's: %s"
          % (total, sums))
    seconds = render.named("FacetCompositeSeconds", "Total")
    check(0 < render.named("FacetCompositeSeconds", "IceT") <= seconds,
          "IceT's time is not within the composite's")
    check("composite: IceT" in render.filter.GetRenderPlan(), render.filter.GetRenderPlan())
    if RANK != target:
        check_receives_nothing(render)
        return
    reference = serial(polydata(points, triangles))
    check_plane("RGBA", render, reference)


def check_estimate_summary(result, estimate):
    """FacetErrorEstimate summarizes `estimate` as the core does: over the pixels with one."""
    estimated = estimate[estimate != 0]
    rmse = float(numpy.sqrt(numpy.mean(numpy.square(estimated, dtype=numpy.float64))))
    predicted = result.named("FacetErrorEstimate", "PredictedRMSE")
    check(abs(predicted - rmse) <= 1e-9 * rmse,
          "PredictedRMSE %r, the composited image's %r" % (predicted, rmse))
    check(result.named("FacetErrorEstimate", "PredictedMax") == float(estimated.max()),
          "PredictedMax is not the composited image's maximum")


@case
def the_error_estimate_is_the_composited_images():
    """Each pixel's error estimate is that of the piece it shows, and FacetErrorEstimate
    summarizes the composited image (the other ranks keep their own piece's): the estimate one
    process gives for the whole input, away from the seams between pieces — a pixel whose
    3 x 3 neighbours show another piece, or whose cell has a corner in another piece too (its
    vertex normals there see only its own piece's cells). In either of the compositor's
    layouts, whose CellIds are the global ids to the last bit."""
    for layout, first_id in ESTIMATE_LAYOUTS.items():
        error_estimate_composites(layout, first_id)


def error_estimate_composites(layout, first_id):
    points, triangles = MESH
    first, last = cell_range(len(triangles), RANK, RANKS)
    piece = piece_of(points, triangles, first, last, with_global_ids=True,
                     first_global_id=first_id(RANK, len(triangles)))
    render = Render(piece, ErrorEstimateArray=True)
    summary_only = Render(piece)  # EstimateError is on by default; no array asked for
    if RANK != 0:
        check_receives_nothing(render)
        check(render.named("FacetErrorEstimate", "PredictedMax") > 0,
              "the other ranks keep their piece's estimate")
        return
    check("ErrorEstimate" not in summary_only.planes, "ErrorEstimate without being asked for")
    check(layout in render.filter.GetRenderPlan(),
          "not '%s': %s" % (layout, render.filter.GetRenderPlan()))
    estimate, rank_id = render.planes["ErrorEstimate"], render.planes["RankId"]
    covered = rank_id >= 0
    check(numpy.array_equal(estimate != 0, covered), "an estimate on the background, or none")
    for result in (render, summary_only):
        check_estimate_summary(result, estimate)
    cell_id = render.planes["CellId"]
    firsts = numpy.array([first_id(r, len(triangles)) for r in range(RANKS)], dtype=numpy.int64)
    local = cell_id[covered] - firsts[rank_id[covered]]
    first_cells = numpy.array([cell_range(len(triangles), r, RANKS)[0] for r in range(RANKS)])
    check(numpy.all((local >= first_cells[rank_id[covered]]) & (local < len(triangles))),
          "%s: CellIds that are not the shown pieces' global ids" % layout)
    owner = numpy.repeat(numpy.arange(RANKS), [numpy.diff(cell_range(len(triangles), r, RANKS))[0]
                                               for r in range(RANKS)])
    lowest = numpy.full(len(points), RANKS)
    highest = numpy.full(len(points), -1)
    for corner in range(3):
        numpy.minimum.at(lowest, triangles[:, corner], owner)
        numpy.maximum.at(highest, triangles[:, corner], owner)
    on_cut = numpy.any((lowest != highest)[triangles], axis=1)
    whole = serial(polydata(points, triangles), ErrorEstimateArray=True)
    cell = whole.planes["CellId"]
    differs = on_cut[numpy.maximum(cell, 0)] & (cell >= 0)
    padded_rank, padded_differs = numpy.pad(rank_id, 1, mode="edge"), numpy.pad(differs, 1)
    seam = numpy.zeros_like(covered)
    for dy in (0, 1, 2):
        for dx in (0, 1, 2):
            seam |= padded_rank[dy:dy + HEIGHT, dx:dx + WIDTH] != rank_id
            seam |= padded_differs[dy:dy + HEIGHT, dx:dx + WIDTH]
    away = covered & ~seam
    check(away.sum() > 0.3 * covered.sum(), "%d of %d pixels away from seams"
          % (away.sum(), covered.sum()))
    expected = whole.planes["ErrorEstimate"]
    if not numpy.array_equal(estimate[away], expected[away]):
        fail(describe_difference("ErrorEstimate away from seams", numpy.where(away, estimate, 0),
                                 numpy.where(away, expected, 0)))


@case
def with_supersampling_the_silhouettes_keep_their_estimate():
    """With 4 samples a pixel whose center shows no polygon may still mix one in: its estimate
    composites too (behind every surface), so the composited image has an estimate exactly
    where one process's render of the whole input has one, and the summary counts them; in
    either layout, and such a pixel stays background in the image."""
    points, triangles = MESH
    first, last = cell_range(len(triangles), RANK, RANKS)
    whole = serial(polydata(points, triangles), ErrorEstimateArray=True, SamplesPerPixel=4)
    for layout, first_id in ESTIMATE_LAYOUTS.items():
        piece = piece_of(points, triangles, first, last, with_global_ids=True,
                         first_global_id=first_id(RANK, len(triangles)))
        render = Render(piece, ErrorEstimateArray=True, SamplesPerPixel=4)
        if RANK != 0:
            continue
        check(layout in render.filter.GetRenderPlan(), "not '%s'" % layout)
        estimate, rank_id = render.planes["ErrorEstimate"], render.planes["RankId"]
        expected = whole.planes["ErrorEstimate"] != 0
        check(numpy.array_equal(estimate != 0, expected),
              "%s: %d pixels with an estimate, %d in one process's render"
              % (layout, numpy.count_nonzero(estimate), numpy.count_nonzero(expected)))
        edges = (rank_id < 0) & (estimate != 0)
        check(numpy.count_nonzero(edges) > 100, "%s: %d silhouette pixels (center on the "
              "background) with an estimate" % (layout, numpy.count_nonzero(edges)))
        check(numpy.all(render.planes["Depth"][edges] == 1.0)
              and numpy.all(render.planes["CellId"][edges] == -1),
              "%s: a silhouette pixel with only an estimate is not background" % layout)
        check_estimate_summary(render, estimate)


@case
def compute_error_measures_each_piece_and_says_so():
    """The measured error (ComputeError) is each piece's against its own reference: named in a
    warning on every rank, with no per-pixel Error beside the composited image."""
    points, triangles = MESH
    first, last = cell_range(len(triangles), RANK, RANKS)
    render = Render(piece_of(points, triangles, first, last, with_global_ids=True),
                    ComputeError=True, Size=(WIDTH // 4, HEIGHT // 4))  # the reference is slow
    check(any("ComputeError across processes" in w for w in render.warnings),
          "no warning that the measurement is per piece: %s" % render.warnings)
    check(render.named("FacetError", "RMSE") >= 0, "no FacetError of the piece")
    if RANK == 0:
        check(render.image.GetPointData().GetArray("Error") is None,
              "a per-piece Error array beside the composited image")


@case
def disagreeing_settings_are_an_error_everywhere():
    points, triangles = MESH
    first, last = cell_range(len(triangles), RANK, RANKS)
    render = Render(piece_of(points, triangles, first, last, with_global_ids=True),
                    Size=(WIDTH + (RANK == 1), HEIGHT))
    check(any("disagree" in e for e in render.errors),
          "no error about the sizes: %s" % render.errors)
    render = Render(piece_of(points, triangles, first, last, with_global_ids=True),
                    CompositeRank=RANKS)
    check(any("CompositeRank is %d" % RANKS in e for e in render.errors),
          "no error about CompositeRank: %s" % render.errors)


# --- One process, and a build without IceT: nothing changes -------------------------------
ONE_PROCESS = []
WITHOUT_ICET = []


def arrays_in(attributes):
    return sorted(attributes.GetArrayName(i) for i in range(attributes.GetNumberOfArrays()))


@ONE_PROCESS.append
def one_process_renders_as_without_a_controller():
    """An MPI controller of one process is no controller: the same planes, arrays and
    field data as SetController(None) (global ids do not replace CellId), and no message."""
    points, triangles = MESH
    data = polydata(points, triangles, numpy.arange(len(triangles)) + 1000)
    render, reference = Render(data), serial(data)
    check(not render.errors and not render.warnings, render.errors + render.warnings)
    for name in ("RGBA", "Depth", "CellId"):
        check_plane(name, render, reference)
    for attributes in ("GetPointData", "GetFieldData"):
        got, expected = (arrays_in(getattr(r.image, attributes)()) for r in (render, reference))
        check(got == expected, "%s: %s instead of %s" % (attributes, got, expected))
    check("composite" not in render.filter.GetRenderPlan(), render.filter.GetRenderPlan())


@WITHOUT_ICET.append
def without_icet_every_rank_keeps_its_piece():
    """A build without IceT: every rank renders its own piece with the camera of all
    pieces, says once that it cannot composite, and fails nothing."""
    points, triangles = MESH
    first, last = cell_range(len(triangles), RANK, RANKS)
    piece = piece_of(points, triangles, first, last, with_global_ids=False)
    render = Render(piece)
    check(not render.errors, render.errors)
    check(len(render.warnings) == 1 and "cannot composite" in render.warnings[0],
          "warnings: %s" % render.warnings)
    camera = render.filter.GetActiveCamera()
    views = MPI.COMM_WORLD.allgather(camera.GetPosition() + camera.GetFocalPoint())
    check(all(view == views[0] for view in views), "the ranks' cameras differ: %s" % views)
    reference = serial(piece, camera=camera)
    for name in ("RGBA", "Depth", "CellId"):
        check_plane(name, render, reference)
    rank_id = render.planes["RankId"]
    check(numpy.array_equal(rank_id, numpy.where(reference.planes["CellId"] < 0, -1, RANK)),
          "RankId is not this rank's where its piece shows")
    render.filter.Modified()
    render.filter.Update()
    check(not render.warnings[1:], "warned again: %s" % render.warnings)


def main():
    if RANKS == 1:
        cases = ONE_PROCESS
    elif vtkFacetRenderFilter.CanComposite() or os.environ.get("FACET_EXPECT_ICET") != "0":
        check(vtkFacetRenderFilter.CanComposite(), "this build cannot composite (no IceT)")
        cases = CASES
    else:
        cases = WITHOUT_ICET
    names = [case.__name__ for case in cases]
    chosen = sys.argv[1:] or names
    for name in chosen:
        started = time.monotonic()
        cases[names.index(name)]()
        CONTROLLER.Barrier()
        if RANK == 0:
            print("%d ranks: %s passed (%.2f s)" % (RANKS, name, time.monotonic() - started),
                  flush=True)


if __name__ == "__main__":
    try:
        main()
    except BaseException:  # noqa: B902 (a failure on one rank must stop every rank)
        sys.stdout.flush()
        traceback.print_exc()
        sys.stderr.flush()
        MPI.COMM_WORLD.Abort(1)
