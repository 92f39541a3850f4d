#include "field/complex_supernodal_solve.h"

#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "solvers/socp/supernodal_layout.h"
#include "solvers/socp/vector_clones.h"

namespace strictmin {
namespace {

// The loops read complex numbers as (re, im) pairs of doubles: std::complex's multiplication
// checks for infinities and NaNs (a library call per product) unless the whole build relaxes that.
using socp::Supernode;
using FactorView = socp::SupernodalView<2>;  // complex entries as (re, im) pairs

// Workspace (complex entries, as pairs) for the rows below one supernode, per thread.
double* below_buffer(int size) {
  thread_local std::vector<double> buffer;
  if (static_cast<int>(buffer.size()) < 2 * size) buffer.resize(static_cast<size_t>(size) * 4);
  return buffer.data();
}

}  // namespace

bool supports_complex_supernodal_solve(const cholmod_factor& L) {
  return L.is_super && L.is_ll && L.xtype == CHOLMOD_COMPLEX && L.dtype == CHOLMOD_DOUBLE &&
         L.itype == CHOLMOD_INT;
}

STRICTMIN_VECTOR_CLONES
void complex_supernodal_forward(const cholmod_factor& L, std::complex<double>* xc) {
  const FactorView view(L);
  double* x = reinterpret_cast<double*>(xc);
  for (long k = 0; k < view.count; ++k) {
    const Supernode sn = view[k];
    double* xs = x + 2L * sn.first;
    // The dense triangle: x_j = x_j / L_jj (real), then the columns' rows inside the supernode.
    for (int j = 0; j < sn.cols; ++j) {
      const double* column = sn.val + 2L * j * sn.rows;
      const double inv = 1.0 / column[2 * j];
      const double a = xs[2 * j] * inv, b = xs[2 * j + 1] * inv;
      xs[2 * j] = a;
      xs[2 * j + 1] = b;
      for (int i = j + 1; i < sn.cols; ++i) {
        xs[2 * i] -= column[2 * i] * a - column[2 * i + 1] * b;
        xs[2 * i + 1] -= column[2 * i] * b + column[2 * i + 1] * a;
      }
    }
    // The rows below: every column's update accumulated in a contiguous buffer, then one
    // scatter per row.
    const int below = sn.rows - sn.cols;
    if (below == 0) continue;
    double* acc = below_buffer(below);
    for (int i = 0; i < 2 * below; ++i) acc[i] = 0.0;
    for (int j = 0; j < sn.cols; ++j) {
      const double* rect = sn.val + 2L * (static_cast<long>(j) * sn.rows + sn.cols);
      const double a = xs[2 * j], b = xs[2 * j + 1];
      for (int i = 0; i < below; ++i) {
        acc[2 * i] += rect[2 * i] * a - rect[2 * i + 1] * b;
        acc[2 * i + 1] += rect[2 * i] * b + rect[2 * i + 1] * a;
      }
    }
    const int* index = sn.index + sn.cols;
    for (int i = 0; i < below; ++i) {
      x[2L * index[i]] -= acc[2 * i];
      x[2L * index[i] + 1] -= acc[2 * i + 1];
    }
  }
}

STRICTMIN_VECTOR_CLONES
void complex_supernodal_backward(const cholmod_factor& L, std::complex<double>* xc) {
  const FactorView view(L);
  double* x = reinterpret_cast<double*>(xc);
  for (long k = view.count - 1; k >= 0; --k) {
    const Supernode sn = view[k];
    double* xs = x + 2L * sn.first;
    // Row j of L^H is column j of L conjugated: x_j = (x_j - sum_{i > j} conj(L_ij) x_i) / L_jj,
    // the x_i below the supernode already final (later supernodes): gathered once.
    const int below = sn.rows - sn.cols;
    double* xb = below_buffer(below);
    const int* index = sn.index + sn.cols;
    for (int i = 0; i < below; ++i) {
      xb[2 * i] = x[2L * index[i]];
      xb[2 * i + 1] = x[2L * index[i] + 1];
    }
    for (int j = sn.cols - 1; j >= 0; --j) {
      const double* column = sn.val + 2L * j * sn.rows;
      const double* rect = column + 2L * sn.cols;
      // Two partial sums per part: one would chain every multiply-add on the previous one.
      double re0 = 0, im0 = 0, re1 = 0, im1 = 0;
      int i = 0;
      for (; i + 1 < below; i += 2) {
        re0 += rect[2 * i] * xb[2 * i] + rect[2 * i + 1] * xb[2 * i + 1];
        im0 += rect[2 * i] * xb[2 * i + 1] - rect[2 * i + 1] * xb[2 * i];
        re1 += rect[2 * i + 2] * xb[2 * i + 2] + rect[2 * i + 3] * xb[2 * i + 3];
        im1 += rect[2 * i + 2] * xb[2 * i + 3] - rect[2 * i + 3] * xb[2 * i + 2];
      }
      for (; i < below; ++i) {
        re0 += rect[2 * i] * xb[2 * i] + rect[2 * i + 1] * xb[2 * i + 1];
        im0 += rect[2 * i] * xb[2 * i + 1] - rect[2 * i + 1] * xb[2 * i];
      }
      for (i = j + 1; i < sn.cols; ++i) {
        re1 += column[2 * i] * xs[2 * i] + column[2 * i + 1] * xs[2 * i + 1];
        im1 += column[2 * i] * xs[2 * i + 1] - column[2 * i + 1] * xs[2 * i];
      }
      const double inv = 1.0 / column[2 * j];
      xs[2 * j] = (xs[2 * j] - (re0 + re1)) * inv;
      xs[2 * j + 1] = (xs[2 * j + 1] - (im0 + im1)) * inv;
    }
  }
}

CompactFactor compact_factor(const cholmod_factor& L) {
  const FactorView view(L);
  CompactFactor c;
  const int n = static_cast<int>(L.n);
  c.start.assign(n + 1, 0);
  c.inverse_diagonal.resize(n);
  c.row.reserve(static_cast<size_t>(L.xsize));  // an upper bound: no reallocation
  c.value.reserve(static_cast<size_t>(L.xsize));
  for (long k = 0; k < view.count; ++k) {
    const Supernode sn = view[k];
    for (int j = 0; j < sn.cols; ++j) {
      const double* column = sn.val + 2L * j * sn.rows;
      c.inverse_diagonal[sn.first + j] = 1.0 / column[2 * j];
      for (int i = j + 1; i < sn.rows; ++i)
        if (column[2 * i] != 0 || column[2 * i + 1] != 0) {
          c.row.push_back(sn.index[i]);
          c.value.emplace_back(column[2 * i], column[2 * i + 1]);
        }
      c.start[sn.first + j + 1] = static_cast<int>(c.row.size());
    }
  }
  return c;
}

#if defined(__SSE2__)
// One complex number per 128-bit register (re, im): a multiply-add is two products and a
// shuffle instead of four scalar products and their bookkeeping.
STRICTMIN_VECTOR_CLONES
void compact_solve(const CompactFactor& L, std::complex<double>* xc) {
  double* x = reinterpret_cast<double*>(xc);
  const double* v = reinterpret_cast<const double*>(L.value.data());
  const int* row = L.row.data();
  const int n = static_cast<int>(L.inverse_diagonal.size());
  // Forward: x_j /= L_jj, then x_i -= L_ij x_j below it.
  for (int j = 0; j < n; ++j) {
    const __m128d xj = _mm_mul_pd(_mm_loadu_pd(x + 2 * j), _mm_set1_pd(L.inverse_diagonal[j]));
    _mm_storeu_pd(x + 2 * j, xj);
    const __m128d re = _mm_unpacklo_pd(xj, xj);                                  // (a, a)
    const __m128d im = _mm_mul_pd(_mm_unpackhi_pd(xj, xj), _mm_set_pd(1.0, -1.0));  // (-b, b)
    for (int k = L.start[j]; k < L.start[j + 1]; ++k) {
      const __m128d l = _mm_loadu_pd(v + 2 * k);  // (p, q): L_ij x_j = (pa - qb, pb + qa)
      const __m128d prod = _mm_add_pd(_mm_mul_pd(l, re), _mm_mul_pd(_mm_shuffle_pd(l, l, 1), im));
      double* xr = x + 2L * row[k];
      _mm_storeu_pd(xr, _mm_sub_pd(_mm_loadu_pd(xr), prod));
    }
  }
  // Backward: x_j = (x_j - sum_i conj(L_ij) x_i) / L_jj; conj(p + iq)(c + id) = (pc + qd, pd - qc).
  for (int j = n - 1; j >= 0; --j) {
    __m128d by_p = _mm_setzero_pd(), by_q = _mm_setzero_pd();  // sum p (c, d), sum q (d, c)
    for (int k = L.start[j]; k < L.start[j + 1]; ++k) {
      const __m128d l = _mm_loadu_pd(v + 2 * k), xi = _mm_loadu_pd(x + 2L * row[k]);
      by_p = _mm_add_pd(by_p, _mm_mul_pd(_mm_unpacklo_pd(l, l), xi));
      by_q = _mm_add_pd(by_q, _mm_mul_pd(_mm_unpackhi_pd(l, l), _mm_shuffle_pd(xi, xi, 1)));
    }
    const __m128d sum = _mm_add_pd(by_p, _mm_mul_pd(by_q, _mm_set_pd(-1.0, 1.0)));
    const __m128d xj = _mm_sub_pd(_mm_loadu_pd(x + 2 * j), sum);
    _mm_storeu_pd(x + 2 * j, _mm_mul_pd(xj, _mm_set1_pd(L.inverse_diagonal[j])));
  }
}
#else
STRICTMIN_VECTOR_CLONES
void compact_solve(const CompactFactor& L, std::complex<double>* xc) {
  double* x = reinterpret_cast<double*>(xc);
  const double* v = reinterpret_cast<const double*>(L.value.data());
  const int* row = L.row.data();
  const int n = static_cast<int>(L.inverse_diagonal.size());
  for (int j = 0; j < n; ++j) {
    const double d = L.inverse_diagonal[j];
    const double a = x[2 * j] * d, b = x[2 * j + 1] * d;
    x[2 * j] = a;
    x[2 * j + 1] = b;
    for (int k = L.start[j]; k < L.start[j + 1]; ++k) {
      const long r = row[k];
      x[2 * r] -= v[2 * k] * a - v[2 * k + 1] * b;
      x[2 * r + 1] -= v[2 * k] * b + v[2 * k + 1] * a;
    }
  }
  for (int j = n - 1; j >= 0; --j) {
    double re = 0, im = 0;
    for (int k = L.start[j]; k < L.start[j + 1]; ++k) {
      const long r = row[k];
      re += v[2 * k] * x[2 * r] + v[2 * k + 1] * x[2 * r + 1];
      im += v[2 * k] * x[2 * r + 1] - v[2 * k + 1] * x[2 * r];
    }
    const double d = L.inverse_diagonal[j];
    x[2 * j] = (x[2 * j] - re) * d;
    x[2 * j + 1] = (x[2 * j + 1] - im) * d;
  }
}
#endif

STRICTMIN_VECTOR_CLONES
void compact_solve_many(const CompactFactor& L, std::complex<double>* xc, int k) {
  double* x = reinterpret_cast<double*>(xc);
  const double* v = reinterpret_cast<const double*>(L.value.data());
  const int* row = L.row.data();
  const int n = static_cast<int>(L.inverse_diagonal.size());
  const long w = 2L * k;  // doubles per row of x
  // Forward: x_j /= L_jj, then x_i -= L_ij x_j below it, for every right-hand side.
  for (int j = 0; j < n; ++j) {
    double* xj = x + w * j;
    const double d = L.inverse_diagonal[j];
    for (long r = 0; r < w; ++r) xj[r] *= d;
    for (int e = L.start[j]; e < L.start[j + 1]; ++e) {
      const double p = v[2 * e], q = v[2 * e + 1];
      double* xi = x + w * row[e];
      for (int r = 0; r < k; ++r) {
        const double a = xj[2 * r], b = xj[2 * r + 1];
        xi[2 * r] -= p * a - q * b;
        xi[2 * r + 1] -= p * b + q * a;
      }
    }
  }
  // Backward: x_j = (x_j - sum_i conj(L_ij) x_i) / L_jj.
  for (int j = n - 1; j >= 0; --j) {
    double* xj = x + w * j;
    for (int e = L.start[j]; e < L.start[j + 1]; ++e) {
      const double p = v[2 * e], q = v[2 * e + 1];
      const double* xi = x + w * row[e];
      for (int r = 0; r < k; ++r) {
        xj[2 * r] -= p * xi[2 * r] + q * xi[2 * r + 1];
        xj[2 * r + 1] -= p * xi[2 * r + 1] - q * xi[2 * r];
      }
    }
    const double d = L.inverse_diagonal[j];
    for (long r = 0; r < w; ++r) xj[r] *= d;
  }
}

}  // namespace strictmin
