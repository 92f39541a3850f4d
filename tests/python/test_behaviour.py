"""What a Python user expects: real values checked against closed forms, the strict order,
progress records, silence by default, results that pickle, Ctrl-C, no leaks."""
import _thread
import os
import pickle
import threading
import time

import numpy as np
import pytest

import strictmin
from conftest import grid, saddle, square_handles


def test_closed_forms():
    V, F = grid(3)
    assert np.allclose(strictmin.distortion(V, F, V, "arap"), 0, atol=1e-14)
    # a uniform scale s: J = s I, ARAP distance to the closest rotation sqrt(2) |s - 1|
    assert np.allclose(strictmin.distortion(V, F, 1.5 * V, "arap"), np.sqrt(2) * 0.5, atol=1e-14)
    assert np.allclose(strictmin.distortion(V, F, 1.5 * V, "asap"), 0, atol=1e-14)
    # a stretch by 2 along x: sigma1 / sigma2 = 2, fd against the identity |2 - 1| = 1
    S = V * np.array([2.0, 1.0])
    assert np.allclose(strictmin.distortion(V, F, S, "qc"), 2, atol=1e-14)
    assert np.allclose(strictmin.distortion(V, F, S, "fd"), 1, atol=1e-14)
    # mirrored: every element flips, qc is infinite
    assert np.all(np.isinf(strictmin.distortion(V, F, V * np.array([-1.0, 1.0]), "qc")))
    w = strictmin.element_weights(V, F)
    assert w.sum() == pytest.approx(1.0, abs=1e-14)


def pulled_square(n, shift=0.3):
    """The paper's Figure 2: the square's boundary fixed, its centre pulled sideways."""
    V, F = grid(n)
    boundary = [i for i, (x, y) in enumerate(V) if min(x, y) < 1e-12 or max(x, y) > 1 - 1e-12]
    centre = int(np.argmin(np.sum((V - 0.5) ** 2, axis=1)))
    idx = np.array(boundary + [centre])
    pos = V[idx].copy()
    pos[-1, 0] += shift
    return V, F, idx, pos


def test_linf_exact_on_a_shear():
    """Top row shifted by s, bottom fixed: the mean of J is I + s e1 e2^T on any map, so no map
    has max ||J - I|| below s, and the affine shear reaches it."""
    n = 6
    V, F = grid(n)
    idx, pos = square_handles(V, n, 0.4)
    linf = strictmin.deform(V, F, idx, pos, method="linf")
    assert linf.status == "solved" and linf.usable
    assert linf.max_distortion == pytest.approx(0.4, rel=1e-7)
    assert linf.lower_bound == pytest.approx(0.4, rel=1e-7)
    assert np.allclose(linf.positions[idx], pos, atol=1e-12)  # the handles are where they were put


def test_linf_against_l2_and_the_strict_order():
    V, F, idx, pos = pulled_square(8)
    l2 = strictmin.deform(V, F, idx, pos, method="l2")
    linf = strictmin.deform(V, F, idx, pos, method="linf")
    relax = strictmin.deform(V, F, idx, pos, method="relax")
    assert linf.lower_bound <= linf.max_distortion <= linf.lower_bound * (1 + 1e-6) + 1e-12
    assert linf.max_distortion < l2.max_distortion
    assert relax.max_distortion <= linf.max_distortion * (1 + 1e-4)
    w = linf.weights
    assert strictmin.compare(linf.distortion, l2.distortion, w).order == -1
    assert strictmin.compare(l2.distortion, linf.distortion, w).order == 1
    c = strictmin.compare(relax.distortion, relax.distortion, w)
    assert (c.order, c.level) == (0, -1)
    order, level = strictmin.compare(np.array([1.0, 0.5]), np.array([1.0, 0.7]), np.array([1.0, 1.0]))
    assert (order, level) == (-1, 1)
    c = strictmin.compare([1.0, 0.5], [1.0, 0.7])
    assert (c.order, c.level, c.value_a, c.value_b) == (-1, 1, 0.5, 0.7)
    back = pickle.loads(pickle.dumps(c))
    assert back == c and back.value_b == 0.7


