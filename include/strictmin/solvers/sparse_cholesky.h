#pragma once
// Sparse Cholesky (CHOLMOD, supernodal, through Eigen's CholmodSupport) with the symbolic
// analysis kept: analyze() once per sparsity pattern, factorize() for every new matrix with
// that pattern, solve() as often as needed.
#include <Eigen/CholmodSupport>
#include <Eigen/SparseCore>
#include <memory>

namespace strictmin {

class SparseCholesky {
 public:
  SparseCholesky();
  ~SparseCholesky();
  SparseCholesky(const SparseCholesky&) = delete;
  SparseCholesky& operator=(const SparseCholesky&) = delete;

  // A is symmetric; only its lower triangle is read.
  void analyze(const Eigen::SparseMatrix<double>& A);
  // False when A is not (numerically) positive definite.
  bool factorize(const Eigen::SparseMatrix<double>& A);
  Eigen::MatrixXd solve(const Eigen::MatrixXd& B) const;
  bool analyzed() const { return analyzed_; }

 private:
  using Llt = Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower>;
  std::unique_ptr<Llt> llt_;
  bool analyzed_ = false;
};

}  // namespace strictmin
