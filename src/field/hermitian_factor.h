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
// Left-looking, as CHOLMOD's t_cholmod_super_numeric: for each supernode s in order, subtract
// L_d L_d^H of every earlier supernode d whose rows meet s's columns, then factor s's diagonal
// block and solve its off-diagonal block.
#include <cholmod.h>

#include <complex>
#include <vector>

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
  int n_ = 0, nsuper_ = 0;
  std::vector<int> super_of_column_;
  std::vector<int> source_;     // the entries used (index e)
  std::vector<long> target_;    // ... where each goes in L->x (complex entries)
  std::vector<char> conjugate_;
  // Workspace of one factorization.
  std::vector<int> head_, next_, position_, map_, relative_;
  std::vector<std::complex<double>> buffer_, update_;
};

}  // namespace strictmin