def test_result_object_and_pickle():
    V, F = saddle(4)
    r = strictmin.param(V, F, method="linf", measure="arap", lg_iterations=3)
    assert r.uv.shape == (len(V), 2) and r.distortion.shape == (len(F),)
    assert r.summary["task"] == "param" and r.summary["method"] == "linf"
    assert r.status in ("solved", "almost-solved", "max-iterations", "stalled")
    assert isinstance(r.history, list) and r.history and {"iteration", "max_distortion"} <= set(r.history[0])
    assert "Result(task='param'" in repr(r) and "status=" in repr(r)
    back = pickle.loads(pickle.dumps(r))
    np.testing.assert_array_equal(back.uv, r.uv)
    np.testing.assert_array_equal(back.distortion, r.distortion)
    assert back.summary == r.summary
    for a in (r.uv, r.distortion):
        np.testing.assert_array_equal(pickle.loads(pickle.dumps(a)), a)
    init = strictmin.param(V, F, method="tutte")
    assert init.summary["method"] == "tutte" and "iterations" not in init.summary


def test_progress_and_silence(capfd):
    V, F, idx, pos = pulled_square(4)
    records = []
    r = strictmin.deform(V, F, idx, pos, method="linf", progress=records.append)
    assert records and all(rec["stage"] == "linf" for rec in records)
    assert records[-1]["max_distortion"] == pytest.approx(r.max_distortion, rel=1e-9)
    assert np.isnan(records[-1]["largest_move"]) and np.isfinite(records[-1]["certified_gap"])
    steps = []
    strictmin.deform(V, F, idx, pos, method="direct", progress=steps.append, k_min=0.2)
    assert any(s["stage"] == "strict" for s in steps)
    # What a level's iteration count counts: the solve's interior-point iterations under the
    # field deviation, local-global steps under ARAP (each a whole L-infinity solve).
    assert {s["level_iteration_unit"] for s in steps} == {"interior-point iterations"}
    arap_steps = []
    strictmin.deform(V, F, idx, pos, method="direct", measure="arap", progress=arap_steps.append, k_min=0.2)
    assert arap_steps and {s["level_iteration_unit"] for s in arap_steps} == {"local-global steps"}
    assert all(s["level_iterations"] >= 1 for s in arap_steps)
    capfd.readouterr()
    strictmin.deform(V, F, idx, pos, method="relax", measure="arap", lg_iterations=2)
    out, err = capfd.readouterr()
    assert out == "" and err == ""
    strictmin.deform(V, F, idx, pos, method="linf", verbose=True)
    out, err = capfd.readouterr()
    assert "linf  iter" in err and "max" in err

    def failing(record):
        raise RuntimeError("stop here")
    with pytest.raises(RuntimeError, match="stop here"):
        strictmin.deform(V, F, idx, pos, method="linf", progress=failing)


def threads_now():
    return len(os.listdir("/proc/self/task"))


def test_interrupt():
    """A long solve stops on Ctrl-C (KeyboardInterrupt sent to the main thread) within 2 s."""
    n = 20
    V, F = grid(n)
    idx, pos = square_handles(V, n, 0.5)
    strictmin.deform(V, F, idx, pos, method="relax", sweeps=2)  # warm up the thread pools
    before = threads_now()
    sent = []

    def interrupt():
        sent.append(time.monotonic())
        _thread.interrupt_main()
    timer = threading.Timer(0.5, interrupt)
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        strictmin.deform(V, F, idx, pos, method="relax", sweeps=10**8)  # hours without the interrupt
    stopped = time.monotonic()
    timer.join()
    assert sent and stopped - sent[0] < 2.0
    time.sleep(0.1)
    assert threads_now() <= before  # the worker was joined
    # the module still works afterwards
    assert strictmin.deform(V, F, idx, pos, method="l2").status == "solved"


def rss_kib():
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    return 0


def test_no_leaks():
    n = 3
    V, F = grid(n)
    idx, pos = square_handles(V, n)

    def calls(count):
        for _ in range(count):
            r = strictmin.deform(V, F, idx, pos, method="l2")
            strictmin.distortion(V, F, r.positions, "arap")
            strictmin.compare(r.distortion, r.distortion, r.weights)
            try:
                strictmin.deform(V, F, idx, pos, gap=2)
            except ValueError:
                pass
    calls(200)
    before = rss_kib()
    calls(1000)
    after = rss_kib()
    assert after - before < 2048, f"resident memory grew by {after - before} KiB over 1,000 calls"


def test_any_layout_and_dtype():
    V, F, idx, pos = pulled_square(4)
    ref = strictmin.deform(V, F, idx, pos, method="linf")
    V32 = V.astype(np.float32).astype(np.float64)  # the values float32 holds
    a = strictmin.deform(V32.astype(np.float32), F.astype(np.uint16), list(idx), pos.tolist(), method="linf")
    b = strictmin.deform(V32, F, idx, pos, method="linf")
    np.testing.assert_array_equal(a.distortion, b.distortion)
    Vt = np.asfortranarray(V)
    Fs = np.repeat(F, 2, axis=0)[::2]  # F as a non-contiguous view
    assert not Fs.flags.c_contiguous
    c = strictmin.deform(Vt, Fs, idx[::-1], pos[::-1], method="linf", threads=1)
    np.testing.assert_allclose(c.distortion, ref.distortion, rtol=0, atol=1e-12)
    assert c.positions.flags.c_contiguous and c.positions.dtype == np.float64


