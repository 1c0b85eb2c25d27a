#!/usr/bin/env python3
"""sizemesh against Gmsh and Netgen on the shared models, with matched settings.

For each model and each accuracy level (phi_c), runs every tool in its own
process (Gmsh and Netgen both link OpenCASCADE and must not share one), then
measures every mesh the same way with bench/mesh_metrics: triangles, share of
min angles below 12 and 24 degrees, distance of triangle centroids and edge
midpoints to the CAD surface relative to the bounding-box diagonal (max and
mean). Prints a Markdown table and
ratios against Gmsh. Never fails on numbers.

    /usr/bin/python3 bench/peers.py [--build build] [--models DIR] [--phi 10 5] [--timeout 300] [--only NAME...]
    /usr/bin/python3 bench/peers.py --sweep [--only NAME...] [--out DIR] [--tools sizemesh sizemesh-fidelity --peers OLD/sweep.csv]

--sweep compares at matched accuracy instead: each tool runs at several levels
of its own refinement parameter (Gmsh: phi_c; sizemesh: the deviation bound,
with phi_c = 30, and with 90 and 20 at the bounds down to 2.83e-4; Netgen 6.2 ignores its meshing parameters on OCC geometry
from Python, so it gives one point), and for every sizemesh mesh the triangles a
peer needs for the same maximum distance are interpolated (log-log)
between that peer's two bracketing meshes. The curves are also written as
sweep.csv and plotted as sweep.png (triangles against maximum and against mean
distance, one column per model; needs python3-matplotlib). A ratio below 1 means sizemesh
needs fewer triangles for the same surface accuracy; "<0.2" means the peer's
finest run is still less accurate, with 5 times sizemesh's triangles. sizemesh runs twice:
with its default proximity sizing, and as "sizemesh-fidelity": proximity off and a
looser gradation (beta 1.5; Gmsh bounds none), sizing from the geometry's curvature
alone as the peers do.

Settings (as the paper's defaults): beta = 1.2, h_max = diag / 20, h_min = diag / 1e4 for all tools;
Gmsh 4.8: Frontal-Delaunay, Mesh.MeshSizeFromCurvature = round(360 / phi_c);
Netgen 6.2: grading = ln(beta), curvaturesafety = 1 / (2 sin(phi_c / 2)), maxh = h_max (no h_min).
One thread for every tool.
"""
import argparse, json, math, os, subprocess, sys, tempfile, time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from models import MODELS  # noqa: E402  (bench/models.py: the one list)
ROOT = os.path.dirname(HERE)
GMSH_UNITS = {"mm": "MM", "m": "M", "cm": "CM", "ft": "FT", "in": "INCH", "um": "UM", "km": "KM"}

GMSH_SCRIPT = r"""
import sys, time, gmsh
path, out, unit, hmin, hmax, npts = sys.argv[1], sys.argv[2], sys.argv[3], float(sys.argv[4]), float(sys.argv[5]), int(sys.argv[6])
gmsh.initialize(); gmsh.option.setNumber("General.Terminal", 0); gmsh.option.setNumber("General.NumThreads", 1)
if unit: gmsh.option.setString("Geometry.OCCTargetUnit", unit)
gmsh.model.occ.importShapes(path); gmsh.model.occ.synchronize()
gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", npts)
gmsh.option.setNumber("Mesh.MeshSizeMin", hmin); gmsh.option.setNumber("Mesh.MeshSizeMax", hmax)
gmsh.option.setNumber("Mesh.Algorithm", 6); gmsh.option.setNumber("Mesh.MshFileVersion", 2.2)
t = time.perf_counter(); gmsh.model.mesh.generate(2); t = time.perf_counter() - t
gmsh.write(out); print(t)
"""

NETGEN_SCRIPT = r"""
import sys, time, math
from netgen.NgOCC import LoadOCCGeometry
import netgen.meshing as nm
path, out, hmax_mm, beta, phi = sys.argv[1], sys.argv[2], float(sys.argv[3]), float(sys.argv[4]), float(sys.argv[5])
geo = LoadOCCGeometry(path)
mp = nm.MeshingParameters(maxh=hmax_mm, grading=math.log(beta), curvaturesafety=1.0 / (2 * math.sin(math.radians(phi) / 2)),
                          perfstepsend=nm.MeshingStep.MESHSURFACE)
t = time.perf_counter(); mesh = geo.GenerateMesh(mp=mp); t = time.perf_counter() - t
mesh.Export(out, "Gmsh2 Format"); print(t)
"""

