"""What the Python module's tests share: small meshes made in code and the command-line tool
(STRICTMIN_CLI, set by ctest) to compare with. The module itself comes from PYTHONPATH
(build/python, set by ctest)."""
import os
import subprocess

import numpy as np
import pytest

import strictmin

CLI = os.environ.get("STRICTMIN_CLI", "")


def grid(n, size=1.0):
    """An n by n planar grid of squares split into triangles (counter-clockwise)."""
    xs = np.linspace(0.0, size, n + 1)
    V = np.array([[x, y] for y in xs for x in xs])
    F = []
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i
            b, c, d = a + 1, a + n + 2, a + n + 1
            F += [[a, b, c], [a, c, d]]
    return V, np.array(F, dtype=np.int64)


def saddle(n):
    """A disk-topology surface: the grid over [-1, 1]^2 lifted to z = 0.4 (x^2 - y^2)."""
    V2, F = grid(n, 2.0)
    V2 = V2 - 1.0
    V = np.column_stack([V2, 0.4 * (V2[:, 0] ** 2 - V2[:, 1] ** 2)])
    return V, F


def tet_bar(n):
    """An n by 1 by 1 bar of unit cubes, each split into 6 positively oriented tets."""
    def vid(i, j, k):
        return (i * 2 + j) * 2 + k
    V = np.array([[i, j, k] for i in range(n + 1) for j in range(2) for k in range(2)], dtype=float)
    T = []
    for i in range(n):
        c = [vid(i + (b >> 2 & 1), b >> 1 & 1, b & 1) for b in range(8)]  # corner b = (x, y, z) bits
        for a, b in ((1, 3), (1, 5), (2, 3), (2, 6), (4, 5), (4, 6)):  # paths 0 -> a -> b -> 7
            T.append([c[0], c[a], c[b], c[7]])
    T = np.array(T)
    for t in T:  # orient every tet positively
        d = np.linalg.det(V[t[1:]] - V[t[0]])
        if d < 0:
            t[[1, 2]] = t[[2, 1]]
    return V, T


def square_handles(V, n, shift=0.25):
    """The bottom row fixed, the top row moved sideways by `shift`."""
    bottom = np.arange(n + 1)
    top = np.arange(n * (n + 1), (n + 1) * (n + 1))
    idx = np.concatenate([bottom, top])
    pos = V[idx].copy()
    pos[n + 1:, 0] += shift
    return idx, pos


def run_cli(*args):
    if not CLI:
        pytest.skip("STRICTMIN_CLI is not set (ctest sets it)")
    # The tool runs on the module's dense kernels: it would otherwise choose better ones than
    # OpenBLAS's generic fallback (src/runtime/blas_kernels.h), and the maps would differ by round-off.
    env = dict(os.environ)
    core = strictmin.blas_kernels()[0]
    if core and "OPENBLAS_CORETYPE" not in env:
        env["OPENBLAS_CORETYPE"] = core
    p = subprocess.run([CLI, *map(str, args)], capture_output=True, text=True, timeout=300, env=env)
    if p.returncode not in (0, 2):
        raise AssertionError(f"strictmin {' '.join(map(str, args))}: exit {p.returncode}\n{p.stderr[-2000:]}")
    return p


def read_numbers(path):
    return np.loadtxt(path, ndmin=1)


def ellipsoid(subdivisions=2, axes=(1.0, 0.8, 0.6)):
    """A closed genus-0 surface: an icosahedron subdivided `subdivisions` times, projected to
    the unit sphere and scaled by `axes` (outward-facing triangles)."""
    t = (1.0 + 5 ** 0.5) / 2
    V = [[-1, t, 0], [1, t, 0], [-1, -t, 0], [1, -t, 0], [0, -1, t], [0, 1, t], [0, -1, -t], [0, 1, -t],
         [t, 0, -1], [t, 0, 1], [-t, 0, -1], [-t, 0, 1]]
    F = [[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4], [11, 10, 2], [10, 7, 6],
         [7, 1, 8], [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8], [3, 8, 9], [4, 9, 5], [2, 4, 11], [6, 2, 10],
         [8, 6, 7], [9, 8, 1]]
    V = [np.array(v, dtype=float) / np.linalg.norm(v) for v in V]
    for _ in range(subdivisions):
        middle = {}

        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in middle:
                m = V[a] + V[b]
                V.append(m / np.linalg.norm(m))
                middle[key] = len(V) - 1
            return middle[key]
        F = [f for a, b, c in F for f in ([a, mid(a, b), mid(c, a)], [b, mid(b, c), mid(a, b)],
                                          [c, mid(c, a), mid(b, c)], [mid(a, b), mid(b, c), mid(c, a)])]
    return np.array(V) * np.asarray(axes, dtype=float), np.array(F, dtype=np.int64)


def ellipsoid_file(tmp_path_factory, subdivisions, folder):
    """ellipsoid(subdivisions) written to an OBJ in a fresh folder and read back: the file, and
    V, F as the tool reads them from it."""
    V, F = ellipsoid(subdivisions)
    mesh = tmp_path_factory.mktemp(folder) / "ellipsoid.obj"
    strictmin.write_mesh(mesh, V, F)
    V, F = strictmin.read_mesh(mesh)
    return mesh, V, F
