#!/usr/bin/env python3
"""Bounded meshing on every test model: wall time and peak memory (from
/usr/bin/time -v), the triangle estimate made from the size map before
meshing against the triangles made, and front steps per triangle.

    /usr/bin/python3 bench/bounded.py [--threads 2] [--models DIR] [files...]

Targets: every model within 20 s wall on 2 threads and under 2 GB, no failed
face, the estimate within 30% of the actual count. Prints; never fails on time.
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from models import MODELS  # noqa: E402  (bench/models.py: the one list)
ROOT = os.path.dirname(HERE)


def run(binary, model, threads, tmp):
    report = os.path.join(tmp, "r.json")
    out = os.path.join(tmp, "m.vtu")
    cmd = ["/usr/bin/time", "-v", binary, model, "-q", "-o", out, "--report", report, "--threads", str(threads)]
    p = subprocess.run(cmd, capture_output=True, text=True)
    wall = re.search(r"Elapsed \(wall clock\) time.*: (?:(\d+):)?(\d+):([\d.]+)", p.stderr)
    seconds = (int(wall.group(1) or 0) * 3600 + int(wall.group(2)) * 60 + float(wall.group(3))) if wall else float("nan")
    rss = re.search(r"Maximum resident set size \(kbytes\): (\d+)", p.stderr)
    peak_mb = int(rss.group(1)) / 1024 if rss else float("nan")
    j = json.load(open(report)) if os.path.exists(report) else {}
    return p.returncode, seconds, peak_mb, j


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--models", default=os.path.join(ROOT, "tests", "data"))
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("files", nargs="*", default=MODELS)
    a = ap.parse_args()
    binary = os.path.join(a.build, "sizemesh")
    print(f"{'model':32s} {'exit':>4s} {'wall s':>7s} {'peak MB':>8s} {'estimate':>10s} {'triangles':>10s} "
          f"{'est/act':>7s} {'steps/tri':>9s} {'failed':>6s} {'inverted':>8s} {'<12deg':>7s} {'avoidable':>9s} "
          f"{'crossing':>8s} {'local':>6s} {'boundary':>8s} {'prepare s':>9s}")
    with tempfile.TemporaryDirectory() as tmp:
        for f in a.files:
            code, wall, peak, j = run(binary, os.path.join(a.models, f), a.threads, tmp)
            mesh, mesher = j.get("mesh", {}), j.get("mesher", {})
            est, tris = mesher.get("estimated_triangles", 0), mesh.get("triangles", 0)
            ratio = est / tris if tris else float("nan")
            print(f"{f:32s} {code:4d} {wall:7.2f} {peak:8.0f} {est:10.0f} {tris:10d} {ratio:7.3f} "
                  f"{mesher.get('front_steps_per_triangle', float('nan')):9.3f} {len(mesh.get('failed_faces', [])):6d} "
                  f"{mesh.get('inverted_triangles', -1):8d} {mesh.get('bad_below_12deg', -1):7d} "
                  f"{mesh.get('avoidable_below_12deg', -1):9d} {mesh.get('self_intersecting_pairs', -1):8d} "
                  f"{mesh.get('local_self_intersecting_pairs', -1):6d} {mesh.get('boundary_edges', -1):8d} "
                  f"{j.get('seconds', {}).get('prepare', float('nan')):9.2f}")
            sys.stdout.flush()


if __name__ == "__main__":
    main()
