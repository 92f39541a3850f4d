#pragma once
// Internal: a dense m by m solve (m <= N, N small) by Gaussian elimination with partial
// pivoting, for the 1-ring solver's Newton polish (one_ring.cpp). The operations and their
// order are those of Eigen's PartialPivLU on a matrix of at most N by N (the pivot: the
// first row of largest |a_ik|; an exactly zero pivot column is left undivided; the unit
// lower and upper triangular solves column by column, zero entries skipped), so the result is bitwise the same
// (tests/test_small_lu.cpp), without the dynamic-size machinery.
#include <cmath>
#include <utility>

namespace strictmin {

// Overwrites b (the first m entries) with A^-1 b; A (the leading m by m block) is destroyed.
// A singular A gives what Eigen's gives (non-finite entries, or finite ones where the
// right-hand side has zeros).
template <int N>
[[gnu::always_inline]] inline void small_lu_solve(double (&A)[N][N], double (&b)[N], int m) {
  for (int k = 0; k < m; ++k) {
    int pivot = k;
    double biggest = std::abs(A[k][k]);
    for (int i = k + 1; i < m; ++i)
      if (std::abs(A[i][k]) > biggest) {
        biggest = std::abs(A[i][k]);
        pivot = i;
      }
    if (biggest != 0) {
      if (pivot != k) {
        for (int j = 0; j < m; ++j) std::swap(A[k][j], A[pivot][j]);
        std::swap(b[k], b[pivot]);  // P b, transposition by transposition
      }
      for (int i = k + 1; i < m; ++i) A[i][k] /= A[k][k];
    }
    for (int i = k + 1; i < m; ++i)
      for (int j = k + 1; j < m; ++j) A[i][j] -= A[i][k] * A[k][j];
  }
  // L y = P b (L unit lower), then U x = y; as Eigen's, an entry that is exactly zero is
  // neither divided nor carried into the others (0 / 0 stays 0).
  for (int k = 0; k < m; ++k)
    if (b[k] != 0)
      for (int i = k + 1; i < m; ++i) b[i] -= b[k] * A[i][k];
  for (int k = m - 1; k >= 0; --k)
    if (b[k] != 0) {
      b[k] /= A[k][k];
      for (int i = 0; i < k; ++i) b[i] -= b[k] * A[i][k];
    }
}

}  // namespace strictmin
