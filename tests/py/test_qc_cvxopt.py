#!/usr/bin/env python3
"""Cross-check of one qc / iso bisection step (the slack feasibility program of
src/solvers/qc/qc_program.cpp, solved by our sparse interior-point method) against CVXOPT.

qc_tool (tests/tools/qc_tool.cpp, path in STRICTMIN_QC_TOOL) builds Figure 2's set-up with
frames from the L2 map and the program

    minimize tau  s.t.  |b_T| <= k <a_T, r_T> + tau          (qc, k = (K-1)/(K+1))
                        |a_T| <= u_T + tau, |b_T| <= S - u_T + tau,
                        |b_T| <= <a_T, r_T> - 1/S + tau       (iso)
                        tau >= -1

as G v + s = h, s in a product of cones, our optimum and the corrected dual bound (the
certificate of an infeasible level, sparse_socp.h: corrected_dual_bound). CVXOPT's conelp
solves the same program; the optimal tau must agree to 1e-6 (levels on both sides of the
optimum: a negative tau means the level is feasible) and the bound must lie below CVXOPT's
optimum (to 1e-9) and within 1e-6 of it. Exit code 77 (skip) when cvxopt is missing.
"""
import json
import os
import subprocess
import sys

try:
    from cvxopt import matrix, spmatrix, solvers
except ImportError:
    print("cvxopt is not installed: skipping")
    sys.exit(77)

TOOL = os.environ.get("STRICTMIN_QC_TOOL")
if not TOOL or not os.path.exists(TOOL):
    print("STRICTMIN_QC_TOOL is not set to the qc_tool executable: skipping")
    sys.exit(77)

CASES = [
    ["6", "0.2", "qc", "1.3"],   # infeasible level (tau > 0)
    ["6", "0.2", "qc", "2.5"],   # feasible level (tau < 0)
    ["8", "0.3", "qc", "1.8"],
    ["6", "0.2", "iso", "1.2"],
    ["6", "0.2", "iso", "2.0"],
]

solvers.options["show_progress"] = False
solvers.options["abstol"] = 1e-9
solvers.options["reltol"] = 1e-9
solvers.options["feastol"] = 1e-9

failures = 0
for case in CASES:
    out = subprocess.run([TOOL] + case, capture_output=True, text=True, check=True)
    p = json.loads(out.stdout)
    dims = p["dims"]
    # CVXOPT wants the half-line rows first: move them in front.
    offsets = [0]
    for d in dims:
        offsets.append(offsets[-1] + d)
    order = [r for i, d in enumerate(dims) if d == 1 for r in range(offsets[i], offsets[i + 1])]
    order += [r for i, d in enumerate(dims) if d > 1 for r in range(offsets[i], offsets[i + 1])]
    where = {r: i for i, r in enumerate(order)}
    nrows, ncols = p["shape"]
    G = spmatrix(p["vals"], [where[r] for r in p["rows"]], p["cols"], (nrows, ncols))
    h = matrix([p["h"][r] for r in order])
    c = matrix(p["c"])
    cone_dims = {"l": sum(1 for d in dims if d == 1), "q": [d for d in dims if d > 1], "s": []}
    sol = solvers.conelp(c, G, h, cone_dims)
    theirs = sol["primal objective"]
    ours = p["pobj"]
    # The corrected dual bound (the certificate of an infeasible level) is a true lower bound.
    bound = p["corrected_bound"]
    ok = sol["status"] == "optimal" and abs(ours - theirs) <= 1e-6 * max(1.0, abs(theirs))
    ok = ok and (bound is None or bound <= theirs + 1e-9) and (bound is None or bound >= theirs - 1e-6)
    print("%-24s ours tau %.10f (%d iterations, %s), certified >= %s  cvxopt %.10f (%s)  %s" %
          (" ".join(case), ours, p["iterations"], p["status"], bound, theirs, sol["status"], "ok" if ok else "MISMATCH"))
    failures += 0 if ok else 1
sys.exit(1 if failures else 0)
