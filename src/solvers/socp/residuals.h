#pragma once
// Residuals and objectives of an iterate (x, k, s, z, y) of a ConeProgram:
//   r_s  = s - (M v + o)                       primal cone residual
//   r_dx = P x + q - G^T z_tails - A^T y       dual residual, x part
//   r_dk = c_k - sum_i a_i z_i,0               dual residual, k part
//   r_eq = A x - beq
// pobj = 1/2 x^T P x + q^T x + c_k k (+ constant), dobj = -1/2 x^T P x - z^T o + y^T beq
// (+ constant), where o = (b_i, -h_i) are the cones' offsets. For a feasible iterate
// pobj - dobj = s^T z.
#include <Eigen/Core>

#include "solvers/socp/cone_program.h"

namespace strictmin::socp {

struct IpmState {
  Eigen::VectorXd x;
  double k = 0;
  Eigen::VectorXd s, z, y;
};

struct Residuals {
  Eigen::VectorXd rs, rdx, req;
  double rdk = 0;
  double pobj = 0, dobj = 0, gap = 0;
  double pres = 0, dres = 0;  // relative, max norm
  // ||G_i x - h_i|| of every element cone (its distortion at x), a by-product of r_s.
  Eigen::VectorXd tail_norms;
};

// Norms used to make the residuals relative (computed once per program).
struct ResidualScales {
  double primal = 1, dual = 1;
};
ResidualScales residual_scales(const ConeProgram& p);

void compute_residuals(const ConeProgram& p, const ResidualScales& scales, const IpmState& st, Residuals& out);

}  // namespace strictmin::socp
