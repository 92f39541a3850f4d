#!/usr/bin/env python3
"""Cross-check of our L-infinity interior-point solver against CVXOPT's SOCP solver.

linf_tool (tests/tools/linf_tool.cpp, path in STRICTMIN_LINF_TOOL) makes a problem, solves it
with solve_linf and dumps the cone program: G (triplets over the free dofs), h, per-element
bounds. Here the same program is given to cvxopt.solvers.socp:

    minimize k  s.t.  (k,   G_T x - h_T) in Q   for free elements
                      (k_T, G_T x - h_T) in Q   for elements with a fixed bound k_T

and we assert that our k agrees to 1e-6 (relative) and that our certified lower bound is
<= our k <= CVXOPT's k + tolerance. Exit code 77 (skip) when cvxopt is missing.
"""
import json
import os
import subprocess
import sys
import tempfile

try:
    import cvxopt
    from cvxopt import matrix, spmatrix, solvers
except ImportError:
    print("cvxopt is not installed: skipping")
    sys.exit(77)

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
]


def run_tool(args):
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "linf.json")
        subprocess.run([TOOL] + args + ["--out", out], check=True)
        with open(out) as f:
            return json.load(f)


def cvxopt_solve(d):
    """min k over (x, k) with CVXOPT; returns (status, k)."""
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
    # CVXOPT can fail (math domain error in its scaling update) when asked for very high
    # accuracy: retry with looser tolerances; 1e-8 is still far inside our 1e-6 comparison.
    for tol in (1e-10, 1e-9, 1e-8):
        solvers.options.update({"show_progress": False, "abstol": tol, "reltol": tol, "feastol": tol,
                                "maxiters": 200})
        try:
            sol = solvers.socp(c, Gq=Gq, hq=hq)
        except (ValueError, ArithmeticError):
            continue
        if sol["status"] in ("optimal", "primal infeasible"):
            break
    k = sol["x"][nx] if sol["x"] is not None else float("nan")
    return sol["status"], k


def main():
    failures = 0
    for args in CASES:
        d = run_tool(args)
        status, k_cvx = cvxopt_solve(d)
        nan = float("nan")
        k = d["k"] if d["k"] is not None else nan
        lb = d["lower_bound"] if d["lower_bound"] is not None else nan  # JSON null: no bound
        line = f"{' '.join(args)}: ours {d['status']} k={k:.10f} bound={lb:.10f} ({d['iterations']} it), " \
               f"cvxopt {status} k={k_cvx:.10f}"
        ok = True
        if status == "primal infeasible":
            ok = d["status"] == "infeasible"
        elif d["status"] != "solved":
            ok = False
        else:
            scale = max(1.0, abs(k_cvx))
            ok = abs(k - k_cvx) <= 1e-6 * scale and lb <= k + 1e-12 and k <= k_cvx + 1e-6 * scale \
                and lb <= k_cvx + 1e-9 * scale
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
