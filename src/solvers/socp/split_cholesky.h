#pragma once
// Sparse Cholesky of a matrix split by a vertex separator into two independent halves,
// factorised on two threads (CHOLMOD runs one factorisation on one core).
//
// The matrix is given in the order [part 0 | part 1 | separator S], with no entry coupling
// the two parts:
//       [A00  0   A0S]
//   A = [ 0  A11  A1S]
//       [AS0 AS1  ASS]
// Each half B_p = [App ApS; ASp ASS] is a principal submatrix of A (so positive definite
// whenever A is) and is factorised by CHOLMOD (supernodal, natural order, S last), in
// parallel: B_p = L_p L_p^T, L_p = [Lpp 0; Cp Tp], Tp Tp^T = ASS - ASp App^-1 ApS. The
// separator's Schur complement of A is then dense and small,
//   S = ASS - AS0 A00^-1 A0S - AS1 A11^-1 A1S = T0 T0^T + T1 T1^T - ASS,
// and is factorised by LAPACK. A solve is one forward and one backward substitution per half
// (in parallel) around a dense solve with S. On the normal equations of the 100k square
// (separator 448 dofs of 99,456) each half is a little more than half the work.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <vector>

namespace strictmin::socp {

class SplitCholesky {
 public:
  SplitCholesky();
  ~SplitCholesky();
  SplitCholesky(const SplitCholesky&) = delete;
  SplitCholesky& operator=(const SplitCholesky&) = delete;

  // upper: the upper triangle's pattern (compressed, column major) in the order above, n0 and
  // n1 the sizes of the parts. False when the pattern does not have that form or CHOLMOD's
  // analysis moves the separator (the caller then uses one factorisation).
  bool analyze(const Eigen::SparseMatrix<double>& upper, int n0, int n1);
  // values: upper's values (same pattern). False when A is not (numerically) positive definite.
  bool factorize(const double* values);
  // x = A^-1 b (b and x in the matrix's order; x may not alias b).
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const;
  // x0 = A^-1 b0 and x1 = A^-1 b1 with one pass over the factors.
  void solve2(const Eigen::VectorXd& b0, const Eigen::VectorXd& b1, Eigen::VectorXd& x0, Eigen::VectorXd& x1) const;
  double flops() const;     // CHOLMOD's flop counts of the halves plus the dense part
  double nonzeros() const;  // nonzeros of the halves' factors plus the dense part

 private:
  struct Half;
  // x[c] = A^-1 b[c] for R = 1 or 2 columns, one pass over the halves' factors.
  void solve_columns(const double* const* b, double* const* x, int R) const;
  std::unique_ptr<Half> half_[2];
  int ns_ = 0, n_ = 0;
  std::vector<int> ass_source_, ass_row_, ass_col_;  // ASS entries: nonzero index, local row >= col
  Eigen::MatrixXd s_;                                // factor of the dense Schur complement (lower)
};

}  // namespace strictmin::socp
