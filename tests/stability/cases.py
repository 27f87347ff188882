"""The stability catalogue: issue 7's stiff and extreme cases, each built as a VTK user builds
it (vtkPolyData, vtkCamera, vtkLight, vtkProperty) with the behaviour Facet states for it.

A case is measured the same way on any renderer's output (`Case.measure`), so the report can
hold VTK's OpenGL pipeline to the same statement; the catalogue test (test_catalogue.py)
asserts it for Facet, plus the checks every render must pass (checks.py). A case whose
statement describes a known defect says so in `defect`: the statement is today's behaviour,
to be flipped when the defect is fixed.
"""
import math
from dataclasses import dataclass, field
from typing import Callable, Optional

import numpy as np
from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.vtkRenderingCore import vtkCamera, vtkLight

from scene import (Scene, camera, convex_polygon_coverage, difference, flat_property,
                   polydata, window_depth)

SMALL = (160, 120)


@dataclass
class Verdict:
    ok: bool
    text: str


@dataclass
class Case:
    name: str
    group: str
    kind: str                            # equal, draw, skip, clamp, clip or error
    behaviour: str                       # what Facet does, as stated to users
    scene: Callable[[], Scene]
    measure: Optional[Callable] = None   # (render, reference render or None, scene) -> Verdict
    reference: Optional[Callable[[], Scene]] = None  # the scene it must look like
    error: Optional[str] = None          # Facet's error (regex) when it must not render
    warnings: list = field(default_factory=list)  # Facet's warnings (regexes), in full
    counts: dict = field(default_factory=dict)  # FacetCounts components it must report
    defect: Optional[str] = None         # a known defect: the statement is today's behaviour


# ---------------------------------------------------------------------------------------------
# Measures (each works on Facet's and on VTK's render)
# ---------------------------------------------------------------------------------------------

def same_image(tolerance=1):
    """Equal to the reference render: no silhouette pixel differs, colors within tolerance."""
    def measure(render, reference, scene):
        d = difference(render, reference)
        return Verdict(d.silhouette == 0 and d.color <= tolerance, str(d))
    return measure


def exact_polygon(corners_of, color=None):
    """Covers exactly the pixel centers the polygon covers (computed by casting rays in
    double precision; pixels within 1/64 px of its projected boundary are left to vertex
    snapping), in one flat color when `color` is given."""
    def measure(render, reference, scene):
        coverage = convex_polygon_coverage(scene.camera, scene.size, corners_of())
        shown = render.covered
        wrong = int(np.count_nonzero((shown != coverage.inside) & ~coverage.band))
        text = "%d px, %d differ from the exact polygon" % (np.count_nonzero(shown), wrong)
        ok = wrong == 0
        if color is not None:
            colors, off = _colors(render, color)
            text += "; %s" % colors
            ok &= bool(shown.any()) and off <= 1
        return Verdict(ok, text)
    return measure


def uniform_color(expected):
    """Covers what the reference covers, every covered pixel the color `expected` (±1)."""
    def measure(render, reference, scene):
        colors, off = _colors(render, expected)
        silhouette = difference(render, reference).silhouette
        return Verdict(off <= 1 and silhouette == 0,
                       "%s, %d silhouette px" % (colors, silhouette))
    return measure


def _colors(render, expected):
    """The covered pixels' colors in words, and their largest difference from `expected`."""
    colors = render.rgba[render.covered][:, :3].astype(int)
    if colors.size == 0:
        return "no color", 255
    off = int(np.abs(colors - np.array(expected)).max())
    low, high = colors.min(axis=0), colors.max(axis=0)
    if (low == high).all():
        return "all %s (Δ %d)" % (tuple(int(v) for v in low), off), off
    return "%s to %s (Δ %d)" % (tuple(int(v) for v in low), tuple(int(v) for v in high),
                                off), off


