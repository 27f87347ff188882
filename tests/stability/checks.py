"""Running a catalogue case through Facet and checking what it did.

`run_facet(case)` renders the case (and its reference scene) with vtkFacetRenderFilter and
returns a `FacetOutcome`; `problems(case, outcome)` lists every way the outcome departs from
the case's statement and from the checks every render must pass (empty: as stated):
- the filter's errors and warnings are exactly those the case states (VTK's executive adds
  its "returned failure" error after a filter error, nothing else may speak);
- with an error: the output is empty;
- without: Depth finite and in [0, 1], CellId in [-1, number of cells), background pixels
  (CellId -1) at depth 1 in the background color, the FacetCounts the case states, and the
  case's own measure holds.
"""
import re
from dataclasses import dataclass

import numpy as np

from scene import render_facet

FILTER = "vtkFacetRenderFilter"
EXECUTIVE_FAILURE = re.compile(r"Algorithm vtkFacetRenderFilter\(0x[0-9a-f]+\) returned failure")


@dataclass
class FacetOutcome:
    render: object
    reference: object = None   # the reference scene's render, when the case has one
    verdict: object = None     # the case's measure, when it rendered

    def summary(self):
        """What Facet did, in a few words (for the report)."""
        errors = self.render.errors(FILTER)
        if errors:
            return "error: " + short(errors[0].replace("cannot render: ", ""))
        text = drawn(self.render)
        warnings = self.render.warnings(FILTER)
        if warnings:
            text += "; warns: " + "; ".join(short(w) for w in warnings)
        return text


def drawn(render):
    count = int(np.count_nonzero(render.covered))
    return "draws %d px" % count if count else "draws nothing"


def short(text, limit=90):
    """The text on one line, cut to `limit` characters."""
    text = " ".join(text.split())
    return text if len(text) <= limit else text[:limit - 1] + "…"


def run_facet(case):
    outcome = FacetOutcome(render_facet(case.scene()))
    if case.reference is not None:
        outcome.reference = render_facet(case.reference())
    if outcome.render.ok and case.measure is not None and not case.error:
        outcome.verdict = case.measure(outcome.render, outcome.reference, case.scene())
    return outcome


def problems(case, outcome):
    render = outcome.render
    found = _message_problems(case, render)
    if case.error:
        if render.ok:
            found.append("rendered an image although the case states an error")
        return found
    if not render.ok:
        return found + ["no image"]
    found += universal_problems(render, case.scene())
    for name, count in case.counts.items():
        if render.counts.get(name) != count:
            found.append("FacetCounts %s is %s, not %d" % (name, render.counts.get(name), count))
    if outcome.reference is not None and outcome.reference.messages:
        found.append("the reference scene's render spoke: %s" % outcome.reference.messages)
    if outcome.verdict is not None and not outcome.verdict.ok:
        found.append("not as stated (%s): %s" % (case.behaviour, outcome.verdict.text))
    return found


def _message_problems(case, render):
    found = []
    errors = render.errors(FILTER)
    warnings = render.warnings(FILTER)
    expected_errors = [case.error] if case.error else []
    for kind, said, stated in (("error", errors, expected_errors),
                               ("warning", warnings, case.warnings)):
        for pattern in stated:
            if not any(re.search(pattern, text) for text in said):
                found.append("no %s matching %r (said: %s)" % (kind, pattern, said))
        for text in said:
            if not any(re.search(pattern, text) for pattern in stated):
                found.append("unexpected %s: %s" % (kind, text))
    for message in render.messages:
        if message.source == FILTER:
            continue
        if errors and message.kind == "error" and EXECUTIVE_FAILURE.search(message.text):
            continue
        found.append("unexpected %s from %s: %s" % (message.kind, message.source or "VTK",
                                                     message.text))
    return found


def universal_problems(render, scene):
    """What every rendered image must satisfy, with the numbers when it does not. (Written
    for 16384² images too: no fancy indexing, which would copy gigabytes.)"""
    found = []
    depth, cell_id = render.depth, render.cell_id
    non_finite = depth.size - np.count_nonzero(np.isfinite(depth))
    if non_finite:
        found.append("Depth has %d non-finite values" % non_finite)
    low, high = float(depth.min()), float(depth.max())
    if low < 0.0 or high > 1.0:
        found.append("Depth spans [%r, %r], outside [0, 1]" % (low, high))
    cells = scene.polydata.GetNumberOfCells()
    ids_low, ids_high = int(cell_id.min()), int(cell_id.max())
    if ids_low < -1 or ids_high >= cells:
        found.append("CellId spans [%d, %d], outside [-1, %d)" % (ids_low, ids_high, cells))
    background = cell_id < 0
    off_depth = np.count_nonzero(background & (depth != 1.0))
    if off_depth:
        found.append("%d background pixels have a depth other than 1" % off_depth)
    expected = np.round(np.array(scene.background) * 255.0)
    rgba = render.rgba
    off_color = background & ((rgba[..., 0] != expected[0]) | (rgba[..., 1] != expected[1]) |
                              (rgba[..., 2] != expected[2]))
    if off_color.any():
        found.append("%d background pixels are not the background color"
                     % np.count_nonzero(off_color))
    return found
