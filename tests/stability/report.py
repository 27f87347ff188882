"""`make stability-report`: every catalogue case through Facet (vtkFacetRenderFilter, in this
process) and through VTK's own OpenGL pipeline (a subprocess per case, with a timeout), in
one run; prints a Markdown table per group of cases: Facet's stated behaviour, what Facet
did, what VTK did, and the measured deviation. Needs an X server for VTK (the make target
runs it under tests/plugin/xvfb_run.sh); --facet-only does without.

    report.py [--facet-only] [-k SUBSTRING ...] [--output FILE]
"""
import argparse
import datetime
import os
import subprocess
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cases import CASES  # noqa: E402
from checks import FILTER, problems, run_facet  # noqa: E402
from scene import difference  # noqa: E402
from vtk_side import run_vtk  # noqa: E402

COMMAND = "make stability-report"


def cell(text):
    return text.replace("|", "\\|").replace("\n", " ")


def short(text, limit=70):
    text = " ".join(text.split())
    return text if len(text) <= limit else text[:limit - 1] + "…"


def pixels(render):
    count = int(np.count_nonzero(render.covered))
    return "draws %d px" % count if count else "draws nothing"


def vtk_summary(case, outcome):
    if outcome.render is None:
        last = [line for line in outcome.log.splitlines() if line.strip()][-1:]
        return outcome.status + (": " + short(last[0], 60) if last else "")
    render = outcome.render
    text = pixels(render)
    if tuple(reversed(render.rgba.shape[:2])) != tuple(case.scene().size):
        text += " in a %d × %d window" % render.rgba.shape[1::-1]
    said = render.errors() or render.warnings()
    if said:
        text += "; says: " + short(said[0])
    return text


def facet_cell(case, facet, found):
    mark = "✓" if not found else "✗ (%s)" % short("; ".join(found), 120)
    return "%s %s" % (mark, facet.summary())


def measured(case, facet, vtk):
    """The case's measure on each renderer, and Facet against VTK where both drew."""
    parts = []
    if case.measure is not None and not case.error and facet.verdict is not None:
        parts.append("Facet: " + facet.verdict.text)
    vtk_render = vtk.render if vtk is not None else None
    same_shape = (vtk_render is not None and facet.render.ok and
                  vtk_render.rgba.shape == facet.render.rgba.shape)
    if vtk_render is not None and case.measure is not None and (
            vtk.reference is not None or case.reference is None):
        try:
            verdict = case.measure(vtk_render, vtk.reference, case.scene())
            parts.append("VTK: %s %s" % ("✓" if verdict.ok else "✗", verdict.text))
        except Exception as error:  # a measure meant for a rendered image of the stated size
            parts.append("VTK: not measurable (%s)" % short(str(error), 50))
    if same_shape and not case.error:
        parts.append("Facet vs VTK: %s" % difference(facet.render, vtk_render))
    return " · ".join(parts) or "—"


def machine():
    return "%d cores, load average %.1f at the start" % (os.cpu_count(), os.getloadavg()[0])


def vtk_about():
    """VTK's version and the OpenGL renderer it gets (from a subprocess, like the cases)."""
    script = ("import vtkmodules.vtkRenderingOpenGL2\n"
              "from vtkmodules.vtkCommonCore import vtkVersion\n"
              "from vtkmodules.vtkRenderingCore import vtkRenderWindow\n"
              "w = vtkRenderWindow(); w.SetOffScreenRendering(1); w.Render()\n"
              "lines = w.ReportCapabilities().splitlines()\n"
              "print('VTK', vtkVersion.GetVTKVersion(), '·', *[l.split(':', 1)[1].strip()"
              " for l in lines if 'renderer string' in l or 'version string' in l])\n")
    try:
        result = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                                timeout=60)
        return result.stdout.strip() or "VTK: no OpenGL context (%s)" % short(result.stderr, 80)
    except subprocess.TimeoutExpired:
        return "VTK: no OpenGL context (timed out)"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--facet-only", action="store_true", help="leave VTK out")
    parser.add_argument("-k", action="append", default=[], metavar="SUBSTRING",
                        help="only the cases whose name contains it (repeatable)")
    parser.add_argument("--output", help="also write the report to this file")
    args = parser.parse_args()
    cases = [c for c in CASES if not args.k or any(k in c.name for k in args.k)]

    start = time.time()
    header = ["# Stability catalogue: Facet against VTK", "",
              "`%s`, %s; %s; %s." % (COMMAND, datetime.date.today().isoformat(), machine(),
                                     "VTK left out" if args.facet_only else vtk_about()),
              "", "Each case is built as a VTK user builds it (vtkPolyData, vtkCamera, vtkLight, "
              "vtkProperty) and rendered by vtkFacetRenderFilter and by VTK's OpenGL pipeline "
              "(vtkPolyDataMapper, flat interpolation, multisampling off, the same camera and "
              "lights; a subprocess per case). ✓/✗: the outcome is/is not what Facet states; "
              "the same measure is applied to VTK's image. *Silhouette px*: pixels covered in "
              "one image and not the other; *color Δ*: the largest channel difference where "
              "both cover (a pixel on an interior edge showing the neighbouring polygon "
              "counts). Against the unit scene, each renderer is compared with its own "
              "rendering of it. The cases are in tests/stability/cases.py; `make test` "
              "asserts Facet's side."]
    lines, defects = [], []
    tally = {"as stated": 0, "not as stated": 0, "VTK crashed": 0, "VTK timed out": 0}
    group = None
    for case in cases:
        if case.group != group:
            group = case.group
            lines += ["", "## " + group[0].upper() + group[1:], "",
                      "| Case | Facet states | Facet does | VTK does | Measured |",
                      "|---|---|---|---|---|"]
        facet = run_facet(case)
        found = problems(case, facet)
        tally["as stated" if not found else "not as stated"] += 1
        vtk = None if args.facet_only else run_vtk(case)
        if vtk is not None and vtk.status.startswith("crashed"):
            tally["VTK crashed"] += 1
        if vtk is not None and vtk.status.startswith("timed out"):
            tally["VTK timed out"] += 1
        name = case.name + (" **(known defect)**" if case.defect else "")
        if case.defect:
            defects.append("- **%s**: %s" % (case.name, case.defect))
        stated = "**%s**: %s" % (case.kind, case.behaviour)
        if case.error:
            stated += " — error “%s”" % case.error.replace("\\", "")
        if case.warnings:
            stated += " — warning “%s”" % "”, “".join(w.replace("\\", "") for w in case.warnings)
        lines.append("| %s |" % " | ".join(cell(text) for text in (
            name, stated, facet_cell(case, facet, found),
            "—" if vtk is None else vtk_summary(case, vtk), measured(case, facet, vtk))))
        print("%-55s %s" % (case.name, "as stated" if not found else "NOT AS STATED"),
              file=sys.stderr, flush=True)
    summary = ["", "%d cases in %.0f s: Facet as stated in %d (%d of them known defects), not "
               "as stated in %d%s." % (len(cases), time.time() - start, tally["as stated"],
                                       len(defects), tally["not as stated"],
                                       "" if args.facet_only else
                                       "; VTK crashed in %d, timed out in %d"
                                       % (tally["VTK crashed"], tally["VTK timed out"]))]
    if defects:
        summary += ["", "Known defects (the statement is today's behaviour, to flip when "
                        "fixed):", ""] + defects
    report = "\n".join(header + summary + lines) + "\n"
    print(report)
    if args.output:
        with open(args.output, "w", encoding="utf-8") as out:
            out.write(report)
    return 0 if tally["not as stated"] == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
