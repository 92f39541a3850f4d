#!/usr/bin/env python3
"""Cross-check of our L-infinity interior-point solver against CVXOPT's SOCP solver.

linf_tool (tests/tools/linf_tool.cpp, path in STRICTMIN_LINF_TOOL) makes a problem, solves it
with solve_linf and dumps the cone program: G (triplets over the free dofs), h, per-element
bounds. Here the same program is given to cvxopt.solvers.socp:

    minimize k  s.t.  (k,   G_T x - h_T) in Q   for free elements
                      (k_T, G_T x - h_T) in Q   for elements with a fixed bound k_T

and we assert that our k agrees to 1e-6 (relative) and that our certified lower bound is
<= our k <= CVXOPT's k + tolerance. Small problems (up to 300 elements) use CVXOPT as it
is; medium ones (a few hundred to a few thousand elements: grids, bars, tets, real planar
meshes, with and without random rotation targets and fixed bounds) give CVXOPT a sparse
solver for its Newton systems (cvxopt_sparse_kkt.py), its algorithm unchanged. Exit code 77
(skip) when cvxopt is missing.
"""
import json
import os
import subprocess
import sys
import tempfile
import time

try:
    import cvxopt
    from cvxopt import matrix, spmatrix, solvers
    from cvxopt_sparse_kkt import ConeBlocks  # needs numpy too
except ImportError:
    print("cvxopt or numpy is not installed: skipping")
    sys.exit(77)

DATA = os.environ.get("STRICTMIN_SHARED_DATA", os.path.join(os.path.dirname(__file__), "..", "..", "..", "shared", "data"))
TOOL = os.environ.get("STRICTMIN_LINF_TOOL")
if not TOOL or not os.path.exists(TOOL):
    print("STRICTMIN_LINF_TOOL is not set to the linf_tool executable: skipping")
    sys.exit(77)

CASES = [
    ["--grid", "6", "6", "--shift", "0.2"],                          # Figure 2, small
    ["--grid", "8", "5", "--shift", "0.3", "--rotations", "4"],      # random rotation targets
    ["--bar", "12", "3", "--bend", "0.7"],                           # bar, one end fixed, other moved
    ["--bar", "10", "3", "--rotations", "7", "--angle", "1.0"],
    ["--tet", "2", "2", "2", "--shift", "0.4"],                      # tets
    ["--tet", "2", "2", "2", "--rotations", "3"],
    ["--grid", "6", "6", "--shift", "0.2", "--bounds", "6", "0.7", "5"],   # fixed bounds (inactive)
    ["--grid", "6", "6", "--shift", "0.2", "--bounds", "20", "0.38", "3"], # fixed bounds (active)
    ["--grid", "6", "6", "--shift", "0.2", "--bounds", "10", "0.3", "4"],
    ["--grid", "6", "6", "--shift", "0.2", "--bounds", "30", "0.39", "6"], # infeasible (phase 1)
    ["--grid", "6", "6", "--shift", "0.3", "--bounds", "70", "0.05", "2"], # fixed bounds (infeasible)
    # Medium problems, a few hundred to a few thousand elements (CVXOPT with a sparse KKT solver).
    ["--grid", "20", "20", "--rotations", "11", "--angle", "0.5"],   # 800 triangles, random targets
    ["--grid", "32", "32", "--shift", "0.25"],                       # 2,048 triangles, Figure 2
    ["--bar", "40", "8", "--rotations", "5", "--angle", "1.0"],      # 640 triangles
    ["--tet", "4", "4", "4", "--rotations", "9"],                    # 384 tets
    ["--grid", "24", "24", "--shift", "0.2", "--rotations", "2", "--angle", "0.3", "--bounds", "200", "0.6", "8"],
    ["--mesh", os.path.join(DATA, "planar", "gecko.obj"), "--rotations", "3", "--angle", "0.3"],  # 1,238
    ["--mesh", os.path.join(DATA, "planar", "woody.obj"), "--rotations", "6", "--angle", "0.6"],  # 1,267
    ["--grid", "40", "40", "--rotations", "4", "--angle", "0.2"],    # 3,200 triangles
]


# Above this many elements CVXOPT solves its Newton systems with cvxopt_sparse_kkt.
SPARSE_KKT_ABOVE = 300
# CVXOPT's iterative refinement steps with the sparse KKT solver (its default is 1): the
# normal equations lose accuracy near the optimum of larger problems.
REFINEMENT = int(os.environ.get("CVXOPT_REFINEMENT", "3"))


def run_tool(args):
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "linf.json")
        subprocess.run([TOOL] + args + ["--out", out], check=True)
        with open(out) as f:
            return json.load(f)


