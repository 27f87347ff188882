"""One catalogue case through VTK's own OpenGL pipeline, in a process of its own (VTK may
crash or hang on some): `vtk_side.py "CASE NAME" OUT.npz` renders the case's scene (and its
reference scene) and saves the planes and the messages VTK's output window received.
`run_vtk(case)` does that in a subprocess with a timeout and an address-space limit, and
returns a `VtkOutcome`. Needs an X server (report.py runs under tests/plugin/xvfb_run.sh).
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
    reference: Render = None
    log: str = ""              # the process's stderr, when it did not render


def _save(path, render, reference):
    arrays = {"rgba": render.rgba, "depth": render.depth,
              "camera": np.array(render.camera, dtype=float)}
    if reference is not None:
        arrays.update(reference_rgba=reference.rgba, reference_depth=reference.depth)
    messages = [[m.kind, m.source, m.text] for m in render.messages]
    np.savez(path, messages=json.dumps(messages), **arrays)


def _load(path, has_reference):
    data = np.load(path)
    render = Render(rgba=data["rgba"], depth=data["depth"],
                    messages=[Message(*m) for m in json.loads(str(data["messages"]))],
                    camera=tuple(map(tuple, data["camera"])))
    reference = None
    if has_reference:
        reference = Render(rgba=data["reference_rgba"], depth=data["reference_depth"])
    return render, reference


def _limit_memory():
    resource.setrlimit(resource.RLIMIT_AS, (ADDRESS_SPACE_BYTES, ADDRESS_SPACE_BYTES))


def _run_once(case, path, attempts=3):
    """(status, stderr) of one run; an X connection that fails under load (see
    tests/plugin/xvfb_run.sh) is tried again."""
    for _ in range(attempts):
        try:
            process = subprocess.run(
                [sys.executable, os.path.abspath(__file__), case.name, path],
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


def run_vtk(case):
    """The case through VTK in a subprocess. A crash is tried once more, to tell VTK's
    behaviour on the case from a crash that does not come back."""
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "vtk.npz")
        status, log = _run_once(case, path)
        if status.startswith("crashed"):
            again, again_log = _run_once(case, path)
            if again == "rendered":
                status = "rendered (%s once, not again)" % status.replace(" (", ": ")[:-1]
            else:
                log = again_log
        if not status.startswith("rendered"):
            return VtkOutcome(status, log=log)
        render, reference = _load(path, case.reference is not None)
        return VtkOutcome(status, render, reference)


def main(name, path):
    sys.path.insert(0, HERE)
    from cases import BY_NAME
    from scene import render_vtk
    case = BY_NAME[name]
    render = render_vtk(case.scene())
    reference = render_vtk(case.reference()) if case.reference is not None else None
    _save(path, render, reference)


if __name__ == "__main__":
    main(*sys.argv[1:])
