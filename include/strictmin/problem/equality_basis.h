#pragma once
// Every map that meets a Problem's fixed vertices and linear equalities, as q = Z y + z0
// (q: the full vertex-major dof vector, y: the independent dofs). Solvers that minimize an
// unconstrained energy (L2, IRLS) solve for y instead of q (docs/gparam.md, "Solvers").
//
// Built by sparse elimination: each equality row, with the earlier eliminations substituted
// in, expresses one of its dofs (the pivot: a largest coefficient, fewest dependents)
// through the others; rows that reduce to nothing are redundant and only checked. Seam
// transitions have coefficients 0 and +-1, so the elimination is exact.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <string>

#include "strictmin/problem/problem.h"

namespace strictmin {

struct EqualityBasis {
  Eigen::SparseMatrix<double> Z;  // n*#V by #y
  Eigen::VectorXd z0;             // n*#V: the fixed values (and constant parts)
  double redundant_residual = 0;  // largest |rhs| left by a row that reduced to nothing
  int num_independent() const { return static_cast<int>(Z.cols()); }
};

EqualityBasis equality_basis(const Problem& p);

// Why p's equalities cannot all hold ("the linear equalities contradict each other (residual
// r)"), or "" when they can: a row that reduced to nothing left a right-hand side beyond
// round-off (1e-9 relative to the largest |rhs|). Every solver reports such a problem
// `infeasible` with this message.
std::string equalities_contradiction(const Problem& p, const EqualityBasis& basis);

}  // namespace strictmin
