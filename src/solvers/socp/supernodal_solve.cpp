#include "strictmin/solvers/socp/supernodal_solve.h"

namespace strictmin::socp {

bool supports_supernodal_solve(const cholmod_factor& L) {
  return L.is_super && L.is_ll && L.xtype == CHOLMOD_REAL && L.dtype == CHOLMOD_DOUBLE && L.itype == CHOLMOD_INT;
}

void supernodal_forward(const cholmod_factor& L, double* x) {
  const int* super = static_cast<const int*>(L.super);
  const int* pi = static_cast<const int*>(L.pi);
  const int* px = static_cast<const int*>(L.px);
  const int* s = static_cast<const int*>(L.s);
  const double* lx = static_cast<const double*>(L.x);
  const long nsuper = static_cast<long>(L.nsuper);
  for (long k = 0; k < nsuper; ++k) {
    const int k1 = super[k], nscol = super[k + 1] - k1;
    const int nsrow = pi[k + 1] - pi[k];
    const int* rows = s + pi[k];
    const double* block = lx + px[k];
    // Column by column: solve for x[k1 + j], then update every row below it.
    for (int j = 0; j < nscol; ++j) {
      const double* column = block + static_cast<long>(j) * nsrow;
      const double xj = x[k1 + j] / column[j];
      x[k1 + j] = xj;
      for (int i = j + 1; i < nscol; ++i) x[k1 + i] -= column[i] * xj;
      for (int i = nscol; i < nsrow; ++i) x[rows[i]] -= column[i] * xj;
    }
  }
}

void supernodal_backward(const cholmod_factor& L, double* x) {
  const int* super = static_cast<const int*>(L.super);
  const int* pi = static_cast<const int*>(L.pi);
  const int* px = static_cast<const int*>(L.px);
  const int* s = static_cast<const int*>(L.s);
  const double* lx = static_cast<const double*>(L.x);
  for (long k = static_cast<long>(L.nsuper) - 1; k >= 0; --k) {
    const int k1 = super[k], nscol = super[k + 1] - k1;
    const int nsrow = pi[k + 1] - pi[k];
    const int* rows = s + pi[k];
    const double* block = lx + px[k];
    // Row j of L^T is column j of L: x_j = (x_j - sum_{i > j} L_ij x_i) / L_jj, the x_i
    // below the supernode already final (later supernodes), those inside it for i > j.
    for (int j = nscol - 1; j >= 0; --j) {
      const double* column = block + static_cast<long>(j) * nsrow;
      // Four partial sums: one would chain every multiply-add on the previous one.
      double t0 = 0, t1 = 0, t2 = 0, t3 = 0;
      int i = nscol;
      for (; i + 3 < nsrow; i += 4) {
        t0 += column[i] * x[rows[i]];
        t1 += column[i + 1] * x[rows[i + 1]];
        t2 += column[i + 2] * x[rows[i + 2]];
        t3 += column[i + 3] * x[rows[i + 3]];
      }
      for (; i < nsrow; ++i) t0 += column[i] * x[rows[i]];
      for (i = j + 1; i < nscol; ++i) t1 += column[i] * x[k1 + i];
      x[k1 + j] = (x[k1 + j] - ((t0 + t1) + (t2 + t3))) / column[j];
    }
  }
}

}  // namespace strictmin::socp
