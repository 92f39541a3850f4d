#pragma once
// Cone programs for the field-deviation L-infinity problems of a Problem (paper Section 5.1):
// which elements are free (D_T <= k), bounded (D_T <= k_T) or constant (every vertex fixed),
// and the element data (gradients, free dofs, h = vec(R_T) minus the fixed corners' part)
// of a ConeProgram over a chosen set of elements and unknown vertices.
#include <Eigen/Core>
#include <limits>
#include <vector>

#include "strictmin/problem/problem.h"
#include "solvers/socp/cone_program.h"

namespace strictmin::socp {

struct ElementClasses {
  std::vector<int> free_elements;     // not constant, bounded by k
  std::vector<int> bounded_elements;  // not constant, with a fixed bound k_T
  std::vector<int> constant_elements; // every vertex fixed (bounded or not)
  std::vector<double> constant_distortion;  // theirs, in the same order
  // Largest distortion of a constant free element: a lower bound on k (-inf if none).
  double constant_max = -std::numeric_limits<double>::infinity();
  // Largest excess D_T - k_T of a constant bounded element, and which (-1 if none).
  double constant_excess = -std::numeric_limits<double>::infinity();
  int constant_excess_element = -1;
};

// bounds: #E or empty; a negative or NaN entry means "free".
ElementClasses classify_elements(const Problem& p, const Eigen::VectorXd& bounds);

// Whether element e has a fixed bound.
inline bool has_bound(const Eigen::VectorXd& bounds, int e) {
  return bounds.size() > 0 && bounds[e] >= 0;  // false for NaN
}

// Element data of a program over `elements`: vertex v is unknown with first dof
// vertex_dof[v] (>= 0), or held at X.row(v) (vertex_dof[v] < 0). num_x = number of dofs.
// Heads, objective and equalities are left for the caller (has_k true, c_k 1, no scalar
// cone); finalize() is called.
ConeProgram element_program(const Problem& p, const std::vector<int>& elements, const std::vector<int>& vertex_dof,
                            int num_x, const Eigen::MatrixXd& X);

// The problem's equalities over the program's dofs (held vertices moved to the right side).
// Rows that involve a vertex that is neither held nor a dof are dropped (a relaxation).
void restrict_equalities(const Problem& p, const std::vector<int>& vertex_dof, int num_x, const Eigen::MatrixXd& X,
                         const std::vector<char>& held, ConeProgram& out);

// Field deviation ||G_i x - h_i|| of every element cone of `p` at x.
Eigen::VectorXd cone_distortions(const ConeProgram& p, const Eigen::VectorXd& x);

}  // namespace strictmin::socp
