#pragma once
// Pinned elements of the direct strict minimizer (docs/strict.md, "Pinned elements").
//
// At a level with optimum k, a fixed or free element whose certificate multiplier lambda_T
// is positive is essential: every optimal map of the level has D_T at its bound. The field
// deviation D_T = ||J_T - R_T||_F is a Euclidean norm, so two optimal maps with different
// J_T would have a midpoint (optimal too, the level's problem is convex) with D_T below the
// bound. J_T is therefore the same on every optimal map of the level, and on every map of
// the later levels, whose feasible sets lie inside this level's optimal set.
//
// Left as a cone at its bound, such an element squeezes the later levels' feasible sets into
// a shell as thin as the bound's slack, and their Newton systems become ill-conditioned.
// Pinned instead, it leaves the program: its J_T is held, which holds its corners' positions
// relative to each other, so the vertices of one connected group of pinned elements move by
// one common translation (equalities q_v - q_w = X_v - X_w along a spanning forest of the
// group's edges), and a group that touches a vertex that does not move at this level does not
// move at all.
#include <Eigen/Core>
#include <vector>

#include "strictmin/problem/problem.h"
#include "strictmin/problem/subproblem.h"
#include "strictmin/solvers/strict.h"

namespace strictmin {

// One level's problem with the pinned elements out (PinnedElements::level_problem).
struct PinnedLevel {
  Subproblem sub;
  // A group of pinned elements free to translate: its root (a vertex of the sub-problem, -1
  // when none is) and its members outside the sub-problem, which follow the root.
  struct Group {
    int root = -1, root_local = -1;
    Eigen::RowVectorXd root_start;
    std::vector<int> outside;
  };
  std::vector<Group> groups;
  // Writes the level's map (sub-problem vertices) into the full map.
  void scatter(const Eigen::MatrixXd& level_positions, Eigen::MatrixXd& positions) const;
};

class PinnedElements {
 public:
  explicit PinnedElements(const Problem& p) : pinned_(p.num_elements(), 0) {}

  // Pins the bounded elements (bounds >= 0) whose multiplier in the level's certificate is
  // at least `threshold` (multipliers sum to 1 over the level's free elements). Returns how
  // many were pinned now.
  int pin_essential(const Eigen::VectorXd& bounds, const Eigen::VectorXd& multipliers, double threshold);

  // Pins element e (an essential element found otherwise: solve_exact's tests).
  void pin(int e) {
    if (!pinned_[e]) ++count_;
    pinned_[e] = 1;
  }

  int count() const { return count_; }

  // The level's problem: the vertices flagged in `moving` that are not held by a pinned
  // group (a group touching a fixed or non-moving vertex), the elements that are neither
  // pinned nor left without a moving vertex, and the translation equalities of the free
  // groups; every other vertex stays at X.
  PinnedLevel level_problem(const Problem& p, const std::vector<char>& moving, const Eigen::MatrixXd& X) const;

 private:
  std::vector<char> pinned_;
  int count_ = 0;
};

// Problem (1) on a level's problem: `bounds` (#E, negative for a free element) are mapped to
// its elements, `solve` runs from the map `previous` (positions #V by n, distortion #E), and
// the result is returned on the whole mesh: the elements left out keep their distortion
// (their Jacobians did not change) with multiplier 0, and a free element left out (no moving
// vertex) raises the lower bound to its distortion, a constant of the level. With no vertex
// to move, the map in hand is the level's exact optimum. immobile (if given) receives those
// free elements left out (they stay constant at every later level too: held groups stay held),
// and the lower bound is then the solve's own, over the level's other free elements.
// duals (if given): the last dual iterate per element of p (LinfWarmStart::element_z rows),
// moved into level_duals (the rows of the level's elements, which `solve` reads and writes)
// before the solve, and back after it.
Result solve_on_level(const Problem& p, const PinnedLevel& level, const Eigen::VectorXd& bounds,
                      const Result& previous, const LinfOptions& linf, const LevelSolver& solve,
                      std::vector<int>* immobile = nullptr, Eigen::MatrixXd* duals = nullptr,
                      Eigen::MatrixXd* level_duals = nullptr);

}  // namespace strictmin
