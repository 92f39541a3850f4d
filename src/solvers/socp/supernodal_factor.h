#pragma once
// Numeric supernodal Cholesky factorisation (LL^T) on CHOLMOD's symbolic analysis, written
// into the CHOLMOD factor's own storage (so supernodal_solve.h and CHOLMOD read it as theirs).
//
// cholmod_factorize does the same left-looking supernodal algorithm, but on the interior-point
// method's normal equations (15,000 supernodes of median width 2 per half on the 100k square)
// its per-supernode overheads dominate: an OpenMP parallel region per supernode (libgomp
// allocates and frees a team even for one thread), a BLAS call per descendant update
// (OpenBLAS takes a lock and a buffer per call), and the transpose and permutation of the
// matrix on every call. Here the matrix's entries are scattered straight into the factor's
// storage through a map built once, updates from narrow supernodes are computed in place by
// short loops, and BLAS (dgemm, dpotrf, dtrsm) is called only for wide ones.
//
// Algorithm: socp::factor_left_looking (supernodal_layout.h) with real kernels.
#include <cholmod.h>

#include <vector>

#include "solvers/socp/supernodal_layout.h"

namespace strictmin::socp {

class SupernodalFactor {
 public:
  // L: CHOLMOD's supernodal analysis (LL^T, int indices) of an n x n matrix, whose numeric
  // storage is allocated here if it has none. Entry e of the matrix's lower triangle, in L's
  // permuted order, is (row[e], col[e]) with row[e] >= col[e]; entries may repeat (summed);
  // an entry with row[e] < 0 is not part of the matrix (the other triangle of a full one).
  // False when L is not such a factor or an entry lies outside its pattern.
  bool setup(cholmod_factor* L, cholmod_common* common, const std::vector<int>& row, const std::vector<int>& col);
  // Factorises the matrix whose entry e is value[e] into L. False when it is not
  // (numerically) positive definite (L then holds a partial factor).
  bool factorize(const double* value);

 private:
  cholmod_factor* L_ = nullptr;
  SupernodalEntryMap entries_;
  // Workspace of one factorisation.
  LeftLookingWorkspace workspace_;
  std::vector<double> buffer_, update_;
};

}  // namespace strictmin::socp
