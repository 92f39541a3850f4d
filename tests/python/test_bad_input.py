"""Every bad input of the C++ contract raises ValueError with the library's message (the one
the command line prints); unknown keywords and wrong types raise TypeError."""
import numpy as np
import pytest

import strictmin
from conftest import ellipsoid, grid, run_cli, square_handles


@pytest.fixture
def square():
    n = 3
    V, F = grid(n)
    idx, pos = square_handles(V, n)
    return V, F, idx, pos


def test_mesh_arrays(square):
    V, F, idx, pos = square
    with pytest.raises(ValueError, match="V must be #V by 2 or 3"):
        strictmin.deform(V[:, :1], F, idx, pos)
    with pytest.raises(ValueError, match="F must be #F by 3"):
        strictmin.deform(V, F[:, :2], idx, pos)
    with pytest.raises(ValueError, match="integer"):
        strictmin.deform(V, F + 0.5, idx, pos)
    bad = V.copy()
    bad[2, 1] = np.nan
    with pytest.raises(ValueError, match="non-finite"):
        strictmin.deform(bad, F, idx, pos)
    out = F.copy()
    out[1, 2] = len(V)
    with pytest.raises(ValueError, match="out of range"):
        strictmin.deform(V, out, idx, pos)
    neg = F.copy()
    neg[0, 0] = -1
    with pytest.raises(ValueError, match="out of range"):
        strictmin.deform(V, neg, idx, pos)
    rep = F.copy()
    rep[0, 1] = rep[0, 0]
    with pytest.raises(ValueError, match="repeated|twice"):
        strictmin.param(np.column_stack([V, V[:, 0] * V[:, 1]]), rep)
    flat = V.copy()
    flat[F[0]] = flat[F[0, 0]]  # collapse one triangle to a point
    with pytest.raises(ValueError):
        strictmin.distortion(flat, F, V)
    with pytest.raises(ValueError, match="empty|no element|no vert"):
        strictmin.distortion(np.zeros((0, 2)), np.zeros((0, 3), dtype=int), np.zeros((0, 2)))


def test_same_message_as_the_cli(tmp_path, square):
    """A degenerate triangle: the library's message, naming the element, as the tool's."""
    V, F, idx, pos = square
    flat = V.copy()
    flat[5] = flat[1]  # triangle (0, 1, 5) collapses to a segment
    with pytest.raises(ValueError) as python_error:
        strictmin.distortion(flat, F, flat)
    path = tmp_path / "bad.off"
    path.write_text(f"OFF\n{len(V)} {len(F)} 0\n" + "".join(f"{x!r} {y!r} 0\n" for x, y in flat) +
                    "".join(f"3 {a} {b} {c}\n" for a, b, c in F))
    p = run_cli_failing("eval", path, path)
    reason = str(python_error.value).split(": ", 1)[1]
    assert reason in p.stderr, (reason, p.stderr)
    p = run_cli_failing("deform", "--example", "square", "--method", "foo")
    with pytest.raises(ValueError) as method_error:
        strictmin.deform(V, F, idx, pos, method="foo")
    assert str(method_error.value) in p.stderr


def run_cli_failing(*args):
    import subprocess
    from conftest import CLI
    if not CLI:
        pytest.skip("STRICTMIN_CLI is not set (ctest sets it)")
    p = subprocess.run([CLI, *map(str, args)], capture_output=True, text=True, timeout=60)
    assert p.returncode == 1, p.stderr
    return p


def test_handles(square):
    V, F, idx, pos = square
    with pytest.raises(ValueError, match="vertex 99 out of range"):
        strictmin.deform(V, F, np.append(idx, 99), np.vstack([pos, [0, 0]]))
    with pytest.raises(ValueError, match="handle_indices but"):
        strictmin.deform(V, F, idx, pos[:-1])
    with pytest.raises(ValueError, match="coordinates, the mesh is 2D"):
        strictmin.deform(V, F, idx, np.column_stack([pos, pos[:, 0]]))
    nan = pos.copy()
    nan[0, 0] = np.nan
    with pytest.raises(ValueError, match="non-finite"):
        strictmin.deform(V, F, idx, nan)
    with pytest.raises(ValueError, match="two different targets"):
        strictmin.deform(V, F, np.append(idx, idx[0]), np.vstack([pos, pos[0] + 1]))
    with pytest.raises(ValueError, match="no handles"):
        strictmin.deform(V, F, [], np.zeros((0, 2)))
    island_V = np.vstack([V, [[5, 5], [6, 5], [5, 6]]])  # a second part, no handle on it
    island_F = np.vstack([F, [[len(V), len(V) + 1, len(V) + 2]]])
    with pytest.raises(ValueError, match="has no handle"):
        strictmin.deform(island_V, island_F, idx, pos)


