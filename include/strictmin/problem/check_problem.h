#pragma once
// The contract every solver's Problem meets (problem.h's field comments), checked at the
// solver's entry: a Problem built in code (not by make_problem from a validated mesh) with
// arrays of the wrong size, indices out of range or non-finite numbers read out of range,
// looped forever (relax with an infinite target) or returned NaN maps as solved.
#include <string>

#include "strictmin/problem/problem.h"

namespace strictmin {

// Throws InputError, prefixed with `who` (the solver's name), when:
// - image_dim / domain_dim are not 2/2, 3/3 or 3/2;
// - elements is not #E by domain_dim + 1, or an index is outside [0, num_vertices);
// - gradients, targets, weights, fixed or positions do not have their documented sizes;
// - a gradient, target, weight or position is not finite, or a weight is negative;
// - eq_matrix does not have image_dim * num_vertices columns, eq_rhs one entry per row, or
//   either is not finite; or an equality whose every unknown belongs to a fixed vertex does
//   not hold at the fixed positions (it cannot hold at all: before, the solvers dropped it
//   and reported the map as solved).
// - a free vertex belongs to no element and no equality (nothing determines it);
// - copy_base is neither empty nor one entry per vertex, an entry is outside [-1, num_vertices),
//   or (with copy_base set) copy_rotation is not image_dim * num_vertices by image_dim or not
//   finite.
// Linear in the problem's size.
void check_problem(const Problem& problem, const std::string& who);

// Throws InputError (prefixed with `who`) unless X is num_vertices by image_dim: a map or
// start given with a problem. (A start that is not finite is a numerical outcome of the
// method that made it: the solvers report it as numerical-error.)
void check_map(const Problem& problem, const Eigen::MatrixXd& X, const std::string& who);

}  // namespace strictmin
