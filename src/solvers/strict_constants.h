#pragma once
// The constant elements of a strict minimization (direct, exact): elements whose vertices are
// all fixed have the same distortion on every map. The levels run over the other elements.
#include <Eigen/Core>
#include <vector>

#include "strictmin/problem/problem.h"
#include "strictmin/solvers/result.h"

namespace strictmin {

// movable[e] = 1 when element e has a free vertex, 0 when it is a constant of the problem.
std::vector<char> movable_elements(const Problem& p);

// Gives every constant element its own value (its field deviation at the problem's
// positions) as fixed bound, so that the L-infinity solves leave it out of k: unbounded, a
// constant above the free elements held k at its value, and the first level's map was then
// only one of many optima for the free elements (gecko with its handles: the level at 1.316
// where the free elements reach 1.035). Returns the largest constant value, -inf when none:
// the minimum over maps of the largest distortion is at least that.
double bound_constant_elements(const Problem& p, const std::vector<char>& movable, Eigen::VectorXd& bounds);

// The answer when no element can move: the problem's map, solved, its maximum as exact bound.
Result unmovable_answer(const Problem& p);

}  // namespace strictmin
