#pragma once
// The 1-ring L-infinity problem of the relaxation algorithm (paper Section 5.3,
// Proposition 3; ../shared/paper/NOTES.md). Moving one vertex to q, with every other vertex
// fixed, each element T of its ring has D_T(q)^2 = a_T ||q - c_T||^2 + b_T, so
//
//   q* = argmin_q max_T  a_T ||q - c_T||^2 + b_T
//
// is a weighted smallest-enclosing-ball problem: LP-type, at most d+1 active elements.
#include <Eigen/Core>

namespace strictmin {

template <int d>
struct RingTerm {
  Eigen::Matrix<double, d, 1> centre;  // c_T
  double a = 1;                         // a_T = ||g_v||^2 > 0
  double b = 0;                         // b_T >= 0: the least squared distortion T can reach
};

template <int d>
struct RingSolution {
  Eigen::Matrix<double, d, 1> q;
  double value = 0;  // max_T D_T(q)^2 at the optimum (squared distortion)
  int active = 0;    // number of elements attaining it (1..d+1)
};

// Exact minimizer (to rounding) for count >= 1 terms.
template <int d>
RingSolution<d> solve_one_ring(const RingTerm<d>* terms, int count);

extern template RingSolution<2> solve_one_ring<2>(const RingTerm<2>*, int);
extern template RingSolution<3> solve_one_ring<3>(const RingTerm<3>*, int);

}  // namespace strictmin
