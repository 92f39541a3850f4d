#pragma once
// The L-infinity problem restricted to the elements near the maximum: a certified lower bound
// and a better map, both from a small solve.
//
// Near the optimum, only the elements whose distortion is within reach of the maximum can
// carry dual weight (complementary slackness), and there are few of them: about a thousand
// on the 100k-triangle square of the paper's Figure 2, about fifty on bimba_89k.
//
// - The bound. The problem restricted to them (every other element dropped, the vertices they
//   do not touch held, the equalities that involve such a vertex dropped, one vertex held per
//   part of them that no fixed vertex anchors: distortion does not change under translation)
//   is a relaxation of the whole problem, so its certified lower bound holds for the whole
//   problem too. Solved to a tighter tolerance, it certifies the optimum as soon as the
//   restriction holds the dual's support, while the main iterates' own certificate only
//   catches up several iterations later (their dual converges slowly where elements sit at
//   the maximum with zero weight).
// - The map. The same elements with every vertex that another element touches held as well
//   (the rim): a restriction of the whole problem, whose solution moves no vertex of the other
//   elements, so it is a map of the whole problem whose maximum is the larger of the
//   restriction's and the others' (unchanged). Widened by a ring or two around the elements
//   near the maximum, it reaches the optimum before the main iterates do.
// solve_linf uses both near the optimum (LinfOptions::active_set_bounds).
#include <Eigen/Core>
#include <vector>

#include "strictmin/problem/problem.h"
#include "strictmin/solvers/linf.h"

namespace strictmin {

struct ActiveSetSolve {
  double lower_bound;           // certified for the whole problem (-inf if none); the bound only
  Eigen::VectorXd multipliers;  // #E: the restriction's dual weights, zero elsewhere; the bound only
  Eigen::MatrixXd positions;    // the restricted solve's map (the held vertices as given)
  int iterations = 0;           // of the restricted solve
  int elements = 0;             // in the restriction
};

// elements: the restriction (indices into the problem's elements); X: the current map (the
// positions of the vertices held); bounds: #E or empty, as LinfOptions::element_bounds.
// Solved by solve_linf with options (no progress, a tenth of the gap tolerance, no nested
// restriction).
ActiveSetSolve active_set_bound(const Problem& p, const std::vector<int>& elements, const Eigen::MatrixXd& X,
                                const Eigen::VectorXd& bounds, const LinfOptions& options);
ActiveSetSolve active_set_map(const Problem& p, const std::vector<int>& elements, const Eigen::MatrixXd& X,
                              const Eigen::VectorXd& bounds, const LinfOptions& options);

// elements and up to `rings` rings of elements around them (sharing a vertex), ring by ring
// while the set stays within max_growth times its first size; after the first min_rings
// rings (all of them if negative) it stops once it holds `enough` elements.
std::vector<int> widen_by_rings(const Problem& p, const std::vector<int>& elements, int rings, double max_growth,
                                int min_rings = -1, size_t enough = 0);

}  // namespace strictmin
