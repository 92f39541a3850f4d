#pragma once
// The planar maps meeting a Problem's equalities as complex numbers, when the equalities
// allow it: z_w = u_w + i v_w per vertex, and every equality, taken two rows at a time, is
// sum_w c_w z_w = 0 with each 2 x 2 coefficient block [a -b; b a] = multiplication by
// c = a + ib (the seam transitions of global parametrization: I and -rot(k pi/2), i.e. 1 and
// -i^k; docs/gparam.md, "Methods"). Then z = sum over terms c_t y_node(t) + z0 with complex
// independent unknowns y, and the L2 energy, whose matrix is the same scalar K for u and v,
// becomes the Hermitian y^H (Z^H K Z) y - 2 Re(y^H Z^H b) + const: half the unknowns of the
// real form (solvers/l2.h).
//
// Built like problem/equality_basis.h, with complex coefficients: each block row, the earlier
// eliminations substituted, expresses one vertex (the pivot: a largest |c|, fewest
// dependents) through the others. Then, as in the interior-point method's block null space
// (src/solvers/socp/null_space.h), every seam branch's two anchors a_0, b_0 (a_j = a_0 + r (b_j
// - b_0)) become one translation node t = a_0 - r b_0 (a_j = t + r b_j): one node per branch,
// not two, couples the elements along it. Coefficients are products of quarter turns (and
// halves at singular vertices), so the basis is exact.
#include <Eigen/Core>
#include <complex>
#include <optional>
#include <vector>

#include "strictmin/problem/problem.h"

namespace strictmin {

struct ComplexEqualityBasis {
  int num_nodes = 0;                              // complex unknowns y
  std::vector<int> offset;                        // vertex w: its terms are [offset[w], offset[w+1])
  std::vector<int> node;                          // term -> y node
  std::vector<std::complex<double>> coefficient;  // term -> c
  Eigen::VectorXcd z0;                            // #V: the fixed vertices' values, 0 elsewhere
};

// Empty when the problem is not of that form: image_dim != 2, no equalities, a row count
// that is odd, a block that is not a rotation-scaling, a right-hand side that is not 0, or a
// fixed vertex away from the origin in an equality.
std::optional<ComplexEqualityBasis> complex_equality_basis(const Problem& p);

}  // namespace strictmin