UNIT_MM = {"mm": 1.0, "m": 1000.0, "cm": 10.0, "ft": 304.8, "in": 25.4, "um": 1e-3, "km": 1e6}


def model_info(build, path):
    out = subprocess.run([os.path.join(build, "sizemesh"), "--info", path], capture_output=True, text=True, check=True).stdout
    info = {}
    for line in out.splitlines():
        key, _, value = line.partition(":")
        info[key.strip()] = value.strip()
    info["diag"] = float(info["bounding box"].rsplit("diagonal", 1)[1])
    return info


def run(cmd, timeout):
    t = time.perf_counter()
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return None, "timeout"
    wall = time.perf_counter() - t
    if p.returncode not in (0, 3):
        return None, (p.stderr.strip().splitlines() or ["exit %d" % p.returncode])[-1][:80]
    return wall, ""


def metrics(build, model, mesh):
    p = subprocess.run([os.path.join(build, "bench", "mesh_metrics"), model, mesh], capture_output=True, text=True)
    return json.loads(p.stdout) if p.returncode == 0 else None


def tool_command(a, tool, name, path, out, info, level):
    """Command line of one run; level is phi_c for the peers, the relative deviation for sizemesh."""
    diag, unit = info["diag"], info["unit"]
    hmin, hmax = diag / 1e4, diag / 20
    if tool.startswith("sizemesh"):
        cmd = [os.path.join(a.build, "sizemesh"), path, "-o", out, "-q", "--threads", "1", "--h-min", repr(hmin),
               "--h-max", repr(hmax)]
        if a.sweep:
            deviation, phi = level if isinstance(level, tuple) else (level, 30)
            cmd += ["--phi-c", str(phi), "--deviation", repr(deviation * diag)]
            if tool == "sizemesh-fidelity":
                cmd += ["--no-proximity", "--beta", "1.5"]
        else:
            cmd += ["--phi-c", str(level)]
        return cmd
    if tool == "gmsh":
        iges = name.lower().endswith((".igs", ".iges"))  # Gmsh takes no target unit for IGES
        return ["/usr/bin/python3", "-c", GMSH_SCRIPT, path, out, "" if iges else GMSH_UNITS.get(unit, ""),
                repr(hmin), repr(hmax), str(round(360 / level))]
    scale = UNIT_MM.get(unit, 1.0)
    return ["/usr/bin/python3", "-c", NETGEN_SCRIPT, path, out, repr(hmax * scale), "1.2", str(level)]


def pareto(points):
    """The runs no other run beats on both counts (smaller distance with no more triangles): the
    settings a user would pick. Others are dropped from the comparison."""
    return sorted({(d, n) for d, n in points if not any(d2 <= d and n2 <= n and (d2, n2) != (d, n) for d2, n2 in points)})


def matched(points, dist):
    """Triangles a tool needs for max distance `dist`, from its (distance, triangles) runs, log-log
    between the two runs that bracket it. Outside its runs, a bound: ("<", n) when even its
    finest run stays above `dist` (it needs more than n), (">", n) when its coarsest is already
    below (it needs fewer than n). None without runs."""
    pts = pareto([p for p in points if p[0] > 0])
    if not pts:
        return None
    for (d0, n0), (d1, n1) in zip(pts, pts[1:]):
        if d0 <= dist <= d1 and d1 > d0:
            w = math.log(dist / d0) / math.log(d1 / d0)
            return ("=", math.exp((1 - w) * math.log(n0) + w * math.log(n1)))
    if dist < pts[0][0]:
        return ("<", max(n for d, n in pts if d == pts[0][0]))
    if dist > pts[-1][0]:
        return (">", min(n for d, n in pts if d == pts[-1][0]))
    return ("=", pts[0][1])


