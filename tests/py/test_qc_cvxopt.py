#!/usr/bin/env python3
"""Cross-check of one qc / iso bisection step (the slack feasibility program of
src/solvers/qc/qc_program.cpp, solved by our sparse interior-point method) against CVXOPT.

qc_tool (tests/tools/qc_tool.cpp, path in STRICTMIN_QC_TOOL) builds Figure 2's set-up with
frames from the L2 map and the program of the bisection (qc: each cone relaxed by
tau * |a_T| of the frames' map, qc_program.h: slack_scales)

    minimize tau  s.t.  |b_T| <= k <a_T, r_T> + rho_T tau     (qc, k = (K-1)/(K+1))
                        |a_T| <= u_T + tau, |b_T| <= S - u_T + tau,
                        |b_T| <= <a_T, r_T> - 1/S + tau       (iso)
                        tau >= -1

as G v + s = h, s in a product of cones, our optimum and the certificate of an infeasible
level (the best corrected dual bound, sparse_socp.h: corrected_dual_bound; null when none).
CVXOPT's conelp solves the same program. Checked:
  - the optimal tau agrees to 1e-6 (levels on both sides of the optimum);
  - the certificate is a true lower bound (<= CVXOPT's optimum + 1e-9) and within 1e-6 of it;
  - the certificate is THERE wherever the level is infeasible by a margin the bisection relies
    on: CVXOPT's tau >= 1e-7, including levels 1e-5 and 1e-6 (relative) below the optimal
    level L*, found here by bisection with CVXOPT (a missing certificate fails the check).
And the iso level in one program (qc_tool's iso-min: minimize S with the rotated cone
v_T S >= 1, qc_program.h: iso_program): our optimum S agrees with CVXOPT's on the same program
to 1e-7, our certified bound lies below CVXOPT's optimum and within 1e-6 of it, and both equal
the least level L* of the slack program found by the CVXOPT bisection above (to its 1e-8):
the one program and the bisection answer the same question.
Exit code 77 (skip) when cvxopt is missing.
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

solvers.options["show_progress"] = False
solvers.options["abstol"] = 1e-9
solvers.options["reltol"] = 1e-9
solvers.options["feastol"] = 1e-9

# Below this CVXOPT tau the level must come with our certificate.
CERTIFY_FROM = 1e-7


def ours(cells, shift, measure, level):
    out = subprocess.run([TOOL, str(cells), str(shift), measure, repr(level)], capture_output=True, text=True,
                         check=True)
    return json.loads(out.stdout)


def cvxopt_tau(p):
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
    try:
        sol = solvers.conelp(c, G, h, cone_dims)
    except ValueError:  # a domain error in CVXOPT's scaling update near the end: retry looser
        sol = solvers.conelp(c, G, h, cone_dims, options={"abstol": 1e-8, "reltol": 1e-8, "feastol": 1e-8,
                                                           "show_progress": False})
    return sol["primal objective"], sol["status"]


def optimal_level(cells, shift, measure, lo, hi):
    """L* of these frames: the least level whose CVXOPT slack is <= 0 (bisection to 1e-8)."""
    while hi - lo > 1e-8 * hi:
        mid = 0.5 * (lo + hi)
        tau, _ = cvxopt_tau(ours(cells, shift, measure, mid))
        lo, hi = (mid, hi) if tau > 0 else (lo, mid)
    return hi


CASES = [
    (6, 0.2, "qc", 1.3),   # infeasible level (tau > 0)
    (6, 0.2, "qc", 2.5),   # feasible level (tau < 0)
    (8, 0.3, "qc", 1.8),
    (6, 0.2, "iso", 1.2),
    (6, 0.2, "iso", 2.0),
]
STARS = {}
for measure, lo, hi in (("qc", 1.3, 2.5), ("iso", 1.2, 2.0)):  # infeasible, feasible (above)
    star = optimal_level(6, 0.2, measure, lo, hi)
    STARS[measure] = star
    print("%s: optimal level of the L2 map's frames L* = %.10f (CVXOPT bisection)" % (measure, star))
    CASES += [(6, 0.2, measure, star * (1 - 1e-5)), (6, 0.2, measure, star * (1 - 1e-6)),
              (6, 0.2, measure, star * (1 + 1e-6))]

failures = 0
for cells, shift, measure, level in CASES:
    p = ours(cells, shift, measure, level)
    theirs, status = cvxopt_tau(p)
    bound = p["corrected_bound"]
    agree = status == "optimal" and abs(p["pobj"] - theirs) <= 1e-6 * max(1.0, abs(theirs))
    valid = bound is None or (theirs - 1e-6 <= bound <= theirs + 1e-9)
    present = theirs < CERTIFY_FROM or (bound is not None and bound > 0)
    ok = agree and valid and present
    why = "" if ok else (" (optimum differs)" if not agree else " (bound above the optimum or far below)"
                         if not valid else " (no certificate of an infeasible level)")
    print("%-5s %d %.1f level %.10f: ours tau %+.6e (%d iterations, %s), certified >= %s  cvxopt %+.6e (%s)  %s%s" %
          (measure, cells, shift, level, p["pobj"], p["iterations"], p["status"],
           "none" if bound is None else "%+.6e" % bound, theirs, status, "ok" if ok else "MISMATCH", why))
    failures += 0 if ok else 1
# The iso level in one program.
p = ours(6, 0.2, "iso-min", 0.0)
theirs, status = cvxopt_tau(p)  # the program's optimum (its objective is S)
bound = p["corrected_bound"]
agree = status == "optimal" and abs(p["pobj"] - theirs) <= 1e-7 * theirs
valid = bound is not None and theirs - 1e-6 <= bound <= theirs + 1e-9
same = abs(theirs - STARS["iso"]) <= 2e-8 * theirs
ok = agree and valid and same
print("iso one program: ours S %.10f (%d iterations, %s), certified >= %s  cvxopt %.10f (%s)  bisection L* %.10f  %s" %
      (p["pobj"], p["iterations"], p["status"], "none" if bound is None else "%.10f" % bound, theirs, status,
       STARS["iso"], "ok" if ok else "MISMATCH"))
failures += 0 if ok else 1
sys.exit(1 if failures else 0)