def nearer_wins(render, reference, scene):
    """Depth pairs: the nearer (red) polygon shows at every pixel either covers."""
    covered = render.covered
    red = covered & (render.rgba[..., 0] > render.rgba[..., 1])
    share = np.count_nonzero(red) / max(1, np.count_nonzero(covered))
    return Verdict(covered.any() and share == 1.0,
                   "nearer shown on %.1f %% of %d px" % (100 * share, np.count_nonzero(covered)))


# ---------------------------------------------------------------------------------------------
# The unit scene, translated and scaled
# ---------------------------------------------------------------------------------------------

GRID = 1.0 / 256.0  # test coordinates are multiples: exact after any translation up to 1e12
TRANSLATION_DIRECTION = (1.0, 0.5, -0.75)


def _snap(p):
    return tuple(round(c / GRID) * GRID for c in p)


def unit_scene(translation=0.0, scale=1.0, clipping=(2.0, 12.0), size=SMALL):
    """A low-resolution sphere in front of a quad, three lights (headlight, positional,
    directional) and a specular material; coordinates on the 1/256 grid, then translated by
    `translation` along TRANSLATION_DIRECTION (exact) or scaled by `scale` about the origin,
    camera and lights with them."""
    offset = np.array(TRANSLATION_DIRECTION) * translation

    def place(p):
        return tuple((np.array(p) * scale + offset).tolist())

    sphere = vtkSphereSource()
    sphere.SetRadius(1.0)
    sphere.SetThetaResolution(12)
    sphere.SetPhiResolution(9)
    sphere.Update()
    source = sphere.GetOutput()
    points = [_snap(source.GetPoint(i)) for i in range(source.GetNumberOfPoints())]
    polys = []
    for i in range(source.GetNumberOfCells()):
        ids = source.GetCell(i).GetPointIds()
        polys.append([ids.GetId(k) for k in range(ids.GetNumberOfIds())])
    colors = [(230, 200, 150)] * len(polys)
    base = len(points)
    points += [(-2.5, -2.0, -1.5), (2.5, -2.0, -1.5), (2.5, 2.0, -1.5), (-2.5, 2.0, -1.5)]
    polys.append([base, base + 1, base + 2, base + 3])
    colors.append((120, 160, 220))

    lights = [_light(headlight=True, intensity=0.5),
              _light(position=place((3.0, 4.0, 2.0)), focal_point=place((0, 0, 0)),
                     positional=True, cone_angle=180.0, intensity=0.4),
              _light(position=place((-1.0, 2.0, 3.0)), focal_point=place((0, 0, 0)),
                     intensity=0.3)]
    return Scene(polydata([place(p) for p in points], polys, colors),
                 camera(place((2.75, 1.5, 4.25)), place((0.125, -0.0625, 0.0)),
                        clipping_range=(clipping[0] * scale, clipping[1] * scale)),
                 lights, flat_property(specular=0.3, specular_power=10.0), size)


def _light(headlight=False, position=(0, 0, 1), focal_point=(0, 0, 0), positional=False,
           cone_angle=30.0, exponent=1.0, intensity=1.0, color=(1, 1, 1),
           attenuation=(1, 0, 0)):
    light = vtkLight()
    if headlight:
        light.SetLightTypeToHeadlight()
    light.SetPosition(*position)
    light.SetFocalPoint(*focal_point)
    light.SetPositional(positional)
    light.SetConeAngle(cone_angle)
    light.SetExponent(exponent)
    light.SetIntensity(intensity)
    light.SetColor(*color)
    light.SetAttenuationValues(*attenuation)
    return light


# ---------------------------------------------------------------------------------------------
# Small scenes: polygons in the plane z = 0 seen from (0, 0, 4)
# ---------------------------------------------------------------------------------------------

def plane_camera():
    return camera((0.0, 0.0, 4.0), (0.0, 0.0, 0.0), clipping_range=(1.0, 10.0))


def plane_scene(points, polys, lights=(), prop=None, cam=None, size=SMALL):
    return Scene(polydata(points, polys), cam or plane_camera(), list(lights),
                 prop or flat_property(), size)