def sweep(a):
    # Netgen 6.2 from Python ignores the meshing parameters of an OCC geometry
    # (its mesh is the same for every curvature safety and maxh tried), so it
    # gives one point per model.
    # sizemesh: deviation bounds in steps of sqrt(2) with phi_c = 30, and down to 2.83e-4
    # also with phi_c = 90 and 20 (at a coarse deviation, 30 degrees per element across
    # small fillets sets the floor, or is too coarse where a bound loose enough to leave
    # thin faces alone is wanted). Steps of 2 missed the knees of the curve: a narrow face
    # or short curve sets a size once the bound falls under half its width or length, and
    # the count jumps there.
    bounds = [1.28e-2 / math.sqrt(2) ** k for k in range(19)]  # 1.28e-2 down to 2.5e-5
    levels = {"sizemesh": [(b, phi) for phi in (90, 20) for b in bounds if b > 2.8e-4] + bounds,
              "gmsh": [30, 20, 10, 7, 5, 3.5, 2.5], "netgen": [5]}
    levels["sizemesh-fidelity"] = levels["sizemesh"]
    tools = [t for t in ["sizemesh", "sizemesh-fidelity", "gmsh", "netgen"] if t in a.tools]
    tmp = tempfile.mkdtemp(prefix="sizemesh_sweep_")
    print("| model | tool | level | wall s | triangles | <12 deg | <24 deg | max dist/diag |")
    print("|---|---|---:|---:|---:|---:|---:|---:|")
    curves, rows = {}, []
    for row in load_peer_rows(a.peers, a.tools):  # earlier peer runs (--peers): the peers do not change
        if a.only and not any(o in row[0] for o in a.only):
            continue
        curves.setdefault((row[0], row[1]), []).append((row[4], row[3]))
        rows.append(row)
    for name in MODELS:
        if a.only and not any(o in name for o in a.only):
            continue
        path = os.path.join(a.models, name)
        info = model_info(a.build, path)
        for tool in tools:
            for level in levels[tool]:
                tag = "%.3g" % level if not isinstance(level, tuple) else "%.3g_phi%g" % level
                out = os.path.join(tmp, "%s_%s_%s.msh" % (name, tool, tag))
                wall, err = run(tool_command(a, tool, name, path, out, info, level), a.timeout)
                m = metrics(a.build, path, out) if wall is not None and os.path.exists(out) else None
                if m is None:
                    print("| %s | %s | %s | %s | - | - | - | - |" % (name, tool, tag, err or "no mesh"))
                    continue
                curves.setdefault((name, tool), []).append((m["max_distance_rel"], m["triangles"]))
                rows.append((name, tool, tag, m["triangles"], m["max_distance_rel"], m["mean_distance_rel"],
                             m["share_below_12"], wall))
                print("| %s | %s | %s | %.2f | %d | %.3f%% | %.3f%% | %.2e |" % (
                    name, tool, tag, wall, m["triangles"], 100 * m["share_below_12"], 100 * m["share_below_24"],
                    m["max_distance_rel"]))
                sys.stdout.flush()
    print("\nTriangles at the same maximum distance, sizemesh / peer (interpolated on the peer's curve;"
          " only runs that no other run of the same tool beats on both counts):\n")
    print("| model | sizemesh run | max dist/diag | triangles | / gmsh | / netgen |")
    print("|---|---|---:|---:|---:|---:|")
    for (name, tool), pts in curves.items():
        if not tool.startswith("sizemesh"):
            continue
        for d, n in pareto(pts):
            ratio = []
            for peer in ("gmsh", "netgen"):
                r = matched(curves.get((name, peer), []), d)
                ratio.append("-" if r is None else "%s%.2f" % ("" if r[0] == "=" else r[0], n / r[1]))
            print("| %s | %s | %.2e | %d | %s | %s |" % (name, tool, d, n, ratio[0], ratio[1]))
    print_peer_levels(curves)
    print_mean_ratios(rows)
    with open(os.path.join(tmp, "curves.json"), "w") as f:
        json.dump({"%s|%s" % k: v for k, v in curves.items()}, f, indent=1)
    out = a.out or tmp
    os.makedirs(out, exist_ok=True)
    write_sweep_csv(os.path.join(out, "sweep.csv"), rows)
    plot_sweep(os.path.join(out, "sweep.png"), rows)
    print("\nmeshes and curves.json in", tmp, "; sweep.csv and sweep.png in", out)


