#pragma once
// Numeric supernodal Cholesky factorization L L^H of a complex Hermitian matrix on CHOLMOD's
// symbolic analysis, written into the CHOLMOD factor's own storage (so the substitutions of
// complex_supernodal_solve.h and CHOLMOD read it as theirs): the complex twin of
// src/solvers/socp/supernodal_factor.h, for the same reason. cholmod_factorize pays per
// supernode an OpenMP region, a BLAS call per descendant update (OpenBLAS takes a lock and a
// buffer per call), and a transpose and permutation of the matrix per call; on the field's
// face graphs and the complex L2 systems most supernodes are a few columns wide. Here the
// matrix's entries go straight into the factor's storage through a map built once, narrow
// updates are short loops, and BLAS (zgemm, zpotrf, ztrsm) is called only for wide ones.
//
// Algorithm: socp::factor_left_looking (solvers/socp/supernodal_layout.h) with complex kernels.
#include <cholmod.h>

#include <complex>
#include <vector>

#include "solvers/socp/supernodal_layout.h"

namespace strictmin {

// Entry e of a matrix's lower triangle, in L's permuted order: (row[e], col[e]) with
// row[e] >= col[e], conjugated when conjugate[e] (an entry of the lower triangle that the
// permutation moved above the diagonal).
struct HermitianEntries {
  std::vector<int> row, col;
  std::vector<char> conjugate;
};

class HermitianFactor {
 public:
  // L: CHOLMOD's supernodal analysis (int indices) of an n x n matrix; its numeric storage
  // is made complex LL^H here. False when L is not such a factor or an entry lies outside
  // its pattern.
  bool setup(cholmod_factor* L, cholmod_common* common, const HermitianEntries& entries);
  // Factors the matrix whose entry e is value[e] into L. False when it is not (numerically)
  // positive definite.
  bool factorize(const std::complex<double>* value);

 private:
  cholmod_factor* L_ = nullptr;
  socp::SupernodalEntryMap entries_;
  std::vector<char> conjugate_;  // per entry used (entries_.source)
  // Workspace of one factorization.
  socp::LeftLookingWorkspace workspace_;
  std::vector<std::complex<double>> buffer_, update_;
};

}  // namespace strictmin