QUAD = [(-1.0, -0.75, 0.0), (1.0, -0.75, 0.0), (1.0, 0.75, 0.0), (-1.0, 0.75, 0.0)]
SQUARE = [(-0.8, -0.8, 0.0), (0.8, -0.8, 0.0), (0.8, 0.8, 0.0), (-0.8, 0.8, 0.0)]
WHITE = (255, 255, 255)
BLACK = (0, 0, 0)


def quad_scene(*lights, prop=None, cam=None, size=SMALL):
    return plane_scene(QUAD, [[0, 1, 2, 3]], lights, prop, cam, size)


def disk(vertices, radius=0.9, clockwise=False):
    step = (-1 if clockwise else 1) * 2.0 * math.pi / vertices
    return [(radius * math.cos(k * step), radius * math.sin(k * step), 0.0)
            for k in range(vertices)]


def pentagram():
    tips = [(0.9 * math.sin(2 * math.pi * k / 5), 0.9 * math.cos(2 * math.pi * k / 5), 0.0)
            for k in range(5)]
    return [tips[(2 * k) % 5] for k in range(5)]


BOWTIE = [(-0.8, -0.6, 0.0), (0.8, 0.6, 0.0), (0.8, -0.6, 0.0), (-0.8, 0.6, 0.0)]


def fan_scene(corners):
    """The polygon's fan from vertex 0, as separate triangles: what VTK's OpenGL draws."""
    n = len(corners)
    return plane_scene(corners, [[0, i, i + 1] for i in range(1, n - 1)])


# ---------------------------------------------------------------------------------------------
# The catalogue
# ---------------------------------------------------------------------------------------------

EQUAL_TO_UNIT = "equal to the unit scene: ≤ 1/255, 0 silhouette px"


def _translations():
    for exponent in range(3, 13):
        t = 10.0 ** exponent
        yield Case("translated by 1e%d" % exponent, "far from the origin", "equal",
                   EQUAL_TO_UNIT + " (data, camera and lights moved)",
                   lambda t=t: unit_scene(translation=t), same_image(), reference=unit_scene)


def _scales():
    for exponent in (-12, -9, -6, -3, 3, 6, 9, 12):
        s = 10.0 ** exponent
        yield Case("scaled by 1e%d" % exponent, "scale", "equal",
                   EQUAL_TO_UNIT + " (data, camera, lights and clipping range scaled)",
                   lambda s=s: unit_scene(scale=s), same_image(), reference=unit_scene)


def _near_far_ratios():
    for exponent in (4, 8, 12):
        ratio = 10.0 ** exponent
        yield Case("far/near = 1e%d" % exponent, "clipping range", "equal",
                   EQUAL_TO_UNIT + " (its far/near is 6)",
                   lambda r=ratio: unit_scene(clipping=(12.0 / r, 12.0)), same_image(),
                   reference=unit_scene)


def depth_pair(gap, ratio, distance=10.0):
    """Two parallel quads facing the camera `distance` away, `gap`·distance apart: the
    farther (green) drawn first, the nearer (red) second; far plane at twice the distance,
    near plane `ratio` times closer."""
    near_z = gap * distance
    points = [(x, y, 0.0) for x, y, _ in QUAD] + [(x, y, near_z) for x, y, _ in QUAD]
    far = 2.0 * distance
    return Scene(polydata(points, [[0, 1, 2, 3], [4, 5, 6, 7]], [(0, 200, 0), (200, 0, 0)]),
                 camera((0.0, 0.0, distance), (0.0, 0.0, 0.0),
                        clipping_range=(far / ratio, far)))


def _depth_pairs():
    for gap_exponent in (4, 5, 6):
        for ratio_exponent in (4, 8, 12):
            gap, ratio = 10.0 ** -gap_exponent, 10.0 ** ratio_exponent
            yield Case("depth pair 1e-%d apart, far/near 1e%d" % (gap_exponent, ratio_exponent),
                       "depth precision", "draw",
                       "the nearer surface (drawn second) wins at every pixel",
                       lambda g=gap, r=ratio: depth_pair(g, r), nearer_wins)


