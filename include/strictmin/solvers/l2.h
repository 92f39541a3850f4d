#pragma once
// L2 field deviation: minimize sum_T A_T ||J_T - R_T||_F^2 over the free vertices.
//
// The energy separates by image coordinate: row r of J_T is sum_j q_j[r] g_j^T, so the
// normal equations are K Q_free = B with one scalar matrix K_ij = sum_T A_T g_i . g_j
// (the cotangent Laplacian for triangles) shared by all coordinates. K is factorized once
// (CHOLMOD) and kept: new targets only change B (the global step of local-global).
// With linear equalities (seams) the unknowns are the independent dofs y of
// problem/equality_basis.h, q = Z y + z0, and the matrix is Z^T (K (x) I) Z (the seams'
// rotations couple the image coordinates). When the equalities are complex-linear (planar
// maps, 2 x 2 blocks that are rotation-scalings, right-hand sides 0: the seams of global
// parametrization) the same minimizer is computed in complex form instead
// (problem/complex_equality_basis.h, src/solvers/l2_complex.h): one complex unknown per
// independent vertex, a Hermitian matrix of half the size.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <vector>

#include "strictmin/problem/equality_basis.h"
#include "strictmin/problem/problem.h"
#include "strictmin/solvers/result.h"
#include "strictmin/solvers/sparse_cholesky.h"

namespace strictmin {

struct L2Options {
  // With complex-linear equalities, solve in complex form (false: the real form, to compare).
  bool complex_equalities = true;
};

class ComplexL2;

class L2Solver {
 public:
  // Assembles and factorizes K for the problem's mesh, weights and fixed vertices.
  explicit L2Solver(const Problem& problem, const L2Options& options = {});
  // New per-element weights (#E, e.g. A_T w_T for IRLS): K is reassembled and factorized
  // again, reusing the symbolic analysis. False when K is not positive definite. Throws
  // InputError (as solve) for a problem of another size or weights that are not #E.
  bool reweight(const Problem& problem, const Eigen::VectorXd& element_weights);
  // Solved-for positions (#V by image_dim) for the problem's current targets and fixed
  // positions (same mesh and fixed set as at construction: another vertex or element count
  // is refused, InputError).
  Eigen::MatrixXd solve(const Problem& problem) const;
  SolveStatus status() const { return status_; }
  const std::string& message() const { return message_; }
  double analyze_s() const { return analyze_s_; }
  double factorize_s() const { return factorize_s_; }
  const Eigen::SparseMatrix<double>& matrix() const { return K_; }

 private:
  void assemble(const Problem& problem, const Eigen::VectorXd& element_weights);
  void assemble_constrained(const Problem& problem, const Eigen::VectorXd& element_weights);
  Eigen::MatrixXd solve_constrained(const Problem& problem) const;
  bool factorize();
  bool factorize_complex(const Problem& problem, const Eigen::VectorXd& element_weights);
  void check_same_size(const Problem& problem) const;

  std::shared_ptr<const EqualityBasis> basis_;  // with equalities only (real form)
  std::shared_ptr<ComplexL2> complex_;          // with complex-linear equalities
  Eigen::SparseMatrix<double> Zt_;              // Z^T
  Eigen::VectorXd Kz0_;                         // (K (x) I) z0

  std::vector<int> free_index_;
  int num_elements_ = 0;  // of the construction's problem (free_index_ has its vertices)
  Eigen::VectorXd element_weights_;
  Eigen::SparseMatrix<double> K_;       // free by free
  Eigen::SparseMatrix<double> K_fixed_; // free by all vertices: couplings to fixed ones
  SparseCholesky cholesky_;
  SolveStatus status_ = SolveStatus::Solved;
  std::string message_;
  double analyze_s_ = 0, factorize_s_ = 0;
};

// The sum_T A_T ||J_T - R_T||^2 minimizer. Status numerical-error (with the reason) when
// the problem has no unique solution (a connected part without any fixed vertex).
Result solve_l2(const Problem& problem, const L2Options& options = {});

}  // namespace strictmin
