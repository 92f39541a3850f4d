#include "strictmin/solvers/socp/split_cholesky.h"

#include <cholmod.h>
#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <tbb/parallel_invoke.h>

#include "strictmin/solvers/cholmod_view.h"
#include "strictmin/solvers/socp/supernodal_factor.h"
#include "strictmin/solvers/socp/supernodal_solve.h"
#include "strictmin/solvers/sparse_cholesky.h"

extern "C" {
void dsyrk_(const char* uplo, const char* trans, const int* n, const int* k, const double* alpha, const double* a,
            const int* lda, const double* beta, double* c, const int* ldc);
void dpotrf_(const char* uplo, const int* n, double* a, const int* lda, int* info);
void dpotrs_(const char* uplo, const int* n, const int* nrhs, const double* a, const int* lda, double* b,
             const int* ldb, int* info);
void dtrmv_(const char* uplo, const char* trans, const char* diag, const int* n, const double* a, const int* lda,
            double* x, const int* incx);
}

namespace strictmin::socp {

struct SplitCholesky::Half {
  int off = 0, n = 0, ns = 0;         // part's first index in A, part size, separator size
  Eigen::SparseMatrix<double> B;      // upper triangle of [App ApS; ASp ASS]
  std::vector<int> source;            // B's nonzeros -> A's
  cholmod_common common;
  cholmod_factor* L = nullptr;
  std::vector<int> perm;              // CHOLMOD's postorder of the part (separator stays last)
  SupernodalFactor numeric;           // our numeric factorisation on CHOLMOD's analysis
  bool own_numeric = false;
  Eigen::MatrixXd T, G;               // trailing factor block Tp and Tp Tp^T (lower)
  // Solve workspace (one solve at a time per half).
  mutable Eigen::VectorXd rhs, y;

  Half() {
    cholmod_start(&common);
    common.print = 0;
    common.nmethods = 1;
    common.method[0].ordering = CHOLMOD_NATURAL;
    common.supernodal = CHOLMOD_SUPERNODAL;
  }
  ~Half() {
    if (L) cholmod_free_factor(&L, &common);
    cholmod_finish(&common);
  }

  cholmod_sparse view() { return cholmod_view(B, 1); }

  bool analyze() {
    cholmod_sparse A = view();
    L = cholmod_analyze(&A, &common);
    if (!L || !L->is_super) return false;
    const int* p = static_cast<const int*>(L->Perm);
    perm.assign(p, p + n + ns);
    for (int k = n; k < n + ns; ++k)
      if (perm[k] != k) return false;
    T.setZero(ns, ns);
    G.setZero(ns, ns);
    rhs.resize(n + ns);
    // B's upper-triangle entries as lower-triangle entries of the permuted matrix.
    std::vector<int> iperm(n + ns), rows, cols;
    for (int k = 0; k < n + ns; ++k) iperm[perm[k]] = k;
    rows.reserve(B.nonZeros());
    cols.reserve(B.nonZeros());
    for (int c = 0; c < B.outerSize(); ++c)
      for (int z = B.outerIndexPtr()[c]; z < B.outerIndexPtr()[c + 1]; ++z) {
        const int pr = iperm[B.innerIndexPtr()[z]], pc = iperm[c];
        rows.push_back(std::max(pr, pc));
        cols.push_back(std::min(pr, pc));
      }
    own_numeric = !std::getenv("STRICTMIN_CHOLMOD_NUMERIC") && numeric.setup(L, &common, rows, cols);
    return true;
  }

