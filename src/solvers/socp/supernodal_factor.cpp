#include "solvers/socp/supernodal_factor.h"

#include <algorithm>
#include <cmath>

#include "solvers/socp/vector_clones.h"

extern "C" {
void dgemm_(const char* transa, const char* transb, const int* m, const int* n, const int* k, const double* alpha,
            const double* a, const int* lda, const double* b, const int* ldb, const double* beta, double* c,
            const int* ldc);
void dpotrf_(const char* uplo, const int* n, double* a, const int* lda, int* info);
void dtrsm_(const char* side, const char* uplo, const char* transa, const char* diag, const int* m, const int* n,
            const double* alpha, const double* a, const int* lda, double* b, const int* ldb);
}

namespace strictmin::socp {
namespace {

// Below these sizes the loops beat a BLAS call (call overhead, lock and buffer per call).
constexpr long kBlasUpdateFlops = 4096;  // m1 * m2 * width of an update
constexpr int kBlasPanelWidth = 24;       // width of a supernode's own factorisation

// In place, column-major with leading dimension ld: the rows x cols panel [A11; A21] of a
// supernode becomes [L11; L21] with A11 = L11 L11^T, L21 = A21 L11^-T (left-looking by
// column). False on a pivot that is not positive.
bool factor_panel_small(double* a, int rows, int cols, int ld) {
  for (int c = 0; c < cols; ++c) {
    double* col = a + static_cast<long>(c) * ld;
    for (int q = 0; q < c; ++q) {
      const double* prev = a + static_cast<long>(q) * ld;
      const double f = prev[c];
      if (f == 0.0) continue;
      for (int r = c; r < rows; ++r) col[r] -= f * prev[r];
    }
    const double d = col[c];
    if (!(d > 0.0) || !std::isfinite(d)) return false;
    const double root = std::sqrt(d), inv = 1.0 / root;
    col[c] = root;
    for (int r = c + 1; r < rows; ++r) col[r] *= inv;
  }
  return true;
}

bool factor_panel_blas(double* a, int rows, int cols, int ld) {
  int info = 0;
  dpotrf_("L", &cols, a, &ld, &info);
  if (info != 0) return false;
  for (int c = 0; c < cols; ++c)
    if (!std::isfinite(a[static_cast<long>(c) * ld + c])) return false;
  const int below = rows - cols;
  if (below > 0) {
    const double one = 1.0;
    dtrsm_("R", "L", "T", "N", &below, &cols, &one, a, &ld, a + cols, &ld);
  }
  return true;
}

// out[i] = sum_c a[c * ld + i] * a[c * ld], i < len: one column of a narrow update.
STRICTMIN_VECTOR_CLONES
void update_column(const double* a, int ld, int width, int len, double* out) {
  {
    const double w = a[0];
    for (int i = 0; i < len; ++i) out[i] = w * a[i];
  }
  for (int c = 1; c < width; ++c) {
    const double* col = a + static_cast<long>(c) * ld;
    const double w = col[0];
    for (int i = 0; i < len; ++i) out[i] += w * col[i];
  }
}

// The real kernels of factor_left_looking (supernodal_layout.h).
struct RealKernels {
  static constexpr long kBlasUpdateFlops = strictmin::socp::kBlasUpdateFlops;
  void update_wide(const double* ld, int ndrow, int m1, int m2, int ndcol, double* buffer) const {
    const double one = 1.0, zero = 0.0;
    dgemm_("N", "T", &m2, &m1, &ndcol, &one, ld, &ndrow, ld, &ndrow, &zero, buffer, &m2);
  }
  void update_column(const double* ld, int ndrow, int ndcol, int len, double* out) const {
    socp::update_column(ld, ndrow, ndcol, len, out);
  }
  bool factor_panel(double* a, int rows, int cols) const {
    return cols >= kBlasPanelWidth ? factor_panel_blas(a, rows, cols, rows) : factor_panel_small(a, rows, cols, rows);
  }
};

}  // namespace

bool SupernodalFactor::setup(cholmod_factor* L, cholmod_common* common, const std::vector<int>& row,
                             const std::vector<int>& col) {
  if (!L || !L->is_super || L->itype != CHOLMOD_INT || row.size() != col.size()) return false;
  if (L->xtype == CHOLMOD_PATTERN) cholmod_change_factor(CHOLMOD_REAL, 1, 1, 1, 1, L, common);
  if (!L->x || L->xtype != CHOLMOD_REAL || !L->is_ll) return false;
  if (!entries_.locate(*L, row, col)) return false;
  L_ = L;
  workspace_.reserve(*L);
  update_.assign(workspace_.relative.size(), 0.0);
  return true;
}

bool SupernodalFactor::factorize(const double* value) {
  double* lx = static_cast<double*>(L_->x);
  std::fill(lx, lx + L_->xsize, 0.0);
  for (size_t q = 0; q < entries_.target.size(); ++q) lx[entries_.target[q]] += value[entries_.source[q]];
  return factor_left_looking(L_, entries_.super_of_column, workspace_, buffer_, update_, RealKernels{});
}

}  // namespace strictmin::socp
