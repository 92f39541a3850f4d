#include "solvers/socp/split_cholesky.h"

#include <cholmod.h>
#include <algorithm>
#include <tbb/parallel_invoke.h>

#include "solvers/socp/supernodal_cholesky.h"

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
  // Solve workspace (one solve at a time per half).
  mutable Eigen::VectorXd work, y;

  bool analyze() {
    if (!cholesky.analyze(B)) return false;
    const std::vector<int>& perm = cholesky.permutation();
    for (int k = n; k < n + ns; ++k)
      if (perm[k] != k) return false;
    T.setZero(ns, ns);
    G.setZero(ns, ns);
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

  // R right-hand sides (1 or 2), interleaved in the work vector (row k of column c at R k + c)
  // so that one pass over the factor serves all of them. b[c] and x[c] point at this half's
  // part of column c.
  // Forward: work = [b_part; 0] (the factor's order), y = L^-1 work; g = C y_part = -T y_sep.
  void forward(const double* const* b, int R, Eigen::MatrixXd& g) const {
    const std::vector<int>& perm = cholesky.permutation();
    work.resize(static_cast<Eigen::Index>(R) * (n + ns));
    for (int k = 0; k < n; ++k)
      for (int c = 0; c < R; ++c) work[R * k + c] = b[c][perm[k]];
    work.tail(R * ns).setZero();
    R == 1 ? cholesky.forward_in_place(work.data()) : cholesky.forward2_in_place(work.data());
    y = work;
    g.resize(ns, R);
    for (int k = 0; k < ns; ++k)
      for (int c = 0; c < R; ++c) g(k, c) = y[R * (n + k) + c];
    const int one = 1;
    for (int c = 0; c < R; ++c) dtrmv_("L", "N", "N", &ns, T.data(), &ns, g.col(c).data(), &one);
    g = -g;
  }
  // Backward: [x_part; v] = L^-T [y_part; T^T x_sep] (then v = x_sep).
  void backward(const Eigen::MatrixXd& x_sep, int R, double* const* x) const {
    work.head(R * n) = y.head(R * n);
    Eigen::MatrixXd t = x_sep;
    const int one = 1;
    for (int c = 0; c < R && ns > 0; ++c) dtrmv_("L", "T", "N", &ns, T.data(), &ns, t.col(c).data(), &one);
    for (int k = 0; k < ns; ++k)
      for (int c = 0; c < R; ++c) work[R * (n + k) + c] = t(k, c);
    R == 1 ? cholesky.backward_in_place(work.data()) : cholesky.backward2_in_place(work.data());
    const std::vector<int>& perm = cholesky.permutation();
    for (int k = 0; k < n; ++k)
      for (int c = 0; c < R; ++c) x[c][perm[k]] = work[R * k + c];
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
  const double* bs[1] = {b.data()};
  double* xs[1] = {x.data()};
  solve_columns(bs, xs, 1);
}

void SplitCholesky::solve2(const Eigen::VectorXd& b0, const Eigen::VectorXd& b1, Eigen::VectorXd& x0,
                           Eigen::VectorXd& x1) const {
  x0.resize(n_);
  x1.resize(n_);
  const double* bs[2] = {b0.data(), b1.data()};
  double* xs[2] = {x0.data(), x1.data()};
  solve_columns(bs, xs, 2);
}

void SplitCholesky::solve_columns(const double* const* b, double* const* x, int R) const {
  const int sep = n_ - ns_;
  Eigen::MatrixXd g[2];
  auto forward = [&](int p) {
    const double* part[2];
    for (int c = 0; c < R; ++c) part[c] = b[c] + half_[p]->off;
    half_[p]->forward(part, R, g[p]);
  };
  tbb::parallel_invoke([&] { forward(0); }, [&] { forward(1); });
  Eigen::MatrixXd xs(ns_, R);
  if (ns_ > 0) {
    for (int c = 0; c < R; ++c) xs.col(c) = Eigen::Map<const Eigen::VectorXd>(b[c] + sep, ns_) - g[0].col(c) - g[1].col(c);
    int info = 0;
    dpotrs_("L", &ns_, &R, s_.data(), &ns_, xs.data(), &ns_, &info);
    for (int c = 0; c < R; ++c) Eigen::Map<Eigen::VectorXd>(x[c] + sep, ns_) = xs.col(c);
  }
  auto backward = [&](int p) {
    double* part[2];
    for (int c = 0; c < R; ++c) part[c] = x[c] + half_[p]->off;
    half_[p]->backward(xs, R, part);
  };
  tbb::parallel_invoke([&] { backward(0); }, [&] { backward(1); });
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
