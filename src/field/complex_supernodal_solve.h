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

namespace strictmin {

// True for the factors these functions handle: supernodal, LL^H, complex double, int indices.
bool supports_complex_supernodal_solve(const cholmod_factor& L);

// x <- L^{-1} x and x <- L^{-H} x (no permutation: CHOLMOD_L and CHOLMOD_Lt).
void complex_supernodal_forward(const cholmod_factor& L, std::complex<double>* x);
void complex_supernodal_backward(const cholmod_factor& L, std::complex<double>* x);

}  // namespace strictmin
