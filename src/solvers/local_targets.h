#pragma once
// The local step of local-global in one pass over the elements (paper Section 5.4,
// docs/maths.md): each element's target, the rotation (or similarity) closest to J_T, and its
// distance D_T = ||J_T - target||. Fixed-size arithmetic for the 2x2, 3x3 and 3x2 (surface)
// Jacobians, elements in parallel: this runs twice per global step.
#include <Eigen/Core>

#include "strictmin/problem/problem.h"
#include "strictmin/solvers/local_global.h"

namespace strictmin {

// D_T for every element of the map X (#V by n); with targets not null, also the local
// targets (#E*n by m, as Problem::targets).
Eigen::VectorXd local_targets(const Problem& problem, const Eigen::MatrixXd& X, const LocalGlobalOptions& options,
                              Eigen::MatrixXd* targets);

// Extrapolated targets: each element's target moved on along its last change, then taken
// back to the nearest rotation (similarity): R + beta (R - R_previous) projected. False (and
// targets unchanged) where the element kind has no fixed-size local step (interpolation's shapes).
bool extrapolate_targets(const Problem& problem, const Eigen::MatrixXd& previous, double beta,
                         const LocalGlobalOptions& options, Eigen::MatrixXd& targets);

}  // namespace strictmin
