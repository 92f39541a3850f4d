#pragma once
// The L-infinity global step of local-global under --no-flips (docs/arap.md,
// "--no-flips"): the field deviation's program for the current targets,
// restricted to a convex subset of orientation-preserving Jacobians around the
// start map. On planar maps it is Lipman's (2012): With a, b the conformal and
// anticonformal parts of J_T and r, s those of the target R_T
// (qc/qc_program.h), ||J_T - R_T||^2 = 2 |a - r|^2 + 2 |b - s|^2, and the step
// is
//   minimize k  subject to, for every element with a free vertex,
//     sqrt(2) ||(a_T - r_T, b_T - s_T)|| <= k                      (a
//     5-dimensional cone) |b_T| <= <a_T, f_T>  when det J_T(X0) > 0, f_T =
//     a_T(X0)/|a_T(X0)|   (a 3-cone)
//   and k >= every constant element's distortion.
// The second cone gives |a| >= |b|, so det J = |a|^2 - |b|^2 >= 0 (> 0 inside
// the cone): no element positive at X0 is flipped. X0 itself is feasible (<a,
// a/|a|> = |a| > |b|), so the step's maximum is no higher than X0's for these
// targets, and local-global's guarantee (the maximum never increases) holds
// without cutting the step back. Solved by the general sparse cone solver of
// the Section 7 measures (qc/sparse_socp.h). On tets, with J_T(X0) = U
// diag(sigma) V^T (det U = det V = 1) and C = diag(sigma)^(-1/2), the symmetric
// part S of C U^T J_T V C is kept diagonally dominant, S_ii >= sqrt(2) ||(S_ij,
// S_il)|| (three 3-cones): S is then positive semidefinite, so the eigenvalues
// of U^T J_T V have non-negative real parts and det J_T >= 0. At X0, S = I.
#include <Eigen/Core>

#include "strictmin/problem/problem.h"
#include "strictmin/solvers/linf.h"
#include "strictmin/solvers/result.h"
#include "strictmin/tasks/method.h"

namespace strictmin {

// What a step minimizes: the maximum (L-infinity, as above) or the
// area-weighted L2 energy sum_T w_T ||J_T - R_T||^2 (each element's cone then
// is the rotated cone t_T >= ||J_T - R_T||^2, and the objective sum_T w_T t_T /
// sum_T w_T), with the same orientation cones.
enum class StepObjective { Maximum, Energy };

// Whether the steps apply: a 2D map of triangles or a 3D map of tets, with no
// linear equalities. linf_without_new_flips_applies also needs no element
// bounds (direct's levels keep the cut-back).
bool steps_without_new_flips_apply(const Problem &problem);
bool linf_without_new_flips_applies(const Problem &problem, const LinfOptions &options);

// sum_T w_T d_T^2 / sum_T w_T.
double weighted_energy(const Problem &problem, const Eigen::VectorXd &distortion);

// The step from X0 (#V by image_dim) for the problem's targets, to the relative
// gap gap_tolerance and relative residuals feasibility_tolerance (the map
// returned is checked either way: no flip added, objective no higher; X0 is
// returned when no iterate improved on it). lower_bound (Maximum): a certified
// bound on this restricted program's optimum (not on the unconstrained field
// deviation's); -inf for Energy. Status from the cone solver (solved,
// max-iterations, numerical-error).
Result step_without_new_flips(const Problem &problem, const Eigen::MatrixXd &X0, StepObjective objective,
                              double gap_tolerance, double feasibility_tolerance = 1e-9);
// The Maximum step.
Result linf_without_new_flips(const Problem &problem, const Eigen::MatrixXd &X0, double gap_tolerance,
                              double feasibility_tolerance = 1e-9);

// --no-flips with field deviation after one solve (deform, param) that added
// flips to `start`: from the solve cut back to add none (cut_back_result),
// steps X <- step(X) until the objective changes by less than relative_change
// (relative) or max_steps steps were taken. `result` is the unconstrained solve
// on entry and the map on return; its lower_bound stays (it bounds every map,
// flip-free or not). Status: solved when the steps converged, stalled when the
// last step's cone program stopped short, max-iterations at max_steps. options:
// gap_tolerance (the finest step gap) and progress (may be null: one record per
// step).
void steps_without_new_flips(const Problem &problem, const Eigen::MatrixXd &start, StepObjective objective,
                             const LinfOptions &options, Result &result, int max_steps = 100,
                             double relative_change = 1e-3);

// --no-flips after one solve: the Maximum steps for linf, the Energy steps for
// l2 (where they apply), else cut_back_result.
void remove_added_flips(const Problem &problem, const Eigen::MatrixXd &start, Method method, const LinfOptions &options,
                        Result &result);

}  // namespace strictmin