def _polygons():
    triangle = [(-0.5, -0.5, 0.0), (0.5, -0.5, 0.0), (0.0, 0.5, 0.0)]
    yield Case("zero-area polygons", "polygons", "skip",
               "skipped and counted, no warning: equal to the valid triangle alone",
               lambda: plane_scene(triangle + [(-0.5, 0.6, 0), (0.0, 0.6, 0), (0.5, 0.6, 0)],
                                   [[0, 1, 2], [3, 4, 5], [0, 0, 0], [0, 1, 0], [1, 2, 2]]),
               same_image(0), reference=lambda: plane_scene(triangle, [[0, 1, 2]]),
               counts={"PolygonsDegenerate": 4, "PolygonsDrawn": 1})

    height = 2.0 / 56.0  # 2 px at this camera; 1e6 times longer
    sliver = [(-0.5e6 * height, 0.0123, 0.0), (0.5e6 * height, 0.0123, 0.0),
              (0.0, 0.0123 + height, 0.0)]
    yield Case("sliver 1e6:1 across the image", "polygons", "clip",
               "2 px tall, 35,714 units long: clipped to the guard band, covers exactly the "
               "pixel centers inside it, lit",
               lambda: plane_scene(sliver, [[0, 1, 2]]), exact_polygon(lambda: sliver, WHITE))
    tiny = [(-0.5, 0.1, 0.0), (0.5, 0.1, 0.0), (0.0, 0.1 + 1e-6, 0.0)]
    yield Case("sliver 1e6:1, sub-pixel", "polygons", "draw",
               "covers exactly the pixel centers inside it (none but on its edges)",
               lambda: plane_scene(tiny, [[0, 1, 2]]), exact_polygon(lambda: tiny))

    run = []
    for a, b in zip(SQUARE, SQUARE[1:] + SQUARE[:1]):
        run += [tuple(a[i] + (b[i] - a[i]) * k / 4.0 for i in range(3)) for k in range(4)]
    yield Case("collinear runs (16 vertices, 4 per side)", "polygons", "draw",
               "the square it is, lit as one polygon",
               lambda: plane_scene(run, [list(range(len(run)))]),
               exact_polygon(lambda: SQUARE, WHITE))
    yield Case("duplicate points (repeated ids, coincident points)", "polygons", "draw",
               "the square it is, lit as one polygon",
               lambda: plane_scene(SQUARE + [SQUARE[1]], [[0, 0, 1, 4, 2, 2, 3, 3, 0]]),
               exact_polygon(lambda: SQUARE, WHITE))
    for clockwise in (False, True):
        yield Case("10,000-vertex disk, %s" % ("clockwise (back)" if clockwise else "ccw"),
                   "polygons", "draw",
                   "the disk, lit from the side it shows (two-sided lighting)",
                   lambda c=clockwise: plane_scene(disk(10000, clockwise=c),
                                                   [list(range(10000))]),
                   exact_polygon(lambda c=clockwise: disk(10000, clockwise=c), WHITE))
    for name, corners in (("bowtie", BOWTIE), ("pentagram", pentagram())):
        yield Case("self-intersecting: %s" % name, "polygons", "draw",
                   "fanned from vertex 0 as VTK fans it, lit as one polygon: equal to its fan "
                   "as separate triangles",
                   lambda c=corners: plane_scene(c, [list(range(len(c)))]), same_image(0),
                   reference=lambda c=corners: fan_scene(c))


