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
  // The minimizer for the problem's targets (#V by 2), after a successful factorize().
  Eigen::MatrixXd solve(const Problem& p) const;
  double analyze_s() const { return cholesky_.analyze_s; }
  double factorize_s() const { return cholesky_.factorize_s; }

 private:
  ComplexEqualityBasis basis_;
  Eigen::VectorXd weights_;
  HermitianCholesky cholesky_;
};

}  // namespace strictmin
