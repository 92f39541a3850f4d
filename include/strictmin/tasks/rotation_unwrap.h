#pragma once
// Rotations made consistent across neighbouring elements before they are interpolated
// (docs/maths.md section 6): a rotation has many logarithms (angle + 2 pi k); a
// breadth-first search over the element adjacency picks, for every element, the one closest
// to its parent's, so that a bar whose end turns by more than 180 degrees is interpolated
// through the turn instead of back the short way (which would fold it).
#include <Eigen/Core>
#include <vector>

namespace strictmin {

// Elements sharing a facet (an edge of a triangle, a face of a tet); F is #E by 3 or 4.
std::vector<std::vector<int>> element_neighbours(const Eigen::MatrixXi& F);

// 2D: angles (#E, any branch) shifted by multiples of 2 pi so that every element differs
// from its BFS parent by at most pi. The first element of each connected part keeps its
// angle reduced to (-pi, pi].
Eigen::VectorXd unwrap_angles(const std::vector<std::vector<int>>& neighbours, const Eigen::VectorXd& angles);

// 3D: rotation vectors (#E by 3, angle in [0, pi]) replaced by the equivalent vector
// (angle + 2 pi k) * axis closest to the BFS parent's (|k| <= 2). `jumps` (optional): the
// elements whose closest one is still more than pi from the parent's, where the blended
// rotations jump instead of turning together. That happens around a twist of a full turn or
// more: an element turned by nearly 2 pi has a rotation near the identity whose axis is its
// own small tilt, and none of its logarithms lies near its parent's (nearly 2 pi about the
// twist's axis). (In 2D a parent's angle is always within pi.)
Eigen::MatrixXd unwrap_rotation_vectors(const std::vector<std::vector<int>>& neighbours, const Eigen::MatrixXd& w,
                                        int* jumps = nullptr);

}  // namespace strictmin