def _lights():
    def case(name, kind, behaviour, color, lights, prop=None):
        # The reference, a headlit white quad, holds the coverage lighting must not change.
        return Case(name, "lights", kind, behaviour,
                    lambda: quad_scene(*lights(), prop=prop() if prop else None),
                    uniform_color(color), reference=quad_scene)

    radians = math.radians
    yield case("grazing directional light (90°)", "draw", "N·L = 0: black where covered", BLACK,
               lambda: [_light(position=(1, 0, 0))])
    yield case("directional light at 89° from the normal", "draw", "255·cos 89° = 4", (4, 4, 4),
               lambda: [_light(position=(math.sin(radians(89)), 0, math.cos(radians(89))))])
    yield case("point light at the polygon's center", "draw",
               "lit head-on (L = N, flat shading at the vertex mean), attenuation at d = 0: "
               "white", WHITE,
               lambda: [_light(position=(0, 0, 0), focal_point=(0, 0, -1), positional=True,
                               cone_angle=180)])
    yield Case("point light inside a closed sphere", "lights", "draw",
               "the outside faces its light from behind: black where covered",
               lambda: _sphere_scene([_light(position=(0, 0, 0), focal_point=(0, 0, -1),
                                             positional=True, cone_angle=180)]),
               uniform_color(BLACK), reference=lambda: _sphere_scene([]))
    for intensity, color in ((0.0, BLACK), (1e-30, BLACK), (1e30, (255, 255, 0))):
        yield case("headlight intensity %g, color (1, 0.5, 0)" % intensity,
                   "clamp" if intensity > 1 else "draw",
                   "color × intensity, saturated once: %s" % (color,), color,
                   lambda i=intensity: [_light(headlight=True, intensity=i, color=(1, 0.5, 0))])
    for values, color, kind, why in (((0, 0, 0), WHITE, "clamp", "factor capped at 1e6: white"),
                                     ((1e30, 1e30, 1e30), BLACK, "draw", "factor 1e-30: black")):
        yield case("point light, attenuation %s" % (values,), kind, why, color,
                   lambda v=values: [_light(position=(0, 0, 2), positional=True,
                                            cone_angle=180, attenuation=v)])

    # A spot at (0, 0, 2) aimed at (0.5, 0, 0): the quad's center is 14.04° off its axis.
    cos_off_axis = math.cos(math.atan2(0.5, 2.0))
    spots = ((0.0, 1.0, BLACK, "draw", "center outside a 0° cone: black"),
             (90.0, 1.0, (round(255 * cos_off_axis),) * 3, "draw",
              "cone = front hemisphere: 255·cos(14.04°) = 247"),
             (180.0, 1.0, WHITE, "draw", "no cone (a point light): white"),
             (30.0, 0.0, WHITE, "draw", "cos^0 = 1 inside the cone: white"),
             (30.0, 1e6, (round(255 * cos_off_axis ** 128),) * 3, "clamp",
              "vtkLight clamps the exponent to 128: 255·cos(14.04°)^128 = 5"))
    for angle, exponent, color, kind, why in spots:
        yield case("spot light, cone %g°, exponent %g" % (angle, exponent), kind, why, color,
                   lambda a=angle, e=exponent: [_light(position=(0, 0, 2),
                                                       focal_point=(0.5, 0, 0), positional=True,
                                                       cone_angle=a, exponent=e)])

    # Specular only (Kd 0, Ks 0.4) from a directional light 1° off the view: R·V = cos 1°.
    tilted = (math.sin(radians(1)), 0, math.cos(radians(1)))
    for power, kind, why in ((0.0, "draw", "(R·V)^0 = 1: 0.4·255 = 102"),
                             (1e6, "clamp", "vtkProperty clamps the power to 128: "
                                            "0.4·255·cos(1°)^128 = 100")):
        value = round(0.4 * 255 * math.cos(radians(1)) ** min(power, 128.0))
        yield case("specular power %g" % power, kind, why, (value,) * 3,
                   lambda: [_light(position=tilted)],
                   prop=lambda p=power: flat_property(diffuse=0.0, specular=0.4,
                                                      specular_power=p))


def _sphere_scene(lights, radius=1.0, cam=None):
    sphere = vtkSphereSource()
    sphere.SetRadius(radius)
    sphere.SetThetaResolution(24)
    sphere.SetPhiResolution(16)
    sphere.Update()
    return Scene(sphere.GetOutput(), cam or plane_camera(), lights, flat_property(), SMALL)


