#pragma once
// The smallest eigenpair of a Hermitian pencil (A, M), M diagonal positive, by Lanczos on
// T = A^-1 M (self-adjoint in the M inner product <x, y> = x^H M y) with one factorization
// of A: the smoothest cross field's eigenvector (docs/gparam.md, "The field"). Private to
// the field code.
#include <Eigen/Core>

#include "field/hermitian_cholesky.h"

namespace strictmin {

struct LanczosResult {
  Eigen::VectorXcd vector;  // ||y||_M = 1, <x0, y>_M real and >= 0
  double residual = 0;      // ||T y - theta y||_M / theta at the end
  int steps = 0;            // solves with A
};

// Fully reorthogonalized Lanczos from x0: stops once the Ritz pair of the largest theta has
// ||T y - theta y||_M <= tolerance * theta (the estimate beta_j |s_j| of the last step) or
// after max_steps solves. The limit is the M-projection of x0 on the eigenvector, as for
// inverse power iteration from x0, reached in far fewer solves.
LanczosResult lanczos_smallest(const HermitianCholesky& A, const Eigen::VectorXd& mass, const Eigen::VectorXcd& x0,
                               int max_steps, double tolerance);

}  // namespace strictmin
