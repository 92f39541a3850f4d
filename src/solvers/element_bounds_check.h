#pragma once
// The per-element fixed bounds the L-infinity solvers take (LinfOptions::element_bounds,
// ConformalOptions::element_bounds; private): empty, or one per element, each finite and at
// most kLargestElementBound; a negative value marks a free element.
#include <Eigen/Core>
#include <string>

namespace strictmin {

// Above this an interior-point method's squared slacks near overflow (measured on a 10 x 10
// square: bounds of 1e100 solve, 1e150 stall); no distortion the solvers reach is that large.
constexpr double kLargestElementBound = 1e100;

// Throws InputError naming `solver`, the element and the reason.
void check_element_bounds(const Eigen::VectorXd& bounds, int elements, const std::string& solver);

}  // namespace strictmin
