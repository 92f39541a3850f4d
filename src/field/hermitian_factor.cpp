#include "field/hermitian_factor.h"

#include <algorithm>
#include <cmath>

#include "solvers/socp/vector_clones.h"

extern "C" {
void zgemm_(const char* transa, const char* transb, const int* m, const int* n, const int* k, const void* alpha,
            const void* a, const int* lda, const void* b, const int* ldb, const void* beta, void* c, const int* ldc);
void zpotrf_(const char* uplo, const int* n, void* a, const int* lda, int* info);
void ztrsm_(const char* side, const char* uplo, const char* transa, const char* diag, const int* m, const int* n,
            const void* alpha, const void* a, const int* lda, void* b, const int* ldb);
}

namespace strictmin {
namespace {

using Complex = std::complex<double>;

// Below these sizes the loops beat a BLAS call (as in supernodal_factor.cpp).
constexpr long kBlasUpdateFlops = 4096;  // m1 * m2 * width of an update
constexpr int kBlasPanelWidth = 24;       // width of a supernode's own factorization

// In place, column-major with leading dimension ld, complex as (re, im) pairs: the rows x
// cols panel [A11; A21] of a supernode becomes [L11; L21] with A11 = L11 L11^H,
// L21 = A21 L11^-H (left-looking by column). False on a pivot that is not positive.
bool factor_panel_small(double* a, int rows, int cols, int ld) {
  for (int c = 0; c < cols; ++c) {
    double* col = a + 2L * c * ld;
    for (int q = 0; q < c; ++q) {
      const double* prev = a + 2L * q * ld;
      const double fr = prev[2 * c], fi = -prev[2 * c + 1];  // conj(L_cq)
      if (fr == 0.0 && fi == 0.0) continue;
      for (int r = c; r < rows; ++r) {  // col_r -= L_rq conj(L_cq)
        col[2 * r] -= prev[2 * r] * fr - prev[2 * r + 1] * fi;
        col[2 * r + 1] -= prev[2 * r] * fi + prev[2 * r + 1] * fr;
      }
    }
    const double d = col[2 * c];
    if (!(d > 0.0) || !std::isfinite(d)) return false;
    const double root = std::sqrt(d), inv = 1.0 / root;
    col[2 * c] = root;
    col[2 * c + 1] = 0.0;
    for (int r = c + 1; r < rows; ++r) {
      col[2 * r] *= inv;
      col[2 * r + 1] *= inv;
    }
  }
  return true;
}

bool factor_panel_blas(Complex* a, int rows, int cols, int ld) {
  int info = 0;
  zpotrf_("L", &cols, a, &ld, &info);
  if (info != 0) return false;
  for (int c = 0; c < cols; ++c)
    if (!std::isfinite(a[static_cast<long>(c) * ld + c].real())) return false;
  const int below = rows - cols;
  if (below > 0) {
    const Complex one(1.0, 0.0);
    ztrsm_("R", "L", "C", "N", &below, &cols, &one, a, &ld, a + cols, &ld);
  }
  return true;
}

// out[i] = sum_c a[c * ld + i] * conj(a[c * ld]), i < len: one column of a narrow update
// L_d L_d^H (pairs (re, im), ld in complex entries).
STRICTMIN_VECTOR_CLONES
void update_column(const double* a, int ld, int width, int len, double* out) {
  for (int i = 0; i < 2 * len; ++i) out[i] = 0.0;
  for (int c = 0; c < width; ++c) {
    const double* col = a + 2L * c * ld;
    const double wr = col[0], wi = -col[1];
    for (int i = 0; i < len; ++i) {
      out[2 * i] += col[2 * i] * wr - col[2 * i + 1] * wi;
      out[2 * i + 1] += col[2 * i] * wi + col[2 * i + 1] * wr;
    }
  }
}

}  // namespace

bool HermitianFactor::setup(cholmod_factor* L, cholmod_common* common, const HermitianEntries& entries) {
  const std::vector<int>&row = entries.row, &col = entries.col;
  const std::vector<char>& conjugate = entries.conjugate;
  if (!L || !L->is_super || L->itype != CHOLMOD_INT || row.size() != col.size() || row.size() != conjugate.size())
    return false;
  if (L->xtype == CHOLMOD_PATTERN) cholmod_change_factor(CHOLMOD_COMPLEX, 1, 1, 1, 1, L, common);
  if (!L->x || L->xtype != CHOLMOD_COMPLEX || !L->is_ll) return false;
  L_ = L;
  n_ = static_cast<int>(L->n);
  nsuper_ = static_cast<int>(L->nsuper);
  const int* super = static_cast<const int*>(L->super);
  const int* pi = static_cast<const int*>(L->pi);
  const int* px = static_cast<const int*>(L->px);
  const int* ls = static_cast<const int*>(L->s);
  super_of_column_.assign(n_, 0);
  for (int s = 0; s < nsuper_; ++s)
    for (int j = super[s]; j < super[s + 1]; ++j) super_of_column_[j] = s;
  // Entries bucketed by supernode, then located through the supernode's row map.
  std::vector<int> start(nsuper_ + 1, 0);
  source_.clear();
  for (size_t e = 0; e < row.size(); ++e) {
    if (col[e] < 0 || col[e] >= n_ || row[e] < col[e] || row[e] >= n_) return false;
    ++start[super_of_column_[col[e]] + 1];
    source_.push_back(static_cast<int>(e));
  }
  for (int s = 0; s < nsuper_; ++s) start[s + 1] += start[s];
  std::vector<int> order(source_.size());
  {
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (int e : source_) order[fill[super_of_column_[col[e]]]++] = e;
  }
  std::vector<long> target_of(row.size(), -1);
  map_.assign(n_, -1);
  for (int s = 0; s < nsuper_; ++s) {
    const int nsrow = pi[s + 1] - pi[s];
    for (int k = 0; k < nsrow; ++k) map_[ls[pi[s] + k]] = k;
    for (int q = start[s]; q < start[s + 1]; ++q) {
      const int e = order[q];
      const int k = map_[row[e]];
      if (k < 0 || ls[pi[s] + k] != row[e]) return false;  // outside the pattern
      target_of[e] = px[s] + static_cast<long>(col[e] - super[s]) * nsrow + k;
    }
    for (int k = 0; k < nsrow; ++k) map_[ls[pi[s] + k]] = -1;
  }
  target_.resize(source_.size());
  conjugate_.resize(source_.size());
  for (size_t q = 0; q < source_.size(); ++q) {
    target_[q] = target_of[source_[q]];
    conjugate_[q] = conjugate[source_[q]];
  }
  head_.assign(nsuper_, -1);
  next_.assign(nsuper_, -1);
  position_.assign(nsuper_, 0);
  int widest_rows = 0;
  for (int s = 0; s < nsuper_; ++s) widest_rows = std::max(widest_rows, pi[s + 1] - pi[s]);
  relative_.assign(widest_rows, 0);
  update_.assign(widest_rows, Complex(0, 0));
  return true;
}

bool HermitianFactor::factorize(const Complex* value) {
  cholmod_factor* L = L_;
  const int* super = static_cast<const int*>(L->super);
  const int* pi = static_cast<const int*>(L->pi);
  const int* px = static_cast<const int*>(L->px);
  const int* ls = static_cast<const int*>(L->s);
  Complex* lx = static_cast<Complex*>(L->x);
  std::fill(lx, lx + L->xsize, Complex(0, 0));
  for (size_t q = 0; q < target_.size(); ++q) {
    const Complex v = value[source_[q]];
    lx[target_[q]] += conjugate_[q] ? std::conj(v) : v;
  }
  std::fill(head_.begin(), head_.end(), -1);
  int* rel = relative_.data();
  for (int s = 0; s < nsuper_; ++s) {
    const int k1 = super[s], k2 = super[s + 1], nscol = k2 - k1;
    const int psi = pi[s], nsrow = pi[s + 1] - psi;
    Complex* ax = lx + px[s];
    for (int k = 0; k < nsrow; ++k) map_[ls[psi + k]] = k;
    // Updates from the supernodes whose rows meet columns k1 .. k2-1.
    for (int d = head_[s]; d != -1;) {
      const int dnext = next_[d];
      const int pdi1 = position_[d], pdend = pi[d + 1], ndrow = pdend - pi[d];
      const int ndcol = super[d + 1] - super[d];
      int pdi2 = pdi1;
      while (pdi2 < pdend && ls[pdi2] < k2) ++pdi2;
      const int m1 = pdi2 - pdi1, m2 = pdend - pdi1;
      for (int ii = 0; ii < m2; ++ii) rel[ii] = map_[ls[pdi1 + ii]];
      const Complex* ld = lx + px[d] + (pdi1 - pi[d]);  // column c at ld + c * ndrow
      if (static_cast<long>(m1) * m2 * ndcol >= kBlasUpdateFlops) {
        if (buffer_.size() < static_cast<size_t>(m1) * m2) buffer_.resize(static_cast<size_t>(m1) * m2);
        const Complex one(1.0, 0.0), zero(0.0, 0.0);
        zgemm_("N", "C", &m2, &m1, &ndcol, &one, ld, &ndrow, ld, &ndrow, &zero, buffer_.data(), &m2);
        for (int jj = 0; jj < m1; ++jj) {
          Complex* target = ax + static_cast<long>(ls[pdi1 + jj] - k1) * nsrow;
          const Complex* c = buffer_.data() + static_cast<long>(jj) * m2;
          for (int ii = jj; ii < m2; ++ii) target[rel[ii]] -= c[ii];
        }
      } else {
        // Column jj of the update, ld * ld[jj, :]^H, accumulated column by column of d
        // (contiguous), then scattered.
        Complex* column = update_.data();
        for (int jj = 0; jj < m1; ++jj) {
          Complex* target = ax + static_cast<long>(ls[pdi1 + jj] - k1) * nsrow;
          const int len = m2 - jj;
          update_column(reinterpret_cast<const double*>(ld + jj), ndrow, ndcol, len, reinterpret_cast<double*>(column));
          for (int ii = 0; ii < len; ++ii) target[rel[jj + ii]] -= column[ii];
        }
      }
      if (pdi2 < pdend) {  // d's next target
        const int t = super_of_column_[ls[pdi2]];
        position_[d] = pdi2;
        next_[d] = head_[t];
        head_[t] = d;
      }
      d = dnext;
    }
    for (int k = 0; k < nsrow; ++k) map_[ls[psi + k]] = -1;
    const bool ok = nscol >= kBlasPanelWidth ? factor_panel_blas(ax, nsrow, nscol, nsrow)
                                             : factor_panel_small(reinterpret_cast<double*>(ax), nsrow, nscol, nsrow);
    if (!ok) {
      L->minor = static_cast<size_t>(k1);
      return false;
    }
    if (nsrow > nscol) {
      const int t = super_of_column_[ls[psi + nscol]];
      position_[s] = psi + nscol;
      next_[s] = head_[t];
      head_[t] = s;
    }
  }
  L->minor = static_cast<size_t>(n_);
  return true;
}

}  // namespace strictmin
