"""What examples/batch.py and examples/dask_batch.py share: finding the CAD
files, meshing one file with the sizemesh command in a process of its own,
and the summary.csv row it gives (the same columns as `sizemesh batch`).
"""
import argparse
import csv
import glob
import json
import os
import shutil
import subprocess
import tempfile
import time

CAD = (".step", ".stp", ".iges", ".igs", ".brep")
COLUMNS = ["file", "status", "exit_code", "seconds", "peak_mb", "triangles", "nodes", "bad_below_12deg",
           "avoidable_below_12deg", "failed_faces", "message"]


def parse(argv, doc, more=None):
    """The arguments both scripts take; those after -- go to every file's run."""
    options = argv[argv.index("--") + 1:] if "--" in argv else []
    argv = argv[:argv.index("--")] if "--" in argv else argv
    ap = argparse.ArgumentParser(description=doc.split("\n\n")[0])
    ap.add_argument("inputs", nargs="+", help="CAD files, folders or glob patterns")
    ap.add_argument("-o", "--output", required=True, help="folder for the meshes and summary.csv")
    ap.add_argument("--format", default="vtu", choices=["vtu", "msh", "stl", "cgns", "mesh", "smesh"])
    ap.add_argument("--timeout", type=float, default=600, help="seconds a file may take")
    ap.add_argument("--sizemesh", help="the sizemesh command (default: this repository's build)")
    if more:
        more(ap)
    a = ap.parse_args(argv)
    a.options = options
    return a


def find_sizemesh(given=None):
    """The sizemesh command: given, next to this repository's build, or on PATH."""
    here = os.path.dirname(os.path.abspath(__file__))
    for path in (given, os.path.join(here, "..", "build", "sizemesh"), shutil.which("sizemesh")):
        if path and os.access(path, os.X_OK):
            return os.path.abspath(path)
    raise SystemExit("sizemesh: error: the sizemesh command was not found (build it, or give --sizemesh)")


def cad_files(inputs):
    """Folders' CAD files, glob matches and files, sorted, each once."""
    files = []
    for item in inputs:
        if os.path.isdir(item):
            found = [os.path.join(item, f) for f in os.listdir(item) if f.lower().endswith(CAD)]
        else:
            found = glob.glob(item)
        if not found:
            raise SystemExit("sizemesh: error: no CAD file matches '%s'" % item)
        files += sorted(found)
    return files


def stems(files):
    """Output names: each file's stem, with a suffix where two share one."""
    used, out = set(), []
    for f in files:
        stem = base = os.path.splitext(os.path.basename(f))[0]
        k = 2
        while stem in used:
            stem, k = "%s_%d" % (base, k), k + 1
        used.add(stem)
        out.append(stem)
    return out


def mesh_one(sizemesh, path, outdir, stem, fmt="vtu", timeout=600, options=()):
    """Meshes one file in a child process; returns its summary row (a dict)."""
    os.makedirs(outdir, exist_ok=True)
    report = os.path.join(outdir, stem + ".json")
    cmd = [sizemesh, path, "-q", "-o", os.path.join(outdir, "%s.%s" % (stem, fmt)), "--report", report, *options]
    out = os.path.join(outdir, "%s.%s" % (stem, fmt))
    for old in (out, report):  # an earlier batch's files must not pass for this run's
        if os.path.exists(old):
            os.remove(old)
    row = dict.fromkeys(COLUMNS, "")
    row["file"] = path
    start = time.perf_counter()
    with tempfile.TemporaryFile("w+") as err:
        p = subprocess.Popen(cmd, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=err)
        # wait4 gives this child's own peak memory.
        while True:
            pid, status, usage = os.wait4(p.pid, os.WNOHANG)
            if pid:
                break
            if time.perf_counter() - start > timeout:
                p.kill()
                os.wait4(p.pid, 0)
                row.update(status="timeout", message="killed after the time limit",
                           seconds="%.3f" % (time.perf_counter() - start))
                return row
            time.sleep(0.02)
        p.returncode = os.waitstatus_to_exitcode(status)
        err.seek(0)
        stderr = err.read()
    row["seconds"] = "%.3f" % (time.perf_counter() - start)
    row["peak_mb"] = "%.4f" % (usage.ru_maxrss / 1024)
    if p.returncode < 0:
        row.update(status="crashed", message="signal %d" % -p.returncode)
        return row
    row["exit_code"] = p.returncode
    row["status"] = {0: "ok", 3: "partial"}.get(p.returncode, "error")
    errors = [l[len("sizemesh: error: "):] for l in stderr.splitlines() if l.startswith("sizemesh: error: ")]
    row["message"] = errors[-1] if errors else ""
    if row["status"] != "error" and os.path.exists(report):
        mesh = json.load(open(report))["mesh"]
        row.update(triangles=mesh["triangles"], nodes=mesh["nodes"], bad_below_12deg=mesh["bad_below_12deg"],
                   avoidable_below_12deg=mesh["avoidable_below_12deg"],
                   failed_faces=" ".join(str(f["face"]) for f in mesh["failed_faces"]))
    return row


def write_summary(outdir, rows):
    with open(os.path.join(outdir, "summary.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=COLUMNS)
        w.writeheader()
        w.writerows(rows)
