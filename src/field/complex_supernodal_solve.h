#pragma once
// Triangular solves with CHOLMOD's complex supernodal L L^H factor (the cross field's
// connection Laplacian, hermitian_cholesky.h), one right-hand side, in place.
//
// cholmod_solve does the same through BLAS (ztrsv, zgemv) once or twice per supernode; on
// the face graphs' factors (supernodes mostly a few columns wide) these loops stream the
// factor once per substitution instead. The layout is the real one of
// src/solvers/socp/supernodal_solve.h with interleaved (re, im) values; L's diagonal is real.
#include <cholmod.h>

#include <complex>
#include <vector>

namespace strictmin {

// True for the factors these functions handle: supernodal, LL^H, complex double, int indices.
bool supports_complex_supernodal_solve(const cholmod_factor& L);

// x <- L^{-1} x and x <- L^{-H} x (no permutation: CHOLMOD_L and CHOLMOD_Lt).
void complex_supernodal_forward(const cholmod_factor& L, std::complex<double>* x);
void complex_supernodal_backward(const cholmod_factor& L, std::complex<double>* x);

// The factor by columns with its stored zeros dropped, for the substitutions: CHOLMOD's
// supernodes are padded to dense blocks (relaxed amalgamation, for the factorization's dense
// kernels), which on the face graphs' factors stores nearly twice L's nonzeros (horse:
// 3.78M entries for 1.96M nonzeros), and the substitutions, memory-bound, stream them all.
// Columns of (row, value) pairs and the inverse diagonal: 20 bytes per nonzero against 16 per
// stored entry, a third less to read per substitution.
struct CompactFactor {
  std::vector<int> start;                   // column j: entries [start[j], start[j+1])
  std::vector<int> row;                     // below the diagonal
  std::vector<std::complex<double>> value;
  std::vector<double> inverse_diagonal;
};

CompactFactor compact_factor(const cholmod_factor& L);

// x <- L^{-H} L^{-1} x with the compact factor (no permutation).
void compact_solve(const CompactFactor& L, std::complex<double>* x);

// The same for k right-hand sides at once, stored by rows (x[i * k + r]: row i of right-hand
// side r): the factor, which the substitutions stream, is read once for all of them.
void compact_solve_many(const CompactFactor& L, std::complex<double>* x, int k);

}  // namespace strictmin
