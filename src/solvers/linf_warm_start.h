#pragma once
// A warm start for a sequence of L-infinity solves of one program structure whose constant
// terms change a little between solves: local-global's global steps (the targets R_T move
// with each local step) and the steps within one level of direct. Private to the solvers.
//
// The dual of the cone program does not depend on the targets (M^T z + c = 0 involves only
// the Jacobian operators and the heads' k coefficients, docs/maths.md section 3), so the
// last dual iterate of the previous solve is (nearly) dual feasible for the next one and its
// objective is already close to the next optimum: the interior-point method then starts a
// few iterations from the end instead of from a generic centred point. To keep the start
// centred enough, each cone's head of the kept dual is raised a little (linf_main_solve.cpp,
// warm_initialize), and the primal k starts just above the start map's maximum.
#include <Eigen/Core>

#include "strictmin/problem/problem.h"
#include "strictmin/solvers/linf.h"
#include "strictmin/solvers/result.h"

namespace strictmin {

struct LinfWarmStart {
  Eigen::VectorXd z, y;  // the last interior-point dual iterate (cones, equalities)
  long cone_size = -1;   // the program's shape it belongs to
  long num_eq = -1;
  // Direct's levels: programs of changing shape on one problem's elements (pinned elements
  // leave, fixed ones become bounded, the moving region shrinks). With element_z set (#E rows
  // of kElementDualColumns), the last dual iterate is kept per element instead: row e holds
  // element e's cone (head first; NaN where the element was not in the program), and the
  // next program takes each of its element cones from its element's row, when at least half
  // of them have one (linf_main_solve.cpp, warm_initialize; docs/strict.md, "Warm levels").
  // z and y above are then unused.
  static constexpr int kElementDualColumns = 10;  // the largest element cone: a tet's 1 + 9
  Eigen::MatrixXd element_z;
  bool by_element() const { return element_z.size() > 0; }
  // The relative change of the start map's maximum expected in the next solve (the caller's
  // last relative change); k starts this far above the maximum (at least 1e-4, at most 1e-2).
  double expected_change = 1e-2;
  bool fits(long cones, long eqs) const { return cone_size == cones && num_eq == eqs && z.size() == cones; }
  // After a large change (the first steps from a far start) the kept dual is a worse start
  // than a centred one: boy.mesh's second step took 13 interior-point iterations warm, about
  // 10 cold; warm only below a 5% change (boy: 15.0 against 16.6 CPU s in all).
  static constexpr double kLargestChange = 0.05;
  bool close_enough() const { return expected_change <= kLargestChange; }
};

// solve_linf, started from *warm when it fits the program (then updated with this solve's
// last dual iterate); warm == nullptr is solve_linf itself.
Result solve_linf_warm(const Problem& problem, const LinfOptions& options, LinfWarmStart* warm);

}  // namespace strictmin
