"""The Python module against the command line: the same arrays to the last
bit, the same option names and the same error messages; partial meshes are
returned with their failures; the size map answers queries at its own
vertices with their sizes. Run by ctest with pytest (Debian python3-pytest).

Environment: PYTHONPATH holds build/python; SIZEMESH_BINARY the command;
SIZEMESH_MODELS_DIR the test models.
"""
import os
import random
import re
import subprocess
import threading

import meshio
import numpy as np
import pytest

import sizemesh

BINARY = os.environ["SIZEMESH_BINARY"]
MODELS = os.environ["SIZEMESH_MODELS_DIR"]
M6 = os.path.join(MODELS, "onera_m6_wing.stp")
CONE = os.path.join(MODELS, "cone70_capsule_sting.step")


def cli(*args):
    return subprocess.run([BINARY, *args], capture_output=True, text=True, timeout=300)


def cli_mesh(tmp_path, model, *flags):
    out = str(tmp_path / "cli.vtu")
    r = cli(model, "-q", "-o", out, *flags)
    assert r.returncode in (0, 3), r.stderr
    return meshio.read(out), r


def assert_same_as_cli(mesh, cli_vtu):
    assert np.array_equal(mesh.points, cli_vtu.points)
    assert np.array_equal(mesh.triangles, cli_vtu.cells_dict["triangle"])
    assert np.array_equal(mesh.face_ids, cli_vtu.cell_data["face_id"][0].astype(int))
    assert np.array_equal(mesh.markers, cli_vtu.cell_data["source_face_id"][0].astype(int))
    assert np.array_equal(mesh.min_angle, cli_vtu.cell_data["min_angle"][0])
    assert np.array_equal(mesh.target_size, cli_vtu.point_data["target_size"])
    assert np.array_equal(mesh.limited_by, cli_vtu.point_data["limited_by"].astype(int))


def test_arrays_are_the_cli_mesh_to_the_last_bit(tmp_path):
    m = sizemesh.mesh(M6)
    ref, _ = cli_mesh(tmp_path, M6)
    assert m.points.dtype == np.float64 and m.points.shape[1] == 3
    assert m.triangles.shape == (m.report["mesh"]["triangles"], 3)
    assert_same_as_cli(m, ref)
    assert m.failures == []
    assert m.report["mesh"]["boundary_edges"] == 0


def test_keyword_arguments_are_the_cli_flags(tmp_path):
    m = sizemesh.mesh(CONE, h_min=0.5, phi_c=20, gaps=False, sew=True, farfield="box", threads=1)
    ref, _ = cli_mesh(tmp_path, CONE, "--h-min", "0.5", "--phi-c", "20", "--no-gaps", "--farfield", "box",
                      "--threads", "1")
    assert_same_as_cli(m, ref)
    assert m.report["sizing"]["h_min"] == 0.5
    assert m.report["domain"]["farfield"] == "box"


@pytest.mark.parametrize("args, kwargs", [
    (["/nonexistent/model.stp"], {}),
    ([M6, "--beta", "0.5"], {"beta": 0.5}),
    ([M6, "--h-min", "10", "--h-max", "1"], {"h_min": 10, "h_max": 1}),
    ([M6, "--farfield", "sphere", "--farfield-size", "1"], {"farfield": "sphere", "farfield_size": 1}),
    ([M6, "--farfield", "cone"], {"farfield": "cone"}),
])
def test_errors_carry_the_cli_message(args, kwargs):
    r = cli(*args, "-q", "-o", "/tmp/sizemesh_python_unused.vtu")
    assert r.returncode in (1, 2)
    with pytest.raises(sizemesh.Error) as e:
        sizemesh.mesh(args[0], **kwargs)
    assert isinstance(e.value, RuntimeError)
    assert r.stderr.strip() == "sizemesh: error: " + str(e.value)


def test_a_file_that_is_not_cad(tmp_path):
    text = tmp_path / "notes.stp"
    text.write_text("this is not a STEP file\n")
    r = cli(str(text), "-q", "-o", str(tmp_path / "x.vtu"))
    with pytest.raises(sizemesh.Error) as e:
        sizemesh.mesh(text)  # a path-like object works too
    assert r.returncode == 1 and r.stderr.strip() == "sizemesh: error: " + str(e.value)


def test_unknown_and_file_options_are_refused():
    with pytest.raises(sizemesh.Error, match="unknown option 'hmin'"):
        sizemesh.mesh(M6, hmin=1)
    with pytest.raises(sizemesh.Error, match="sizemesh.write"):
        sizemesh.mesh(M6, output="x.vtu")


