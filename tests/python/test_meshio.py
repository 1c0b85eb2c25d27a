"""meshio (Debian python3-meshio), the common Python mesh reader, opens every
mesh file sizemesh writes for a solver or a volume mesher (.vtu, .msh, .mesh)
and the background mesh with its size fields (--background, .vtu)
and finds in each the same points, triangles and face markers.

Usage: test_meshio.py SIZEMESH_BINARY MODEL WORKDIR
"""
import json
import os
import subprocess
import sys

import meshio
import numpy as np


def run(binary, model, out, *extra):
    subprocess.run([binary, model, "-q", "-o", out, *extra], check=True, timeout=300)


def triangles_by_marker(points, triangles, markers):
    """Sorted corner coordinates of each triangle -> its marker."""
    out = {}
    for tri, marker in zip(triangles, markers):
        key = tuple(sorted(tuple(np.round(points[n], 9)) for n in tri))
        out[key] = int(marker)
    return out


def main():
    binary, model, work = sys.argv[1:4]
    os.makedirs(work, exist_ok=True)
    vtu, msh, medit, report = (os.path.join(work, "m6." + e) for e in ("vtu", "msh", "mesh", "json"))
    background = os.path.join(work, "m6_background.vtu")
    run(binary, model, vtu, "--report", report, "--background", background)
    run(binary, model, msh)
    run(binary, model, medit)
    counts = json.load(open(report))["mesh"]

    m = meshio.read(vtu)
    tris = m.cells_dict["triangle"]
    assert len(tris) == counts["triangles"], (len(tris), counts)
    assert len(m.points) == counts["nodes"], (len(m.points), counts)
    assert tris.min() == 0 and tris.max() == len(m.points) - 1
    for name in ("face_id", "source_face_id", "min_angle"):
        data = m.cell_data[name][0]
        assert len(data) == len(tris), name
        assert np.all(np.isfinite(data)), name
    for name in ("target_size", "limited_by", "classification_dim", "classification_id"):
        assert len(m.point_data[name]) == len(m.points), name
    assert m.point_data["target_size"].min() > 0
    # Codes of sizing/size_map.h's Limit: the M6 is sized by curvature most of all.
    codes = m.point_data["limited_by"].astype(int)
    assert codes.min() >= -1 and codes.max() <= 10
    assert np.count_nonzero(codes == 1) > 0.3 * len(codes)
    reference = triangles_by_marker(m.points, tris, m.cell_data["source_face_id"][0])

    g = meshio.read(msh)
    gt = g.cells_dict["triangle"]
    assert len(gt) == counts["triangles"]
    physical = np.concatenate([d for d, c in zip(g.cell_data["gmsh:physical"], g.cells) if c.type == "triangle"])
    assert triangles_by_marker(g.points, gt, physical) == reference, "msh markers differ from the vtu's"

    d = meshio.read(medit)
    dt = d.cells_dict["triangle"]
    assert len(dt) == counts["triangles"]
    refs = np.concatenate([r for r, c in zip(d.cell_data["medit:ref"], d.cells) if c.type == "triangle"])
    assert triangles_by_marker(d.points, dt, refs) == reference, "Medit references differ from the vtu's markers"
    b = meshio.read(background)
    summary = json.load(open(report))["background"]
    assert len(b.cells_dict["triangle"]) == summary["triangles"] and len(b.points) == summary["vertices"]
    for name in ("h_initial", "h_smoothed", "classification_dim", "classification_id"):
        assert len(b.point_data[name]) == len(b.points), name
    assert np.all(b.point_data["h_smoothed"] <= b.point_data["h_initial"])

    print("meshio read %d triangles, %d points, %d markers from .vtu, .msh and .mesh"
          % (len(tris), len(m.points), len(set(reference.values()))))


if __name__ == "__main__":
    main()
