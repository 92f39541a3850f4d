"""quads: the quad mesh of an integer-grid map gives the command line's quads and summary,
a closed quad mesh where the map has no flips, and ValueError for maps that are not
integer-grid maps."""
import json

import numpy as np
import pytest

import strictmin
from conftest import ellipsoid_file, run_cli
from test_matches_cli import same_summary


@pytest.fixture(scope="module")
def closed(tmp_path_factory):
    """A small closed surface (1280 triangles) as the tool reads it back from a file."""
    return ellipsoid_file(tmp_path_factory, 3, "quads")


def read_quad_obj(path):
    V, Q = [], []
    for line in open(path):
        p = line.split()
        if p and p[0] == "v":
            V.append([float(x) for x in p[1:4]])
        elif p and p[0] == "f":
            Q.append([int(x.split("/")[0]) - 1 for x in p[1:]])
    return np.array(V), np.array(Q)


def test_matches_cli(tmp_path, closed):
    mesh, V, F = closed
    run_cli("gparam", mesh, "-o", tmp_path / "map.obj", "--integer-grid", "--quads", 200, "--quiet")
    run_cli("quads", tmp_path / "map.obj", "-o", tmp_path / "quads.obj", "--summary", tmp_path / "s.json", "--quiet")
    summary = json.loads((tmp_path / "s.json").read_text())
    r = strictmin.gparam(V, F, quads=200, integer_grid=True)
    q = strictmin.quads(V, F, r.uv, r.fuv)
    assert summary["input"] == str(tmp_path / "map.obj") and summary["output"] == str(tmp_path / "quads.obj")
    same_summary(q["summary"], {k: v for k, v in summary.items() if k not in ("input", "output")})
    Vq, Qq = read_quad_obj(tmp_path / "quads.obj")
    np.testing.assert_allclose(q["V"], Vq, rtol=0, atol=1e-12)
    np.testing.assert_array_equal(q["Q"], Qq)
    assert q["complete"] == (summary["status"] == "complete")
    assert summary["quads"] == len(Qq) and Qq.shape[1] == 4


def test_complete_quad_mesh(closed):
    _, V, F = closed
    r = strictmin.gparam(V, F, quads=2000, integer_grid=True, method="linf", grid_guide="linf")
    q = strictmin.quads(V, F, r.uv, r.fuv)
    s = q["summary"]
    if r.summary["flipped"]:
        pytest.skip("this map flips triangles")  # the test is about flip-free maps
    assert q["complete"] and s["status"] == "complete" and s["holes"] == 0
    assert s["euler_characteristic"] == 2 == len(q["V"]) - s["edges"] + len(q["Q"])
    assert len(q["Q"]) == round(s["uv_area"])
    # Valence 4 - k at each cone of index k/4; every other vertex 4.
    valence = np.bincount(q["Q"].ravel(), minlength=len(q["V"]))
    expected = {}
    for _, k in r.singularities:
        expected[4 - k] = expected.get(4 - k, 0) + 1
    expected[4] = len(q["V"]) - len(r.singularities)
    assert {int(k): v for k, v in s["valences"].items()} == expected == dict(zip(*np.unique(valence, return_counts=True)))
    # Each vertex lies where its barycentric coordinates put it on the input.
    P = np.einsum("ij,ijk->ik", q["vertex_barycentric"], V[F[q["vertex_face"]]])
    np.testing.assert_allclose(P, q["V"], rtol=0, atol=1e-12)


def folded(V, F, uv, fuv):
    """The map with one vertex away from the seams (it and its neighbours have one uv each)
    moved by more than a grid unit, for each such vertex in turn: maps with a fold."""
    uses, neighbours = {}, {}
    for f in range(len(F)):
        for k in range(3):
            uses.setdefault(F[f, k], set()).add(fuv[f, k])
            neighbours.setdefault(F[f, k], set()).update(F[f])
    for v in sorted(uses):
        if all(len(uses[x]) == 1 for x in neighbours[v]):
            moved = uv.copy()
            moved[next(iter(uses[v]))] += [1.7, 0.9]
            yield moved


def test_fill_holes_matches_cli(tmp_path, closed):
    _, V, F = closed
    r = strictmin.gparam(V, F, quads=3000, integer_grid=True)
    # The first fold whose hole can be filled (no cone inside or on it).
    uv, q = next((uv, q) for uv in folded(V, F, r.uv, r.fuv)
                 for q in [strictmin.quads(V, F, uv, r.fuv, fill_holes=True)] if q["summary"]["status"] == "filled")
    assert q["summary"]["fill_holes"] is True and q["complete"]
    assert q["summary"]["filled_squares"] >= 1 and q["summary"]["holes"] == 0
    assert len(q["Q"]) == round(q["summary"]["uv_area"])
    filled = q["vertex_face"] < 0  # a hole's inner grid points, if it has any: off the surface
    assert np.isnan(q["vertex_barycentric"][filled]).all()
    # The same map through the command line: the same summary.
    lines = [f"v {x!r} {y!r} {z!r}" for x, y, z in V] + [f"vt {a!r} {b!r}" for a, b in uv]
    lines += ["f " + " ".join(f"{v + 1}/{t + 1}" for v, t in zip(F[f], r.fuv[f])) for f in range(len(F))]
    (tmp_path / "folded.obj").write_text("\n".join(lines) + "\n")
    run_cli("quads", tmp_path / "folded.obj", "--fill-holes", "--summary", tmp_path / "s.json", "--quiet")
    summary = json.loads((tmp_path / "s.json").read_text())
    same_summary(q["summary"], {k: v for k, v in summary.items() if k not in ("input", "output")})
    with pytest.raises(TypeError, match="fill_holes"):
        strictmin.quads(V, F, r.uv, r.fuv, fill_holes=1)


def test_bad_input(closed):
    _, V, F = closed
    r = strictmin.gparam(V, F, quads=200, edge_length=None)
    with pytest.raises(ValueError, match="misses a pair of integers"):
        strictmin.quads(V, F, r.uv, r.fuv)
    g = strictmin.gparam(V, F, quads=200, integer_grid=True)
    with pytest.raises(ValueError, match="fuv must be #F by 3"):
        strictmin.quads(V, F, g.uv, g.fuv[:-1])
    with pytest.raises(ValueError, match="tolerance"):
        strictmin.quads(V, F, g.uv, g.fuv, tolerance=0.5)
    with pytest.raises(TypeError, match="tolerance"):
        strictmin.quads(V, F, g.uv, g.fuv, tolerance="small")
    for bad_uv in (g.uv[:, :1], g.uv.ravel(), np.c_[g.uv, np.zeros(len(g.uv))]):
        with pytest.raises(ValueError, match=r"uv must be #UV by 2, got shape"):
            strictmin.quads(V, F, bad_uv, g.fuv)