  bool factorize(const double* values) {
    double* bx = B.valuePtr();
    for (size_t k = 0; k < source.size(); ++k) bx[k] = values[source[k]];
    if (own_numeric) {
      SerialCholmodScope serial;
      if (!numeric.factorize(bx)) return false;
    } else {
      cholmod_sparse A = view();
      {
        SerialCholmodScope serial;
        cholmod_factorize(&A, L, &common);
      }
      if (common.status != CHOLMOD_OK || L->minor < L->n) return false;
    }
    // The separator's columns: the trailing block of the supernodes that hold them.
    const int* super = static_cast<const int*>(L->super);
    const int* pi = static_cast<const int*>(L->pi);
    const int* px = static_cast<const int*>(L->px);
    const int* s = static_cast<const int*>(L->s);
    const double* x = static_cast<const double*>(L->x);
    for (long k = static_cast<long>(L->nsuper) - 1; k >= 0 && super[k + 1] > n; --k) {
      const int nrows = pi[k + 1] - pi[k];
      for (int col = std::max(super[k], n); col < super[k + 1]; ++col) {
        const double* column = x + px[k] + static_cast<long>(col - super[k]) * nrows;
        for (int i = col - super[k]; i < nrows; ++i) T(s[pi[k] + i] - n, col - n) = column[i];
      }
    }
    // G = T T^T (lower triangle).
    const double one = 1.0, zero = 0.0;
    dsyrk_("L", "N", &ns, &ns, &one, T.data(), &ns, &zero, G.data(), &ns);
    return true;
  }