def test_options(square):
    V, F, idx, pos = square
    with pytest.raises(ValueError, match="^gap: .*gap_tolerance must be in \\(0, 1\\) \\(got 2\\)"):
        strictmin.deform(V, F, idx, pos, gap=2)
    with pytest.raises(ValueError, match="^delta_k: .*delta_k must be > 0"):
        strictmin.deform(V, F, idx, pos, method="direct", delta_k=0)
    # lg_* keywords with a measure that takes no local steps were accepted and ignored.
    with pytest.raises(ValueError, match="lg_iterations applies to measure 'arap' or 'asap' .*not 'fd'"):
        strictmin.deform(V, F, idx, pos, lg_iterations=5)
    with pytest.raises(ValueError, match="lg_cold_start applies to measure 'arap' or 'asap' .*not 'qc'"):
        strictmin.param(V, F, measure="qc", lg_cold_start=True)
    # gparam has no asap: its message names arap alone.
    with pytest.raises(ValueError, match="^lg_iterations applies to measure 'arap' \\(its local-global iterations\\), not 'fd'"):
        strictmin.gparam(V, F, lg_iterations=5)
    assert strictmin.deform(V, F, idx, pos, measure="arap", lg_iterations=3).positions.shape == V[:, :2].shape
    # exact's size limit names the keyword too (the message named only the CLI's flag).
    with pytest.raises(ValueError, match="18 elements is above its limit of 10 .*exact_max_elements in Python"):
        strictmin.deform(V, F, idx, pos, method="exact", exact_max_elements=10)
    with pytest.raises(ValueError, match="^sweeps: "):
        strictmin.deform(V, F, idx, pos, sweeps=-1)
    with pytest.raises(ValueError, match="^accept_tolerance: "):
        strictmin.deform(V, F, idx, pos, accept_tolerance=float("nan"))
    with pytest.raises(ValueError, match="^threads must be >= 0"):
        strictmin.deform(V, F, idx, pos, threads=-2)
    with pytest.raises(ValueError, match="^lg_iterations must be >= 1"):
        strictmin.deform(V, F, idx, pos, measure="arap", lg_iterations=0)
    with pytest.raises(ValueError, match="unknown measure 'foo'"):
        strictmin.deform(V, F, idx, pos, measure="foo")
    with pytest.raises(ValueError, match="unknown init"):
        strictmin.deform(V, F, idx, pos, method="relax", init="direct")
    with pytest.raises(ValueError, match="unknown start"):
        strictmin.deform(V, F, idx, pos, measure="arap", start="middle")
    with pytest.raises(TypeError, match="unexpected keyword argument 'gapp'"):
        strictmin.deform(V, F, idx, pos, gapp=1e-3)
    with pytest.raises(TypeError, match="unexpected keyword argument 'pin'"):
        strictmin.deform(V, F, idx, pos, pin=3)
    with pytest.raises(TypeError, match="sweeps must be an integer"):
        strictmin.deform(V, F, idx, pos, sweeps=2.5)
    with pytest.raises(TypeError, match="progress must be callable"):
        strictmin.deform(V, F, idx, pos, progress=3)
    # An int too large for the option is out of range (ValueError), not "not an integer".
    with pytest.raises(ValueError, match="^sweeps: 9223372036854775808 is out of range"):
        strictmin.deform(V, F, idx, pos, sweeps=2**63)
    # A string t is not iterated character by character.
    with pytest.raises(TypeError, match="t must be a number or a sequence"):
        strictmin.interp(V, F, V * 2, "0.5")
    with pytest.raises(ValueError, match="unknown relax_init 'direct'"):
        strictmin.param(np.column_stack([V, 0 * V[:, 0]]), F, method="relax", relax_init="direct")


