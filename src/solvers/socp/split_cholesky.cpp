#include "strictmin/solvers/socp/split_cholesky.h"

#include <cholmod.h>
#include <algorithm>
#include <tbb/parallel_invoke.h>

#include "strictmin/solvers/socp/supernodal_cholesky.h"

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
  SupernodalCholesky cholesky;        // of B; its postorder keeps the separator last
  Eigen::MatrixXd T, G;               // trailing factor block Tp and Tp Tp^T (lower)
  // Solve workspace (one solve at a time per half); rhs2, y2: two right-hand sides interleaved.
  mutable Eigen::VectorXd rhs, y, rhs2, y2;

  bool analyze() {
    if (!cholesky.analyze(B)) return false;
    const std::vector<int>& perm = cholesky.permutation();
    for (int k = n; k < n + ns; ++k)
      if (perm[k] != k) return false;
    T.setZero(ns, ns);
    G.setZero(ns, ns);
    rhs.resize(n + ns);
    rhs2.resize(2 * (n + ns));
    return true;
  }

  bool factorize(const double* values) {
    double* bx = B.valuePtr();
    for (size_t k = 0; k < source.size(); ++k) bx[k] = values[source[k]];
    if (!cholesky.factorize(bx)) return false;
    // The separator's columns: the trailing block of the supernodes that hold them.
    const cholmod_factor& L = cholesky.factor();
    const int* super = static_cast<const int*>(L.super);
    const int* pi = static_cast<const int*>(L.pi);
    const int* px = static_cast<const int*>(L.px);
    const int* s = static_cast<const int*>(L.s);
    const double* x = static_cast<const double*>(L.x);
    for (long k = static_cast<long>(L.nsuper) - 1; k >= 0 && super[k + 1] > n; --k) {
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

  // Forward: rhs = [b_part; 0] (the factor's order), y = L^-1 rhs; g = C y_part = -T y_sep.
  void forward(const double* b_part, Eigen::VectorXd& g) const {
    const std::vector<int>& perm = cholesky.permutation();
    for (int k = 0; k < n; ++k) rhs[k] = b_part[perm[k]];
    rhs.tail(ns).setZero();
    cholesky.forward_in_place(rhs.data());
    y = rhs;
    g = y.tail(ns);
    const int one = 1;
    dtrmv_("L", "N", "N", &ns, T.data(), &ns, g.data(), &one);
    g = -g;
  }
  // forward for two right-hand sides at once.
  void forward2(const double* b0, const double* b1, Eigen::VectorXd& g0, Eigen::VectorXd& g1) const {
    const std::vector<int>& perm = cholesky.permutation();
    for (int k = 0; k < n; ++k) {
      rhs2[2 * k] = b0[perm[k]];
      rhs2[2 * k + 1] = b1[perm[k]];
    }
    rhs2.tail(2 * ns).setZero();
    cholesky.forward2_in_place(rhs2.data());
    y2 = rhs2;
    g0.resize(ns);
    g1.resize(ns);
    for (int k = 0; k < ns; ++k) {
      g0[k] = y2[2 * (n + k)];
      g1[k] = y2[2 * (n + k) + 1];
    }
    const int one = 1;
    dtrmv_("L", "N", "N", &ns, T.data(), &ns, g0.data(), &one);
    dtrmv_("L", "N", "N", &ns, T.data(), &ns, g1.data(), &one);
    g0 = -g0;
    g1 = -g1;
  }
  // backward for two right-hand sides at once.
  void backward2(const Eigen::VectorXd& xs0, const Eigen::VectorXd& xs1, double* x0, double* x1) const {
    rhs2.head(2 * n) = y2.head(2 * n);
    Eigen::VectorXd t0 = xs0, t1 = xs1;
    if (ns > 0) {
      const int one = 1;
      dtrmv_("L", "T", "N", &ns, T.data(), &ns, t0.data(), &one);
      dtrmv_("L", "T", "N", &ns, T.data(), &ns, t1.data(), &one);
    }
    for (int k = 0; k < ns; ++k) {
      rhs2[2 * (n + k)] = t0[k];
      rhs2[2 * (n + k) + 1] = t1[k];
    }
    cholesky.backward2_in_place(rhs2.data());
    const std::vector<int>& perm = cholesky.permutation();
    for (int k = 0; k < n; ++k) {
      x0[perm[k]] = rhs2[2 * k];
      x1[perm[k]] = rhs2[2 * k + 1];
    }
  }
  // Backward: [x_part; v] = L^-T [y_part; T^T x_sep] (then v = x_sep).
  void backward(const Eigen::VectorXd& x_sep, double* x_part) const {
    rhs.head(n) = y.head(n);
    rhs.tail(ns) = x_sep;
    if (ns > 0) {
      const int one = 1;
      dtrmv_("L", "T", "N", &ns, T.data(), &ns, rhs.data() + n, &one);
    }
    cholesky.backward_in_place(rhs.data());
    const std::vector<int>& perm = cholesky.permutation();
    for (int k = 0; k < n; ++k) x_part[perm[k]] = rhs[k];
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

void SplitCholesky::solve2(const Eigen::VectorXd& b0, const Eigen::VectorXd& b1, Eigen::VectorXd& x0,
                           Eigen::VectorXd& x1) const {
  x0.resize(n_);
  x1.resize(n_);
  Eigen::VectorXd g[2][2];
  tbb::parallel_invoke(
      [&] { half_[0]->forward2(b0.data() + half_[0]->off, b1.data() + half_[0]->off, g[0][0], g[0][1]); },
      [&] { half_[1]->forward2(b0.data() + half_[1]->off, b1.data() + half_[1]->off, g[1][0], g[1][1]); });
  Eigen::MatrixXd xs(ns_, 2);
  if (ns_ > 0) {
    xs.col(0) = b0.tail(ns_) - g[0][0] - g[1][0];
    xs.col(1) = b1.tail(ns_) - g[0][1] - g[1][1];
    const int two = 2;
    int info = 0;
    dpotrs_("L", &ns_, &two, s_.data(), &ns_, xs.data(), &ns_, &info);
    x0.tail(ns_) = xs.col(0);
    x1.tail(ns_) = xs.col(1);
  }
  const Eigen::VectorXd xs0 = xs.col(0), xs1 = xs.col(1);
  tbb::parallel_invoke(
      [&] { half_[0]->backward2(xs0, xs1, x0.data() + half_[0]->off, x1.data() + half_[0]->off); },
      [&] { half_[1]->backward2(xs0, xs1, x0.data() + half_[1]->off, x1.data() + half_[1]->off); });
}

double SplitCholesky::flops() const {
  double f = static_cast<double>(ns_) * ns_ * ns_ / 3.0 + 2.0 * static_cast<double>(ns_) * ns_ * ns_;
  for (const auto& h : half_)
    if (h) f += h->cholesky.flops();
  return f;
}

double SplitCholesky::nonzeros() const {
  double z = 0.5 * static_cast<double>(ns_) * (ns_ + 1);
  for (const auto& h : half_)
    if (h) z += h->cholesky.nonzeros();
  return z;
}

}  // namespace strictmin::socp
