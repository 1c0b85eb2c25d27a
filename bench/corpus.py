#!/usr/bin/env python3
"""Every model of tests/data to a wetted surface: one table.

    /usr/bin/python3 bench/corpus.py [--threads 2] [--timeout 120] [--no-tetgen] [files...]

Per model: exit status, wall time and peak memory (/usr/bin/time -v), triangles,
the union's route (how many components took each), boundary / non-manifold /
misoriented edges, intersecting triangle pairs, the share of all triangles under
12 degrees, the share under 12 degrees but those at feature corners sharper than 12 degrees (issue
"composite faces": at most 0.05%), the share under 24 degrees (at most
0.5%), how many under 12 are avoidable (not forced by a CAD corner, a
narrow face or a short curve), inverted triangles, the faces closed only by
the front's lenient run (which may accept a triangle turned against the
surface; the optimiser usually repairs it), the share sized at h_min, and TetGen's verdict on the .smesh
(`tetgen -pYQ` builds a volume only inside a closed surface free of
self-intersections). A half model (a half wing whose root lies on a
coordinate plane) is run with `--farfield box --symmetry` on that plane. Must hold (issue "every aircraft to one clean wetted surface"):
exit 0, 0 in every edge, pair, avoidable and inverted column, TetGen ok, under
20 s and 2 GB.
Prints; never fails on time.
"""
import argparse
import collections
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from models import DIR, MODELS  # noqa: E402  (bench/models.py: the one list)
ROOT = os.path.dirname(HERE)
# Half wings of tests/data and the plane their root lies on.
HALF_MODELS = {"wing_blunt_te_openvsp.stp": "y", "wing_blunt_te2_openvsp.stp": "y",
               "c172_wing_pygeo.igs": "z", "onera_m6_wing.stp": "y"}


def timed(cmd, timeout):
    """Exit status (124 on time-out), wall seconds, peak MB and stderr of one command."""
    try:
        p = subprocess.run(["/usr/bin/time", "-v"] + cmd, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return 124, float(timeout), float("nan"), ""
    wall = re.search(r"Elapsed \(wall clock\) time.*: (?:(\d+):)?(\d+):([\d.]+)", p.stderr)
    seconds = (int(wall.group(1) or 0) * 3600 + int(wall.group(2)) * 60 + float(wall.group(3))) if wall else float("nan")
    rss = re.search(r"Maximum resident set size \(kbytes\): (\d+)", p.stderr)
    return p.returncode, seconds, (int(rss.group(1)) / 1024 if rss else float("nan")), p.stderr


def tetgen_verdict(smesh, timeout):
    if not shutil.which("tetgen"):
        return "absent"
    try:
        p = subprocess.run(["tetgen", "-pYQ", smesh], capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return "timeout"
    return "ok" if p.returncode == 0 else "fails"


def routes(report):
    """Components per union route: 'B-rep union 11, not united 1'."""
    count = collections.Counter()
    for c in report.get("preparation", {}).get("components", []):
        route = c.get("route") or c.get("role", "?")
        count[route.split(":")[0]] += 1
    return ", ".join(f"{k} {n}" for k, n in count.most_common())


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--timeout", type=float, default=120)
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--no-tetgen", action="store_true")
    ap.add_argument("files", nargs="*", default=MODELS)
    a = ap.parse_args()
    binary = os.path.join(a.build, "sizemesh")
    head = (f"{'model':30s} {'exit':>4s} {'wall s':>7s} {'peak MB':>7s} {'prep s':>6s} {'triangles':>9s} "
            f"{'bound':>5s} {'nonman':>6s} {'misor':>5s} {'pairs':>6s} {'<12 all%':>7s} {'<12deg %':>8s} {'<24deg %':>7s} {'avoid':>5s} {'inv':>3s} {'lenient':>7s} {'h_min %':>7s} "
            f"{'tetgen':>7s}  route")
    print(head)
    with tempfile.TemporaryDirectory() as tmp:
        for f in a.files:
            model = os.path.join(DIR, f)
            smesh, report = os.path.join(tmp, "m.smesh"), os.path.join(tmp, "r.json")
            for stale in (smesh, report):
                if os.path.exists(stale):
                    os.remove(stale)
            cmd = [binary, model, "-q", "-o", smesh, "--report", report, "--threads", str(a.threads)]
            plane = HALF_MODELS.get(f)
            if plane:
                cmd += ["--farfield", "box", "--symmetry", plane]
            code, wall, peak, err = timed(cmd, a.timeout)
            j = json.load(open(report)) if os.path.exists(report) else {}
            mesh = j.get("mesh", {})
            tris = mesh.get("triangles", 0)
            verdict = "-" if a.no_tetgen or not os.path.exists(smesh) else tetgen_verdict(smesh, a.timeout)
            share = 100.0 * mesh.get("below_12deg_elsewhere", mesh.get("bad_below_12deg", 0)) / tris if tris else float("nan")
            share_all = 100.0 * mesh.get("bad_below_12deg", 0) / tris if tris else float("nan")
            share24 = 100.0 * mesh.get("low_quality_below_24deg", 0) / tris if tris else float("nan")
            name = f + (f" (half, {plane})" if plane else "")
            line = (f"{name:30s} {code:4d} {wall:7.2f} {peak:7.0f} {j.get('seconds', {}).get('prepare', float('nan')):6.2f} "
                    f"{tris:9d} {mesh.get('boundary_edges', -1):5d} {mesh.get('nonmanifold_edges', -1):6d} "
                    f"{mesh.get('orientation_conflicts', -1):5d} {mesh.get('self_intersecting_pairs', -1):6d} "
                    f"{share_all:7.3f} {share:8.3f} {share24:7.3f} {mesh.get('avoidable_below_12deg', -1):5d} {mesh.get('inverted_triangles', -1):3d} {j.get('mesher', {}).get('faces_lenient', -1):7d} {100.0 * mesh.get('share_at_h_min', float('nan')):7.2f} {verdict:>7s}  {routes(j)}")
            errors = [e for e in err.splitlines() if e.startswith("sizemesh: error:")]
            if code not in (0, 3) and errors:
                line += "  | " + errors[-1][len("sizemesh: error: "):][:160]
            print(line, flush=True)


if __name__ == "__main__":
    main()