def damaged_m6(path):
    """The M6 with three control points moved (seed 7): face 1 folds over."""
    rnd = random.Random(7)
    lines = open(M6).read().split("\n")
    points = [i for i, l in enumerate(lines) if "CARTESIAN_POINT" in l]
    for _ in range(3):
        i = rnd.choice(points)
        lines[i] = re.sub(r"(-?\d+\.\d+)", lambda m: str(float(m.group(1)) * rnd.choice([1.5, -3, 10, 0.2])),
                          lines[i], count=1)
    path.write_text("\n".join(lines))
    return path


def test_a_partial_mesh_is_returned_with_its_failures(tmp_path):
    model = str(damaged_m6(tmp_path / "damaged.stp"))
    ref, r = cli_mesh(tmp_path, model)
    assert r.returncode == 3
    m = sizemesh.mesh(model)
    assert [f for f, _ in m.failures] == [1]
    assert "front" in m.failures[0][1]
    assert m.report["mesh"]["failed_faces"] == [{"face": 1, "reason": m.failures[0][1]}]
    assert len(m.triangles) > 10000 and 1 not in set(m.face_ids)
    assert any("face 1 was not meshed" in w for w in m.warnings)
    assert_same_as_cli(m, ref)


def test_a_mesh_family_grows_by_its_ratio_around_the_default_mesh():
    family = sizemesh.mesh_family(M6, levels=3, ratio=3.0)
    n = [len(m.triangles) for m in family]
    assert 2.5 <= n[1] / n[0] <= 3.5 and 2.5 <= n[2] / n[1] <= 3.5, n
    default = sizemesh.mesh(M6)
    assert np.array_equal(family[1].points, default.points)
    assert np.array_equal(family[1].triangles, default.triangles)
    for m in family:
        assert m.report["mesh"]["boundary_edges"] == 0 and m.report["mesh"]["self_intersecting_pairs"] == 0
    with pytest.raises(sizemesh.Error, match="levels must be 1 to 8"):
        sizemesh.mesh_family(M6, levels=9)


def test_repeatable_options_take_a_list_and_sources_label_their_nodes():
    box = "box 700 1000 -50 1200 1250 50 6"
    one = sizemesh.mesh(M6, source=box)
    two = sizemesh.mesh(M6, source=[box, "sphere 300 300 0 40 4"])
    assert np.count_nonzero(one.limited_by == 9) > 0
    assert np.count_nonzero(two.limited_by == 9) > np.count_nonzero(one.limited_by == 9)
    assert len(two.triangles) > len(one.triangles)
    with pytest.raises(sizemesh.Error, match="--source"):
        sizemesh.mesh(M6, source="box 1 2 3")


def test_size_map_queries_at_its_vertices_give_their_sizes():
    s = sizemesh.size_map(M6)
    assert s.sizes.shape == (len(s.points),)
    assert np.all(s.sizes >= s.h_min) and np.all(s.sizes <= s.h_max * (1 + 1e-12))
    assert np.all(s.sizes <= s.initial_sizes)  # smoothing only lowers
    assert set(s.limited_by) <= {"h_max", "curvature", "face proximity (2A/l)", "curve length", "h_min",
                                 "gap through the fluid", "thickness of the solid"}
    assert s.model["faces"] == 11
    for face in range(1, 12):
        uv, vertex = s.face_uv(face)
        assert np.allclose(s.query(face, uv), s.sizes[vertex], rtol=1e-9, atol=0)
    with pytest.raises(sizemesh.Error, match="face 12 is not in the model"):
        s.query(12, np.zeros((1, 2)))


def test_background_mesh_is_classified():
    bg = sizemesh.background_mesh(M6)
    assert bg["points"].shape[1] == 3 and bg["triangles"].max() < len(bg["points"])
    assert set(np.unique(bg["classification_dim"])) == {0, 1, 2}
    assert set(np.unique(bg["face_ids"])) == set(range(1, 12))


def test_write_and_to_meshio(tmp_path):
    m = sizemesh.mesh(CONE)
    for ext in ("vtu", "msh", "mesh", "stl"):
        path = str(tmp_path / ("cone." + ext))
        sizemesh.write(m, path)
        back = meshio.read(path)
        assert len(back.cells_dict["triangle"]) == len(m.triangles), ext
    with pytest.raises(sizemesh.Error, match="unknown mesh format"):
        m.write(str(tmp_path / "cone.xyz"))
    mm = m.to_meshio()
    assert np.array_equal(mm.points, m.points)
    assert np.array_equal(mm.cell_data["marker"][0], m.markers)


def test_threads_mesh_side_by_side_with_the_same_results():
    alone = [sizemesh.mesh(p) for p in (M6, CONE)]
    out = [None, None]

    def work(i, p):
        out[i] = sizemesh.mesh(p)

    threads = [threading.Thread(target=work, args=(i, p)) for i, p in enumerate((M6, CONE))]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for a, b in zip(alone, out):
        assert np.array_equal(a.points, b.points) and np.array_equal(a.triangles, b.triangles)
