"""A scene as a VTK user sets it up, rendered by Facet's filter or by VTK's OpenGL pipeline.

A `Scene` is what both renderers are given: a vtkPolyData, a vtkCamera (None: the automatic
camera), vtkLights (none: the automatic headlight), a vtkProperty (flat interpolation), the
image size and background. `render_facet` runs it through vtkFacetRenderFilter in this
process; `render_vtk` through vtkPolyDataMapper / vtkActor / vtkRenderer with multisampling
off (it needs an X server: run it under xvfb-run, in a subprocess of its own, as report.py
does). Both return a `Render`: the image as numpy arrays, row 0 at the bottom, and the
messages VTK's output window received while rendering.

Facet's scene ambient light is set to 0 throughout, as VTK's OpenGL renderer has none.
"""
import math
import re
from dataclasses import dataclass, field

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonCore import (vtkLogger, vtkOutputWindow, vtkPoints,
                                      vtkStringOutputWindow, vtkUnsignedCharArray)
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
from vtkmodules.vtkRenderingCore import vtkCamera, vtkProperty

# VTK's logger echoes every warning and error to stderr; the output window keeps them.
vtkLogger.SetStderrVerbosity(vtkLogger.VERBOSITY_OFF)


# ---------------------------------------------------------------------------------------------
# Building scenes
# ---------------------------------------------------------------------------------------------

@dataclass
class Scene:
    polydata: vtkPolyData
    camera: vtkCamera = None          # None: the automatic camera (fitted to the input)
    lights: list = field(default_factory=list)  # empty: the automatic headlight
    property: vtkProperty = None      # None: white, Kd 1, flat
    size: tuple = (160, 120)
    background: tuple = (0.0, 0.0, 0.0)


def polydata(points, polys, colors=None):
    """A vtkPolyData with double points (as data far from the origin needs) and polygons
    given as lists of point ids; `colors`: one (r, g, b) byte triple per polygon, stored as
    unsigned char cell scalars (drawn as colors by both renderers)."""
    vtk_points = vtkPoints()
    vtk_points.SetDataTypeToDouble()
    for p in points:
        vtk_points.InsertNextPoint(*p)
    cells = vtkCellArray()
    for ids in polys:
        cells.InsertNextCell(len(ids), list(ids))
    data = vtkPolyData()
    data.SetPoints(vtk_points)
    data.SetPolys(cells)
    if colors is not None:
        scalars = vtkUnsignedCharArray()
        scalars.SetName("Colors")
        scalars.SetNumberOfComponents(3)
        for c in colors:
            scalars.InsertNextTuple3(*c)
        data.GetCellData().SetScalars(scalars)
    return data


def camera(position, focal_point, view_up=(0.0, 1.0, 0.0), clipping_range=None,
           view_angle=30.0, parallel_scale=None):
    """A vtkCamera set as a user sets one, in this order (vtkCamera's setters adjust some
    values: a position equal to the focal point, a thin clipping range)."""
    c = vtkCamera()
    c.SetPosition(*position)
    c.SetFocalPoint(*focal_point)
    c.SetViewUp(*view_up)
    c.SetViewAngle(view_angle)
    if parallel_scale is not None:
        c.ParallelProjectionOn()
        c.SetParallelScale(parallel_scale)
    if clipping_range is not None:
        c.SetClippingRange(*clipping_range)
    return c


def flat_property(color=(1.0, 1.0, 1.0), ambient=0.0, diffuse=1.0, specular=0.0,
                  specular_power=1.0):
    p = vtkProperty()
    p.SetInterpolationToFlat()
    p.SetColor(*color)
    p.SetAmbient(ambient)
    p.SetDiffuse(diffuse)
    p.SetSpecular(specular)
    p.SetSpecularPower(specular_power)
    return p


# ---------------------------------------------------------------------------------------------
# Rendering
# ---------------------------------------------------------------------------------------------

@dataclass
class Message:
    kind: str      # "warning" or "error"
    source: str    # the VTK class that sent it
    text: str


