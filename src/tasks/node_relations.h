#pragma once
// The integer relations among the integer-grid rounding's values (docs/gparam.md,
// "Integer-grid maps", "The node relations"). Private to the library.
//
// The values (UV units, two integers each on an integer-grid map): per singular vertex s the
// position f_s of its held wedge (the wedge of its first fan corner), per branch b its
// translation t_b (f_left = R_b f_right + t_b, BranchEnds' convention). Walking once around
// a vertex v of the cut through its fan, the wedge value changes only across cut edges, by
// the transition of the edge's branch:
//   leaving the branch's left side:  f_next = R_b^T (f_prev - t_b)
//   leaving its right side:          f_next = R_b f_prev + t_b
// so back at the first wedge f_0 = P f_0 + sum_b Q_b t_b, P the product of the quarter turns
// and Q_b integer 2x2 matrices (sums of products of quarter turns). v's relation is
//   (I - P) f_0 - sum_b Q_b t_b = 0.
// At a regular vertex P = I and f_0 drops out; inside a branch the two crossings cancel
// (0 = 0, left out). At a singular vertex f_0 is f_s. These are all the relations: given
// values that meet them, wedge values around every node follow from f_0 and the crossings,
// every branch's interior copies from its left side and t_b, and the disk's interior is free,
// so a seamless map with exactly these values exists.
#include <Eigen/Core>
#include <vector>

#include "solvers/integer_hermite.h"
#include "strictmin/field/cut_graph.h"
#include "strictmin/field/singularities.h"
#include "strictmin/field/surface_graph.h"

namespace strictmin {

struct NodeRelations {
  int num_singular = 0, num_branches = 0;
  // Value k has coordinates 2k and 2k + 1: the singular vertices first, then the branches.
  int num_values() const { return num_singular + num_branches; }
  int singular_value(int i) const { return i; }
  int branch_value(int b) const { return num_singular + b; }
  IntegerMatrix matrix;     // two rows per vertex with a relation, two columns per value
  std::vector<int> vertex;  // per row pair: its vertex

  // The relations' left-hand sides for real values (2 per value): A x.
  Eigen::VectorXd residual(const Eigen::VectorXd& values) const;
};

NodeRelations node_relations(const SurfaceGraph& graph, const CutGraph& cut, const std::vector<Singularity>& singular);

}  // namespace strictmin
