#pragma once
// Field deviation ||J_T - R_T||_F of a map, read straight from a Problem (its gradients and
// targets): the measure every solver minimizes (measures.h has it for one differential J).
#include <Eigen/Core>

#include "strictmin/problem/problem.h"

namespace strictmin {

// #E: the field deviation of every element for the map X (#V by image_dim).
Eigen::VectorXd field_deviation(const Problem& problem, const Eigen::MatrixXd& X);
// The field deviation of element e alone.
double field_deviation(const Problem& problem, const Eigen::MatrixXd& X, int e);

}  // namespace strictmin
