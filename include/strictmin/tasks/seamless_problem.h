#pragma once
// The seamless problem of the paper's Appendix A (docs/gparam.md, "The seamless problem"):
// one 2D unknown per wedge (the cut mesh's vertices), element frames as in make_problem,
// targets R_T = rot(-combed angle) (the rotation taking the combed direction to the u axis;
// the 1/h of R_T = (1/h) rot is applied to the solution afterwards: the problem is
// homogeneous, so solving at h = 1 and dividing by h is the same map), and per cut edge
// (a, b) the transition with its translation eliminated,
//   (uv_b - uv_a)(face-0 side) = rot(k pi/2) (uv_b - uv_a)(face-1 side),
// which with the cut's branches is f_left = R f_right + t with one free t per branch. Wedge 0
// is pinned at the origin (the problem is otherwise translation invariant).
#include <Eigen/Core>
#include <vector>

#include "strictmin/field/cut_graph.h"
#include "strictmin/field/surface_graph.h"
#include "strictmin/mesh/mesh.h"
#include "strictmin/problem/problem.h"

namespace strictmin {

Problem seamless_problem(const Mesh& mesh, const SurfaceGraph& graph, const CutGraph& cut);

// The wedge (cut-mesh vertex) of vertex v's corner in face f, -1 when v is not a corner of f.
int corner_wedge_of(const Mesh& mesh, const CutGraph& cut, int f, int v);

// The two wedges of a branch's first vertex on its left and right sides, and its rotation:
// the branch's translation is t = X(left) - R X(right) (branch_translations' convention).
struct BranchEnds {
  int left = -1, right = -1;
  Eigen::Matrix2d rotation = Eigen::Matrix2d::Identity();
};
BranchEnds branch_ends(const Mesh& mesh, const SurfaceGraph& graph, const CutGraph& cut, const SeamBranch& branch);

// Each branch's translation t = mean over its vertices of uv_left - R uv_right (#branches by
// 2), and the largest |uv_left - R uv_right - t| over every branch vertex (the transitions'
// violation) in *error. X: #wedges by 2.
Eigen::MatrixXd branch_translations(const Mesh& mesh, const SurfaceGraph& graph, const CutGraph& cut,
                                    const Eigen::MatrixXd& X, double* error);

}  // namespace strictmin
