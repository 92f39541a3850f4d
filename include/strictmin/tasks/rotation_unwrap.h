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

// Rotations blended relative to their neighbours', for poses that twist by a full turn or
// more (where unwrap_rotation_vectors reports jumps; docs/maths.md section 6). Each element's
// rotation is written as its spanning-tree parent's times a small relative rotation,
// R_e = R_p Q_e (Q_e in the parent's own frame, so a rigid turn of the whole target leaves
// it unchanged), and at time t
//   R_root(t) = exp(t log R_root),   R_e(t) = R_p(t) exp(t log Q_e).
// Neighbours along the tree then turn together however far the poses twist, and t = 0 and
// t = 1 give I and R_e exactly. A pure twist or bend about one axis (commuting rotations)
// gives exp(t w_e) as the logarithms do. The tree is a breadth-first one from the least
// turned element of each connected part, whose own rotation is blended the short way: the
// whole blend turns the short way where the poses turn least.
class TreeRotationBlend {
 public:
  TreeRotationBlend() = default;
  // rotations: #E of them; neighbours: element_neighbours.
  TreeRotationBlend(const std::vector<std::vector<int>>& neighbours, const std::vector<Eigen::Matrix3d>& rotations);
  // The #E rotations at time t.
  std::vector<Eigen::Matrix3d> at(double t) const;
  bool empty() const { return order_.empty(); }

 private:
  std::vector<int> order_, parent_;  // root first in each part; parent -1 at a root
  Eigen::MatrixXd logs_;             // #E by 3: log R_e at a root, log Q_e elsewhere
};

// How far blended rotations are from turning together: the pairs of neighbours e, f whose
// blended rotations at time t differ by more than `angle` (radians) from the relative rotation
// between them blended too, R_f(t) against R_e(t) exp(t log(R_e^T R_f)). rotations: the #E
// rotations at t = 1; blended: at t. 0 for commuting rotations (a twist or bend about one
// axis) however far they turn; not 0 where neighbours turn by about 180 degrees relative to
// each other (the direction of their relative turn is then ambiguous), where the blend
// jumps, or where the rotations wind around a loop of elements.
int count_disagreeing_neighbours(const std::vector<std::vector<int>>& neighbours,
                                 const std::vector<Eigen::Matrix3d>& rotations,
                                 const std::vector<Eigen::Matrix3d>& blended, double t, double angle);

}  // namespace strictmin