def _cameras():
    yield Case("camera position = focal point (0, 0, 4)", "camera", "error",
               "no view direction (the automatic headlight along it is not warned about: "
               "the camera's error says it all)",
               lambda: quad_scene(cam=camera((0, 0, 4), (0, 0, 4))),
               error=r"Camera\.focalPoint equals Camera\.position \(0, 0, 4\): there is no "
                     r"view direction")

    def at_origin():
        c = vtkCamera()  # focal point (0, 0, 0): vtkCamera moves it to (0, 0, -1e-20)
        c.SetPosition(0, 0, 0)
        c.SetClippingRange(1, 10)
        return c
    far_quad = [(x, y, -4.0) for x, y, _ in QUAD]
    yield Case("camera position = focal point (0, 0, 0)", "camera", "draw",
               "renders along focal point − position = (0, 0, −1e-20), which vtkCamera "
               "leaves, with a warning that the camera is degenerate (vtkCamera's direction "
               "of projection is 0; VTK draws nothing)",
               lambda: plane_scene(far_quad, [[0, 1, 2, 3]], cam=at_origin()),
               exact_polygon(lambda: far_quad, WHITE),
               warnings=[r"the camera is degenerate: its position was set onto its focal point"])
    yield Case("view-up parallel to the view", "camera", "error", "view-up parallel",
               lambda: quad_scene(cam=camera((0, 0, 4), (0, 0, 0), view_up=(0, 0, 1),
                                             clipping_range=(1, 10))),
               error=r"Camera\.viewUp is \(0, 0, 1\), parallel to the view direction")
    yield Case("near = far", "camera", "error",
               "far must exceed near (vtkCamera keeps (4, 4): 4 + 1e-20 = 4)",
               lambda: quad_scene(cam=camera((0, 0, 4), (0, 0, 0), clipping_range=(4, 4))),
               error=r"Camera\.farClip is 4, must be greater than Camera\.nearClip 4")
    for near in (0.0, -1.0):
        yield Case("near = %g (perspective)" % near, "camera", "error",
                   "a perspective near plane must be > 0",
                   lambda n=near: quad_scene(cam=camera((0, 0, 4), (0, 0, 0),
                                                        clipping_range=(n, 10))),
                   error=r"Camera\.nearClip \(perspective\) is %g, must be > 0" % near)
    yield Case("near = −2 (parallel projection)", "camera", "equal",
               "draws what lies in [−2, 10] along the view: equal to the camera moved back by "
               "4 with range [2, 14]",
               lambda: _parallel_scene(0.0, (-2.0, 10.0)), same_image(),
               reference=lambda: _parallel_scene(4.0, (2.0, 14.0)))
    yield Case("camera inside a closed sphere", "camera", "draw",
               "sees the inside (back faces, lit by two-sided lighting): every pixel covered",
               lambda: _sphere_scene([], radius=2.0,
                                     cam=camera((0, 0, 0), (0, 0, -1), clipping_range=(0.01, 10))),
               _everything_lit)
    floor = [(-3.0, -1.0, -6.0), (3.0, -1.0, -6.0)]
    for w, label in ((0.0, "0"), (1e-300, "−1e-300 (behind the eye)")):
        corners = floor + [(0.0, -1.0, w)]
        yield Case("vertex at w = %s" % label, "camera", "clip",
                   "clipped at the near plane: covers exactly the pixel centers that see the "
                   "triangle beyond it",
                   lambda c=corners: plane_scene(c, [[0, 1, 2]], cam=_eye_camera((0.1, 100))),
                   exact_polygon(lambda c=corners: c))
    huge = [(-1e15, -1e15, -5.0), (1e15, -1e15, -5.0), (0.0, 1e15, -5.0)]
    yield Case("vertices 4.5e16 px off screen (fixed point: ±2^23)", "camera", "clip",
               "clipped to the guard band: every pixel covered, depth exact (to the float)",
               lambda: plane_scene(huge, [[0, 1, 2]], cam=_eye_camera((1.0, 10.0))),
               _whole_image_at_depth(5.0))


