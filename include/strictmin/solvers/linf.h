#pragma once
// L-infinity field deviation (paper Section 5.1, equations (1)/(2)) as a second-order cone
// program, solved by our own primal-dual interior-point method on CHOLMOD:
//
//   minimize k  subject to  ||J_T(x) - R_T||_F <= k    for the free elements,
//                           ||J_T(x) - R_T||_F <= k_T  for elements with a fixed bound,
//                           eq_matrix q = eq_rhs (seams), fixed vertices eliminated.
//
// Returns the map, k (Result.distortion.maxCoeff() over free elements), a certified lower
// bound from the dual (no map does better), iterations, status and per-iteration history.
//
// Method (src/solvers/socp/): primal-dual path-following interior-point method with
// Nesterov-Todd scaling and Mehrotra predictor-corrector, normal equations on CHOLMOD with
// the dense k column eliminated by bordering (one symbolic analysis per solve). Starts from
// the L2 map. Fixed bounds that the start misses are first checked by a phase-1 solve
// (min t s.t. D_T <= k_T + t), which certifies infeasibility. Elements whose vertices are
// all fixed are constants: a lower bound on k, or a bound that must already hold. Linear
// equalities are supported (penalty elimination with refinement).
#include <Eigen/Core>
#include <functional>
#include <string>

#include "strictmin/problem/problem.h"
#include "strictmin/solvers/result.h"

namespace strictmin {

struct LinfOptions {
  double gap_tolerance = 1e-8;       // stop when (k - lower_bound) <= gap_tolerance * max(1, |k|)
  double feasibility_tolerance = 1e-8;
  int max_iterations = 100;
  // Per-element fixed bounds k_T (size #E; a negative value means "free element", bounded by
  // k; NaN, inf and values above 1e100 are refused). Empty: every element is free. Passed by
  // the strict-minimizer algorithms.
  Eigen::VectorXd element_bounds;
  // Paper Section 5.1 (a): among the L-infinity minimizers, return the one with the least
  // area-weighted L2 field deviation (a second solve with D_T <= k*).
  bool minimize_l2_among_optimal = false;
  // Called after every iteration (progress on stderr in the CLI).
  std::function<void(const IterationRecord&)> progress;

  // --- added by the solver (defaults are fine) ---
  // Fixed bounds that the best map misses by more than infeasibility_tolerance *
  // max(1, k_T) make the problem infeasible (decided by a phase-1 solve, certified).
  // Smaller misses are absorbed: those bounds are relaxed by the miss.
  double infeasibility_tolerance = 1e-7;
  // minimize_l2_among_optimal solves with D_T <= k* + l2_slack * max(1, k*) (the set of
  // exact minimizers has no interior, which an interior-point method needs).
  double l2_slack = 1e-6;
  // When the interior-point method cannot reach gap_tolerance (near the optimum the Newton
  // systems of badly graded meshes exceed double precision), a certified relative gap below
  // acceptable_gap_tolerance ends almost-solved (usable), with a "reduced accuracy" message.
  double acceptable_gap_tolerance = 1e-6;
  // Near the optimum, certify with the problem restricted to the elements within reach of the
  // maximum (a relaxation, so its certified bound holds for the whole problem; see
  // src/solvers/linf_active_set.h). It certifies several iterations before the iterates'
  // own dual does.
  bool active_set_bounds = true;
  // With equalities (the seams of global parametrization), also probe earlier: the same
  // bound and map from the iterate where the method's own gap falls below 5e-2, on the
  // elements near the maximum of the iterate and of where the iterates are heading, when
  // they are at most 1/40 of the elements (docs/linf.md, "Probes"). Only with
  // active_set_bounds.
  bool active_set_probes = true;
  // Interior-point internals (see src/solvers/socp/settings.h).
  double step_fraction = 0.95;
  double regularization = 1e-15;
  int refinement_steps = 10;
  // Linear equalities in vertex-block form (the seams of global parametrization) are
  // eliminated exactly in the Newton systems (socp/null_space.h); false keeps the older
  // penalty with refinement for them too (for comparisons).
  bool eliminate_equalities = true;
  int verbose = 0;  // 1: one line per interior-point iteration on stderr; 2: also linear-algebra details

  // Ranges: gap_tolerance, feasibility_tolerance, infeasibility_tolerance and
  // acceptable_gap_tolerance in (0, 1); max_iterations >= 1; l2_slack > 0; step_fraction in
  // (0, 1); regularization >= 0; refinement_steps >= 0; verbose in [0, 2]. False with the
  // reason in *why otherwise (element_bounds is checked against the problem by solve_linf).
  bool is_valid(std::string* why = nullptr) const;
};

// Starts from the L2 map or problem.positions, whichever is better. Throws InputError for
// invalid options.
Result solve_linf(const Problem& problem, const LinfOptions& options = {});

}  // namespace strictmin
