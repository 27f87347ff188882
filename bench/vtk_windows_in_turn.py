#!/usr/bin/env python3
"""VTK render windows one after another, as bench/compare_vtk.py makes them, counting the
processes that abort on VTK's "bad X server connection" (bench/peers-runs.md).

Each of --processes processes in turn makes --windows windows with vtk_seconds_per_frame
(a new vtkRenderWindow per call, deleted on return, which closes its X connection;
multisampling off and VTK's default in turn), small (96 x 64), one frame each. Without
Xvfb's -noreset the server resets whenever the last window has closed, and the next window,
connecting milliseconds later, may be dropped by that reset:

    xvfb-run -a -s "-screen 0 1920x1080x24" /usr/bin/python3 bench/vtk_windows_in_turn.py
    tests/plugin/xvfb_run.sh /usr/bin/python3 bench/vtk_windows_in_turn.py   # -noreset
"""
import argparse
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))


def windows_in_turn(windows, log):
    """The child: `windows` windows, a line in `log` after each one rendered."""
    sys.path.insert(0, HERE)
    import compare_vtk
    compare_vtk.WIDTH, compare_vtk.HEIGHT = 96, 64
    with open(log, "a") as out:
        for i in range(windows):
            compare_vtk.vtk_seconds_per_frame(20, 1, 0 if i % 2 == 0 else None)
            out.write("rendered\n")
            out.flush()


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--processes", type=int, default=10)
    parser.add_argument("--windows", type=int, default=20, help="windows per process")
    parser.add_argument("--child-log", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.child_log:
        return windows_in_turn(args.windows, args.child_log)

    log = f"/tmp/vtk_windows_in_turn.{os.getpid()}"
    aborted = other = 0
    try:
        for _ in range(args.processes):
            child = subprocess.run(
                [sys.executable, __file__, "--windows", str(args.windows), "--child-log", log],
                capture_output=True, text=True)
            if child.returncode != 0:
                if "bad X server connection" in child.stderr:
                    aborted += 1
                else:
                    other += 1
                    print(child.stderr[-2000:], file=sys.stderr)
        rendered = 0
        if os.path.exists(log):
            with open(log) as lines:
                rendered = sum(1 for _ in lines)
    finally:
        if os.path.exists(log):
            os.remove(log)
    print(f"DISPLAY={os.environ.get('DISPLAY')}: windows rendered {rendered} of "
          f"{args.processes * args.windows}; processes aborted on bad X server connection "
          f"{aborted} of {args.processes}; other failures {other}")
    return 1 if aborted or other else 0


if __name__ == "__main__":
    sys.exit(main())
