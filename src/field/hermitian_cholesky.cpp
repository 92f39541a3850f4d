#include "field/hermitian_cholesky.h"

#include <cholmod.h>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>

#include "field/complex_supernodal_solve.h"
#include "field/hermitian_factor.h"
#include "strictmin/solvers/timing.h"

namespace strictmin {

struct HermitianCholesky::Impl {
  cholmod_common common;
  cholmod_factor* L = nullptr;
  CompactFactor compact;  // L without its stored zeros, for the substitutions
  int n = 0;                          // the analysed pattern
  std::vector<int> start, row;
  bool factored = false;              // the last factorization succeeded
  std::unique_ptr<HermitianFactor> numeric;  // our numeric factorization (hermitian_factor.h)
  Eigen::VectorXcd work;  // the permuted right-hand side
  // cholmod_solve2's result and workspace, kept between solves (no allocation per solve).
  cholmod_dense *X = nullptr, *Y = nullptr, *E = nullptr;
  Impl() {
    cholmod_start(&common);
    common.print = 0;
    // AMD only: on the face graphs of 100k triangles METIS saves 30% of the factorization's
    // time but its ordering costs 7 times AMD's (0.49 s against 0.07 s CPU).
    common.nmethods = 1;
    common.method[0].ordering = CHOLMOD_AMD;
    common.postorder = 1;
    common.supernodal = CHOLMOD_SUPERNODAL;
  }
  ~Impl() {
    for (cholmod_dense** d : {&X, &Y, &E})
      if (*d) cholmod_free_dense(d, &common);
    if (L) cholmod_free_factor(&L, &common);
    cholmod_finish(&common);
  }
};

namespace {

// M's lower-triangle entries as entries of the permuted matrix's lower triangle: (r, c) goes
// to (p(r), p(c)), or conjugated to (p(c), p(r)) when the permutation puts it above the
// diagonal.
HermitianEntries permuted_entries(const HermitianLower& M, const cholmod_factor* L) {
  const int* perm = static_cast<const int*>(L->Perm);
  std::vector<int> inverse(M.n);
  for (int k = 0; k < M.n; ++k) inverse[perm[k]] = k;
  HermitianEntries e;
  e.row.reserve(M.row.size());
  e.col.reserve(M.row.size());
  e.conjugate.reserve(M.row.size());
  for (int c = 0; c < M.n; ++c)
    for (int k = M.start[c]; k < M.start[c + 1]; ++k) {
      const int pr = inverse[M.row[k]], pc = inverse[c];
      e.row.push_back(std::max(pr, pc));
      e.col.push_back(std::min(pr, pc));
      e.conjugate.push_back(pr < pc);
    }
  return e;
}

}  // namespace

HermitianCholesky::HermitianCholesky() : impl_(new Impl) {}
HermitianCholesky::~HermitianCholesky() { delete impl_; }

bool HermitianCholesky::factorize(const HermitianLower& M) {
  cholmod_common& c = impl_->common;
  // The same pattern as the last good factorization's (IRLS reweighting): its analysis stays.
  const bool same = impl_->L && impl_->factored && M.n == impl_->n && M.start == impl_->start && M.row == impl_->row;
  if (impl_->L && !same) cholmod_free_factor(&impl_->L, &c);
  // A view of M's arrays: CHOLMOD's complex type is interleaved (re, im), as std::complex.
  cholmod_sparse A;
  std::memset(&A, 0, sizeof A);
  A.nrow = A.ncol = static_cast<size_t>(M.n);
  A.nzmax = M.row.size();
  A.p = const_cast<int*>(M.start.data());
  A.i = const_cast<int*>(M.row.data());
  A.x = const_cast<std::complex<double>*>(M.value.data());
  A.stype = -1;
  A.itype = CHOLMOD_INT;
  A.xtype = CHOLMOD_COMPLEX;
  A.dtype = CHOLMOD_DOUBLE;
  A.sorted = 1;
  A.packed = 1;
  auto t0 = std::chrono::steady_clock::now();
  impl_->factored = false;
  if (!same) {
    impl_->L = cholmod_analyze(&A, &c);
    impl_->n = M.n;
    impl_->start = M.start;
    impl_->row = M.row;
    impl_->numeric.reset();
    if (impl_->L && c.status == CHOLMOD_OK && impl_->L->is_super && !std::getenv("STRICTMIN_CHOLMOD_NUMERIC")) {
      impl_->numeric = std::make_unique<HermitianFactor>();
      if (!impl_->numeric->setup(impl_->L, &c, permuted_entries(M, impl_->L))) impl_->numeric.reset();
    }
  }
  analyze_s = seconds_since(t0);
  if (!impl_->L || c.status != CHOLMOD_OK) return false;
  t0 = std::chrono::steady_clock::now();
  impl_->compact = CompactFactor{};
  if (impl_->numeric) {
    impl_->factored = impl_->numeric->factorize(M.value.data());
  } else {
    const int ok = cholmod_factorize(&A, impl_->L, &c);
    impl_->factored = ok && c.status == CHOLMOD_OK && impl_->L->minor == impl_->L->n;
  }
  factorize_s = seconds_since(t0);
  return impl_->factored;
}

void HermitianCholesky::compact_for_solves() {
  if (impl_->L && supports_complex_supernodal_solve(*impl_->L)) impl_->compact = compact_factor(*impl_->L);
}

void HermitianCholesky::solve_many_in_place(Eigen::MatrixXcd& B) const {
  const cholmod_factor* L = impl_->L;
  const Eigen::Index n = B.rows(), k = B.cols();
  if (k == 0) return;
  if (impl_->compact.start.empty() || !L || static_cast<Eigen::Index>(L->n) != n) {
    for (Eigen::Index c = 0; c < k; ++c) {
      Eigen::VectorXcd x = B.col(c);
      solve_in_place(x);
      B.col(c) = x;
    }
    return;
  }
  // Rows of P B, each row's k values together (compact_solve_many's layout).
  const int* perm = static_cast<const int*>(L->Perm);
  Eigen::Matrix<std::complex<double>, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> Y(n, k);
  for (Eigen::Index i = 0; i < n; ++i) Y.row(i) = B.row(perm[i]);
  compact_solve_many(impl_->compact, Y.data(), static_cast<int>(k));
  for (Eigen::Index i = 0; i < n; ++i) B.row(perm[i]) = Y.row(i);
}

Eigen::VectorXcd HermitianCholesky::solve(const Eigen::VectorXcd& b) const {
  Eigen::VectorXcd x = b;
  solve_in_place(x);
  return x;
}

void HermitianCholesky::solve_in_place(Eigen::VectorXcd& b) const {
  const cholmod_factor* L = impl_->L;
  if (L && supports_complex_supernodal_solve(*L) && static_cast<Eigen::Index>(L->n) == b.size() &&
      !std::getenv("STRICTMIN_CHOLMOD_SOLVE")) {
    // x = P^T L^-H L^-1 P b with our loops (complex_supernodal_solve.h).
    const int* perm = static_cast<const int*>(L->Perm);
    const Eigen::Index n = b.size();
    Eigen::VectorXcd& y = impl_->work;
    y.resize(n);
    for (Eigen::Index k = 0; k < n; ++k) y(k) = b(perm[k]);
    if (!impl_->compact.start.empty()) {
      compact_solve(impl_->compact, y.data());
    } else {
      complex_supernodal_forward(*L, y.data());
      complex_supernodal_backward(*L, y.data());
    }
    for (Eigen::Index k = 0; k < n; ++k) b(perm[k]) = y(k);
    return;
  }
  cholmod_common& c = impl_->common;
  cholmod_dense B;
  std::memset(&B, 0, sizeof B);
  B.nrow = B.d = static_cast<size_t>(b.size());
  B.ncol = 1;
  B.nzmax = B.nrow;
  B.x = const_cast<std::complex<double>*>(b.data());
  B.xtype = CHOLMOD_COMPLEX;
  B.dtype = CHOLMOD_DOUBLE;
  if (!cholmod_solve2(CHOLMOD_A, impl_->L, &B, nullptr, &impl_->X, nullptr, &impl_->Y, &impl_->E, &c)) {
    b.setConstant(std::complex<double>(std::numeric_limits<double>::quiet_NaN(), 0));
    return;
  }
  std::memcpy(b.data(), impl_->X->x, sizeof(std::complex<double>) * static_cast<size_t>(b.size()));
}

}  // namespace strictmin
