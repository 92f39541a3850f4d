#pragma once
// The equalities of a relaxation (linf_active_set.h): the problem restricted to some elements,
// the other elements dropped. The vertices that no kept element touches (outside) then appear
// in the equalities only, so the relaxation's equalities are the projection of A x = b onto
// the other vertices: {x_in : A_in x_in + A_out x_out = b for some x_out}. Dropping every row
// through an outside vertex (the simplest relaxation) frees far more: on the seamless problems
// of global parametrization a cut edge's rows tie its two wedge pairs, d_b = d_a with
// d = w0 - R w1 (docs/gparam.md), so dropping them leaves every element near a seam free to
// shift against its copy, and the bound is useless (0.39 against an optimum of 0.55 on
// horse). Eliminating the outside vertices instead keeps d_c = d_a between the nearest kept
// pairs along the branch.
//
// A translation of a part of the kept elements changes no distortion, but the projected rows
// couple parts (T_P - T_Q - R (T_P' - T_Q') = 0 for the parts of a row's four wedges). The
// translations the rows allow are the null space S of their action on the parts'
// translations; the relaxation holds vertices chosen so that S maps one to one onto their
// positions: every point of the relaxation is then a translate (within S) of one with the
// held vertices where they are, so holding them keeps the optimum. Parts not held are then
// held by the equalities alone (the certificate's least squares includes A^T A there,
// socp/certificate.h).
#include <vector>

#include "strictmin/problem/parts.h"
#include "strictmin/problem/problem.h"

namespace strictmin {

struct RelaxedEqualities {
  bool ok = false;                                 // false: A is not in vertex blocks of n rows
  Eigen::SparseMatrix<double, Eigen::RowMajor> A;  // the projected rows (every vertex inside or fixed)
  Eigen::VectorXd b;
  std::vector<int> held;  // vertices to hold: one per n dimensions of the allowed translations
};

// inside: #V flags, the vertices of the kept elements; parts: those elements' parts;
// anchor: #V flags of vertices that hold still (the fixed ones). Rows that cannot be
// eliminated block by block are dropped (still a relaxation).
RelaxedEqualities relaxed_equalities(const Problem& p, const std::vector<char>& inside, const ElementParts& parts,
                                     const std::vector<char>& anchor);

// The same choice of held vertices for a whole problem: empty when its fixed vertices and
// equalities leave no part free to translate (without equalities: unanchored_components).
std::vector<int> free_translations(const Problem& p);

}  // namespace strictmin
