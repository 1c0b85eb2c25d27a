"""examples/batch.py and examples/dask_batch.py (the latter on a local Dask
cluster of 2 workers) over the test models (but the union corpus) plus a corrupted copy: one
summary row per file, the corrupted file failed, every other one meshed.

Environment: SIZEMESH_BINARY the command; SIZEMESH_MODELS_DIR the models.
"""
import csv
import os
import subprocess
import sys

BINARY = os.environ["SIZEMESH_BINARY"]
MODELS = os.environ["SIZEMESH_MODELS_DIR"]
EXAMPLES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "examples")
CAD = (".step", ".stp", ".iges", ".igs", ".brep")
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "bench"))
from models import UNION_CORPUS  # noqa: E402  (aircraft that do not all mesh closed yet)


def inputs(tmp_path, names):
    folder = tmp_path / "in"
    folder.mkdir()
    for n in names:
        (folder / n).symlink_to(os.path.join(MODELS, n))
    m6 = open(os.path.join(MODELS, "onera_m6_wing.stp"), "rb").read()
    (folder / "corrupted.stp").write_bytes(m6[:len(m6) // 3])  # cut in the middle of its entities
    return folder


def run_example(script, folder, out, *extra):
    p = subprocess.run([sys.executable, os.path.join(EXAMPLES, script), str(folder), "-o", str(out),
                        "--sizemesh", BINARY, *extra], capture_output=True, text=True, timeout=900)
    rows = list(csv.DictReader(open(out / "summary.csv")))
    return p, {os.path.basename(r["file"]): r for r in rows}, len(rows)


def check(rows, count, names):
    assert count == len(names) + 1
    assert rows["corrupted.stp"]["status"] == "error" and rows["corrupted.stp"]["message"]
    for n in names:
        assert rows[n]["status"] == "ok", rows[n]
        assert int(rows[n]["triangles"]) > 1000 and float(rows[n]["peak_mb"]) > 1


def test_dask_batch_over_every_model_on_a_local_cluster(tmp_path):
    names = sorted(f for f in os.listdir(MODELS) if f.lower().endswith(CAD) and f not in UNION_CORPUS)
    assert len(names) >= 9
    p, rows, count = run_example("dask_batch.py", inputs(tmp_path, names), tmp_path / "out", "--workers", "2")
    assert p.returncode == 3, p.stderr[-2000:]
    check(rows, count, names)


def test_batch_with_a_process_per_file(tmp_path):
    names = ["cone70_capsule_sting.step", "hemisphere_cylinder_domain.stp", "onera_m6_wing.stp"]
    p, rows, count = run_example("batch.py", inputs(tmp_path, names), tmp_path / "out", "--jobs", "2")
    assert p.returncode == 3, p.stderr[-2000:]
    check(rows, count, names)