def cvxopt_solve(d):
    """min k over (x, k) with CVXOPT; returns (status, k, the tolerance it reached)."""
    n, m = d["n"], d["m"]
    t = n * m
    nx = d["num_x"]
    nv = nx + 1
    rows = {}
    for i, j, v in zip(d["G"]["i"], d["G"]["j"], d["G"]["v"]):
        rows.setdefault(i // t, []).append((i % t, j, v))
    h = d["h"]
    Gq, hq = [], []
    for e, bound in enumerate(d["bounds"]):
        vals, I, J = [], [], []
        if bound < 0:  # s0 = k = 0 - (-1) k
            vals.append(-1.0)
            I.append(0)
            J.append(nx)
            h0 = 0.0
        else:  # s0 = k_T
            h0 = bound
        for r, j, v in rows.get(e, []):  # s1 = G_T x - h_T = -h_T - (-G_T) x
            vals.append(-v)
            I.append(1 + r)
            J.append(j)
        Gq.append(spmatrix(vals, I, J, (t + 1, nv)) if vals else spmatrix([], [], [], (t + 1, nv)))
        hq.append(matrix([h0] + [-h[e * t + r] for r in range(t)]))
    c = matrix([0.0] * nx + [1.0])
    # Small problems: CVXOPT's own (dense) Newton systems. Medium ones: our sparse KKT solver
    # for CVXOPT's algorithm (cvxopt_sparse_kkt.py), CVXOPT's dense ones would take minutes.
    kktsolver = None
    if len(d["bounds"]) > SPARSE_KKT_ABOVE:
        cone_rows = []
        for e, bound in enumerate(d["bounds"]):
            rows_e = [(0, nx, -1.0)] if bound < 0 else []
            rows_e += [(1 + r, j, -v) for r, j, v in rows.get(e, [])]
            cone_rows.append(rows_e)
        kktsolver = ConeBlocks(cone_rows, t + 1, nv).kktsolver
    # CVXOPT can fail (math domain error in its scaling update) when asked for very high
    # accuracy: retry with looser tolerances; 1e-8 is still far inside our 1e-6 comparison.
    sol, used = None, None
    for tol in (1e-10, 1e-9, 1e-8, 1e-7):
        solvers.options.update({"show_progress": False, "abstol": tol, "reltol": tol, "feastol": tol,
                                "maxiters": 200, "refinement": 1 if kktsolver is None else REFINEMENT})
        try:
            sol = solvers.socp(c, Gq=Gq, hq=hq, kktsolver=kktsolver)
        except (ValueError, ArithmeticError):
            continue
        used = tol
        if sol["status"] in ("optimal", "primal infeasible"):
            break
    if sol is None:
        return "error (every tolerance failed)", float("nan"), None
    k = sol["x"][nx] if sol["x"] is not None else float("nan")
    return sol["status"], k, used


def main():
    failures = 0
    for args in CASES:
        if "--mesh" in args and not os.path.exists(args[args.index("--mesh") + 1]):
            print(f"skip {' '.join(args)}: the shared data folder is not here")
            continue
        d = run_tool(args)
        start = time.perf_counter()
        status, k_cvx, tol = cvxopt_solve(d)
        cvx_time = time.perf_counter() - start
        nan = float("nan")
        k = d["k"] if d["k"] is not None else nan
        lb = d["lower_bound"] if d["lower_bound"] is not None else nan  # JSON null: no bound
        # Times (docs/performance.md): ours is solve_linf's own time_s, CVXOPT's its socp calls.
        line = f"{' '.join(args)}: ours {d['status']} k={k:.10f} bound={lb:.10f} ({d['iterations']} it, " \
               f"{d['time_s']:.3f} s), cvxopt {status} k={k_cvx:.10f} (tolerance {tol}, {cvx_time:.3f} s)"
        ok = True
        if status == "primal infeasible":
            ok = d["status"] == "infeasible"
        elif d["status"] != "solved" or status != "optimal":
            ok = False
        else:
            scale = max(1.0, abs(k_cvx))
            # CVXOPT's k is its primal objective at a point feasible to its tolerance `tol`: our
            # certified bound may exceed it by that much, no more (1e-9 at the finest).
            ok = abs(k - k_cvx) <= 1e-6 * scale and lb <= k + 1e-12 and k <= k_cvx + 1e-6 * scale \
                and lb <= k_cvx + max(1e-9, tol) * scale
            # Bounded elements meet their bounds.
            for e, bound in enumerate(d["bounds"]):
                if bound >= 0 and d["distortion"][e] > bound + 1e-7:
                    ok = False
                    line += f" [element {e} exceeds its bound]"
        print(("ok   " if ok else "FAIL ") + line)
        failures += 0 if ok else 1
    print(f"{len(CASES) - failures} passed, {failures} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
