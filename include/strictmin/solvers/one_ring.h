#pragma once
// The 1-ring L-infinity problem of the relaxation algorithm (paper Section 5.3,
// Proposition 3; docs/maths.md). Moving one vertex to q, with every other vertex
// fixed, each element T of its ring has D_T(q)^2 = a_T ||q - c_T||^2 + b_T, so
//
//   q* = argmin_q max_T  a_T ||q - c_T||^2 + b_T
//
// is a weighted smallest-enclosing-ball problem: LP-type, at most d+1 active elements.
#include <Eigen/Core>
#include <array>

namespace strictmin {

template <int d>
struct RingTerm {
  Eigen::Matrix<double, d, 1> centre;  // c_T
  double a = 1;                         // a_T = ||g_v||^2 > 0
  double b = 0;                         // b_T >= 0: the least squared distortion T can reach
};

// The term of an element whose deviation J_T - R_T is M + q g^T when its ring vertex moves
// by q (M: n by m, with n the image and m the domain dimension; g: that corner's gradient,
// inv_a = 1 / ||g||^2): a = ||g||^2, c = -M g / a, and b = ||M (I - g g^T / a)||^2, M on the
// complement of g (>= 0 without cancellation). Expanding ||M + q g^T||^2 = ||M||^2 +
// 2 q^T M g + ||g||^2 ||q||^2 gives a ||q - c||^2 + b for any n and m (docs/maths.md): a
// triangle of a 3D surface (3 by 2 Jacobian) gives a term in q in R^3 like a tet.
template <int n, int m>
inline RingTerm<n> ring_term(const Eigen::Matrix<double, n, m>& M, const Eigen::Matrix<double, m, 1>& g,
                             double inv_a) {
  const Eigen::Matrix<double, n, 1> Mg = M * g;
  RingTerm<n> t;
  t.a = g.squaredNorm();
  t.centre = -inv_a * Mg;
  t.b = (M - (inv_a * Mg) * g.transpose()).squaredNorm();
  return t;
}

// The square case (planar triangles, tets): d by d.
template <int d>
inline RingTerm<d> ring_term(const Eigen::Matrix<double, d, d>& M, const Eigen::Matrix<double, d, 1>& g,
                             double inv_a) {
  return ring_term<d, d>(M, g, inv_a);
}

template <int d>
struct RingSolution {
  Eigen::Matrix<double, d, 1> q;
  double value = 0;  // max_T D_T(q)^2 at the optimum (squared distortion)
  int active = 0;    // number of elements attaining it (1..d+1)
  std::array<int, d + 1> support{};  // the first `active` entries: indices of those terms
};

// Exact minimizer (to rounding) for count >= 1 terms (a_T > 0, b_T >= 0): combinatorial
// pivoting over support sets of at most d+1 terms with closed-form support points
// (one_ring.cpp). The returned q is a KKT point: its support terms agree to 1e-13
// (relative; Newton-polished to ~1e-15 where possible) and q lies in the convex hull of
// their centres. value is the objective at q: within 1e-13 relative of the optimum, plus
// the rounding of coordinates (eps |q|) far from the origin.
template <int d>
RingSolution<d> solve_one_ring(const RingTerm<d>* terms, int count);

// The same, starting from a guess of the support set (term indices, e.g. the support of the
// previous solve on the same vertex): fewer pivots when the guess is right. Invalid
// guesses are ignored; the answer does not depend on the guess (up to rounding).
template <int d>
RingSolution<d> solve_one_ring(const RingTerm<d>* terms, int count, const int* guess, int guess_size);

extern template RingSolution<2> solve_one_ring<2>(const RingTerm<2>*, int);
extern template RingSolution<3> solve_one_ring<3>(const RingTerm<3>*, int);
extern template RingSolution<2> solve_one_ring<2>(const RingTerm<2>*, int, const int*, int);
extern template RingSolution<3> solve_one_ring<3>(const RingTerm<3>*, int, const int*, int);

}  // namespace strictmin
