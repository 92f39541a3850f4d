#include "strictmin/solvers/sparse_cholesky.h"

namespace strictmin {

SparseCholesky::SparseCholesky() : llt_(std::make_unique<Llt>()) {
  llt_->cholmod().print = 0;  // a non-positive-definite matrix is reported by factorize()
}

SparseCholesky::~SparseCholesky() = default;

void SparseCholesky::analyze(const Eigen::SparseMatrix<double>& A) {
  llt_->analyzePattern(A);
  analyzed_ = true;
}

bool SparseCholesky::factorize(const Eigen::SparseMatrix<double>& A) {
  if (!analyzed_) analyze(A);
  llt_->factorize(A);
  return llt_->info() == Eigen::Success;
}

Eigen::MatrixXd SparseCholesky::solve(const Eigen::MatrixXd& B) const { return llt_->solve(B); }

}  // namespace strictmin
