#pragma once
// A Problem restricted to the vertices that may move, the others held where a map X has them.
//
// Used by the direct strict minimizer (strict.h, DirectOptions::moving_rings): once most
// elements have their bounds fixed, a level only needs the vertices near the elements still
// free; the rest of the mesh is a constant of that level's problem. The restriction keeps
// every element with a movable vertex (with its targets, gradients and weight), and those
// elements' other vertices as fixed vertices at X. Linear equalities are restricted too: the
// columns of vertices left out move to the right-hand side, rows with no movable dof go.
#include <Eigen/Core>
#include <vector>

#include "strictmin/problem/problem.h"

namespace strictmin {

struct Subproblem {
  Problem problem;
  std::vector<int> vertex;   // sub-problem vertex -> vertex of the full problem
  std::vector<int> element;  // sub-problem element -> element of the full problem
};

// movable: #V flags (a vertex fixed in p never moves, whatever its flag). X: #V by n, the map
// the held vertices keep (and the movable ones start from). elements: #E flags, the elements
// that may be kept (null: every one; the L-infinity active-set solves drop the others).
Subproblem restrict_to_movable(const Problem& p, const std::vector<char>& movable, const Eigen::MatrixXd& X,
                               const std::vector<char>* elements = nullptr);

// Vertices within `rings` rings of the seeds: the seeds (ring 1), then every vertex sharing
// an element with a vertex of the previous ring. rings <= 0: every vertex.
std::vector<char> vertices_within_rings(const Problem& p, const std::vector<char>& seeds, int rings);

}  // namespace strictmin
