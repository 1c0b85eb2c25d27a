"""A first session with the sizemesh Python module: mesh the ONERA M6 wing,
look at the size map behind the mesh, and plot the quality.

    PYTHONPATH=build/python /usr/bin/python3 examples/tutorial_m6.py [OUTDIR]

Writes OUTDIR/m6.vtu (open it in ParaView) and OUTDIR/m6_min_angle.png.
"""
import collections
import os
import sys

import matplotlib

matplotlib.use("Agg")  # files only, no window
import matplotlib.pyplot as plt
import numpy as np

import sizemesh

here = os.path.dirname(os.path.abspath(__file__))
model = os.path.join(here, "onera_m6_wing.stp")
out = sys.argv[1] if len(sys.argv) > 1 else "."
os.makedirs(out, exist_ok=True)

# 1. What is in the file.
info = sizemesh.load(model)
print("model: %(faces)d faces, %(curves)d curves, diagonal %(diagonal).1f %(unit)s" % info)

# 2. The size map (paper sections 3.1-3.4): sizes on the background mesh,
# and what set each one before smoothing.
sizes = sizemesh.size_map(model)
print("size map: %d background vertices, h_min %.3g, h_max %.3g, about %d triangles expected"
      % (len(sizes.sizes), sizes.h_min, sizes.h_max, sizes.estimated_triangles))
for reason, n in collections.Counter(sizes.limited_by).most_common():
    print("  %-24s %6d vertices" % (reason, n))
lowered = np.count_nonzero(sizes.sizes < sizes.initial_sizes)
print("  smoothing lowered %d vertices, at most %.1fx" % (lowered, np.max(sizes.initial_sizes / sizes.sizes)))
# The size anywhere on a face, from (u, v): here across the largest face's parameters.
face = int(np.bincount(sizes.face_ids).argmax())
uv, _ = sizes.face_uv(face)
line = np.linspace(uv.min(axis=0), uv.max(axis=0), 6)
print("  sizes across face %d:" % face, np.round(sizes.query(face, line), 2))

# 3. The mesh, with the same options as the command line (h_min=..., phi_c=...).
mesh = sizemesh.mesh(model)
report = mesh.report["mesh"]
print("mesh: %d triangles, %d nodes; worst angle %.1f deg, %d below 12 deg (%d forced by the CAD)"
      % (len(mesh.triangles), len(mesh.points), report["worst_min_angle_deg"], report["bad_below_12deg"],
         report["forced_below_12deg"]))
mesh.write(os.path.join(out, "m6.vtu"))

# 4. The min-angle histogram.
fig, ax = plt.subplots(figsize=(6, 3.5))
ax.hist(mesh.min_angle, bins=np.arange(0, 61, 2), color="tab:blue")
ax.axvline(12, color="tab:red", linestyle="--", label="12 deg")
ax.set_xlabel("smallest angle of a triangle (deg)")
ax.set_ylabel("triangles")
ax.set_title("ONERA M6: %d triangles" % len(mesh.triangles))
ax.legend()
fig.tight_layout()
png = os.path.join(out, "m6_min_angle.png")
fig.savefig(png, dpi=100)
print("wrote", os.path.join(out, "m6.vtu"), "and", png)
