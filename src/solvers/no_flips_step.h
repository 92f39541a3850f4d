#pragma once
// One global step under --no-flips (docs/arap.md, "--no-flips"): the field deviation's
// program for the current targets, restricted to a convex subset of orientation-preserving
// Jacobians around the start map X0, minimizing the maximum (L-infinity) or the L2 energy.
//
// Planar maps, Lipman's (2012) cone: with a, b the conformal and anticonformal parts of J_T
// and r, s those of the target R_T (qc/qc_program.h), ||J_T - R_T||^2 = 2 |a - r|^2 + 2 |b - s|^2,
// and every element positive at X0 gets |b_T| <= <a_T, f_T>, f_T = a_T(X0) / |a_T(X0)| (a
// 3-cone): then |a| >= |b|, so det J = |a|^2 - |b|^2 >= 0 (> 0 inside the cone).
//
// Tets: with J_T(X0) = U diag(sigma) V^T (det U = det V = 1) and C = diag(sigma)^(-1/2), the
// symmetric part S of C U^T J_T V C is kept diagonally dominant, S_ii >= sqrt(2) ||(S_ij, S_il)||
// (three 3-cones): S is then positive semidefinite, so the eigenvalues of U^T J_T V have
// non-negative real parts and det J_T >= 0. At X0, S = I.
//
// The objective's cones: sqrt(2) ||(a - r, b - s)|| <= k (or ||J - R||_F <= k on tets) and k
// above every constant element's distortion (Maximum), or the rotated cones
// t_T >= ||J_T - R_T||^2 and the objective sum_T w_T t_T / sum_T w_T (Energy). X0 itself is
// feasible, so the step's objective is no higher than X0's for these targets, and local-global's
// guarantee (its objective never increases) holds without cutting the step back. Solved by the
// general sparse cone solver of the Section 7 measures (qc/sparse_socp.h).
#include <Eigen/Core>

#include "strictmin/problem/problem.h"
#include "strictmin/solvers/linf.h"
#include "strictmin/solvers/result.h"

namespace strictmin {

// What a step minimizes: the maximum, or the area-weighted L2 energy sum_T w_T ||J_T - R_T||^2.
enum class StepObjective { Maximum, Energy };

// Whether the steps apply: a 2D map of triangles or a 3D map of tets, with no linear
// equalities. linf_without_new_flips_applies also needs no element bounds (direct's levels
// keep the cut-back).
bool steps_without_new_flips_apply(const Problem& problem);
bool linf_without_new_flips_applies(const Problem& problem, const LinfOptions& options);

// sum_T w_T d_T^2 / sum_T w_T.
double weighted_energy(const Problem& problem, const Eigen::VectorXd& distortion);

// The step from X0 (#V by image_dim) for the problem's targets, to the relative gap
// gap_tolerance and relative residuals feasibility_tolerance (the map returned is checked
// either way: no flip added, objective no higher; X0 is returned when no iterate improved on
// it). lower_bound (Maximum, with certify): a certified bound on this restricted program's
// optimum (not on the unconstrained field deviation's; it costs a factorization more); -inf for
// Energy or without certify. Status from the cone solver (solved, max-iterations; stalled when
// it stopped short or failed: the map is usable either way).
Result step_without_new_flips(const Problem& problem, const Eigen::MatrixXd& X0, StepObjective objective,
                              double gap_tolerance, double feasibility_tolerance = 1e-9, bool certify = true);
// The Maximum step.
Result linf_without_new_flips(const Problem& problem, const Eigen::MatrixXd& X0, double gap_tolerance,
                              double feasibility_tolerance = 1e-9);

}  // namespace strictmin
