"""gparam: the global parametrization of a closed surface gives the command line's map and
summary, singularities that satisfy Poincare-Hopf, and ValueError for bad input."""
import numpy as np
import pytest

import strictmin
from conftest import ellipsoid_file, grid, saddle
from test_matches_cli import cli_run, same_summary


@pytest.fixture(scope="module")
def closed(tmp_path_factory):
    """A small closed surface (320 triangles) as the tool reads it back from a file."""
    return ellipsoid_file(tmp_path_factory, 2, "gparam")


def test_matches_cli(tmp_path, closed):
    mesh, V, F = closed
    summary, dist = cli_run(tmp_path, ["gparam", mesh, "--method", "linf", "--quads", 60])
    r = strictmin.gparam(V, F, method="linf", quads=60)
    np.testing.assert_allclose(r.distortion, dist, rtol=0, atol=1e-12)
    same_summary(r.summary, summary)
    assert r.summary["task"] == "gparam" and r.status == summary["status"] and r.usable == summary["usable"]
    assert r.lower_bound == pytest.approx(summary["lower_bound"], rel=1e-12, abs=1e-12)
    assert r.singularities == [(s["vertex"], s["index"]) for s in summary["singularity_indices"]]
    assert r.uv.shape == (summary["cut_mesh_vertices"], 2)
    assert r.fuv.shape == F.shape and r.fuv.min() >= 0 and r.fuv.max() < len(r.uv)
    assert r.edge_length == pytest.approx(summary["edge_length"], rel=1e-12)
    assert "singularities=" in repr(r) and "task='gparam'" in repr(r)


def test_matches_cli_arap_given_field(tmp_path, closed):
    mesh, V, F = closed
    field = strictmin.gparam(V, F, quads=60).field  # the smoothest field, written and read back
    assert field.shape == (len(F), 3)
    path = tmp_path / "field.txt"
    np.savetxt(path, field, fmt="%.17g")
    summary, dist = cli_run(tmp_path, ["gparam", mesh, "--field", path, "--measure", "arap", "--edge-length", 0.3,
                                       "--lg-iterations", 3])
    r = strictmin.gparam(V, F, measure="arap", field=np.loadtxt(path), edge_length=0.3, lg_iterations=3)
    np.testing.assert_allclose(r.distortion, dist, rtol=0, atol=1e-12)
    summary["field"] = "given"  # the tool names the file
    same_summary(r.summary, summary)


def test_poincare_hopf(closed):
    _, V, F = closed
    for field in ("smoothest", "unit", "curvature"):
        r = strictmin.gparam(V, F, field=field, quads=60)
        assert r.euler_characteristic == 2 == len(V) - len(F) * 3 // 2 + len(F)
        assert r.singularities and all(q != 0 for _, q in r.singularities)
        assert sum(q for _, q in r.singularities) == 4 * r.euler_characteristic
        assert r.summary["singularities"] == len(r.singularities)
        assert r.summary["field"] == field
        if field == "unit":
            assert r.summary["field_unit_steps"] >= 1
            assert r.summary["field_energy"] <= r.summary["field_eigen_energy"]


def test_cones_and_parallel(tmp_path, closed):
    """cones= gives the field with exactly those singularities (the CLI's --cones on the same
    cone file); parallel=True keeps the smoothest field's and lowers its energy."""
    mesh, V, F = closed
    smooth = strictmin.gparam(V, F, quads=60)
    quarters = np.zeros(len(V), dtype=int)
    for v, q in smooth.singularities:
        quarters[v] = q
    r = strictmin.gparam(V, F, method="linf", quads=60, cones=quarters)
    assert r.singularities == smooth.singularities
    assert r.summary["field"] == "cones" and r.summary["field_parallel"] and r.summary["cones_missed"] == 0
    assert r.summary["field_energy"] < smooth.summary["field_energy"]
    path = tmp_path / "cones.txt"
    np.savetxt(path, 2 * np.pi - quarters * np.pi / 2, fmt="%.17g")
    summary, dist = cli_run(tmp_path, ["gparam", mesh, "--cones", path, "--method", "linf", "--quads", 60])
    np.testing.assert_allclose(r.distortion, dist, rtol=0, atol=1e-12)
    summary["field"] = "cones"
    same_summary(r.summary, summary)
    p = strictmin.gparam(V, F, quads=60, parallel=True)
    assert p.singularities == smooth.singularities and p.summary["field_parallel"]
    assert p.summary["field_energy"] == pytest.approx(r.summary["field_energy"], rel=1e-12)
    with pytest.raises(ValueError, match="Euler characteristic"):
        strictmin.gparam(V, F, cones=np.zeros(len(V), dtype=int))
    with pytest.raises(ValueError, match="integers"):
        strictmin.gparam(V, F, cones=np.zeros(len(V)))
    with pytest.raises(ValueError, match="not both"):
        strictmin.gparam(V, F, field="unit", cones=quarters)
    with pytest.raises(TypeError):
        strictmin.gparam(V, F, parallel=1)


