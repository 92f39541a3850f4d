#pragma once
// A certified lower bound on the L-infinity optimum from the elements near the maximum.
//
// Near the optimum, only the elements whose distortion is within reach of the maximum can
// carry dual weight (complementary slackness), and there are few of them: about a thousand
// on the 100k-triangle square of the paper's Figure 2, about fifty on bimba_89k. The problem
// restricted to them (every other element dropped, the vertices they do not touch held, the
// equalities that involve such a vertex dropped, one vertex held per part of them that no
// fixed vertex anchors: distortion does not change under translation) is a relaxation of
// the whole problem, so its certified lower bound holds for the whole problem too. Solved to
// a tighter tolerance, it certifies the optimum as soon as the restriction holds the dual's
// support, while the main iterates' own certificate only catches up several iterations
// later (their dual converges slowly where elements sit at the maximum with zero weight).
// solve_linf tries it near the optimum (LinfOptions::active_set_bounds).
#include <Eigen/Core>
#include <vector>

#include "strictmin/problem/problem.h"
#include "strictmin/solvers/linf.h"

namespace strictmin {

struct ActiveSetBound {
  double lower_bound;           // certified for the whole problem (-inf if none)
  Eigen::VectorXd multipliers;  // #E: the restricted problem's dual weights, zero elsewhere
  int iterations = 0;           // of the restricted solve
  int elements = 0;             // in the restriction
};

// elements: the restriction (indices into the problem's elements); X: the current map (the
// positions of the vertices held); bounds: #E or empty, as LinfOptions::element_bounds.
// The restricted problem is solved by solve_linf with options (no progress, a tenth of the
// gap tolerance, no nested restriction).
ActiveSetBound active_set_bound(const Problem& p, const std::vector<int>& elements, const Eigen::MatrixXd& X,
                                const Eigen::VectorXd& bounds, const LinfOptions& options);

}  // namespace strictmin
