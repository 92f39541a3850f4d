#pragma once
// Sparse Cholesky (supernodal: CHOLMOD's symbolic analysis and fill-reducing order, our
// numeric factorisation and substitutions, src/solvers/socp/supernodal_cholesky.h) with the
// symbolic analysis kept: analyze() once per sparsity pattern, factorize() for every new
// matrix with that pattern (a matrix with another pattern is analysed again), solve() as
// often as needed. CHOLMOD stays behind the private implementation.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>

namespace strictmin {

namespace socp {
class SupernodalCholesky;
}

class SparseCholesky {
 public:
  // amd_only: AMD for the fill-reducing order (no METIS: safe to run beside another thread's
  // METIS, whose random generator is global); otherwise CHOLMOD's default choice.
  explicit SparseCholesky(bool amd_only = false);
  ~SparseCholesky();
  SparseCholesky(const SparseCholesky&) = delete;
  SparseCholesky& operator=(const SparseCholesky&) = delete;

  // A is symmetric; only its lower triangle is read.
  void analyze(const Eigen::SparseMatrix<double>& A);
  // False when A is not (numerically) positive definite.
  bool factorize(const Eigen::SparseMatrix<double>& A);
  // A^{-1} B, two columns per pass over the factor.
  Eigen::MatrixXd solve(const Eigen::MatrixXd& B) const;
  bool analyzed() const { return analyzed_; }

 private:
  bool same_pattern(const Eigen::SparseMatrix<double>& A) const;
  bool amd_only_ = false;
  Eigen::SparseMatrix<double> pattern_;  // compressed copy of the analysed matrix
  std::unique_ptr<socp::SupernodalCholesky> cholesky_;
  bool analyzed_ = false, factorized_ = false;
};

}  // namespace strictmin
