"""The module and the command-line tool give the same maps on the same inputs: distortion
arrays to 1e-12 and summaries with the same keys and the same values (but times and file
names)."""
import json

import numpy as np
import pytest

import strictmin
from conftest import grid, read_numbers, run_cli, saddle, square_handles, tet_bar

VARYING = {"time_s", "solver_time_s", "init_time_s", "graph_time_s", "field_time_s", "cut_time_s", "rounding_time_s", "input", "output", "distortion_file",
           "source", "target"}


def same_summary(py, cli, top=True):
    """The same keys and values. Every summary the tool writes carries its version; one the
    tool's build does not write yet (before the version key) is the only key allowed to differ."""
    if top:
        assert py["version"] == strictmin.__version__
        if "version" not in cli:
            py = {k: v for k, v in py.items() if k != "version"}
    assert set(py) == set(cli), f"keys differ: {set(py) ^ set(cli)}"
    for key in cli:
        if key in VARYING:
            continue
        if key == "frames":
            assert len(py[key]) == len(cli[key])
            for a, b in zip(py[key], cli[key]):
                same_summary(a, b, top=False)
        elif isinstance(cli[key], float):
            assert py[key] == pytest.approx(cli[key], rel=1e-12, abs=1e-12), key
        else:
            assert py[key] == cli[key], key


def cli_run(tmp_path, args, name="run"):
    summary, dist = tmp_path / f"{name}.json", tmp_path / f"{name}.txt"
    run_cli(*args, "--quiet", "--summary", summary, "--distortion", dist)
    return json.loads(summary.read_text()), read_numbers(dist)


@pytest.mark.parametrize("method,measure", [("linf", "fd"), ("l2", "arap"), ("relax", "fd"), ("direct", "fd")])
def test_deform(tmp_path, method, measure):
    n = 6
    V, F = grid(n)
    idx, pos = square_handles(V, n)
    mesh, handles = tmp_path / "rest.obj", tmp_path / "handles.txt"
    strictmin.write_mesh(mesh, V, F)
    handles.write_text("".join(f"{i} {x!r} {y!r}\n" for i, (x, y) in zip(idx, pos)))
    V, F = strictmin.read_mesh(mesh)  # the coordinates the tool reads
    relax = {"sweeps": 5} if method == "relax" else {}  # other methods refuse relax's options
    summary, dist = cli_run(tmp_path, ["deform", mesh, "--handles", handles, "--method", method, "--measure", measure,
                                       *(["--sweeps", 5] if relax else [])])
    r = strictmin.deform(V, F, idx, pos, method=method, measure=measure, **relax)
    np.testing.assert_allclose(r.distortion, dist, rtol=0, atol=1e-12)
    same_summary(r.summary, summary)
    assert r.status == summary["status"] and r.usable == summary["usable"]


def test_deform_tets(tmp_path):
    V, T = tet_bar(3)
    left = np.flatnonzero(V[:, 0] == 0)
    right = np.flatnonzero(V[:, 0] == 3)
    idx = np.concatenate([left, right])
    pos = V[idx].copy()
    pos[len(left):, 1] += 0.6  # the right end moved sideways
    mesh, handles = tmp_path / "bar.mesh", tmp_path / "handles.txt"
    strictmin.write_mesh(mesh, V, T)
    handles.write_text("".join(f"{i} {x!r} {y!r} {z!r}\n" for i, (x, y, z) in zip(idx, pos)))
    V, T = strictmin.read_mesh(mesh)
    summary, dist = cli_run(tmp_path, ["deform", mesh, "--handles", handles, "--method", "linf"])
    r = strictmin.deform(V, T, idx, pos, method="linf")
    np.testing.assert_allclose(r.distortion, dist, rtol=0, atol=1e-12)
    same_summary(r.summary, summary)
    assert r.positions.shape == V.shape and r.summary["dimension"] == 3


def test_param(tmp_path):
    V, F = saddle(5)
    mesh = tmp_path / "saddle.obj"
    strictmin.write_mesh(mesh, V, F)
    V, F = strictmin.read_mesh(mesh)
    summary, dist = cli_run(tmp_path, ["param", mesh, "--method", "linf", "--measure", "arap", "--lg-iterations", 5])
    r = strictmin.param(V, F, method="linf", measure="arap", lg_iterations=5)
    np.testing.assert_allclose(r.distortion, dist, rtol=0, atol=1e-12)
    same_summary(r.summary, summary)
    assert r.uv.shape == (len(V), 2)


def test_interp(tmp_path):
    n = 5
    V, F = grid(n)
    angle = 1.0
    rot = np.array([[np.cos(angle), -np.sin(angle)], [np.sin(angle), np.cos(angle)]])
    Vt = V @ rot.T * np.array([1.3, 0.8])
    src, dst = tmp_path / "source.obj", tmp_path / "target.obj"
    strictmin.write_mesh(src, V, F)
    strictmin.write_mesh(dst, Vt, F)
    V, F = strictmin.read_mesh(src)
    Vt, _ = strictmin.read_mesh(dst)
    summary, dist = cli_run(tmp_path, ["interp", src, dst, "--t", "0.5", "--method", "linf", "--lg-iterations", 3])
    r = strictmin.interp(V, F, Vt, 0.5, method="linf", lg_iterations=3)
    np.testing.assert_allclose(r.distortion, dist, rtol=0, atol=1e-12)
    same_summary(r.summary, summary)
    frames = strictmin.interp(V, F, Vt, [0.0, 0.5], method="linf", lg_iterations=3)
    assert [f.t for f in frames] == [0.0, 0.5]
    np.testing.assert_allclose(frames[1].distortion, dist, rtol=0, atol=1e-12)