def test_progress_records(closed):
    _, V, F = closed
    records = []
    strictmin.gparam(V, F, method="linf", quads=60, progress=records.append)
    phases = [r["message"] for r in records if r["stage"] == "gparam"]
    assert any(p.startswith("field:") for p in phases) and any(p.startswith("cut:") for p in phases)
    assert any(r["stage"] == "linf" for r in records)
    assert all(strictmin._format_record(r) for r in records)


def test_bad_input(closed):
    _, V, F = closed
    Vd, Fd = saddle(3)  # a disk: mapped (test_surface_with_boundary), but not with the closed-only options
    with pytest.raises(ValueError, match="boundary loop.*--integer-grid"):
        strictmin.gparam(Vd, Fd, integer_grid=True)
    with pytest.raises(ValueError, match="boundary loop.*--parallel"):
        strictmin.gparam(Vd, Fd, parallel=True)
    with pytest.raises(ValueError, match="edge_length must be a positive finite number"):
        strictmin.gparam(V, F, edge_length=0)
    with pytest.raises(ValueError, match="edge_length must be a positive finite number"):
        strictmin.gparam(V, F, edge_length=float("inf"))
    # Out of the surface's scale: the keyword, not the command line's flag (it said --edge-length).
    with pytest.raises(ValueError, match=r"^edge_length 1e-12 is out of scale for this surface"):
        strictmin.gparam(V, F, edge_length=1e-12)
    with pytest.raises(ValueError, match="quads must be positive"):
        strictmin.gparam(V, F, quads=0)
    with pytest.raises(ValueError, match="not both"):
        strictmin.gparam(V, F, edge_length=0.1, quads=10)
    with pytest.raises(ValueError, match="for gparam"):
        strictmin.gparam(V, F, measure="qc")
    with pytest.raises(ValueError, match="unknown method"):
        strictmin.gparam(V, F, method="best")
    with pytest.raises(ValueError, match="field takes"):
        strictmin.gparam(V, F, field="nicest")
    with pytest.raises(ValueError, match="#F by 3"):
        strictmin.gparam(V, F, field=np.ones((len(F), 2)))
    with pytest.raises(ValueError, match="directions for"):
        strictmin.gparam(V, F, field=np.ones((len(F) - 1, 3)))
    with pytest.raises(ValueError, match="not finite"):
        strictmin.gparam(V, F, field=np.full((len(F), 3), np.nan))
    # An array has rows, not lines: the message names the face alone.
    zero = np.ones((len(F), 3))
    zero[5] = 0
    with pytest.raises(ValueError, match=r"^field: face 5: the direction is zero$"):
        strictmin.gparam(V, F, field=zero)
    with pytest.raises(ValueError, match="curvature_alignment"):
        strictmin.gparam(V, F, field="curvature", curvature_alignment=0)
    # Only the curvature field has an alignment: elsewhere it would be ignored in silence.
    with pytest.raises(ValueError, match=r"curvature_alignment applies to field='curvature' only \(the field is 'unit'\)"):
        strictmin.gparam(V, F, field="unit", curvature_alignment=0.5)
    with pytest.raises(ValueError, match="the field is from cones"):
        strictmin.gparam(V, F, cones=np.zeros(len(V), dtype=int), curvature_alignment=0.5)
    with pytest.raises(ValueError, match="gap"):
        strictmin.gparam(V, F, method="linf", gap=2.0)
    with pytest.raises(TypeError, match="unexpected keyword argument 'pin'"):
        strictmin.gparam(V, F, pin=0)
    with pytest.raises(TypeError):
        strictmin.gparam(V, F, quads=1.5)


