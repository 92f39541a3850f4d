#pragma once
// The L-infinity global step of local-global under --no-flips on planar maps (docs/arap.md,
// "--no-flips"): the field deviation's program for the current targets, restricted to
// Lipman's (2012) convex subset of orientation-preserving Jacobians around the start map.
// With a, b the conformal and anticonformal parts of J_T and r, s those of the target R_T
// (qc/qc_program.h), ||J_T - R_T||^2 = 2 |a - r|^2 + 2 |b - s|^2, and the step is
//   minimize k  subject to, for every element with a free vertex,
//     sqrt(2) ||(a_T - r_T, b_T - s_T)|| <= k                      (a 5-dimensional cone)
//     |b_T| <= <a_T, f_T>  when det J_T(X0) > 0, f_T = a_T(X0)/|a_T(X0)|   (a 3-cone)
//   and k >= every constant element's distortion.
// The second cone gives |a| >= |b|, so det J = |a|^2 - |b|^2 >= 0 (> 0 inside the cone): no
// element positive at X0 is flipped. X0 itself is feasible (<a, a/|a|> = |a| > |b|), so the
// step's maximum is no higher than X0's for these targets, and local-global's guarantee
// (the maximum never increases) holds without cutting the step back. Solved by the general
// sparse cone solver of the Section 7 measures (qc/sparse_socp.h).
#include <Eigen/Core>

#include "strictmin/problem/problem.h"
#include "strictmin/solvers/linf.h"
#include "strictmin/solvers/result.h"

namespace strictmin {

// Whether the step applies: a 2D map of triangles with no linear equalities and no element
// bounds (direct's levels keep the cut-back).
bool linf_without_new_flips_applies(const Problem& problem, const LinfOptions& options);

// The step from X0 (#V by 2) for the problem's targets, to the relative gap gap_tolerance.
// lower_bound: a certified bound on this restricted program's optimum (not on the
// unconstrained field deviation's). Status from the cone solver (solved, max-iterations,
// numerical-error); X0 is returned when no iterate improved on it.
Result linf_without_new_flips(const Problem& problem, const Eigen::MatrixXd& X0, double gap_tolerance);

}  // namespace strictmin
