#pragma once
// The paper's Section 7 measures as convex cones for fixed per-triangle frames (docs/maths.md,
// "Section 7 measures as convex constraints"; Lipman 2012, Aigerman & Lipman 2013).
//
// In 2D, J = A + B with A conformal and B anticonformal, represented by the 2-vectors
//   a = ((J00 + J11)/2, (J10 - J01)/2),   b = ((J00 - J11)/2, (J10 + J01)/2),
// sigma1 = |a| + |b|, sigma2 = |a| - |b|. With a unit frame r_T per triangle, |a| is replaced
// by the linear <a, r_T> <= |a|, which makes each constraint a second-order cone:
//   qc  (k = (K-1)/(K+1)):  |b| <= k_T <a, r_T>
//   iso (S):                |a| <= u_T,  |b| <= S_T - u_T   (|a| + |b| <= S_T, u_T auxiliary)
//                           |b| <= <a, r_T> - 1/S_T          (sigma2 >= 1/S_T)
// Every such map has <a, r_T> >= |b|, so |a| >= |b| and det J = |a|^2 - |b|^2 >= 0: feasible
// maps are orientation-preserving (strictly, when the cone holds strictly).
//
// The feasibility question "do some positions meet every cone at these levels?" is posed with
// a slack (every cone's head + tau, minimize tau, tau >= -cap): feasible iff the optimum is
// negative, never relying on an infeasibility certificate at the boundary.
#include <Eigen/Core>
#include <vector>

#include "strictmin/measures/measures.h"
#include "strictmin/problem/problem.h"
#include "solvers/qc/sparse_socp.h"

namespace strictmin::qc {

// The per-triangle affine maps x -> a_T, b_T over the free dofs (x laid out as
// Problem::free_index), for the elements with a free vertex.
struct ConformalParts {
  std::vector<int> element;                   // active element -> problem element
  Eigen::SparseMatrix<double, Eigen::RowMajor> A, B;  // 2 rows per active element
  Eigen::VectorXd a0, b0;                     // offsets (the fixed vertices' share)
  int num_x = 0;
  // The cone programs' map variables are y = x / map_scale, in units of the rest pose's
  // length (1/map_scale = the RMS of A's coefficients), so that the normal equations' map
  // columns have comparable scales whatever the mesh's units.
  double map_scale = 1;
  int count() const { return static_cast<int>(element.size()); }
};

// Appends c * (row r of M) to the triplets of row out_row (the cone programs' rows are built
// from rows of ConformalParts::A and B).
void add_row(const Eigen::SparseMatrix<double, Eigen::RowMajor>& M, int r, double c, int out_row,
             std::vector<Eigen::Triplet<double>>& t);

// Throws InputError for anything but 2D maps of triangles (image_dim = domain_dim = 2) or for
// linear equalities (seams), which these measures do not support.
ConformalParts conformal_parts(const Problem& problem);

// a and b of every active element at x (2 per element, stacked).
void evaluate_ab(const ConformalParts& parts, const Eigen::VectorXd& x, Eigen::VectorXd& a, Eigen::VectorXd& b);

// Frames r_T = a_T / |a_T| of the map x ((1, 0) where a_T = 0).
Eigen::VectorXd frames_of(const ConformalParts& parts, const Eigen::VectorXd& x);

// The frame-relative value of the measure on each active element (the quantity the cones
// bound): qc: |b| / <a, r> as K = (1 + t)/(1 - t) with t = |b| / <a, r> (+inf when
// <a, r> <= |b|); iso: max(|a| + |b|, 1 / (<a, r> - |b|)) (+inf when <a, r> <= |b|).
// Never below the true measure (<a, r> <= |a|).
Eigen::VectorXd frame_values(Measure m, const ConformalParts& parts, const Eigen::VectorXd& frames,
                             const Eigen::VectorXd& x);

// qc: K <-> k = (K - 1)/(K + 1) (K = +inf <-> k = 1).
double k_of_K(double K);
double K_of_k(double k);

// The slack program for levels `level` (one per active element, in measure units: K for qc,
// S for iso). Variables: y = x / parts.map_scale (num_x), then iso's u_T (one per active element), then tau.
// Element T's cones are relaxed by tau * slack_scale[T] (empty: 1): any positive scales give
// the same feasible levels (tau <= 0), and scales that make the slack comparable across the
// elements make its optimum sensitive to the level, so that levels close below the optimum
// are still certified (slack_scales).
SparseSocp slack_program(Measure m, const ConformalParts& parts, const Eigen::VectorXd& frames,
                         const Eigen::VectorXd& level, double tau_cap, const Eigen::VectorXd& slack_scale = {});

// The slack scales for frames taken from the map x: qc, |a_T| (the cone |b| <= k <a, r> is
// homogeneous in the map's local scale, so the slack is measured relative to it: near the
// optimum, tau then moves with k at a rate of about one, not |a_T| of the active elements);
// at least 1e-6 of the largest. iso (levels of absolute size): 1.
Eigen::VectorXd slack_scales(Measure m, const ConformalParts& parts, const Eigen::VectorXd& x);
int slack_index(Measure m, const ConformalParts& parts);  // index of tau among the variables
// A starting vector for the slack program from the map x (iso: u_T = |a_T|, tau = 0).
Eigen::VectorXd slack_start(Measure m, const ConformalParts& parts, const Eigen::VectorXd& x);

// iso for fixed frames as one program, no bisection (docs/measures.md, "iso in one program"):
//   minimize S  subject to, for every free active element T,
//     |a_T| <= u_T,  |b_T| <= S - u_T,  |b_T| <= <a_T, r_T> - v_T,  v_T S >= 1,
//   the last a rotated cone, written as the 3-cone (v_T + S, v_T - S, 2) ((v+S)^2 - (v-S)^2 = 4vS);
//   for the bounded elements (bounds[i] >= 0: direct's fixed levels S_i) the first three with
//   S_i in place of S and 1/S_i in place of v_T; and S >= 1 (iso is never below 1; keeps S
//   bounded when every element is bounded). Its optimum is the least level of the
//   bisection's slack program (the same maps meet both at the same S), in one solve.
// Variables: y = x / parts.map_scale (num_x), u (one per active element), v (one per free
// active element), S.
struct IsoProgram {
  SparseSocp program;
  std::vector<int> v_index;  // per active element: its v's variable index, -1 when bounded
  int s_index = 0;           // index of S among the variables
  // Per cone, its head's bound on the maps with S <= S_max: S_max * head_per_s + head_const
  // (u, S - u, <a, r> - v <= S; v + S <= 2 S; a bounded element's heads <= S_i).
  Eigen::VectorXd head_per_s, head_const;
  Eigen::VectorXd head_bounds(double s_max) const { return s_max * head_per_s + head_const; }
};
IsoProgram iso_program(const ConformalParts& parts, const Eigen::VectorXd& frames, const Eigen::VectorXd& bounds);
// A starting vector from the map x: u_T = |a_T|, v_T = <a_T, r_T> - |b_T| (at least 1e-3 of its largest), S = s0.
Eigen::VectorXd iso_start(const IsoProgram& program, const ConformalParts& parts, const Eigen::VectorXd& frames,
                          const Eigen::VectorXd& x, double s0);

}  // namespace strictmin::qc
