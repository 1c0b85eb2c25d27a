"""examples/paraview_view.py draws the M6 wing's mesh and background mesh with ParaView, off-screen:
sizemesh writes M6.vtu and M6_bg.vtu, pvpython renders one PNG per field, and each PNG must have the
size asked for and show the model in colours of a colour map (not a blank or one-colour picture).

Usage: paraview_check.py SIZEMESH_BINARY MODEL WORKDIR [PVPYTHON]
Exit status: 0 pass, 1 fail (one line says why), 77 skipped (no pvpython).
"""
import os
import re
import shutil
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
VIEW_SCRIPT = os.path.join(HERE, "..", "examples", "paraview_view.py")
SIZE = (800, 480)
EXPECTED = ["M6_target_size.png", "M6_min_angle.png", "M6_limited_by.png", "M6_bg_h_smoothed.png",
            "M6_bg_limited_by.png"]
# The model's part of a picture (the colour bar is on the right, past 80% of the width) must be at
# least DRAWN covered, at least COLOURED of that in saturated colours, with at least COLOURS of them.
DRAWN, COLOURED, COLOURS = 0.10, 0.05, 12


class Failure(Exception):
    pass


def run(command, log, what):
    with open(log, "w") as out:
        status = subprocess.run(command, stdout=out, stderr=subprocess.STDOUT, timeout=600).returncode
    if status != 0:
        # The telling line: an error of VTK's log or Python's, else the last line that is not a stack frame.
        lines = [re.sub(r"\x1b\[[0-9;]*m", "", l).strip() for l in open(log, errors="replace")]
        lines = [l for l in lines if l and not l[0].isdigit()]
        errors = [l for l in lines if "ERR|" in l or "Error" in l or l.startswith("paraview_view.py:")]
        last = (errors or lines or ["no output"])[-1][:240]
        raise Failure("%s exited with %d: %s (all output in %s)" % (what, status, last, log))


def check_png(path):
    import matplotlib.image

    if not os.path.isfile(path):
        raise Failure("%s was not written" % path)
    rgb = matplotlib.image.imread(path)[:, :, :3]  # floats in [0, 1]
    if (rgb.shape[1], rgb.shape[0]) != SIZE:
        raise Failure("%s is %dx%d, not %dx%d" % (path, rgb.shape[1], rgb.shape[0], SIZE[0], SIZE[1]))
    model = rgb[:, : int(0.8 * SIZE[0])].reshape(-1, 3)
    colours, counts = np.unique((model * 255).round().astype(np.uint8), axis=0, return_counts=True)
    background = colours[counts.argmax()].astype(float) / 255
    drawn = model[np.abs(model - background).max(axis=1) > 0.03]
    coloured = drawn[drawn.max(axis=1) - drawn.min(axis=1) > 0.15]
    distinct = len(np.unique((coloured * 31).round().astype(np.uint8), axis=0))  # 5 bits a channel
    summary = "%s: %.0f%% drawn, %.0f%% of it coloured, %d colours" % (
        os.path.basename(path), 100 * len(drawn) / len(model), 100 * len(coloured) / max(1, len(drawn)), distinct)
    if len(drawn) < DRAWN * len(model):
        raise Failure("%s is blank: %s (at least %d%% drawn expected)" % (path, summary, 100 * DRAWN))
    if len(coloured) < COLOURED * len(drawn) or distinct < COLOURS:
        raise Failure("%s shows no colour map: %s (at least %d%% coloured and %d colours expected)"
                      % (path, summary, 100 * COLOURED, COLOURS))
    return summary


def main():
    if len(sys.argv) not in (4, 5):
        raise Failure("usage: paraview_check.py SIZEMESH_BINARY MODEL WORKDIR [PVPYTHON]")
    binary, model, work = sys.argv[1:4]
    pvpython = sys.argv[4] if len(sys.argv) == 5 else shutil.which("pvpython")
    if not pvpython or not shutil.which(pvpython):
        print("paraview_check: skipped: no pvpython (Debian's python3-paraview)")
        sys.exit(77)
    os.makedirs(work, exist_ok=True)
    for name in EXPECTED:
        if os.path.exists(os.path.join(work, name)):
            os.remove(os.path.join(work, name))
    mesh, background = os.path.join(work, "M6.vtu"), os.path.join(work, "M6_bg.vtu")
    run([binary, model, "-q", "-o", mesh, "--background", background], os.path.join(work, "sizemesh.log"),
        "sizemesh")
    run([pvpython, VIEW_SCRIPT, mesh, "--background", background, "--out", work, "--size", "%dx%d" % SIZE],
        os.path.join(work, "pvpython.log"), "pvpython examples/paraview_view.py")
    summaries = [check_png(os.path.join(work, name)) for name in EXPECTED]
    print("paraview_view.py drew %d pictures %dx%d:\n  %s" % (len(EXPECTED), SIZE[0], SIZE[1], "\n  ".join(summaries)))


if __name__ == "__main__":
    try:
        main()
    except Failure as e:
        print("paraview_check: FAIL: %s" % e, file=sys.stderr)
        sys.exit(1)
    except subprocess.TimeoutExpired as e:
        print("paraview_check: FAIL: timed out after %d s: %s" % (e.timeout, " ".join(e.cmd)), file=sys.stderr)
        sys.exit(1)
