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
#include <Eigen/Core>
#include <functional>

#include "strictmin/problem/problem.h"
#include "strictmin/solvers/result.h"

namespace strictmin {

struct LinfOptions {
  double gap_tolerance = 1e-8;       // stop when (k - lower_bound) <= gap_tolerance * max(1, |k|)
  double feasibility_tolerance = 1e-8;
  int max_iterations = 100;
  // Per-element fixed bounds k_T (size #E; a negative value or NaN means "free element",
  // bounded by k). Empty: every element is free. Passed by the strict-minimizer algorithms.
  Eigen::VectorXd element_bounds;
  // Paper Section 5.1 (a): among the L-infinity minimizers, return the one with the least
  // area-weighted L2 field deviation (a second solve with D_T <= k*).
  bool minimize_l2_among_optimal = false;
  // Called after every iteration (progress on stderr in the CLI).
  std::function<void(const IterationRecord&)> progress;
};

Result solve_linf(const Problem& problem, const LinfOptions& options = {});

}  // namespace strictmin
