"""Catalogue cases through VTK's own OpenGL pipeline, each image in a process of its own (VTK
may crash or hang on some): `vtk_side.py "CASE NAME" scene|reference OUT.npz` renders the
case's scene or its reference scene and saves the planes and the messages VTK's output
window received. `run_vtk(case)` does so in subprocesses with a timeout and an
address-space limit, and returns a `VtkOutcome`. Needs an X server (report.py runs under
tests/plugin/xvfb_run.sh).

One image per process: with VTK 9.1 on Mesa's llvmpipe under Xvfb, a second render window
rendering in the same process aborts about one time in ten (measured: 6 of 60 runs with a
scene and its reference, 0 of 60 with one image; not told apart then, it may have been the X
server's reset between the two windows that tests/plugin/xvfb_run.sh now turns off).
"""
import json
import os
import resource
import signal
import subprocess
import sys
import tempfile
from dataclasses import dataclass

import numpy as np

from scene import Message, Render

HERE = os.path.dirname(os.path.abspath(__file__))
TIMEOUT_SECONDS = 120
ADDRESS_SPACE_BYTES = 16 << 30  # a case asking for an absurd window fails, not the machine
NO_X_CONNECTION = "bad X server connection"


@dataclass
class VtkOutcome:
    status: str                # "rendered", "crashed (SIGSEGV)", "timed out (120 s)", ...
    render: Render = None
    reference: Render = None   # the reference scene's image, when the case has one
    log: str = ""              # the process's stderr, when it did not render


def _save(path, render):
    messages = [[m.kind, m.source, m.text] for m in render.messages]
    np.savez(path, rgba=render.rgba, depth=render.depth,
             camera=np.array(render.camera, dtype=float), messages=json.dumps(messages))


def _load(path):
    data = np.load(path)
    return Render(rgba=data["rgba"], depth=data["depth"],
                  messages=[Message(*m) for m in json.loads(str(data["messages"]))],
                  camera=tuple(map(tuple, data["camera"])))


def _limit_memory():
    resource.setrlimit(resource.RLIMIT_AS, (ADDRESS_SPACE_BYTES, ADDRESS_SPACE_BYTES))


def _run_once(case, which, path, attempts=3):
    """(status, stderr) of one process; VTK's "bad X server connection" is tried again (an
    X server that resets when its last client leaves can drop the next case's connection;
    tests/plugin/xvfb_run.sh starts Xvfb with -noreset, another server may not)."""
    for _ in range(attempts):
        try:
            process = subprocess.run(
                [sys.executable, os.path.abspath(__file__), case.name, which, path],
                capture_output=True, text=True, timeout=TIMEOUT_SECONDS,
                preexec_fn=_limit_memory)
        except subprocess.TimeoutExpired:
            return "timed out (%d s)" % TIMEOUT_SECONDS, ""
        if process.returncode == 0 or NO_X_CONNECTION not in process.stderr:
            break
    if process.returncode < 0:
        return "crashed (%s)" % signal.Signals(-process.returncode).name, process.stderr
    if process.returncode > 0:
        return "failed (exit %d)" % process.returncode, process.stderr
    return "rendered", process.stderr


def _run(case, which, folder):
    """(status, Render or None, stderr). A crash is tried once more, to tell VTK's behaviour
    on the case from a crash that does not come back."""
    path = os.path.join(folder, which + ".npz")
    status, log = _run_once(case, which, path)
    if status.startswith("crashed"):
        again, again_log = _run_once(case, which, path)
        if again == "rendered":
            status = "rendered (%s once, not again)" % status.replace(" (", ": ")[:-1]
        else:
            log = again_log
    return status, _load(path) if status.startswith("rendered") else None, log


def run_vtk(case):
    with tempfile.TemporaryDirectory() as folder:
        status, render, log = _run(case, "scene", folder)
        outcome = VtkOutcome(status, render, log=log if render is None else "")
        if render is not None and case.reference is not None:
            outcome.reference = _run(case, "reference", folder)[1]
        return outcome


def main(name, which, path):
    sys.path.insert(0, HERE)
    from cases import BY_NAME
    from scene import render_vtk
    case = BY_NAME[name]
    _save(path, render_vtk(case.scene() if which == "scene" else case.reference()))


if __name__ == "__main__":
    main(*sys.argv[1:])