@dataclass
class Render:
    """One renderer's output: arrays of shape (height, width[, 4]), row 0 at the bottom."""
    rgba: np.ndarray = None
    depth: np.ndarray = None
    cell_id: np.ndarray = None      # Facet only
    messages: list = field(default_factory=list)
    counts: dict = field(default_factory=dict)  # Facet's FacetCounts
    camera: tuple = None            # (position, focal point) rendered with
    image: object = None            # Facet's output vtkImageData: the arrays view its memory

    @property
    def ok(self):
        return self.rgba is not None and self.rgba.size > 0

    @property
    def covered(self):
        """Pixels a surface covers: Facet's CellId, else VTK's depth buffer."""
        if self.cell_id is not None:
            return self.cell_id >= 0
        return self.depth < 1.0

    def warnings(self, source=None):
        return [m.text for m in self.messages
                if m.kind == "warning" and source in (None, m.source)]

    def errors(self, source=None):
        return [m.text for m in self.messages if m.kind == "error" and source in (None, m.source)]


_MESSAGE = re.compile(r"^(Warning|ERROR|Generic Warning): In .*?, line \d+\n"
                      r"(?:(\w+) \(0x[0-9a-f]+\): )?(.*?)\n\n", re.M | re.S)


def parse_messages(text):
    """vtkStringOutputWindow's text as Messages."""
    return [Message("error" if kind == "ERROR" else "warning", source or "", body.strip())
            for kind, source, body in _MESSAGE.findall(text)]


class CapturedMessages:
    """Sends VTK's output window to a string for the duration of a `with` block."""

    def __enter__(self):
        self._previous = vtkOutputWindow.GetInstance()
        self._previous.Register(None)  # keep it alive while replaced
        self._window = vtkStringOutputWindow()
        vtkOutputWindow.SetInstance(self._window)
        self.messages = []
        return self

    def __exit__(self, *exc):
        self.messages = parse_messages(self._window.GetOutput())
        vtkOutputWindow.SetInstance(self._previous)
        self._previous.UnRegister(None)
        return False


def _image(array, width, height, components=1):
    values = vtk_to_numpy(array)
    return values.reshape((height, width, components) if components > 1 else (height, width))


def _field_counts(image):
    counts = image.GetFieldData().GetArray("FacetCounts")
    if counts is None:
        return {}
    return {counts.GetComponentName(i): int(counts.GetComponent(0, i))
            for i in range(counts.GetNumberOfComponents())}


def facet_filter(scene):
    """A vtkFacetRenderFilter set up for the scene (not updated)."""
    from facet import vtkFacetRenderFilter
    render = vtkFacetRenderFilter()
    render.SetInputData(scene.polydata)
    render.SetSize(*scene.size)
    render.SetBackground(*scene.background)
    render.SetAmbientLightColor(0.0, 0.0, 0.0)
    render.SetProperty(scene.property or flat_property())
    if scene.camera is not None:
        render.SetCamera(scene.camera)
    for light in scene.lights:
        render.AddLight(light)
    return render


def render_facet(scene):
    """The scene through vtkFacetRenderFilter, with the messages it caused."""
    render = facet_filter(scene)
    with CapturedMessages() as captured:
        render.Update()
    image = render.GetOutput()
    result = Render(messages=captured.messages, counts=_field_counts(image))
    width, height, _ = image.GetDimensions()
    points = image.GetPointData()
    if width * height > 0 and points.GetArray("RGBA") is not None:
        result.rgba = _image(points.GetArray("RGBA"), width, height, 4)
        result.depth = _image(points.GetArray("Depth"), width, height)
        result.cell_id = _image(points.GetArray("CellId"), width, height)
        result.image = image
    active = render.GetActiveCamera()
    result.camera = (active.GetPosition(), active.GetFocalPoint())
    return result