def test_small_bad_values_are_quoted_as_given(square):
    """A value out of range by a little is quoted with its digits: these messages printed
    -1e-12 as "-0.000000" (std::to_string's fixed six decimals)."""
    V, F, idx, pos = square
    surface = np.column_stack([V, 0.1 * V[:, 0] * V[:, 1]])
    with pytest.raises(ValueError, match=r"accept_tolerance must be in \[0, 1\) \(got -1e-09\)"):
        strictmin.deform(V, F, idx, pos, method="relax", accept_tolerance=-1e-9)
    with pytest.raises(ValueError, match=r"lg_tolerance must be >= 0 \(got -1e-09\)"):
        strictmin.deform(V, F, idx, pos, measure="arap", lg_tolerance=-1e-9)
    with pytest.raises(ValueError, match=r"target_extrapolation must be in \[0, 1\] \(got 1.0000001\)"):
        strictmin.param(surface, F, lg_extrapolation=1.0000001)
    with pytest.raises(ValueError, match=r"edge_length must be a positive finite number, got -1e-12$"):
        strictmin.gparam(V, F, edge_length=-1e-12)
    with pytest.raises(ValueError, match=r"curvature_alignment must be a positive number, got -1e-12$"):
        strictmin.gparam(V, F, field="curvature", curvature_alignment=-1e-12)


def test_param_init_contradicting_the_start_method(square):
    """method="tutte" is Tutte's map itself: init="lscm" beside it was silently dropped."""
    V, F, _, _ = square
    surface = np.column_stack([V, 0.1 * V[:, 0] * V[:, 1]])
    with pytest.raises(ValueError, match="init='lscm' contradicts method='tutte'"):
        strictmin.param(surface, F, method="tutte", init="lscm")
    with pytest.raises(ValueError, match="init='tutte' contradicts method='lscm'"):
        strictmin.param(surface, F, method="lscm", init="tutte")
    assert strictmin.param(surface, F, method="lscm").summary["init"] == "lscm"
    assert strictmin.param(surface, F, method="tutte", init="tutte").summary["init"] == "tutte"
    assert strictmin.param(surface, F, method="l2").summary["init"] == "tutte"


def test_tasks(square):
    V, F, idx, pos = square
    surface = np.column_stack([V, V[:, 0] * V[:, 1]])
    # A 3D surface deforms in 3D: handles with 2 coordinates are refused.
    with pytest.raises(ValueError, match="2 coordinates, the mesh is 3D"):
        strictmin.deform(surface, F, idx, np.column_stack([pos]))
    with pytest.raises(ValueError, match="'relax' is not available"):
        strictmin.param(surface, F, measure="qc", method="relax")
    with pytest.raises(ValueError, match="outside \\[0, 1\\]"):
        strictmin.interp(V, F, V * 2, 1.5)
    # A method's own keyword with another method would be ignored: refused, as on the command line.
    with pytest.raises(ValueError, match="sweeps applies to method relax; method 'linf' does not read it"):
        strictmin.deform(V, F, idx, pos, method="linf", sweeps=3)
    with pytest.raises(ValueError, match="p applies to method lp \\(or relax starting from lp\\)"):
        strictmin.param(surface, F, method="l2", p=8)
    # Shown as given (it read "t: -0.000000 is outside [0, 1]").
    with pytest.raises(ValueError, match="t: -1e-09 is outside"):
        strictmin.interp(V, F, V * 2, -1e-9)
    with pytest.raises(ValueError, match="target has"):
        strictmin.interp(V, F, V[:-1], 0.5)
    with pytest.raises(ValueError, match="pin"):
        strictmin.interp(V, F, V * 2, 0.5, pin=len(V))
    with pytest.raises(ValueError, match="U has"):
        strictmin.distortion(V, F, V[:-1])
    with pytest.raises(ValueError, match="one length"):
        strictmin.compare(np.ones(3), np.ones(4))
    for bad in ({"value_tolerance": -1}, {"value_tolerance": float("nan")}, {"area_tolerance": -1}):
        with pytest.raises(ValueError, match="must be >= 0"):
            strictmin.compare(np.ones(3), np.ones(3), **bad)
    # Infinite maxima tie (inf - inf made each of two identical vectors the lesser).
    assert strictmin.compare(np.array([np.inf, 1.0]), np.array([np.inf, 1.0])).order == 0


