#!/usr/bin/env python3
"""Two builds, the same meshes: byte comparison of their outputs on every model.

    /usr/bin/python3 bench/identical.py BASE_BUILD NEW_BUILD [files...]

Each build folder holds a `sizemesh` binary. Every model of tests/data is
meshed by both at default settings (`-o mesh.msh --background bg.vtu`, two
threads; the mesh does not depend on the thread count), and each half wing
also with a box far field and its symmetry plane; the .msh files (and the
background .vtu, unless --mesh-only) must be byte-identical. A refactoring that claims not to
change behaviour is checked with it. Prints a line per run; exits 1 when any
output differs or either build fails where the other does not.
"""
import argparse
import filecmp
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from models import DIR, MODELS  # noqa: E402
from corpus import HALF_MODELS  # noqa: E402


def run(binary, model, extra, out, timeout):
    os.makedirs(out, exist_ok=True)
    cmd = [binary, os.path.join(DIR, model), "-o", os.path.join(out, "mesh.msh"),
           "--background", os.path.join(out, "bg.vtu"), "--threads", "2", "-q"] + extra
    try:
        return subprocess.run(cmd, capture_output=True, timeout=timeout).returncode
    except subprocess.TimeoutExpired:
        return 124


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("base")
    ap.add_argument("new")
    ap.add_argument("--timeout", type=float, default=300)
    ap.add_argument("--mesh-only", action="store_true",
                    help="compare the meshes only (when a change adds a field to the background's file)")
    ap.add_argument("files", nargs="*", default=MODELS)
    a = ap.parse_args()
    runs = [(m, []) for m in a.files]
    runs += [(m, ["--farfield", "box", "--symmetry", HALF_MODELS[m]]) for m in a.files if m in HALF_MODELS]
    bad = 0
    with tempfile.TemporaryDirectory() as tmp:
        for i, (model, extra) in enumerate(runs):
            outs, codes = [], []
            for side, build in (("base", a.base), ("new", a.new)):
                out = os.path.join(tmp, f"{i}_{side}")
                codes.append(run(os.path.join(build, "sizemesh"), model, extra, out, a.timeout))
                outs.append(out)
            # Both failing to mesh proves nothing: counted as a difference.
            same = codes[0] == codes[1] and os.path.exists(os.path.join(outs[0], "mesh.msh"))
            for name in ("mesh.msh",) if a.mesh_only else ("mesh.msh", "bg.vtu"):
                p, q = (os.path.join(o, name) for o in outs)
                if os.path.exists(p) != os.path.exists(q) or (os.path.exists(p) and not filecmp.cmp(p, q, shallow=False)):
                    same = False
            bad += not same
            label = model + ("" if not extra else " " + " ".join(extra))
            print(f"{label:60s} exit {codes[0]}/{codes[1]}  {'identical' if same else 'DIFFERENT'}", flush=True)
    print(f"{len(runs) - bad} of {len(runs)} runs identical")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