def print_peer_levels(curves):
    """The other way round: at each peer mesh's maximum distance, the triangles each sizemesh
    curve needs (interpolated on it) over the peer's. Netgen gives one mesh per model, so this
    is the only exact ratio against it."""
    print("\nAt each peer mesh's maximum distance, triangles sizemesh needs (interpolated on its curve) / the peer's:\n")
    print("| model | peer run | max dist/diag | peer triangles | sizemesh / peer | sizemesh-fidelity / peer |")
    print("|---|---|---:|---:|---:|---:|")
    tally = {}  # (model, tool) -> [levels at most 1, levels over 1, levels not decided]
    for (name, peer), pts in curves.items():
        if peer.startswith("sizemesh"):
            continue
        for d, n in pareto(pts):
            ratio = []
            for tool in ("sizemesh", "sizemesh-fidelity"):
                r = matched(curves.get((name, tool), []), d)
                # matched() bounds sizemesh's count here: "<" (its finest run is still less
                # accurate) means it needs more than r[1], a ratio of at least r[1] / n, and so on.
                flip = {"=": "", "<": ">", ">": "<"}
                ratio.append("-" if r is None else "%s%.2f" % (flip[r[0]], r[1] / n))
                if r is not None:
                    x, sign = r[1] / n, flip[r[0]]
                    t = tally.setdefault((name, tool), [0, 0, 0])
                    t[0 if x <= 1 and sign != ">" else 1 if x > 1 and sign != "<" else 2] += 1
            print("| %s | %s | %.2e | %d | %s | %s |" % (name, peer, d, n, ratio[0], ratio[1]))
    print("\nPeer levels where sizemesh needs no more triangles than the peer (ratio <= 1), per model:\n")
    print("| model | sizemesh run | at most 1 | over 1 | undecided (a bound across 1) |")
    print("|---|---|---:|---:|---:|")
    for (name, tool), (le, gt, unknown) in sorted(tally.items()):
        print("| %s | %s | %d | %d | %d |" % (name, tool, le, gt, unknown))


def print_mean_ratios(rows):
    """As print_peer_levels, at each peer mesh's mean distance (no tally: the must-hold is on the maximum)."""
    print("\nAt each peer mesh's mean distance, triangles sizemesh needs (interpolated on its mean curve) / the peer's:\n")
    print("| model | peer run | mean dist/diag | peer triangles | sizemesh / peer | sizemesh-fidelity / peer |")
    print("|---|---|---:|---:|---:|---:|")
    flip = {"=": "", "<": ">", ">": "<"}
    for name, peer, level, n, _, mean, _, _ in rows:
        if peer.startswith("sizemesh"):
            continue
        ratio = []
        for tool in ("sizemesh", "sizemesh-fidelity"):
            r = matched([(row[5], row[3]) for row in rows if row[0] == name and row[1] == tool], mean)
            ratio.append("-" if r is None else "%s%.2f" % (flip[r[0]], r[1] / n))
        print("| %s | %s %s | %.2e | %d | %s | %s |" % (name, peer, level, mean, n, ratio[0], ratio[1]))


def load_peer_rows(paths, tools):
    """Rows of earlier sweep.csv files for the tools not run now: Gmsh and Netgen take minutes
    per model and do not change between sizemesh versions; with no --tools at all, the tables
    are printed again from the files alone."""
    rows = []
    for path in paths or []:
        with open(path) as f:
            next(f)
            for line in f:
                c = line.strip().split(",")
                if len(c) == 8 and c[1] not in tools:
                    rows.append((c[0], c[1], c[2], int(c[3]), float(c[4]), float(c[5]), float(c[6]), float(c[7])))
    return rows


def write_sweep_csv(path, rows):
    """One line per mesh: the curve points behind the plot."""
    with open(path, "w") as f:
        f.write("model,tool,level,triangles,max_distance_rel,mean_distance_rel,share_below_12deg,wall_s\n")
        for r in rows:
            f.write("%s,%s,%s,%d,%.6e,%.6e,%.6f,%.3f\n" % r)


COLOURS = {"sizemesh": "C2", "sizemesh-fidelity": "C3", "gmsh": "C0", "netgen": "C1"}  # the same in every panel