def _eye_camera(clipping):
    return camera((0.0, 0.0, 0.0), (0.0, 0.0, -1.0), clipping_range=clipping)


def _parallel_scene(back, clipping):
    """Two quads at z = 1 and z = −3 seen by a parallel camera at z = back."""
    points = [(x, y, 1.0) for x, y, _ in SQUARE] + [(1.5 * x, 0.5 * y, -3.0) for x, y, _ in QUAD]
    return Scene(polydata(points, [[0, 1, 2, 3], [4, 5, 6, 7]], [(200, 0, 0), (0, 200, 0)]),
                 camera((0.0, 0.0, back), (0.0, 0.0, back - 1.0), clipping_range=clipping,
                        parallel_scale=1.2))


def _everything_lit(render, reference, scene):
    covered = int(np.count_nonzero(render.covered))
    darkest = int(render.rgba[..., :3][render.covered].max(axis=1).min()) if covered else 0
    return Verdict(covered == render.covered.size and darkest > 0,
                   "%d of %d px covered, darkest %d" % (covered, render.covered.size, darkest))


def _whole_image_at_depth(view_depth):
    def measure(render, reference, scene):
        expected = window_depth(scene.camera, view_depth)
        covered = int(np.count_nonzero(render.covered))
        error = float(np.abs(render.depth.astype(float) - expected).max())
        ulp = float(np.spacing(np.float32(expected)))
        return Verdict(covered == render.covered.size and error <= ulp,
                       "%d of %d px covered, depth error %.2g (1 ulp = %.2g)"
                       % (covered, render.covered.size, error, ulp))
    return measure


SKIPPED_NON_FINITE = r"skipped 1 cells that use points with NaN or infinite coordinates"
def _inputs():
    triangle = [(-0.5, -0.5, 0.0), (0.5, -0.5, 0.0), (0.0, 0.5, 0.0)]
    for label, value in (("NaN", float("nan")), ("+Inf", float("inf"))):
        bad = triangle + [(value, 0.7, 0.0)]
        yield Case("%s coordinate" % label, "input", "skip",
                   "its cell skipped and counted, with warning W: equal to the rest alone",
                   lambda b=bad: plane_scene(b, [[0, 1, 2], [0, 1, 3]]), same_image(0),
                   reference=lambda: plane_scene(triangle, [[0, 1, 2]]),
                   warnings=[SKIPPED_NON_FINITE], counts={"PolygonsNonFinite": 1})
        yield Case("%s coordinate, automatic camera" % label, "input", "skip",
                   "its cell skipped with warning W and its point left out of the camera's "
                   "bounds: equal to the rest alone",
                   lambda b=bad: _automatic(b, [[0, 1, 2], [0, 1, 3]]), same_image(0),
                   reference=lambda: _automatic(triangle, [[0, 1, 2]]),
                   warnings=[SKIPPED_NON_FINITE], counts={"PolygonsNonFinite": 1})
    for exponent in (15, 300):
        tall = triangle[:2] + [(0.0, 10.0 ** exponent, 0.0)]
        yield Case("1e%d coordinate" % exponent, "input", "clip",
                   "a 1 × 1e%d triangle, 1 unit wide on screen: its normal comes from its "
                   "largest angle (not its size), so it is clipped to the guard band and "
                   "covers exactly the pixel centers inside it, lit" % exponent,
                   lambda t=tall: plane_scene(t, [[0, 1, 2]]),
                   exact_polygon(lambda t=tall: t, WHITE))
    yield Case("1e300 coordinate, automatic camera", "input", "draw",
               "the camera fits the bounds clamped to ±1e100 and stays finite; from there "
               "the data is far below a pixel: nothing drawn, no message",
               lambda: _automatic(triangle[:2] + [(0.0, 1e300, 0.0)], [[0, 1, 2]]),
               _finite_camera_nothing_drawn)
    for label, ids in (("out-of-range point id (7 of 3)", [0, 1, 7]),
                       ("negative point id", [0, 1, -1])):
        yield Case(label, "input", "error", "names the id and its cell; output empty",
                   lambda i=ids: plane_scene(triangle, [[0, 1, 2], i]),
                   error=r"the input's polys: polygons\.connectivity\[5\] is %d, outside "
                         r"\[0, points\.count\) \(polygon 1\)" % ids[2])
    yield Case("empty cells (0, 1 and 2 points)", "input", "skip",
               "skipped and counted, no warning: equal to the rest alone",
               lambda: plane_scene(triangle, [[0, 1, 2], [], [0], [0, 1]]), same_image(0),
               reference=lambda: plane_scene(triangle, [[0, 1, 2]]),
               counts={"PolygonsDegenerate": 3, "PolygonsDrawn": 1})
    yield Case("1 × 1 image", "input", "draw", "the one pixel center: the quad, white",
               lambda: quad_scene(size=(1, 1)), exact_polygon(lambda: QUAD, WHITE))
    yield Case("16384 × 16384 image", "input", "draw",
               "the largest size (4.5 GiB of output planes): the quad's exact pixels",
               lambda: quad_scene(size=(16384, 16384)), _quad_rectangle)
    for w, h in ((65536, 65536), (2 ** 31 - 1, 2 ** 31 - 1), (0, 0)):
        yield Case("size %d × %d" % (w, h), "input", "error",
                   "each side must be in [1, 16384] (so no byte count overflows); output empty",
                   lambda w=w, h=h: quad_scene(size=(w, h)),
                   error=r"Size is %d x %d; each side must be in \[1, 16384\] pixels" % (w, h))