def test_lower_bound_as_in_the_summary():
    V, F, idx, pos = pulled_square(4)
    linf = strictmin.deform(V, F, idx, pos, method="linf")
    assert linf.lower_bound == linf.summary["lower_bound"]
    arap = strictmin.deform(V, F, idx, pos, method="linf", measure="arap", lg_iterations=3)
    assert np.isnan(arap.lower_bound) and arap.summary["lower_bound"] is None
    assert arap.fd_step_lower_bound == arap.summary["fd_step_lower_bound"]
    assert [h["iteration"] for h in arap.history] == [h["iteration"] for h in arap.summary["history"]]
    assert all(h["stage"] == "local-global" for h in arap.history)


def test_read_write_round_trip(tmp_path):
    V, F = saddle(3)
    uv = V[:, :2] * 0.5
    q = np.arange(len(F), dtype=float)
    strictmin.write_mesh(tmp_path / "m.obj", V, F, uv=uv)
    strictmin.write_mesh(tmp_path / "m.ply", V, F, quality=q)
    V2, F2 = strictmin.read_mesh(tmp_path / "m.obj")
    np.testing.assert_array_equal(F2, F)
    np.testing.assert_allclose(V2, V, rtol=0, atol=1e-15)
    assert "property float quality" in (tmp_path / "m.ply").read_text()
    # the UVs written are the map: its distortion read back from the file's vt
    d_file = strictmin.distortion(V, F, uv, "asap")
    assert np.allclose(d_file, strictmin.distortion(V2, F2, uv, "asap"), atol=1e-15)
    with pytest.raises(ValueError, match="no file|cannot|No such"):
        strictmin.read_mesh(tmp_path / "missing.obj")
    with pytest.raises(ValueError, match="quality has 3 values"):
        strictmin.write_mesh(tmp_path / "q.ply", V, F, quality=q[:3])


def test_write_mesh_refuses_what_the_format_cannot_hold(tmp_path):
    # uv is an OBJ's vt, quality a PLY's face property: elsewhere they were dropped silently.
    V, F = grid(2)
    uv = V.copy()
    for ext in ("ply", "off"):
        with pytest.raises(ValueError, match="cannot hold it"):
            strictmin.write_mesh(tmp_path / f"x.{ext}", V, F, uv=uv)
    with pytest.raises(ValueError, match="cannot hold it"):
        strictmin.write_mesh(tmp_path / "x.obj", V, F, quality=np.ones(len(F)))
    strictmin.write_mesh(tmp_path / "x.obj", V, F, uv=uv)
    strictmin.write_mesh(tmp_path / "x.ply", V, F, quality=np.ones(len(F)))


def test_surface_relax_in_3d():
    """A saddle surface in 3D deforms in 3D with relax (3x2 Jacobians): its far edge turned
    about the z axis and lifted, the near edge held. With fd, arap and asap relax is no higher
    than linf and less distorting in the strict order; the handles stay."""
    n = 8
    V, F = saddle(n)
    near = np.arange(n + 1)
    far = np.arange(n * (n + 1), (n + 1) * (n + 1))
    idx = np.concatenate([near, far])
    c, s = np.cos(0.4), np.sin(0.4)
    pos = V[idx].copy()
    pos[n + 1:] = pos[n + 1:] @ np.array([[c, s, 0], [-s, c, 0], [0, 0, 1]]) + [0, 0, 0.3]
    for measure in ("arap", "asap", "fd"):
        linf = strictmin.deform(V, F, idx, pos, method="linf", measure=measure)
        relax = strictmin.deform(V, F, idx, pos, method="relax", measure=measure)
        assert relax.usable, relax.summary["stop_reason"]
        assert relax.positions.shape == V.shape
        assert np.allclose(relax.positions[idx], pos, atol=1e-12)
        assert relax.summary["dimension"] == 3 and relax.summary["method"] == "relax"
        assert linf.max_distortion > 0.01  # a real deformation (asap: 0.03)
        assert relax.max_distortion <= linf.max_distortion * (1 + 1e-4)
        tolerance = 1e-4 * linf.max_distortion
        assert strictmin.compare(relax.distortion, linf.distortion, linf.weights, tolerance).order == -1