def render_vtk(scene):
    """The scene through VTK's own OpenGL pipeline: flat interpolation, no multisampling,
    the same camera and lights (needs an X server)."""
    import vtkmodules.vtkRenderingOpenGL2  # noqa: F401  (the OpenGL factory overrides)
    from vtkmodules.vtkRenderingCore import (vtkActor, vtkLight, vtkPolyDataMapper, vtkRenderer,
                                             vtkRenderWindow, vtkWindowToImageFilter)

    def opengl(kind, thing):
        """A copy made now: objects made before the OpenGL overrides were loaded (plain
        vtkProperty, vtkCamera, vtkLight) crash VTK's OpenGL renderer."""
        copy = kind()
        copy.DeepCopy(thing)
        return copy

    with CapturedMessages() as captured:
        window = vtkRenderWindow()
        window.SetOffScreenRendering(1)
        window.SetMultiSamples(0)
        window.SetSize(*scene.size)
        renderer = vtkRenderer()
        renderer.SetBackground(*scene.background)
        window.AddRenderer(renderer)
        mapper = vtkPolyDataMapper()
        mapper.SetInputData(scene.polydata)
        actor = vtkActor()
        actor.SetMapper(mapper)
        actor.SetProperty(opengl(vtkProperty, scene.property or flat_property()))
        renderer.AddActor(actor)
        if scene.camera is not None:
            renderer.SetActiveCamera(opengl(vtkCamera, scene.camera))
        for light in scene.lights:
            renderer.AddLight(opengl(vtkLight, light))
        window.Render()
        planes = {}
        for name, set_buffer in (("rgba", "SetInputBufferTypeToRGBA"),
                                 ("depth", "SetInputBufferTypeToZBuffer")):
            grab = vtkWindowToImageFilter()
            grab.SetInput(window)
            grab.ReadFrontBufferOff()
            getattr(grab, set_buffer)()
            grab.Update()
            planes[name] = grab.GetOutput().GetPointData().GetScalars()
            width, height, _ = grab.GetOutput().GetDimensions()  # VTK's, whatever was asked
    active = renderer.GetActiveCamera()
    return Render(rgba=_image(planes["rgba"], width, height, 4).copy(),
                  depth=_image(planes["depth"], width, height).copy(),
                  messages=captured.messages,
                  camera=(active.GetPosition(), active.GetFocalPoint()))


# ---------------------------------------------------------------------------------------------
# Comparing
# ---------------------------------------------------------------------------------------------

@dataclass
class Difference:
    silhouette: int       # pixels covered in one image and not the other
    color: int            # largest RGB channel difference over pixels covered in both
    off: int              # pixels covered in both whose colors differ by more than 1/255
    cell: int = 0         # pixels showing another cell (both Facet renders)

    def __str__(self):
        text = "%d silhouette px, color Δ %d/255" % (self.silhouette, self.color)
        if self.off:
            text += " (%d px > 1/255)" % self.off
        return text + (", %d px show another cell" % self.cell if self.cell else "")


def difference(a, b):
    both = a.covered & b.covered
    rgb = np.abs(a.rgba[..., :3].astype(np.int16) - b.rgba[..., :3].astype(np.int16)).max(axis=-1)
    cell = 0
    if a.cell_id is not None and b.cell_id is not None:
        cell = int(np.count_nonzero(both & (a.cell_id != b.cell_id)))
    return Difference(silhouette=int(np.count_nonzero(a.covered != b.covered)),
                      color=int(rgb[both].max()) if both.any() else 0,
                      off=int(np.count_nonzero(both & (rgb > 1))), cell=cell)


# ---------------------------------------------------------------------------------------------
# The analytic picture of one planar convex polygon
# ---------------------------------------------------------------------------------------------

def _unit(v):
    """v / |v| (each row of v) without overflow for components up to DBL_MAX."""
    v = np.asarray(v, dtype=float)
    v = v / np.max(np.abs(v), axis=-1, keepdims=True)
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


@dataclass
class Coverage:
    inside: np.ndarray   # pixel centers whose ray meets the polygon between near and far
    band: np.ndarray     # pixel centers within `tolerance` px of its projected boundary


