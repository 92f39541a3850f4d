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

// The complex kernels of socp::factor_left_looking (solvers/socp/supernodal_layout.h).
struct HermitianKernels {
  static constexpr long kBlasUpdateFlops = strictmin::kBlasUpdateFlops;
  void update_wide(const Complex* ld, int ndrow, int m1, int m2, int ndcol, Complex* buffer) const {
    const Complex one(1.0, 0.0), zero(0.0, 0.0);
    zgemm_("N", "C", &m2, &m1, &ndcol, &one, ld, &ndrow, ld, &ndrow, &zero, buffer, &m2);
  }
  void update_column(const Complex* ld, int ndrow, int ndcol, int len, Complex* out) const {
    strictmin::update_column(reinterpret_cast<const double*>(ld), ndrow, ndcol, len, reinterpret_cast<double*>(out));
  }
  bool factor_panel(Complex* a, int rows, int cols) const {
    return cols >= kBlasPanelWidth ? factor_panel_blas(a, rows, cols, rows)
                                   : factor_panel_small(reinterpret_cast<double*>(a), rows, cols, rows);
  }
};

}  // namespace

bool HermitianFactor::setup(cholmod_factor* L, cholmod_common* common, const HermitianEntries& entries) {
  if (!L || !L->is_super || L->itype != CHOLMOD_INT || entries.row.size() != entries.conjugate.size()) return false;
  if (L->xtype == CHOLMOD_PATTERN) cholmod_change_factor(CHOLMOD_COMPLEX, 1, 1, 1, 1, L, common);
  if (!L->x || L->xtype != CHOLMOD_COMPLEX || !L->is_ll) return false;
  if (!entries_.locate(*L, entries.row, entries.col)) return false;
  L_ = L;
  conjugate_.resize(entries_.source.size());
  for (size_t q = 0; q < entries_.source.size(); ++q) conjugate_[q] = entries.conjugate[entries_.source[q]];
  workspace_.reserve(*L);
  update_.assign(workspace_.relative.size(), Complex(0, 0));
  return true;
}

bool HermitianFactor::factorize(const Complex* value) {
  Complex* lx = static_cast<Complex*>(L_->x);
  std::fill(lx, lx + L_->xsize, Complex(0, 0));
  for (size_t q = 0; q < entries_.target.size(); ++q) {
    const Complex v = value[entries_.source[q]];
    lx[entries_.target[q]] += conjugate_[q] ? std::conj(v) : v;
  }
  return socp::factor_left_looking(L_, entries_.super_of_column, workspace_, buffer_, update_, HermitianKernels{});
}

}  // namespace strictmin
