#pragma once
// Triangular solves with a CHOLMOD supernodal LL^T factor, one right-hand side, in place.
//
// cholmod_solve does the same, but for one column it calls BLAS (dtrsv, dgemv) once or twice
// per supernode and allocates its result and workspace on every call. The normal equations
// of the interior-point method have thousands of tiny supernodes (median width 2 on the 100k
// square), so call overhead and allocation dominated; these loops stream the factor once per
// substitution. They read CHOLMOD's supernodal layout: supernode k holds columns
// super[k] .. super[k+1]-1, its rows are s[pi[k] .. pi[k+1]) (the columns themselves first),
// its values column-major at x[px[k]] with leading dimension pi[k+1] - pi[k].
#include <cholmod.h>

namespace strictmin::socp {

// True for the factors these functions handle: supernodal, LL^T, real double, int indices.
bool supports_supernodal_solve(const cholmod_factor& L);

// x <- L^{-1} x and x <- L^{-T} x (no permutation: CHOLMOD_L and CHOLMOD_Lt).
void supernodal_forward(const cholmod_factor& L, double* x);
void supernodal_backward(const cholmod_factor& L, double* x);

// The same for two right-hand sides at once, interleaved (x[2 i], x[2 i + 1] are row i of the
// first and the second): the factor is streamed once for both.
void supernodal_forward2(const cholmod_factor& L, double* x);
void supernodal_backward2(const cholmod_factor& L, double* x);

}  // namespace strictmin::socp
