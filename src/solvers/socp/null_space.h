#pragma once
// A basis of the null space of a cone program's equalities A x = 0 in vertex blocks, so that
// the Newton systems can be solved on dx = Z dy exactly (kkt.h) instead of with a penalty.
//
// The free vertices' dofs come in blocks of n. Rows of A are taken n at a time (a block row:
// the seam transitions of global parametrization, docs/gparam.md, are two rows per cut edge
// with coefficient blocks I and -rot(k pi/2)). Each block row, with the earlier eliminations
// substituted, expresses one vertex block (the pivot: a block of largest |det|, fewest
// dependents) through the others; block rows that reduce to nothing are redundant. Every
// free vertex is then x_f = sum_t B_t y_{node_t}, the y nodes being the vertices that were
// never pivots. Along a seam branch that makes a_j = R b_j + a_0 - R b_0; a change of basis
// then takes t = a_0 - R b_0 as the node in a_0's place (a_j = R b_j + t, a_0 = t + R b_0), so
// that one node per branch, not two, couples the elements along it. Quarter-turn blocks have
// entries 0 and +-1 (and (I - R)^-1 of one, at singular vertices, halves), so the basis is
// exact.
//
// Not every A has this form (rows not in blocks of n, a block row whose reduced blocks are
// all singular): ok is then false and the caller keeps the penalty.
#include <vector>

#include "solvers/socp/cone_program.h"

namespace strictmin::socp {

struct BlockNullSpace {
  bool ok = false;
  int num_nodes = 0;             // y nodes (n dofs each)
  std::vector<int> offset;       // free vertex f: its terms are [offset[f], offset[f+1])
  std::vector<int> node;         // term -> y node
  std::vector<double> block;     // term -> n x n block, row-major
  std::vector<int> node_vertex;  // y node -> the free vertex it was
  int num_dofs(int n) const { return num_nodes * n; }
};

BlockNullSpace block_null_space(const ConeProgram& p);

// x = Z y (x: num_x, y: num_nodes * n) and y = Z^T x.
void apply_z(const BlockNullSpace& z, int n, const Eigen::VectorXd& y, Eigen::VectorXd& x);
void apply_zt(const BlockNullSpace& z, int n, const Eigen::VectorXd& x, Eigen::VectorXd& y);

}  // namespace strictmin::socp