  // Forward: rhs = [b_part; 0] (CHOLMOD's order), y = L^-1 rhs; g = C y_part = -T y_sep.
  void forward(const double* b_part, Eigen::VectorXd& g) const {
    for (int k = 0; k < n; ++k) rhs[k] = b_part[perm[k]];
    rhs.tail(ns).setZero();
    solve_in_place(CHOLMOD_L);
    y = rhs;
    g = y.tail(ns);
    const int one = 1;
    dtrmv_("L", "N", "N", &ns, T.data(), &ns, g.data(), &one);
    g = -g;
  }
  // Backward: [x_part; v] = L^-T [y_part; T^T x_sep] (then v = x_sep).
  void backward(const Eigen::VectorXd& x_sep, double* x_part) const {
    rhs.head(n) = y.head(n);
    rhs.tail(ns) = x_sep;
    if (ns > 0) {
      const int one = 1;
      dtrmv_("L", "T", "N", &ns, T.data(), &ns, rhs.data() + n, &one);
    }
    solve_in_place(CHOLMOD_Lt);
    for (int k = 0; k < n; ++k) x_part[perm[k]] = rhs[k];
  }
  void solve_in_place(int sys) const {
    if (supports_supernodal_solve(*L)) {  // the usual case: no BLAS calls, no allocation
      if (sys == CHOLMOD_L)
        supernodal_forward(*L, rhs.data());
      else
        supernodal_backward(*L, rhs.data());
      return;
    }
    cholmod_dense b;
    std::memset(&b, 0, sizeof b);
    b.nrow = b.d = n + ns;
    b.ncol = 1;
    b.nzmax = n + ns;
    b.x = rhs.data();
    b.xtype = CHOLMOD_REAL;
    b.dtype = CHOLMOD_DOUBLE;
    auto& c = const_cast<cholmod_common&>(common);
    cholmod_dense* out = cholmod_solve(sys, L, &b, &c);
    if (out) {
      std::memcpy(rhs.data(), out->x, sizeof(double) * (n + ns));
      cholmod_free_dense(&out, &c);
    } else {
      rhs.setConstant(std::numeric_limits<double>::quiet_NaN());
    }
  }
};

SplitCholesky::SplitCholesky() = default;
SplitCholesky::~SplitCholesky() = default;

bool SplitCholesky::analyze(const Eigen::SparseMatrix<double>& upper, int n0, int n1) {
  const int N = static_cast<int>(upper.rows());
  n_ = N;
  ns_ = N - n0 - n1;
  if (n0 <= 0 || n1 <= 0 || ns_ < 0) return false;
  const int sep = n0 + n1;
  const int* outer = upper.outerIndexPtr();
  const int* inner = upper.innerIndexPtr();
  ass_source_.clear();
  ass_row_.clear();
  ass_col_.clear();
  // The halves (pattern and CHOLMOD's symbolic analysis) in parallel.
  auto build_half = [&](int p) {
    half_[p] = std::make_unique<Half>();
    Half& h = *half_[p];
    h.off = p == 0 ? 0 : n0;
    h.n = p == 0 ? n0 : n1;
    h.ns = ns_;
    const int size = h.n + ns_;
    std::vector<int> b_outer(size + 1, 0), b_inner;
    h.source.clear();
    auto local = [&](int r) { return r >= sep ? h.n + (r - sep) : (r >= h.off && r < h.off + h.n ? r - h.off : -1); };
    for (int lc = 0; lc < size; ++lc) {
      const int col = lc < h.n ? h.off + lc : sep + (lc - h.n);
      for (int z = outer[col]; z < outer[col + 1]; ++z) {
        const int lr = local(inner[z]);
        if (lr < 0) {
          if (col < sep) return false;  // an entry couples the parts: not split
          continue;
        }
        b_inner.push_back(lr);
        h.source.push_back(z);
      }
      b_outer[lc + 1] = static_cast<int>(b_inner.size());
    }
    h.B = Eigen::SparseMatrix<double>(size, size);
    h.B.resizeNonZeros(static_cast<Eigen::Index>(b_inner.size()));
    std::copy(b_outer.begin(), b_outer.end(), h.B.outerIndexPtr());
    std::copy(b_inner.begin(), b_inner.end(), h.B.innerIndexPtr());
    std::fill(h.B.valuePtr(), h.B.valuePtr() + b_inner.size(), 0.0);
    return h.analyze();
  };
  bool ok[2] = {false, false};
  tbb::parallel_invoke([&] { ok[0] = build_half(0); }, [&] { ok[1] = build_half(1); });
  if (!ok[0] || !ok[1]) return false;
  for (int col = sep; col < N; ++col)
    for (int z = outer[col]; z < outer[col + 1]; ++z)
      if (inner[z] >= sep) {
        ass_source_.push_back(z);
        ass_row_.push_back(col - sep);  // upper (row <= col) -> lower (col, row)
        ass_col_.push_back(inner[z] - sep);
      }
  s_.setZero(ns_, ns_);
  return true;
}

bool SplitCholesky::factorize(const double* values) {
  bool ok[2] = {false, false};
  tbb::parallel_invoke([&] { ok[0] = half_[0]->factorize(values); }, [&] { ok[1] = half_[1]->factorize(values); });
  if (!ok[0] || !ok[1]) return false;
  if (ns_ == 0) return true;
  s_ = half_[0]->G + half_[1]->G;
  for (size_t e = 0; e < ass_source_.size(); ++e) s_(ass_row_[e], ass_col_[e]) -= values[ass_source_[e]];
  int info = 0;
  dpotrf_("L", &ns_, s_.data(), &ns_, &info);
  return info == 0 && s_.allFinite();
}

void SplitCholesky::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
  x.resize(n_);
  Eigen::VectorXd g0, g1;
  tbb::parallel_invoke([&] { half_[0]->forward(b.data() + half_[0]->off, g0); },
                       [&] { half_[1]->forward(b.data() + half_[1]->off, g1); });
  Eigen::VectorXd xs = b.tail(ns_);
  if (ns_ > 0) {
    xs -= g0 + g1;
    const int one = 1;
    int info = 0;
    dpotrs_("L", &ns_, &one, s_.data(), &ns_, xs.data(), &ns_, &info);
    x.tail(ns_) = xs;
  }
  tbb::parallel_invoke([&] { half_[0]->backward(xs, x.data() + half_[0]->off); },
                       [&] { half_[1]->backward(xs, x.data() + half_[1]->off); });
}

double SplitCholesky::flops() const {
  double f = static_cast<double>(ns_) * ns_ * ns_ / 3.0 + 2.0 * static_cast<double>(ns_) * ns_ * ns_;
  for (const auto& h : half_)
    if (h) f += h->common.fl;
  return f;
}

double SplitCholesky::nonzeros() const {
  double z = 0.5 * static_cast<double>(ns_) * (ns_ + 1);
  for (const auto& h : half_)
    if (h) z += h->common.lnz;
  return z;
}

}  // namespace strictmin::socp
