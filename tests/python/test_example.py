"""examples/python/param_histograms.py runs on a small disk and writes its maps (read back
with meshio) and its PNG."""
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import strictmin
from conftest import saddle

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "python" / "param_histograms.py"


def test_example_writes_maps_and_png(tmp_path):
    meshio = pytest.importorskip("meshio")
    pytest.importorskip("matplotlib")
    V, F = saddle(6)
    mesh = tmp_path / "saddle.obj"
    strictmin.write_mesh(mesh, V, F)
    out = tmp_path / "out"
    p = subprocess.run([sys.executable, str(EXAMPLE), str(mesh), "--out", str(out)], capture_output=True, text=True,
                       timeout=120, env=dict(os.environ))
    assert p.returncode == 0, p.stderr
    png = out / "histograms.png"
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    m = meshio.read(out / "saddle_linfinity.obj")
    uv = m.point_data["obj:vt"]
    r = strictmin.param(V, F, method="linf", measure="arap")
    np.testing.assert_allclose(uv, r.uv, rtol=0, atol=1e-12)


def test_example_without_its_mesh_says_so(tmp_path):
    p = subprocess.run([sys.executable, str(EXAMPLE), str(tmp_path / "absent.obj"), "--out", str(tmp_path)],
                       capture_output=True, text=True, timeout=60, env=dict(os.environ))
    assert p.returncode == 0 and "is not there" in p.stderr
