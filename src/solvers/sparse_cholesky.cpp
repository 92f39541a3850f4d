#include "strictmin/solvers/sparse_cholesky.h"

#include <dlfcn.h>

#include <mutex>

#include "strictmin/solvers/socp/supernodal_solve.h"

namespace strictmin {
namespace {

using GetInt = int (*)();
using SetInt = void (*)(int);

// A get/set pair of the runtime libraries CHOLMOD was linked with, if present.
struct RuntimeSetting {
  GetInt get = nullptr;
  SetInt set = nullptr;
  RuntimeSetting(const char* get_name, const char* set_name) {
    get = reinterpret_cast<GetInt>(dlsym(RTLD_DEFAULT, get_name));
    set = reinterpret_cast<SetInt>(dlsym(RTLD_DEFAULT, set_name));
    if (!get || !set) get = nullptr, set = nullptr;
  }
};

const RuntimeSetting& openmp_levels() {  // libgomp on Debian
  static const RuntimeSetting s("omp_get_max_active_levels", "omp_set_max_active_levels");
  return s;
}

const RuntimeSetting& openblas_threads() {
  static const RuntimeSetting s("openblas_get_num_threads", "openblas_set_num_threads");
  return s;
}

std::mutex blas_mutex;
int blas_scopes = 0, blas_saved = 0;

}  // namespace

SerialCholmodScope::SerialCholmodScope() {
  if (const RuntimeSetting& blas = openblas_threads(); blas.set) {
    std::lock_guard<std::mutex> lock(blas_mutex);
    if (blas_scopes++ == 0) {
      blas_saved = blas.get();
      if (blas_saved != 1) blas.set(1);
    }
  }
  const RuntimeSetting& omp = openmp_levels();
  if (!omp.set) return;
  saved_ = omp.get();
  omp.set(0);
}

SerialCholmodScope::~SerialCholmodScope() {
  if (saved_ >= 0) openmp_levels().set(saved_);
  if (const RuntimeSetting& blas = openblas_threads(); blas.set) {
    std::lock_guard<std::mutex> lock(blas_mutex);
    if (--blas_scopes == 0 && blas_saved != 1) blas.set(blas_saved);
  }
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

Eigen::MatrixXd SparseCholesky::solve(const Eigen::MatrixXd& B) const {
  const cholmod_factor* L = llt_->factor();
  if (!L || !socp::supports_supernodal_solve(*L) || llt_->info() != Eigen::Success ||
      static_cast<Eigen::Index>(L->n) != B.rows()) {
    SerialCholmodScope serial;
    return llt_->solve(B);
  }
  // L L^T = P A P^T with (P b)_k = b_{Perm[k]}: x = P^T L^-T L^-1 P b.
  const int* perm = static_cast<const int*>(L->Perm);
  const Eigen::Index n = B.rows();
  Eigen::MatrixXd X(n, B.cols());
  Eigen::VectorXd y(n);
  for (Eigen::Index c = 0; c < B.cols(); ++c) {
    for (Eigen::Index k = 0; k < n; ++k) y[k] = B(perm ? perm[k] : k, c);
    socp::supernodal_forward(*L, y.data());
    socp::supernodal_backward(*L, y.data());
    for (Eigen::Index k = 0; k < n; ++k) X(perm ? perm[k] : k, c) = y[k];
  }
  return X;
}

}  // namespace strictmin
