#!/usr/bin/python3
"""Draws facet-render --report's CSV: RMSE against render time, log-log, one panel per group
(the sphere sweep, each mesh), a marker per mode and a color per sample count, and the Pareto
front (the renders no other render beats in both time and error) as a line.

usage: facet_report_plot.py REPORT.csv REPORT.png
"""

import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

MARKERS = {"flat": "s", "Gouraud": "^", "Phong": "o"}
COLORS = {1: "tab:blue", 4: "tab:orange", 16: "tab:green"}


def pareto_front(points):
    """The points not beaten in both coordinates, by increasing time."""
    front, best = [], math.inf
    for time, error, *_ in sorted(points):
        if error < best:
            front.append((time, error))
            best = error
    return front


def marker_of(mode):
    return MARKERS.get(mode, "D")  # adaptive


def main(csv_path, png_path):
    with open(csv_path, newline="") as f:
        rows = list(csv.DictReader(f))
    groups = list(dict.fromkeys(row["group"] for row in rows))
    columns = min(3, len(groups))
    lines = math.ceil(len(groups) / columns)
    figure, axes = plt.subplots(lines, columns, figsize=(5.5 * columns, 4.5 * lines), squeeze=False)
    for axis, group in zip(axes.flat, groups):
        points = [(float(r["time_ms"]), float(r["rmse"]), r) for r in rows if r["group"] == group]
        for time, error, row in points:
            axis.scatter(time, error, marker=marker_of(row["mode"]),
                         color=COLORS[int(row["samples"])], s=28, alpha=0.8)
        front = pareto_front(points)
        axis.plot([p[0] for p in front], [p[1] for p in front], color="black", lw=1,
                  label="Pareto front")
        if group == "sphere":  # label the tessellations along the flat, 1-sample points
            for time, error, row in points:
                if row["mode"] == "flat" and row["samples"] == "1":
                    axis.annotate(row["mesh"].split()[-1], (time, error), fontsize=7,
                                  xytext=(3, 3), textcoords="offset points")
        axis.set_xscale("log")
        axis.set_yscale("log")
        title = group
        if group == "sphere":
            segments = sorted(int(row["mesh"].split()[-1]) for _, _, row in points)
            title += f" (against the exact sphere; {segments[0]} to {segments[-1]} segments)"
        axis.set_title(title, fontsize=10)
        axis.set_xlabel("render time, ms")
        axis.set_ylabel("RMSE, 8-bit units")
        axis.grid(True, which="both", alpha=0.3)
    for axis in list(axes.flat)[len(groups):]:
        axis.axis("off")
    handles = [plt.Line2D([], [], marker=m, ls="", color="gray", label=name)
               for name, m in list(MARKERS.items()) + [("adaptive", "D")]]
    handles += [plt.Line2D([], [], marker="o", ls="", color=c, label=f"{n} samples")
                for n, c in COLORS.items()]
    handles.append(plt.Line2D([], [], color="black", label="Pareto front"))
    figure.legend(handles=handles, loc="lower center", ncol=len(handles), fontsize=8)
    figure.tight_layout(rect=(0, 0.05, 1, 1))
    figure.savefig(png_path, dpi=110)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
