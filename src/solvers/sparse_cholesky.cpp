#include "strictmin/solvers/sparse_cholesky.h"

#include <dlfcn.h>

namespace strictmin {
namespace {

using GetLevels = int (*)();
using SetLevels = void (*)(int);

struct OpenMpLevels {
  GetLevels get = nullptr;
  SetLevels set = nullptr;
  OpenMpLevels() {
    // The OpenMP runtime CHOLMOD was linked with, if any (libgomp on Debian).
    get = reinterpret_cast<GetLevels>(dlsym(RTLD_DEFAULT, "omp_get_max_active_levels"));
    set = reinterpret_cast<SetLevels>(dlsym(RTLD_DEFAULT, "omp_set_max_active_levels"));
    if (!get || !set) get = nullptr, set = nullptr;
  }
};

const OpenMpLevels& openmp_levels() {
  static const OpenMpLevels levels;
  return levels;
}

}  // namespace

SerialCholmodScope::SerialCholmodScope() {
  const OpenMpLevels& omp = openmp_levels();
  if (!omp.set) return;
  saved_ = omp.get();
  omp.set(0);
}

SerialCholmodScope::~SerialCholmodScope() {
  if (saved_ >= 0) openmp_levels().set(saved_);
}

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
  SerialCholmodScope serial;
  llt_->factorize(A);
  return llt_->info() == Eigen::Success;
}

Eigen::MatrixXd SparseCholesky::solve(const Eigen::MatrixXd& B) const { return llt_->solve(B); }

}  // namespace strictmin