def test_images_beyond_1e150_are_refused(square):
    # An image's coordinates overflowed its distortions: an interpolation target of 1e200 gave
    # frames "solved" with a NaN maximum, distortion() inf (as the CLI's eval and interp).
    V, F, idx, pos = square
    with pytest.raises(ValueError, match="target: vertex 1 \\(0-based\\) has the coordinate .*, beyond 1e150"):
        strictmin.interp(V, F, V * 1e200, 0.5)
    with pytest.raises(ValueError, match="U: vertex 1 \\(0-based\\) has the coordinate .*e\\+199, beyond 1e150"):
        strictmin.distortion(V, F, V * 1e200)
    with pytest.raises(ValueError, match="U: corner image 0 \\(0-based\\) has the coordinate 1e\\+200, beyond 1e150"):
        strictmin.distortion(V, F, np.full((F.size, 2), 1e200))  # one image per corner
    with pytest.raises(ValueError, match="U: vertex 0 \\(0-based\\) has a non-finite coordinate \\(inf\\)"):
        strictmin.distortion(V, F, V + np.inf)
    with pytest.raises(ValueError, match="U: corner image 0 \\(0-based\\) has a non-finite coordinate \\(nan\\)"):
        strictmin.distortion(V, F, np.full((F.size, 2), np.nan))
    # 1e140 is within the limit: the closed form (fd of x -> s x is |s - 1| sqrt(2)).
    assert strictmin.distortion(V, F, V * 1e140, "fd").max() == pytest.approx(np.sqrt(2) * 1e140)


def test_keywords_that_do_not_apply_are_refused(square):
    # frame_iterations (qc / iso) and start (arap / asap) were ignored elsewhere.
    V, F, idx, pos = square
    with pytest.raises(ValueError, match="frame_iterations applies to measure 'qc' or 'iso'.*'fd'"):
        strictmin.deform(V, F, idx, pos, measure="fd", frame_iterations=3)
    with pytest.raises(ValueError, match="frame_iterations applies to measure 'qc' or 'iso'.*'arap'"):
        strictmin.param(V, F, measure="arap", frame_iterations=3)
    with pytest.raises(ValueError, match="frame_iterations applies to measure 'qc' or 'iso'.*interp"):
        strictmin.interp(V, F, V * 2, 0.5, frame_iterations=3)
    with pytest.raises(ValueError, match="frame_iterations applies"):
        strictmin.gparam(*ellipsoid(), frame_iterations=3)
    for measure in ("fd", "qc", "iso"):
        with pytest.raises(ValueError, match=f"start applies to measure 'arap' or 'asap'.*'{measure}'"):
            strictmin.deform(V, F, idx, pos, measure=measure, start="rest")
    with pytest.raises(ValueError, match="frame_iterations applies to method 'linf' or 'direct'.*'l2'"):
        strictmin.deform(V, F, idx, pos, "l2", measure="qc", frame_iterations=3)  # the starting map
    assert strictmin.deform(V, F, idx, pos, measure="qc", frame_iterations=3).usable
    assert strictmin.deform(V, F, idx, pos, measure="arap", start="rest").usable


def test_every_vertex_a_handle_is_solved_under_qc_and_iso(square):
    # Nothing to optimise: the frame loop ran to its cap and said max-iterations.
    V, F, _, _ = square
    idx = np.arange(len(V))
    pos = V * [1.5, 1.0]
    for measure in ("qc", "iso"):
        r = strictmin.deform(V, F, idx, pos, method="linf", measure=measure)
        assert r.status == "solved", r.message
        assert "nothing to optimise" in r.message
        assert r.summary["frame_iterations"] == 0 and r.iterations == 0
        assert r.max_distortion == pytest.approx(1.5)


def test_surface_deforms_in_3d(square):
    # A 3D triangle surface takes 3D handles (as the CLI): handles at their rest positions
    # give the identity map, distortion 0.
    V, F, idx, _ = square
    surface = np.column_stack([V, V[:, 0] * V[:, 1]])
    r = strictmin.deform(surface, F, idx, surface[idx], method="linf", measure="arap")
    assert r.usable
    assert r.positions.shape == surface.shape
    assert r.distortion.max() < 1e-6


def test_read_mesh_of_a_flipped_map(tmp_path):
    # A map's image with a flipped triangle (an interpolation target, a frame): the command
    # line reads it without the geometry checks; read_mesh could not (no option).
    path = tmp_path / "flipped.obj"
    path.write_text("v 0 0\nv 1 0\nv 0 1\nv 0.2 0.2\nf 1 2 3\nf 2 4 3\n")  # vertex 3 folded over: f 2 is clockwise
    with pytest.raises(ValueError):
        strictmin.read_mesh(path)
    V, F = strictmin.read_mesh(path, check_geometry=False)
    assert V.shape == (4, 2) and F.shape == (2, 3)
    with pytest.raises(TypeError, match="path must be a str"):
        strictmin.read_mesh(None)
    with pytest.raises(TypeError, match="path must be a str"):
        strictmin.read_mesh(b"flipped.obj")


