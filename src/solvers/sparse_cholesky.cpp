#include "strictmin/solvers/sparse_cholesky.h"

#include <dlfcn.h>

#include <algorithm>
#include <limits>
#include <mutex>

#include "solvers/serial_cholmod_scope.h"
#include "solvers/socp/supernodal_cholesky.h"

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

SparseCholesky::SparseCholesky(bool amd_only) : amd_only_(amd_only) {}

SparseCholesky::~SparseCholesky() = default;

void SparseCholesky::analyze(const Eigen::SparseMatrix<double>& A) {
  using socp::SupernodalCholesky;
  pattern_ = A;
  pattern_.makeCompressed();
  cholesky_ = std::make_unique<SupernodalCholesky>(
      amd_only_ ? SupernodalCholesky::Ordering::Amd : SupernodalCholesky::Ordering::Cholmod,
      SupernodalCholesky::Triangle::Lower);
  analyzed_ = cholesky_->analyze(pattern_);
  factorized_ = false;
}

bool SparseCholesky::same_pattern(const Eigen::SparseMatrix<double>& A) const {
  if (A.rows() != pattern_.rows() || A.cols() != pattern_.cols() ||
      A.nonZeros() != pattern_.nonZeros())
    return false;
  const Eigen::Index n = A.outerSize(), nnz = A.nonZeros();
  return std::equal(A.outerIndexPtr(), A.outerIndexPtr() + n + 1, pattern_.outerIndexPtr()) &&
         std::equal(A.innerIndexPtr(), A.innerIndexPtr() + nnz, pattern_.innerIndexPtr());
}

bool SparseCholesky::factorize(const Eigen::SparseMatrix<double>& A) {
  if (!A.isCompressed()) {  // the factor reads the values in compressed order
    Eigen::SparseMatrix<double> compressed = A;
    compressed.makeCompressed();
    return factorize(compressed);
  }
  if (!analyzed_ || !same_pattern(A)) analyze(A);
  factorized_ = analyzed_ && cholesky_->factorize(A.valuePtr());
  return factorized_;
}

Eigen::MatrixXd SparseCholesky::solve(const Eigen::MatrixXd& B) const {
  Eigen::MatrixXd X(B.rows(), B.cols());
  if (!factorized_ || B.rows() != pattern_.rows()) {
    X.setConstant(std::numeric_limits<double>::quiet_NaN());
    return X;
  }
  Eigen::Index c = 0;
  for (; c + 1 < B.cols(); c += 2)  // two columns per pass over the factor
    cholesky_->solve2(B.col(c).data(), B.col(c + 1).data(), X.col(c).data(), X.col(c + 1).data());
  if (c < B.cols()) cholesky_->solve(B.col(c).data(), X.col(c).data());
  return X;
}

}  // namespace strictmin