def test_integer_grid_matches_cli(tmp_path, closed):
    # The ellipsoid is of genus 0: every singular vertex and seam translation is rounded, the
    # map is on the grid to round-off, and the module gives the command line's map.
    mesh, V, F = closed
    summary, dist = cli_run(tmp_path, ["gparam", mesh, "--method", "linf", "--quads", 60, "--integer-grid"])
    r = strictmin.gparam(V, F, method="linf", quads=60, integer_grid=True)
    np.testing.assert_allclose(r.distortion, dist, rtol=0, atol=1e-12)
    same_summary(r.summary, summary)
    assert r.summary["integer_grid"] is True and r.summary["integer_error"] < 1e-9
    assert r.summary["off_grid_translations"] == 0 and r.summary["off_grid_singularities"] == 0
    assert r.summary["rounded_singularities"] >= len(r.singularities) - 1
    with pytest.raises(TypeError, match="integer_grid must be True or False"):
        strictmin.gparam(V, F, integer_grid=1)
    # The rounding's account as attributes, as the docstring says (they were in summary only).
    for key in ("integer_error", "rounded_singularities", "rounded_translations", "off_grid_singularities",
                "off_grid_translations"):
        assert getattr(r, key) == summary[key], key
    assert not hasattr(strictmin.gparam(V, F, quads=60), "integer_error")
    assert r.grid_guide == "l2" == summary["grid_guide"]


def test_integer_grid_linf_guide_matches_cli(tmp_path, closed):
    # grid_guide="linf" (the CLI's --grid-guide linf): the same map as the command line's, on
    # the grid; refused without integer_grid and for a name other than l2 / linf.
    mesh, V, F = closed
    summary, dist = cli_run(tmp_path, ["gparam", mesh, "--method", "linf", "--quads", 60, "--integer-grid",
                                       "--grid-guide", "linf"])
    r = strictmin.gparam(V, F, method="linf", quads=60, integer_grid=True, grid_guide="linf")
    np.testing.assert_allclose(r.distortion, dist, rtol=0, atol=1e-12)
    same_summary(r.summary, summary)
    assert r.grid_guide == "linf" == r.summary["grid_guide"]
    assert r.integer_error < 1e-9
    with pytest.raises(ValueError, match="grid_guide applies to integer_grid=True only"):
        strictmin.gparam(V, F, grid_guide="linf")
    with pytest.raises(ValueError, match="grid_guide takes 'l2' or 'linf', not 'l1'"):
        strictmin.gparam(V, F, integer_grid=True, grid_guide="l1")


def test_cones_out_of_range_and_empty(closed):
    """cones= is held to the cone file's range (-10000 <= q <= 3: a positive total angle, at
    most 10,000 quarter turns beyond 2 pi); q = 100000 was solved. An empty list names the
    count (it said 'got dtype float64')."""
    _, V, F = closed
    for q in (4, 100000, -10001):
        cones = np.zeros(len(V), dtype=int)
        cones[0], cones[1] = q, 8 - q
        with pytest.raises(ValueError, match=rf"cones: vertex 0: the index {q}/4 .*-10000 <= q <= 3"):
            strictmin.gparam(V, F, cones=cones)
    with pytest.raises(ValueError, match=f"cones: 0 cone indices for {len(V)} vertices"):
        strictmin.gparam(V, F, cones=[])


def test_surface_with_boundary(tmp_path):
    """A saddle-shaped disk: the field follows the boundary, Poincare-Hopf holds with the
    boundary's indices (chi 1), and the module gives the command line's map; a planar square
    grid (#V by 2) is mapped without distortion (its field is parallel to the sides)."""
    V, F = saddle(8)
    path = tmp_path / "saddle.obj"
    with open(path, "w") as f:
        f.writelines(f"v {x:.17g} {y:.17g} {z:.17g}\n" for x, y, z in V)
        f.writelines(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in F)
    summary, dist = cli_run(tmp_path, ["gparam", str(path), "--method", "linf", "--quads", 60])
    r = strictmin.gparam(V, F, method="linf", quads=60)
    np.testing.assert_allclose(r.distortion, dist, rtol=0, atol=1e-12)
    same_summary(r.summary, summary)
    assert r.boundary_loops == 1 == summary["boundary_loops"]
    assert r.euler_characteristic == 1
    assert sum(q for _, q in r.singularities) == 4
    assert r.seam_error < 1e-9
    flat = strictmin.gparam(*grid(6), method="linf", quads=30)
    assert flat.boundary_loops == 1
    assert sorted(q for _, q in flat.singularities) == [1, 1, 1, 1]  # the square's corners
    assert flat.summary["max_distortion"] < 1e-9
