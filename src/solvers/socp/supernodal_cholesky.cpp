#include "solvers/socp/supernodal_cholesky.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <limits>

#include "solvers/cholmod_view.h"
#include "solvers/serial_cholmod_scope.h"
#include "solvers/socp/supernodal_factor.h"
#include "solvers/socp/supernodal_solve.h"

namespace strictmin::socp {

SupernodalCholesky::SupernodalCholesky(Ordering ordering, Triangle triangle)
    : stype_(triangle == Triangle::Upper ? 1 : -1) {
  cholmod_start(&common_);
  common_.print = 0;
  common_.supernodal = CHOLMOD_SUPERNODAL;
  if (ordering != Ordering::Cholmod) {
    common_.nmethods = 1;
    common_.method[0].ordering = ordering == Ordering::Given ? CHOLMOD_NATURAL : CHOLMOD_AMD;
  }
}

SupernodalCholesky::~SupernodalCholesky() {
  if (L_) cholmod_free_factor(&L_, &common_);
  cholmod_finish(&common_);
}

bool SupernodalCholesky::analyze(const Eigen::SparseMatrix<double>& pattern) {
  if (L_) cholmod_free_factor(&L_, &common_);
  numeric_.reset();
  pattern_ = &pattern;
  const int n = static_cast<int>(pattern.rows());
  perm_.clear();
  if (n == 0) return true;  // nothing to factorise
  cholmod_sparse A = cholmod_view(const_cast<Eigen::SparseMatrix<double>&>(pattern), stype_);
  L_ = cholmod_analyze(&A, &common_);
  if (!L_ || common_.status != CHOLMOD_OK) return false;
  const int* p = static_cast<const int*>(L_->Perm);
  perm_.assign(p, p + n);
  // The given triangle's entries as lower-triangle entries of the permuted matrix (the other
  // triangle's marked unused).
  if (L_->is_super && !std::getenv("STRICTMIN_CHOLMOD_NUMERIC")) {
    std::vector<int> iperm(n), rows, cols;
    for (int k = 0; k < n; ++k) iperm[perm_[k]] = k;
    rows.reserve(pattern.nonZeros());
    cols.reserve(pattern.nonZeros());
    for (int c = 0; c < n; ++c)
      for (int z = pattern.outerIndexPtr()[c]; z < pattern.outerIndexPtr()[c + 1]; ++z) {
        const int r = pattern.innerIndexPtr()[z];
        const bool used = stype_ > 0 ? r <= c : r >= c;
        const int pr = iperm[r], pc = iperm[c];
        rows.push_back(used ? std::max(pr, pc) : -1);
        cols.push_back(std::min(pr, pc));
      }
    numeric_ = std::make_unique<SupernodalFactor>();
    if (!numeric_->setup(L_, &common_, rows, cols)) numeric_.reset();
  }
  return true;
}

bool SupernodalCholesky::factorize(const double* values) {
  if (!L_) return pattern_ && pattern_->rows() == 0;
  SerialCholmodScope serial;  // serial_cholmod_scope.h: one BLAS thread (the wide supernodes' calls)
  if (numeric_) {
    if (!numeric_->factorize(values)) return false;
  } else {
    // CHOLMOD reads the values through the pattern's view.
    cholmod_sparse A = cholmod_view(const_cast<Eigen::SparseMatrix<double>&>(*pattern_), stype_);
    A.x = const_cast<double*>(values);
    cholmod_factorize(&A, L_, &common_);
    if (common_.status != CHOLMOD_OK || L_->minor < L_->n) return false;
  }
  own_solve_ = supports_supernodal_solve(*L_);
  return true;
}

// One substitution (L or L^T) with one or two interleaved right-hand sides: our supernodal
// loops, or CHOLMOD's solve for a factor they do not handle.
void SupernodalCholesky::substitute(int system, int columns, double* y) const {
  using Loop = void (*)(const cholmod_factor&, double*);
  static constexpr Loop loops[2][2] = {{supernodal_forward, supernodal_backward},
                                       {supernodal_forward2, supernodal_backward2}};
  if (own_solve_)
    loops[columns - 1][system == CHOLMOD_L ? 0 : 1](*L_, y);
  else if (columns == 1)
    cholmod_solve_in_place(system, y);
  else
    cholmod_solve2_in_place(system, y);
}

void SupernodalCholesky::forward_in_place(double* y) const { substitute(CHOLMOD_L, 1, y); }
void SupernodalCholesky::backward_in_place(double* y) const { substitute(CHOLMOD_Lt, 1, y); }
void SupernodalCholesky::forward2_in_place(double* y) const { substitute(CHOLMOD_L, 2, y); }
void SupernodalCholesky::backward2_in_place(double* y) const { substitute(CHOLMOD_Lt, 2, y); }

void SupernodalCholesky::solve2(const double* b0, const double* b1, double* x0, double* x1) const {
  const int n = static_cast<int>(perm_.size());
  if (n == 0) return;
  thread_local std::vector<double> work;
  if (static_cast<int>(work.size()) < 2 * n) work.resize(2 * static_cast<size_t>(n));
  double* y = work.data();
  for (int k = 0; k < n; ++k) {
    y[2 * k] = b0[perm_[k]];
    y[2 * k + 1] = b1[perm_[k]];
  }
  forward2_in_place(y);
  backward2_in_place(y);
  for (int k = 0; k < n; ++k) {
    x0[perm_[k]] = y[2 * k];
    x1[perm_[k]] = y[2 * k + 1];
  }
}

void SupernodalCholesky::solve(const double* b, double* x) const {
  const int n = static_cast<int>(perm_.size());
  if (n == 0) return;
  thread_local std::vector<double> work;  // solves may run on several threads at once
  if (static_cast<int>(work.size()) < n) work.resize(n);
  double* y = work.data();
  for (int k = 0; k < n; ++k) y[k] = b[perm_[k]];
  forward_in_place(y);
  backward_in_place(y);
  for (int k = 0; k < n; ++k) x[perm_[k]] = y[k];
}

void SupernodalCholesky::cholmod_solve2_in_place(int system, double* y) const {
  const size_t n = perm_.size();
  std::vector<double> column(n);
  for (int c = 0; c < 2; ++c) {
    for (size_t k = 0; k < n; ++k) column[k] = y[2 * k + c];
    cholmod_solve_in_place(system, column.data());
    for (size_t k = 0; k < n; ++k) y[2 * k + c] = column[k];
  }
}

void SupernodalCholesky::cholmod_solve_in_place(int system, double* y) const {
  const size_t n = perm_.size();
  cholmod_dense b;
  std::memset(&b, 0, sizeof b);
  b.nrow = b.d = b.nzmax = n;
  b.ncol = 1;
  b.x = y;
  b.xtype = CHOLMOD_REAL;
  b.dtype = CHOLMOD_DOUBLE;
  cholmod_dense* out = cholmod_solve(system, L_, &b, &common_);
  if (out) {
    std::memcpy(y, out->x, sizeof(double) * n);
    cholmod_free_dense(&out, &common_);
  } else {
    std::fill(y, y + n, std::numeric_limits<double>::quiet_NaN());
  }
}

}  // namespace strictmin::socp