def plot_sweep(path, rows):
    """Triangles against maximum (top) and mean (bottom) distance, log-log, one column per
    model, one curve per tool: each tool's runs that no other of its runs beats on both counts."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("no plot: python3-matplotlib is not installed")
        return
    models = sorted({r[0] for r in rows})
    if not models:
        return
    fig, axes = plt.subplots(2, len(models), figsize=(5 * len(models), 9), squeeze=False)
    for col, name in enumerate(models):
        tools = sorted({r[1] for r in rows if r[0] == name})
        for row, (column, label) in enumerate([(4, "maximum"), (5, "mean")]):
            ax = axes[row][col]
            for tool in tools:
                pts = pareto([(r[column], r[3]) for r in rows if r[0] == name and r[1] == tool and r[column] > 0])
                ax.loglog([p[0] for p in pts], [p[1] for p in pts], "o-", label=tool, markersize=4,
                          color=COLOURS.get(tool))
            ax.set_title(name)
            ax.set_xlabel("%s distance of centroids and edge midpoints from the CAD / diagonal" % label, fontsize=8)
            ax.set_ylabel("triangles")
            ax.grid(True, which="both", alpha=0.3)
            ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--models", default=os.path.join(ROOT, "tests", "data"))
    ap.add_argument("--phi", type=float, nargs="+", default=[10.0, 5.0])
    ap.add_argument("--timeout", type=float, default=300)
    ap.add_argument("--only", nargs="*")
    ap.add_argument("--tools", nargs="*", default=["sizemesh", "sizemesh-fidelity", "gmsh", "netgen"])
    ap.add_argument("--sweep", action="store_true")
    ap.add_argument("--out", help="--sweep: directory for sweep.csv and sweep.png (default: the scratch directory)")
    ap.add_argument("--peers", nargs="*", help="--sweep: earlier sweep.csv files whose rows are used for the "
                    "tools left out of --tools")
    a = ap.parse_args()
    if a.sweep:
        return sweep(a)
    tmp = tempfile.mkdtemp(prefix="sizemesh_peers_")
    rows = []
    print("| model | phi_c | tool | wall s | triangles | tris/s | <12 deg | <24 deg | max dist/diag | mean dist/diag |")
    print("|---|---:|---|---:|---:|---:|---:|---:|---:|---:|")
    for name in MODELS:
        if a.only and not any(o in name for o in a.only):
            continue
        path = os.path.join(a.models, name)
        info = model_info(a.build, path)
        for phi in a.phi:
            for tool in [t for t in a.tools if t in ("sizemesh", "gmsh", "netgen")]:
                out = os.path.join(tmp, "%s_%s_%g.msh" % (name, tool, phi))
                cmd = tool_command(a, tool, name, path, out, info, phi)
                wall, err = run(cmd, a.timeout)
                m = metrics(a.build, path, out) if wall is not None and os.path.exists(out) else None
                row = {"model": name, "phi_c": phi, "tool": tool, "wall": wall, "error": err, "metrics": m}
                rows.append(row)
                if m is None:
                    print("| %s | %g | %s | %s | - | - | - | - | - | - |" % (name, phi, tool, err or "no mesh"))
                else:
                    print("| %s | %g | %s | %.2f | %d | %.0f | %.3f%% | %.3f%% | %.2e | %.2e |" % (
                        name, phi, tool, wall, m["triangles"], m["triangles"] / wall, 100 * m["share_below_12"],
                        100 * m["share_below_24"], m["max_distance_rel"], m["mean_distance_rel"]))
                sys.stdout.flush()
    # Ratios against Gmsh at the same model and phi_c.
    print("\n| model | phi_c | throughput sizemesh/gmsh | triangles sizemesh/gmsh | triangles sizemesh/netgen |")
    print("|---|---:|---:|---:|---:|")
    by = {(r["model"], r["phi_c"], r["tool"]): r for r in rows}
    for (model, phi, tool), r in by.items():
        if tool != "sizemesh" or not r["metrics"]:
            continue
        g, n = by.get((model, phi, "gmsh")), by.get((model, phi, "netgen"))
        ts = r["metrics"]["triangles"] / r["wall"]
        tg = g["metrics"]["triangles"] / g["wall"] if g and g["metrics"] else None
        fmt = lambda x: "%.2f" % x if x else "-"
        print("| %s | %g | %s | %s | %s |" % (model, phi, fmt(ts / tg if tg else None),
              fmt(r["metrics"]["triangles"] / g["metrics"]["triangles"] if g and g["metrics"] else None),
              fmt(r["metrics"]["triangles"] / n["metrics"]["triangles"] if n and n["metrics"] else None)))
    with open(os.path.join(tmp, "results.json"), "w") as f:
        json.dump(rows, f, indent=1)
    print("\nmeshes and results.json in", tmp)


if __name__ == "__main__":
    main()
