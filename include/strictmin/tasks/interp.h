#pragma once
// Shape interpolation (paper Section 5.4 after Levi & Gotsman 2015; docs/maths.md "Shape
// interpolation"). Source and target meshes with the same elements define per element
// J_T = R_T Y_T (polar). At time t the target differential is R_T(t) Y_T(t) with
// Y_T(t) = (1 - t) I + t Y_T and R_T(t) the rotation of the unwrapped logarithm scaled by t,
// or in 3D where those jump the rotations blended along a tree (rotation_unwrap.h); one FD solve with these targets starts local-global iterations whose
// local step keeps the shape Y_T(t) and re-fits the rotation. The translation is pinned: the
// centroid (or one vertex) moves linearly from source to target.
//
// Element kinds: planar triangles (2D maps), tets (3D), and 3D surface triangles (each in
// an isometric 2D frame, mapped into 3D: image_dim 3, domain_dim 2; there R_T is the 3D
// rotation taking the source triangle's frame and normal to the target's).
#include <Eigen/Core>
#include <string>
#include <vector>

#include "strictmin/mesh/mesh.h"
#include "strictmin/problem/problem.h"
#include "strictmin/report/stats.h"
#include "strictmin/solvers/local_global.h"
#include "strictmin/solvers/result.h"
#include "strictmin/tasks/method.h"
#include "strictmin/tasks/rotation_unwrap.h"

namespace strictmin {

enum class InterpKind { Planar, Surface, Tets };
std::string interp_kind_name(InterpKind k);  // "planar", "surface", "tets"

// How 3D rotations are blended (rotation_unwrap.h): each element's own unwrapped logarithm
// scaled by t, or relative to the neighbours' along a spanning tree. Auto takes the
// logarithms unless they jump somewhere (rotation_jumps > 0: a twist of about a full turn).
enum class RotationBlend { Auto, Logarithms, Tree };
std::string rotation_blend_name(RotationBlend b);  // "auto", "logarithms", "tree"
// Throws InputError naming `flag` for another word.
RotationBlend parse_rotation_blend(const std::string& word, const std::string& flag);

// direct's k_min for interpolation: 0, every element fixed. The paper's 0.1 is a level of
// field deviation on parametrizations; an interpolation's distortion is often below it
// everywhere (the tet bar at t = 0.5: 0.02), where direct stopped after its first level and
// returned the L-infinity map.
inline constexpr double kInterpKMin = 0.0;

struct InterpOptions {
  InterpOptions() { solver.direct.k_min = kInterpKMin; }
  SolverOptions solver;             // the global step's method (exact is not available)
  LocalGlobalOptions local_global;  // max_iterations (0: the FD solve only), relative_change, progress
  int pin_vertex = -1;              // -1: pin the centroid (vertex mean) of every connected part
};

struct InterpFrame {
  double t = 0;
  Result result;            // positions (#V by image_dim), distortion ||J - Q Y(t)||, status, history
  Mesh mesh;                // the source mesh with the interpolated positions
  DistortionStats stats;    // of result.distortion; flipped: det J <= 0 (planar and tets only)
  Eigen::VectorXd weights;  // #E source areas / volumes (the weights of stats)
};

class Interpolator {
 public:
  // Throws InputError when the meshes can't be interpolated: different element kinds, vertex
  // or element counts, or elements (the first differing one is named), or a blend other than
  // Auto for planar poses (their rotations are angles, which unwrap without jumps).
  Interpolator(const Mesh& source, const Mesh& target, const std::string& source_name = "source",
               const std::string& target_name = "target", RotationBlend blend = RotationBlend::Auto);

  // The shape at time t in [0, 1]. Throws InputError for t outside [0, 1], a pinned vertex
  // out of range (below -1 too), or a method that can't run on this kind of element (relax and direct on
  // 3D surfaces, exact anywhere).
  InterpFrame at(double t, const InterpOptions& options) const;

  InterpKind kind() const { return kind_; }
  const Problem& problem() const { return problem_; }
  // Per element the unwrapped rotation: angle (#E by 1) in 2D, rotation vector (#E by 3) in 3D.
  const Eigen::MatrixXd& rotation_logs() const { return logs_; }
  // 3D: the elements whose rotation has no logarithm near their spanning-tree parent's
  // (rotation_unwrap.h): 0 unless the poses twist by about a full turn or more. Where it is not
  // 0 the frames blend across a jump and may fold (warning()).
  int rotation_jumps() const { return rotation_jumps_; }
  // How the rotations are blended: "angles" (planar), "logarithms" (3D: each element's own
  // unwrapped logarithm scaled by t) or "tree" (3D where the logarithms jump: relative to the
  // neighbours' along a spanning tree, TreeRotationBlend).
  std::string rotation_blend() const;
  // 3D: the pairs of neighbours whose blended rotations at t = 0.5 are more than 90 degrees
  // from turning together (count_disagreeing_neighbours); warning() when not 0.
  int rotation_disagreements() const { return rotation_disagreements_; }
  // Empty, or a sentence saying where the frames cannot follow the poses' rotations.
  std::string warning() const;

 private:
  Eigen::MatrixXd targets_at(double t, Eigen::MatrixXd* shapes) const;
  std::vector<Eigen::Matrix3d> blended_rotations(double t) const;  // 3D: per element at time t

  InterpKind kind_ = InterpKind::Planar;
  Mesh source_;
  Problem problem_;                 // source rest pose, targets identity
  Eigen::MatrixXd source_X_, target_X_;  // #V by image_dim
  double source_z_ = 0, target_z_ = 0;   // planar meshes given in 3D: their planes
  Eigen::MatrixXd frames_;          // surfaces: #E*3 by 2, the source triangle's 3D frame
  Eigen::MatrixXd shapes_;          // #E*d by d: Y_T
  Eigen::MatrixXd logs_;
  int rotation_jumps_ = 0;
  TreeRotationBlend tree_blend_;    // 3D with rotation_jumps_ > 0: rotations blended along a tree
  int rotation_disagreements_ = 0;
  std::vector<int> component_;      // per vertex: connected part (-1 when in no element)
  int num_components_ = 0;
};

}  // namespace strictmin