def convex_polygon_coverage(cam, size, corners, tolerance=1.0 / 64.0):
    """Which pixel centers see a planar convex polygon (world-space corners) through a
    perspective vtkCamera, computed exactly in double precision by casting rays; and which
    lie so close to the boundary (an edge, or the line where the polygon meets the near or
    far plane) that snapping vertices to 1/256 pixel may decide them either way.

    Each boundary is a linear function of the pixel coordinates (the side of the plane
    through the eye and an edge that a pixel's ray passes on), so the distance to it in
    pixels is |f| / |grad f|. (Outside the polygon, the band uses a lower bound of the
    distance, the largest by which a ray misses one edge: it may hold a few pixels more.)"""
    width, height = size
    eye = np.array(cam.GetPosition())
    forward = _unit(np.array(cam.GetFocalPoint()) - eye)
    right = _unit(np.cross(forward, cam.GetViewUp()))
    up = np.cross(right, forward)
    tan_half = math.tan(math.radians(cam.GetViewAngle()) / 2.0)
    aspect = width / height
    # A pixel's ray: forward + x·sx·right + y·sy·up, x and y in NDC; d(x, y) · forward = 1.
    sx, sy = tan_half * aspect, tan_half
    x = (np.arange(width) + 0.5) * 2.0 / width - 1.0
    y = (np.arange(height) + 0.5) * 2.0 / height - 1.0
    x, y = (grid.ravel() for grid in np.meshgrid(x, y))
    rays = np.outer(forward, np.ones_like(x)) + np.outer(sx * right, x) + np.outer(sy * up, y)

    def gradient(normals):
        """|grad (d(x, y) · normal)| in pixels, for each normal (rows)."""
        return np.hypot(sx * (normals @ right) * 2.0 / width, sy * (normals @ up) * 2.0 / height)

    corners = np.asarray(corners, dtype=float)
    inner_point = _unit(corners.mean(axis=0) - eye)  # the polygon's centroid, from the eye

    def edge_normals(corners):
        """For each edge, the normal of the plane through the eye and the edge, oriented
        toward the polygon and scaled so that d · normal is the signed distance in pixels
        from the edge's projection, positive inside."""
        toward = _unit(corners - eye)
        normals = _unit(np.cross(toward, np.roll(toward, -1, axis=0)))
        normals *= np.sign(normals @ inner_point)[:, np.newaxis]
        return normals / gradient(normals)[:, np.newaxis]

    if len(corners) > 256:
        nearest = _many_edges(edge_normals(corners), edge_normals(corners[::64]), rays, tolerance)
    else:
        nearest = _nearest_edge(edge_normals(corners), rays)
    in_cone, distance = nearest > 0, np.abs(nearest)

    # Where the ray meets the plane: view depth t = ((P0 - E)·n) / (d·n). It is `plane`
    # (near, far) on the line offset − plane·(d·n) = 0, unless the plane faces the view.
    plane_normal = _unit(np.cross(corners[1] - corners[0], corners[2] - corners[0]))
    offset = (corners[0] - eye) @ plane_normal
    facing = plane_normal @ rays
    with np.errstate(divide="ignore", invalid="ignore"):
        t = offset / facing
    near, far = cam.GetClippingRange()
    inside = in_cone & (t >= near) & (t <= far)
    slope = gradient(plane_normal[np.newaxis])[0]
    if slope > 0:
        for plane in (near, far):
            distance = np.minimum(distance, np.abs(offset / plane - facing) / slope)
    inside, distance = inside.reshape(height, width), distance.reshape(height, width)
    return Coverage(inside=inside, band=distance < tolerance)


def _nearest_edge(normals, rays):
    """Per ray (column of `rays`), the smallest signed distance in pixels to an edge: > 0
    inside the polygon's cone (the distance to its boundary), < 0 outside (at most minus the
    distance to the polygon)."""
    nearest = np.full(rays.shape[1], np.inf)
    for chunk in range(0, len(normals), 1024):  # a matrix product per chunk of edges
        nearest = np.minimum(nearest, (normals[chunk:chunk + 1024] @ rays).min(axis=0))
    return nearest


def _many_edges(normals, coarse_normals, rays, tolerance):
    """_nearest_edge for a convex polygon of many corners, in far fewer operations: the
    polygon of every 64th corner lies inside it, and it lies inside the half-space of each
    of its edges, so the rays deep inside the first or far outside one of the second are
    decided; only those near the boundary meet every edge."""
    nearest = _nearest_edge(coarse_normals, rays)  # deep inside where >= tolerance
    outside = _nearest_edge(normals[::64], rays)
    nearest[outside <= -tolerance] = outside[outside <= -tolerance]
    undecided = (nearest < tolerance) & (nearest > -tolerance)
    nearest[undecided] = _nearest_edge(normals, rays[:, undecided])
    return nearest


def window_depth(cam, view_depth):
    """VTK's window depth in [0, 1] of points at view depth t (perspective)."""
    near, far = cam.GetClippingRange()
    return (far / (far - near)) * (1.0 - near / view_depth)