def _automatic(points, polys):
    return Scene(polydata(points, polys), None, [], flat_property(), SMALL)


def _dropped_as_degenerate(corners_of):
    def measure(render, reference, scene):
        exact = convex_polygon_coverage(scene.camera, scene.size, corners_of()).inside
        count = int(np.count_nonzero(render.covered))
        return Verdict(count == 0, "%d px (the exact triangle: %d px)"
                       % (count, np.count_nonzero(exact)))
    return measure


def _finite_camera_nothing_drawn(render, reference, scene):
    position, focal = render.camera
    finite = bool(np.isfinite(position).all() and np.isfinite(focal).all())
    count = int(np.count_nonzero(render.covered))
    return Verdict(finite and count == 0,
                   "camera %s, %d px" % ("finite" if finite else "NOT finite", count))


def _quad_rectangle(render, reference, scene):
    """The quad at 16384²: the covered pixels form the rectangle whose columns and rows are
    those of the pixel centers inside it (1-D, exact), all white."""
    width, height = scene.size
    half_height = 4.0 * math.tan(math.radians(scene.camera.GetViewAngle()) / 2.0)  # at z = 0
    half_width = half_height * width / height
    columns = np.abs(((np.arange(width) + 0.5) * 2.0 / width - 1.0) * half_width) < 1.0
    rows = np.abs(((np.arange(height) + 0.5) * 2.0 / height - 1.0) * half_height) < 0.75
    covered = render.covered
    shown_columns, shown_rows = covered.any(axis=0), covered.any(axis=1)
    count = int(np.count_nonzero(covered))
    exact = (count == int(shown_columns.sum()) * int(shown_rows.sum()) and
             bool((shown_columns == columns).all() and (shown_rows == rows).all()))
    white = bool((render.rgba[height // 2, width // 2, :3] == 255).all())
    return Verdict(exact and white, "%d px, %s rectangle, %s" % (
        count, "the exact" if exact else "NOT the exact", "white" if white else "not white"))


CASES = [*_translations(), *_scales(), *_near_far_ratios(), *_depth_pairs(), *_polygons(),
         *_lights(), *_cameras(), *_inputs()]
BY_NAME = {case.name: case for case in CASES}
assert len(BY_NAME) == len(CASES), "case names must be unique"
assert all(case.kind in ("equal", "draw", "skip", "clamp", "clip", "error") for case in CASES)