def test_iso_frame_iteration_cap():
    # frame_iterations caps the qc/iso frame loop: one iteration either converged at once or
    # says max-iterations; 0 is refused like the CLI's --frame-iterations 0.
    V, F = saddle(4)
    r = strictmin.param(V, F, method="linf", measure="iso", frame_iterations=1)
    assert r.summary["frame_iterations"] == 1 and r.summary["flipped"] == 0
    assert r.status in ("solved", "max-iterations")
    full = strictmin.param(V, F, method="linf", measure="iso")
    assert full.summary["max_distortion"] <= r.summary["max_distortion"] + 1e-9
    with pytest.raises(ValueError, match="frame_iterations"):
        strictmin.param(V, F, method="linf", measure="iso", frame_iterations=0)


def test_local_global_step_options():
    # lg_extrapolation / lg_warm_start / lg_acceleration reach local-global: a run without the
    # faster steps ends at the same local optimum to the stopping tolerance; out-of-range
    # values are refused naming the option.
    V, F, idx, pos = pulled_square(6)
    fast = strictmin.deform(V, F, idx, pos, method="linf", measure="arap", lg_tolerance=1e-8, lg_iterations=300)
    plain = strictmin.deform(V, F, idx, pos, method="linf", measure="arap", lg_tolerance=1e-8, lg_iterations=300,
                             lg_extrapolation=0.0, lg_warm_start=False, lg_acceleration=0)
    assert abs(fast.max_distortion - plain.max_distortion) <= 1e-6
    with pytest.raises(ValueError, match="target_extrapolation"):
        strictmin.deform(V, F, idx, pos, method="linf", measure="arap", lg_extrapolation=1.5)
    # The command line's flag names work as keywords too: lg_cold_start (= not lg_warm_start).
    cold = strictmin.deform(V, F, idx, pos, method="linf", measure="arap", lg_tolerance=1e-8, lg_iterations=300,
                            lg_extrapolation=0.0, lg_cold_start=True, lg_acceleration=0)
    assert cold.max_distortion == plain.max_distortion
    # interp does not take lg_extrapolation (its targets are the blended shapes' rotations,
    # which are not extrapolated; the value was ignored).
    with pytest.raises(TypeError, match="lg_extrapolation"):
        strictmin.interp(V, F, V + 0.1, 0.5, method="linf", lg_extrapolation=0.0)


def test_cli_flags_as_keywords():
    # no_flips, max_levels and relax_init beside init (param), as the command line's flags.
    V, F = saddle(6)
    capped = strictmin.param(V, F, method="direct", measure="fd", max_levels=2)
    assert capped.status == "max-iterations" and capped.iterations == 2
    kept = strictmin.param(V, F, method="linf", measure="arap", no_flips=True)
    assert kept.summary["no_flips"] is True and kept.summary["flips_added"] == 0
    r = strictmin.param(V, F, method="relax", init="lscm", relax_init="l2", sweeps=3)
    assert r.summary["init"] == "lscm" and r.summary["relax_init"] == "l2"
    default = strictmin.param(V, F, method="relax", sweeps=3)
    assert default.summary["init"] == "tutte" and default.summary["relax_init"] == "linf"


def test_blas_kernels_reports_the_kernels_and_a_better_set_only_after_the_generic_fallback():
    import subprocess
    import sys
    core, better = strictmin.blas_kernels()
    assert isinstance(core, str)
    assert better is None or (core == "Prescott" and better in ("SkylakeX", "Haswell"))
    if not core:
        pytest.skip("the BLAS is not OpenBLAS")
    # OPENBLAS_CORETYPE, read when OpenBLAS loads, is the user's choice: nothing better is offered.
    env = dict(os.environ, OPENBLAS_CORETYPE="Haswell")
    out = subprocess.run([sys.executable, "-c", "import strictmin; print(strictmin.blas_kernels())"],
                         env=env, capture_output=True, text=True, timeout=60)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "('Haswell', None)"


def test_write_mesh_refuses_coordinates_that_are_not_finite(tmp_path):
    # "nan" and "inf" in a file are read back by no reader: refused before any file is made.
    V, F = grid(2)
    bad = V.copy()
    bad[3, 1] = np.nan
    with pytest.raises(ValueError, match="vertex 3"):
        strictmin.write_mesh(tmp_path / "v.obj", bad, F)
    uv = V[:, :2].copy()
    uv[2, 0] = np.inf
    with pytest.raises(ValueError, match=r"texture coordinate 2 \(0-based\) has a non-finite value \(inf\)"):
        strictmin.write_mesh(tmp_path / "u.obj", V, F, uv=uv)
    assert list(tmp_path.iterdir()) == []