def test_wrong_types_name_the_argument(square, tmp_path):
    """An argument of the wrong type names itself and what it takes (numpy's and pybind11's
    own messages named neither: "could not convert string to float: 'a'", "'complex' object
    is not iterable", "incompatible function arguments")."""
    import decimal
    V, F, idx, pos = square
    cases = [
        (lambda: strictmin.deform(V.astype(str), F, idx, pos), "V must hold real numbers, not str"),
        (lambda: strictmin.deform(V + 0j, F, idx, pos), "V must hold real numbers, not complex"),
        (lambda: strictmin.deform(V, F.astype(str), idx, pos), "F must hold integer indices, not str"),
        (lambda: strictmin.deform(V, F, ["a"] * len(idx), pos), "handle_indices must hold integer indices, not str"),
        (lambda: strictmin.deform(V, F, None, pos), "handle_indices must hold integer indices, not NoneType"),
        (lambda: strictmin.deform(V, F, idx, pos.astype(str)), "handle_positions must hold real numbers, not str"),
        (lambda: strictmin.deform(V, F, idx, pos * 1j), "handle_positions must hold real numbers, not complex"),
        (lambda: strictmin.deform(V, F, idx, [[0, "a"]] * len(idx)), "handle_positions must hold real numbers, not str"),
        (lambda: strictmin.deform(V, F, idx, pos, method=3), "method must be a string, not int"),
        (lambda: strictmin.deform(V, F, idx, pos, measure=None), "measure must be a string, not NoneType"),
        (lambda: strictmin.param(V, F, init=3), "init must be a string, not int"),
        (lambda: strictmin.deform(V, F, idx, pos, linf_min_l2=1), "linf_min_l2 must be True or False, not int"),
        (lambda: strictmin.interp(V, F, V * 2, 0.5 + 1j), "t must be a number or a sequence of numbers in \\[0, 1\\], not complex"),
        (lambda: strictmin.interp(V, F, V * 2, None), "not NoneType"),
        (lambda: strictmin.interp(V, F, V * 2, [0.25, 0.5 + 1j]), "t\\[1\\] must be a real number, not complex"),
        (lambda: strictmin.interp(V, F, V * 2, ["0.5"]), "t\\[0\\] must be a real number, not str"),
        (lambda: strictmin.interp(V, F, V * 2, np.array(0.5j)), "t must be a real number, not complex"),
        (lambda: strictmin.interp(V, F, (V * 2).astype(str), 0.5), "V_target must hold real numbers, not str"),
        (lambda: strictmin.distortion(V, F, V.astype(str)), "U must hold real numbers, not str"),
        (lambda: strictmin.distortion(V, F, V, measure=1), "measure must be a string, not int"),
        (lambda: strictmin.compare(["a"], [1.0]), "d1 must hold real numbers, not str"),
        (lambda: strictmin.compare([1.0], [1j]), "d2 must hold real numbers, not complex"),
        (lambda: strictmin.compare([1.0], [1.0], [None]), "weights must hold real numbers, not NoneType"),
        (lambda: strictmin.compare([1.0], [1.0], value_tolerance="x"), "value_tolerance must be a real number, not str"),
        (lambda: strictmin.compare([1.0], [1.0], area_tolerance=1j), "area_tolerance must be a real number, not complex"),
        (lambda: strictmin.write_mesh(tmp_path / "q.ply", V, F, quality=["a"] * len(F)),
         "quality must hold real numbers, not str"),
        (lambda: strictmin.write_mesh(3, V, F), "write_mesh: path must be a str or os.PathLike, not int"),
        (lambda: strictmin.gparam(V, F, edge_length=1j), "edge_length must be a real number, not complex"),
        (lambda: strictmin.gparam(V, F, field="curvature", curvature_alignment="0.1"), "curvature_alignment must be a real number, not str"),
    ]
    for call, message in cases:
        with pytest.raises(TypeError, match=message):
            call()
    with pytest.raises(ValueError, match="handle_positions must be an array of real numbers, got rows of different"):
        strictmin.deform(V, F, idx[:2], [[0.0, 0.0], [1.0]])
    with pytest.raises(ValueError, match="F: index 4294967296 out of range"):
        strictmin.deform(V, np.array([[0, 1, 2**32]], dtype=object), idx, pos)
    # Real numbers of other types are taken as numbers.
    r = strictmin.interp(V, F, V * 2, decimal.Decimal("0.5"), method="l2")
    assert r.t == 0.5
    assert [x.t for x in strictmin.interp(V, F, V * 2, [decimal.Decimal("0.25"), np.float32(0.5)], method="l2")] == [0.25, 0.5]
    assert strictmin.compare(np.array([1, 2], dtype=object), [decimal.Decimal(1), 2]).order == 0