def test_interp_of_a_planar_source_to_a_surface(tmp_path):
    # A 2-column source and a 3-column target: the command line reads such files as a surface
    # interpolation; the module refused the arrays ("target has ... by 3 vertices").
    V, F = grid(4)
    Vt = np.column_stack([V * 1.2, 0.3 * V[:, 0] * V[:, 1]])
    src, dst = tmp_path / "source.obj", tmp_path / "target.obj"
    src.write_text("".join(f"v {x!r} {y!r}\n" for x, y in V) + "".join(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in F))
    strictmin.write_mesh(dst, Vt, F)
    summary, dist = cli_run(tmp_path, ["interp", src, dst, "--t", "0.5", "--method", "linf", "--lg-iterations", 3])
    r = strictmin.interp(V, F, Vt, 0.5, method="linf", lg_iterations=3)
    np.testing.assert_allclose(r.distortion, dist, rtol=0, atol=1e-12)
    same_summary(r.summary, summary)
    assert r.positions.shape == (len(V), 3)


def twisted_tet_bar(degrees, nz=24, length=12.0):
    """A 2 x 2 x nz bar of cubes cut into 6 tets each, and the same bar twisted about its axis."""
    index = lambda i, j, k: (k * 3 + j) * 3 + i
    V = np.array([[i / 2 - 0.5, j / 2 - 0.5, k * length / nz] for k in range(nz + 1) for j in range(3) for i in range(3)])
    T = []
    for k in range(nz):
        for j in range(2):
            for i in range(2):
                c = [index(i + a, j + b, k + z) for z in (0, 1) for b in (0, 1) for a in (0, 1)]
                for path in ((1, 2, 4), (1, 4, 2), (2, 1, 4), (2, 4, 1), (4, 1, 2), (4, 2, 1)):
                    corners = [0, path[0], path[0] + path[1], 7]
                    tet = [c[x] for x in corners]
                    if np.linalg.det((V[tet[1:]] - V[tet[0]]).T) < 0:
                        tet[2], tet[3] = tet[3], tet[2]
                    T.append(tet)
    phi = np.radians(degrees) * V[:, 2] / length
    Vt = np.column_stack([V[:, 0] * np.cos(phi) - V[:, 1] * np.sin(phi), V[:, 0] * np.sin(phi) + V[:, 1] * np.cos(phi), V[:, 2]])
    return V, np.array(T), Vt


def test_interp_rotation_blend(tmp_path):
    # A tet bar twisted by 540 degrees: its logarithms jump (rotation_jumps), so the rotations
    # are blended along a tree, which follows the twist; forced to the logarithms, the pairs
    # that cannot turn together are counted and warned about. The module and the command line
    # agree in both.
    V, F, Vt = twisted_tet_bar(540)
    src, dst = tmp_path / "rest.mesh", tmp_path / "twisted.mesh"
    strictmin.write_mesh(src, V, F)
    strictmin.write_mesh(dst, Vt, F)
    V, F = strictmin.read_mesh(src)
    Vt, _ = strictmin.read_mesh(dst)
    for blend in ("auto", "logarithms"):
        summary, dist = cli_run(tmp_path, ["interp", src, dst, "--t", "0.5", "--method", "l2", "--lg-iterations", 5,
                                           "--rotation-blend", blend])
        r = strictmin.interp(V, F, Vt, 0.5, method="l2", lg_iterations=5, rotation_blend=blend)
        np.testing.assert_allclose(r.distortion, dist, rtol=0, atol=1e-12)
        same_summary(r.summary, summary)
        assert r.rotation_jumps == summary["rotation_jumps"] > 0
        assert r.rotation_blend == summary["rotation_blend"] == ("tree" if blend == "auto" else "logarithms")
        assert r.rotation_disagreements == summary["rotation_disagreements"]
        if blend == "auto":
            assert summary["rotation_disagreements"] == 0 and summary["warnings"] == []
            assert summary["frames"][0]["flipped"] == 0
        else:
            assert summary["rotation_disagreements"] > 0
            assert "more than 90 degrees apart" in summary["warnings"][0]
    with pytest.raises(ValueError, match="rotation_blend takes auto, logarithms or tree, not 'shortest'"):
        strictmin.interp(V, F, Vt, 0.5, rotation_blend="shortest")


@pytest.mark.parametrize("measure", ["arap", "qc"])
def test_distortion_matches_eval(tmp_path, measure):
    n = 4
    V, F = grid(n)
    U = V + 0.05 * np.column_stack([np.sin(3 * V[:, 1]), np.cos(2 * V[:, 0])])
    rest, mapped = tmp_path / "rest.obj", tmp_path / "mapped.obj"
    strictmin.write_mesh(rest, V, F)
    strictmin.write_mesh(mapped, U, F)
    V, F = strictmin.read_mesh(rest)
    U, _ = strictmin.read_mesh(mapped)
    dist = tmp_path / "d.txt"
    run_cli("eval", rest, mapped, "--measure", measure, "--quiet", "--distortion", dist)
    np.testing.assert_allclose(strictmin.distortion(V, F, U, measure=measure), read_numbers(dist), rtol=0, atol=1e-12)
