#include "solvers/socp/supernodal_solve.h"

#include <vector>

#include "solvers/socp/supernodal_layout.h"
#include "solvers/socp/vector_clones.h"

namespace strictmin::socp {
namespace {

using FactorView = SupernodalView<1>;  // real entries

// Workspace for the rows below one supernode, kept per thread (the halves of SplitCholesky
// substitute on two threads at once).
double* below_buffer(int size) {
  thread_local std::vector<double> buffer;
  if (static_cast<int>(buffer.size()) < size) buffer.resize(static_cast<size_t>(size) * 2);
  return buffer.data();
}

}  // namespace

bool supports_supernodal_solve(const cholmod_factor& L) {
  return L.is_super && L.is_ll && L.xtype == CHOLMOD_REAL && L.dtype == CHOLMOD_DOUBLE && L.itype == CHOLMOD_INT;
}

STRICTMIN_VECTOR_CLONES
void supernodal_forward(const cholmod_factor& L, double* x) {
  const FactorView view(L);
  for (long k = 0; k < view.count; ++k) {
    const Supernode sn = view[k];
    double* xs = x + sn.first;
    // The dense triangle: x_j = x_j / L_jj, then the columns' rows inside the supernode.
    for (int j = 0; j < sn.cols; ++j) {
      const double* column = sn.val + static_cast<long>(j) * sn.rows;
      const double xj = xs[j] / column[j];
      xs[j] = xj;
      for (int i = j + 1; i < sn.cols; ++i) xs[i] -= column[i] * xj;
    }
    // The rows below: accumulate every column's update in a contiguous buffer (one vector
    // loop per column), then scatter once per row instead of once per column and row.
    const int below = sn.rows - sn.cols;
    if (below == 0) continue;
    double* acc = below_buffer(below);
    {
      const double* column = sn.val + sn.cols;
      const double xj = xs[0];
      for (int i = 0; i < below; ++i) acc[i] = column[i] * xj;
    }
    for (int j = 1; j < sn.cols; ++j) {
      const double* column = sn.val + static_cast<long>(j) * sn.rows + sn.cols;
      const double xj = xs[j];
      for (int i = 0; i < below; ++i) acc[i] += column[i] * xj;
    }
    const int* index = sn.index + sn.cols;
    for (int i = 0; i < below; ++i) x[index[i]] -= acc[i];
  }
}

STRICTMIN_VECTOR_CLONES
void supernodal_backward(const cholmod_factor& L, double* x) {
  const FactorView view(L);
  for (long k = view.count - 1; k >= 0; --k) {
    const Supernode sn = view[k];
    double* xs = x + sn.first;
    // Row j of L^T is column j of L: x_j = (x_j - sum_{i > j} L_ij x_i) / L_jj, the x_i below
    // the supernode already final (later supernodes): gather them once.
    const int below = sn.rows - sn.cols;
    double* xb = below_buffer(below);
    const int* index = sn.index + sn.cols;
    for (int i = 0; i < below; ++i) xb[i] = x[index[i]];
    for (int j = sn.cols - 1; j >= 0; --j) {
      const double* column = sn.val + static_cast<long>(j) * sn.rows;
      const double* rect = column + sn.cols;
      // Four partial sums: one would chain every multiply-add on the previous one (and the
      // compiler may not reassociate a floating-point sum to vectorise it).
      double t0 = 0, t1 = 0, t2 = 0, t3 = 0;
      int i = 0;
      for (; i + 3 < below; i += 4) {
        t0 += rect[i] * xb[i];
        t1 += rect[i + 1] * xb[i + 1];
        t2 += rect[i + 2] * xb[i + 2];
        t3 += rect[i + 3] * xb[i + 3];
      }
      for (; i < below; ++i) t0 += rect[i] * xb[i];
      for (i = j + 1; i < sn.cols; ++i) t1 += column[i] * xs[i];
      xs[j] = (xs[j] - ((t0 + t1) + (t2 + t3))) / column[j];
    }
  }
}

}  // namespace strictmin::socp

namespace strictmin::socp {

STRICTMIN_VECTOR_CLONES
void supernodal_forward2(const cholmod_factor& L, double* x) {
  const FactorView view(L);
  for (long k = 0; k < view.count; ++k) {
    const Supernode sn = view[k];
    double* xs = x + 2 * static_cast<long>(sn.first);
    for (int j = 0; j < sn.cols; ++j) {
      const double* column = sn.val + static_cast<long>(j) * sn.rows;
      const double inv = 1.0 / column[j];
      const double a = xs[2 * j] * inv, b = xs[2 * j + 1] * inv;
      xs[2 * j] = a;
      xs[2 * j + 1] = b;
      for (int i = j + 1; i < sn.cols; ++i) {
        xs[2 * i] -= column[i] * a;
        xs[2 * i + 1] -= column[i] * b;
      }
    }
    const int below = sn.rows - sn.cols;
    if (below == 0) continue;
    double* acc = below_buffer(2 * below);
    for (int i = 0; i < 2 * below; ++i) acc[i] = 0.0;
    for (int j = 0; j < sn.cols; ++j) {
      const double* column = sn.val + static_cast<long>(j) * sn.rows + sn.cols;
      const double a = xs[2 * j], b = xs[2 * j + 1];
      for (int i = 0; i < below; ++i) {
        acc[2 * i] += column[i] * a;
        acc[2 * i + 1] += column[i] * b;
      }
    }
    const int* index = sn.index + sn.cols;
    for (int i = 0; i < below; ++i) {
      x[2 * static_cast<long>(index[i])] -= acc[2 * i];
      x[2 * static_cast<long>(index[i]) + 1] -= acc[2 * i + 1];
    }
  }
}

STRICTMIN_VECTOR_CLONES
void supernodal_backward2(const cholmod_factor& L, double* x) {
  const FactorView view(L);
  for (long k = view.count - 1; k >= 0; --k) {
    const Supernode sn = view[k];
    double* xs = x + 2 * static_cast<long>(sn.first);
    const int below = sn.rows - sn.cols;
    double* xb = below_buffer(2 * below);
    const int* index = sn.index + sn.cols;
    for (int i = 0; i < below; ++i) {
      xb[2 * i] = x[2 * static_cast<long>(index[i])];
      xb[2 * i + 1] = x[2 * static_cast<long>(index[i]) + 1];
    }
    for (int j = sn.cols - 1; j >= 0; --j) {
      const double* column = sn.val + static_cast<long>(j) * sn.rows;
      const double* rect = column + sn.cols;
      double a0 = 0, a1 = 0, b0 = 0, b1 = 0;  // two partial sums per right-hand side
      int i = 0;
      for (; i + 1 < below; i += 2) {
        a0 += rect[i] * xb[2 * i];
        b0 += rect[i] * xb[2 * i + 1];
        a1 += rect[i + 1] * xb[2 * i + 2];
        b1 += rect[i + 1] * xb[2 * i + 3];
      }
      for (; i < below; ++i) {
        a0 += rect[i] * xb[2 * i];
        b0 += rect[i] * xb[2 * i + 1];
      }
      for (i = j + 1; i < sn.cols; ++i) {
        a1 += column[i] * xs[2 * i];
        b1 += column[i] * xs[2 * i + 1];
      }
      xs[2 * j] = (xs[2 * j] - (a0 + a1)) / column[j];
      xs[2 * j + 1] = (xs[2 * j + 1] - (b0 + b1)) / column[j];
    }
  }
}

}  // namespace strictmin::socp
