#pragma once
// The scalar-independent parts of our supernodal Cholesky on CHOLMOD's symbolic analysis,
// shared by the real factorization of the interior-point method (supernodal_factor.h,
// supernodal_solve.h) and the complex Hermitian one of the field and L2 (field/hermitian_factor.h,
// field/complex_supernodal_solve.h):
// - SupernodalView: one supernode's columns, rows and block, read from the factor's arrays;
// - SupernodalEntryMap: where each entry of the matrix goes in the factor's storage;
// - factor_left_looking: the left-looking loop (as CHOLMOD's t_cholmod_super_numeric): for
//   each supernode s in order, subtract the updates of every earlier supernode d whose rows
//   meet s's columns (d waits in a linked list keyed by the next supernode it updates), then
//   factor s's own panel. The scalar arithmetic comes from a Kernels type.
#include <cholmod.h>

#include <vector>

namespace strictmin::socp {

// Supernode k of a supernodal factor whose entries are kDoubles doubles wide (1: real,
// 2: complex as (re, im) pairs).
struct Supernode {
  int first;          // first column (and row) of the supernode
  int cols;           // its width
  int rows;           // rows of its block (the columns themselves first)
  const int* index;   // the block's row indices
  const double* val;  // the block, column-major, leading dimension `rows` (entries)
};

template <int kDoubles>
struct SupernodalView {
  const int *super, *pi, *px, *s;
  const double* lx;
  long count;
  explicit SupernodalView(const cholmod_factor& L)
      : super(static_cast<const int*>(L.super)),
        pi(static_cast<const int*>(L.pi)),
        px(static_cast<const int*>(L.px)),
        s(static_cast<const int*>(L.s)),
        lx(static_cast<const double*>(L.x)),
        count(static_cast<long>(L.nsuper)) {}
  Supernode operator[](long k) const {
    return {super[k], super[k + 1] - super[k], pi[k + 1] - pi[k], s + pi[k], lx + kDoubles * static_cast<long>(px[k])};
  }
};

// Entry e of a matrix's lower triangle in L's permuted order is (row[e], col[e]) with
// row[e] >= col[e]; entries may repeat (summed); an entry with row[e] < 0 is not part of the
// matrix. source[q] is an entry used and target[q] its position in L->x (in entries), grouped
// by supernode.
struct SupernodalEntryMap {
  std::vector<int> super_of_column;
  std::vector<int> source;
  std::vector<long> target;
  // False when an entry lies outside L's pattern or its indices are out of range.
  bool locate(const cholmod_factor& L, const std::vector<int>& row, const std::vector<int>& col);
};

// The linked lists and row maps of one left-looking factorization.
struct LeftLookingWorkspace {
  std::vector<int> head, next, position, map, relative;
  void reserve(const cholmod_factor& L);  // sized for L (map all -1)
};

// Kernels, for entries of type Scalar (the factor's L->x):
//   void update_wide(const Scalar* ld, int ndrow, int m1, int m2, int ndcol, Scalar* buffer)
//     buffer (m2 x m1, column-major) = ld ld[0:m1, :]^H, a BLAS call;
//   void update_column(const Scalar* ld, int ndrow, int ndcol, int len, Scalar* out)
//     out[i] = sum_c ld[c * ndrow + i] conj(ld[c * ndrow]), i < len;
//   bool factor_panel(Scalar* a, int rows, int cols)
//     [A11; A21] -> [L11; L21] in place (leading dimension rows); false on a pivot that is
//     not positive;
// and the size above which an update goes through update_wide, kBlasUpdateFlops.
template <class Scalar, class Kernels>
bool factor_left_looking(cholmod_factor* L, const std::vector<int>& super_of_column, LeftLookingWorkspace& w,
                         std::vector<Scalar>& buffer, std::vector<Scalar>& update, const Kernels& kernels) {
  const int* super = static_cast<const int*>(L->super);
  const int* pi = static_cast<const int*>(L->pi);
  const int* px = static_cast<const int*>(L->px);
  const int* ls = static_cast<const int*>(L->s);
  Scalar* lx = static_cast<Scalar*>(L->x);
  const int nsuper = static_cast<int>(L->nsuper);
  std::fill(w.head.begin(), w.head.end(), -1);
  int* rel = w.relative.data();
  for (int s = 0; s < nsuper; ++s) {
    const int k1 = super[s], k2 = super[s + 1], nscol = k2 - k1;
    const int psi = pi[s], nsrow = pi[s + 1] - psi;
    Scalar* ax = lx + px[s];
    for (int k = 0; k < nsrow; ++k) w.map[ls[psi + k]] = k;
    // Updates from the supernodes whose rows meet columns k1 .. k2-1.
    for (int d = w.head[s]; d != -1;) {
      const int dnext = w.next[d];
      const int pdi1 = w.position[d], pdend = pi[d + 1], ndrow = pdend - pi[d];
      const int ndcol = super[d + 1] - super[d];
      int pdi2 = pdi1;
      while (pdi2 < pdend && ls[pdi2] < k2) ++pdi2;
      const int m1 = pdi2 - pdi1, m2 = pdend - pdi1;
      for (int ii = 0; ii < m2; ++ii) rel[ii] = w.map[ls[pdi1 + ii]];
      const Scalar* ld = lx + px[d] + (pdi1 - pi[d]);  // column c at ld + c * ndrow
      if (static_cast<long>(m1) * m2 * ndcol >= Kernels::kBlasUpdateFlops) {
        if (buffer.size() < static_cast<size_t>(m1) * m2) buffer.resize(static_cast<size_t>(m1) * m2);
        kernels.update_wide(ld, ndrow, m1, m2, ndcol, buffer.data());
        for (int jj = 0; jj < m1; ++jj) {
          Scalar* target = ax + static_cast<long>(ls[pdi1 + jj] - k1) * nsrow;
          const Scalar* c = buffer.data() + static_cast<long>(jj) * m2;
          for (int ii = jj; ii < m2; ++ii) target[rel[ii]] -= c[ii];
        }
      } else {
        // Column jj of the update, accumulated column by column of d (contiguous,
        // vectorised), then scattered.
        Scalar* column = update.data();
        for (int jj = 0; jj < m1; ++jj) {
          Scalar* target = ax + static_cast<long>(ls[pdi1 + jj] - k1) * nsrow;
          const int len = m2 - jj;
          kernels.update_column(ld + jj, ndrow, ndcol, len, column);
          for (int ii = 0; ii < len; ++ii) target[rel[jj + ii]] -= column[ii];
        }
      }
      if (pdi2 < pdend) {  // d's next target
        const int t = super_of_column[ls[pdi2]];
        w.position[d] = pdi2;
        w.next[d] = w.head[t];
        w.head[t] = d;
      }
      d = dnext;
    }
    for (int k = 0; k < nsrow; ++k) w.map[ls[psi + k]] = -1;
    if (!kernels.factor_panel(ax, nsrow, nscol)) {
      L->minor = static_cast<size_t>(k1);
      return false;
    }
    if (nsrow > nscol) {
      const int t = super_of_column[ls[psi + nscol]];
      w.position[s] = psi + nscol;
      w.next[s] = w.head[t];
      w.head[t] = s;
    }
  }
  L->minor = static_cast<size_t>(L->n);
  return true;
}

}  // namespace strictmin::socp
