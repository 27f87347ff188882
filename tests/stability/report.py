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

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cases import CASES, Verdict  # noqa: E402
from checks import drawn, problems, run_facet, short  # noqa: E402
from scene import difference  # noqa: E402
from vtk_side import run_vtk  # noqa: E402

COMMAND = "make stability-report"


def cell(text):
    return text.replace("|", "\\|").replace("\n", " ")


def vtk_summary(case, outcome):
    if outcome.render is None:
        lines = [line for line in outcome.log.splitlines() if line.strip()]
        said = [line for line in lines if "rror" in line][:1] or lines[-1:]
        return outcome.status + (": " + short(said[0], 60) if said else "")
    render = outcome.render
    text = drawn(render)
    if outcome.status != "rendered":
        text += " (%s)" % outcome.status.replace("rendered (", "")[:-1]
    if tuple(reversed(render.rgba.shape[:2])) != tuple(case.scene().size):
        text += " in a %d × %d window" % render.rgba.shape[1::-1]
    said = render.errors() or render.warnings()
    if said:
        text += "; says: " + short(said[0])
    return text


def facet_cell(case, facet, found):
    mark = "✓" if not found else "✗ (%s)" % short("; ".join(found), 120)
    return "%s %s" % (mark, facet.summary())


def vtk_verdict(case, vtk):
    """The case's measure on VTK's image; None where the case states an error or has no
    measure, a failed Verdict where VTK drew no image."""
    if case.measure is None or case.error or vtk is None:
        return None
    if vtk.render is None:
        return Verdict(False, vtk.status)
    if case.reference is not None and vtk.reference is None:
        return Verdict(False, "no reference image")
    try:
        return case.measure(vtk.render, vtk.reference, case.scene())
    except Exception as error:  # a measure meant for an image of the stated size
        return Verdict(False, "not measurable (%s)" % short(str(error), 50))


def measured(case, facet, vtk, verdict):
    """The case's measure on each renderer, and Facet against VTK where both drew."""
    parts = []
    if facet.verdict is not None:
        parts.append("Facet: " + facet.verdict.text)
    if verdict is not None and vtk.render is not None:
        parts.append("VTK: %s %s" % ("✓" if verdict.ok else "✗", verdict.text))
    if (vtk is not None and vtk.render is not None and facet.render.ok and not case.error and
            vtk.render.rgba.shape == facet.render.rgba.shape):
        parts.append("Facet vs VTK: %s" % difference(facet.render, vtk.render))
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


EXPLANATION = (
    "Each case is built as a VTK user builds it (vtkPolyData, vtkCamera, vtkLight, "
    "vtkProperty) and rendered by vtkFacetRenderFilter and by VTK's OpenGL pipeline "
    "(vtkPolyDataMapper, flat interpolation, multisampling off, the same camera and lights; a "
    "subprocess per case). ✓/✗: the outcome is/is not what Facet states; the same measure is "
    "applied to VTK's image. *Silhouette px*: pixels covered in one image and not the other; "
    "*color Δ*: the largest channel difference where both cover (a pixel on an interior edge "
    "showing the neighbouring polygon counts). Against the unit scene, each renderer is "
    "compared with its own rendering of it. VTK's flat interpolation makes the normal flat but "
    "still lights each fragment (positional lights, spots, specular), while Facet lights a "
    "polygon once, at the mean of its vertices: where such a light varies across a polygon, "
    "the two differ by design. The cases are in tests/stability/cases.py; `make test` asserts "
    "Facet's side.")
TABLE_HEAD = ["| Case | Facet states | Facet does | VTK does | Measured |", "|---|---|---|---|---|"]


def title(group):
    return group[0].upper() + group[1:]


def stated(case):
    """The case's statement: kind, behaviour, and the messages and counts it must give."""
    text = "**%s**: %s" % (case.kind, case.behaviour)
    if case.error:
        text += " — error “%s”" % case.error.replace("\\", "")
    if case.warnings:
        text += " — warning “%s”" % "”, “".join(
            pattern.replace("\\", "") for pattern in case.warnings)
    if case.counts:
        text += " — FacetCounts " + ", ".join("%s %d" % item for item in case.counts.items())
    return text


class Report:
    """The table rows and the tallies, one case at a time."""

    def __init__(self, with_vtk):
        self.with_vtk = with_vtk
        self.lines, self.defects = [], {}  # defect: the cases it shows in
        self.groups = {}  # group: [cases, Facet as stated, VTK measured, VTK as stated, no image]
        self.vtk_statuses = []

    def add(self, case):
        if case.group not in self.groups:
            self.groups[case.group] = [0] * 5
            self.lines += ["", "## " + title(case.group), ""] + TABLE_HEAD
        facet = run_facet(case)
        found = problems(case, facet)
        vtk = run_vtk(case) if self.with_vtk else None
        verdict = vtk_verdict(case, vtk)
        tally = self.groups[case.group]
        tally[0] += 1
        tally[1] += not found
        if vtk is not None:
            self.vtk_statuses.append(vtk.status)
            tally[2] += verdict is not None
            tally[3] += verdict is not None and verdict.ok
            tally[4] += vtk.render is None
        if case.defect:
            self.defects.setdefault(case.defect, []).append(case.name)
        name = case.name + (" **(known defect)**" if case.defect else "")
        self.lines.append("| %s |" % " | ".join(cell(text) for text in (
            name, stated(case), facet_cell(case, facet, found),
            "—" if vtk is None else vtk_summary(case, vtk), measured(case, facet, vtk, verdict))))
        print("%-55s %s" % (case.name, "NOT AS STATED" if found else "as stated"),
              file=sys.stderr, flush=True)

    @property
    def not_as_stated(self):
        return sum(cases - as_stated for cases, as_stated, *_ in self.groups.values())

    def summary(self, seconds):
        count = sum(tally[0] for tally in self.groups.values())
        defective = sum(map(len, self.defects.values()))
        text = ("%d cases in %.0f s. Facet: as stated in %d (%d of the statements describe a "
                "known defect), not as stated in %d."
                % (count, seconds, count - self.not_as_stated, defective, self.not_as_stated))
        if self.with_vtk:
            statuses = [sum(s.startswith(what) for s in self.vtk_statuses)
                        for what in ("crashed", "failed", "timed out")]
            text += (" VTK: crashed in %d (each crash tried twice), failed in %d, timed out in "
                     "%d." % tuple(statuses))
        lines = ["", text, ""]
        lines += ["| Group | Cases | Facet as stated | VTK meets Facet's statement | "
                  "VTK drew no image |", "|---|--:|--:|--:|--:|"]
        for group, (cases, facet, measured_, vtk, no_image) in self.groups.items():
            meets = "%d of %d" % (vtk, measured_) if measured_ else "—"
            lines.append("| %s | %d | %d | %s | %s |" % (
                title(group), cases, facet, meets, no_image if self.with_vtk else "—"))
        if self.defects:
            lines += ["", "Known defects (the statement is today's behaviour, to flip when "
                          "fixed):", ""]
            lines += ["- %s: %s" % (", ".join("**%s**" % name for name in names), defect)
                      for defect, names in self.defects.items()]
        return lines


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
              "", EXPLANATION]
    report = Report(with_vtk=not args.facet_only)
    for case in cases:
        report.add(case)
    text = "\n".join(header + report.summary(time.time() - start) +
                     report.lines) + "\n"
    print(text)
    if args.output:
        with open(args.output, "w", encoding="utf-8") as out:
            out.write(text)
    return 1 if report.not_as_stated else 0


if __name__ == "__main__":
    sys.exit(main())
