#pragma once
// The certified lower bound (dual objective of a dual-feasible point) and the weighted
// least-squares solves it needs.
//
// Any z in the cones and y give a lower bound once the dual equations hold exactly:
// r = G^T z_tails + A^T y is corrected by delta = -W G (G^T W G)^{-1} r on the tails
// (W = element weights), which makes G^T (z_tails + delta) + A^T y = 0; raising each head by
// ||delta_i|| keeps z_i in its cone, and dividing by sum_i a_i z_i,0 restores the k
// equation. The dual objective of the corrected point is then a valid bound by weak duality
// (for a program with c_k = 1 and no quadratic term): no x, k does better.
//
// G^T W G = K (x) I_n with K = sum_i w_i L_i (L_i the corners' gradient Gram matrix), the
// area-weighted L2 matrix of the free vertices (the cotangent Laplacian for triangles):
// factorised once (in AMD order: no METIS, so that it may be built while another thread
// orders the normal equations), solved per image coordinate.
//
// A program whose parts are held by its equalities only (an active-set relaxation of a
// seamless problem, linf_relaxed_equalities.h) has a singular G^T W G: its parts' translations.
// There (with_equalities) the matrix is K (x) I_n + A^T A, and the correction
// u = (G^T W G + A^T A)^{-1} r moves the tails by delta = -W G u and the equalities'
// multipliers by -A u, which again makes G^T (z_tails + delta) + A^T y = 0 exactly.
#include <Eigen/Core>

#include "solvers/socp/cone_program.h"
#include "strictmin/solvers/sparse_cholesky.h"

namespace strictmin::socp {

class WeightedLeastSquares {
 public:
  explicit WeightedLeastSquares(const ConeProgram& p, bool with_equalities = false);
  bool ok() const { return ok_; }
  bool with_equalities() const { return with_eq_; }
  // (G^T W G)^{-1} r, or (G^T W G + A^T A)^{-1} r with_equalities.
  Eigen::VectorXd solve(const Eigen::VectorXd& r) const;
  // argmin_x sum_i w_i ||G_i x - h_i||^2 (the L2 map, without the equalities; with_equalities
  // plus ||A x - b||^2).
  Eigen::VectorXd minimizer() const;

 private:
  void factor_with_equalities();

  const ConeProgram& p_;
  SparseCholesky cholesky_;
  bool ok_ = true;
  bool with_eq_ = false;
};

// Certified lower bound on the optimal k of `p` (c_k = 1, no quadratic objective) from any
// z strictly inside the cones and any y. -inf when it cannot be formed. With `multipliers`,
// also the corrected dual's heads, one per element cone, normalised so that
// sum_i head_a_i * lambda_i = 1: for every x meeting the bounded cones,
// sum_i lambda_i (D_i(x) - head_b_i) >= bound (the weak-duality inequality behind the bound).
double certified_lower_bound(const ConeProgram& p, const WeightedLeastSquares& ls, const Eigen::VectorXd& z,
                             const Eigen::VectorXd& y, Eigen::VectorXd* multipliers = nullptr);

}  // namespace strictmin::socp
