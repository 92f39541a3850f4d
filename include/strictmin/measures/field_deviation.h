#pragma once
// Field deviation ||J_T - R_T||_F of a map, read straight from a Problem (its gradients and
// targets): the measure every solver minimizes (measures.h has it for one differential J).
#include <Eigen/Core>

#include "strictmin/problem/problem.h"

namespace strictmin {

// A largest distortion at or below this is zero to rounding (distortions are dimensionless):
// the map is exact, and a relative change or decrement of it is round-off. A surface's rest
// frames, computed from 3D coordinates, leave about 1e-11 on an exact map (lion's interp frame
// at t = 0: 6e-12). Local-global and lp stop there.
constexpr double kZeroDistortion = 1e-10;

// #E: the field deviation of every element for the map X (#V by image_dim).
Eigen::VectorXd field_deviation(const Problem& problem, const Eigen::MatrixXd& X);
// The field deviation of element e alone.
double field_deviation(const Problem& problem, const Eigen::MatrixXd& X, int e);

}  // namespace strictmin
