#pragma once
// The L2 normal equations of a problem whose equalities are complex-linear
// (problem/complex_equality_basis.h): with z = u + iv per vertex and z = Z y + z0, the energy
// sum_T A_T ||J_T - R_T||_F^2 is y^H (Z^H K Z) y - 2 Re(y^H Z^H (b - K z0)) + const, K the
// scalar matrix of solvers/l2.h and b_w = sum_T A_T (R_T g_w)_u + i (R_T g_w)_v. Z^H K Z is
// assembled straight from the elements (no sparse products) and factored as a complex
// Hermitian matrix (src/field/hermitian_cholesky.h): half the unknowns and about half the
// factorization's flops of the real form with the same basis.
#include <Eigen/Core>

#include "field/hermitian_cholesky.h"
#include "strictmin/problem/complex_equality_basis.h"
#include "strictmin/problem/problem.h"

namespace strictmin {

class ComplexL2 {
 public:
  explicit ComplexL2(ComplexEqualityBasis basis) : basis_(std::move(basis)) {}
  // Assembles Z^H K Z with these element weights and factors it; false when it is not
  // (numerically) positive definite.
  bool factorize(const Problem& p, const Eigen::VectorXd& element_weights);
  // The minimizer for the problem's targets (#V by 2), after a successful factorize():
  // positions(solve_reduced(reduced_rhs(p))).
  Eigen::MatrixXd solve(const Problem& p) const;
  // The parts of solve(), for solvers that add rows of their own (src/tasks/bordered_l2.h):
  // Z^H (b - K z0) for p's targets; y = (Z^H K Z)^-1 rhs; the positions z = Z y + z0.
  Eigen::VectorXcd reduced_rhs(const Problem& p) const;
  Eigen::VectorXcd solve_reduced(const Eigen::VectorXcd& rhs) const;
  void solve_reduced_many(Eigen::MatrixXcd& rhs) const;  // column by column, in place
  Eigen::MatrixXd positions(const Eigen::VectorXcd& y) const;
  const ComplexEqualityBasis& basis() const { return basis_; }
  // Before many solve_reduced() calls (HermitianCholesky::compact_for_solves).
  void prepare_many_solves() { cholesky_.compact_for_solves(); }
  double analyze_s() const { return cholesky_.analyze_s; }
  double factorize_s() const { return cholesky_.factorize_s; }

 private:
  ComplexEqualityBasis basis_;
  Eigen::VectorXd weights_;
  HermitianCholesky cholesky_;
};

}  // namespace strictmin
