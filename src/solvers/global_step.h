#pragma once
// The global step of local-global (paper Section 5.4): the chosen method with the targets
// fixed, run from the current map. Keeps what can be reused across steps: the L2 matrix's
// factorization (only the right-hand side changes with the targets, Liu et al. 2008) and
// the relaxation's rings and colouring.
#include <Eigen/Core>
#include <memory>

#include "strictmin/problem/problem.h"
#include "strictmin/solvers/l2.h"
#include "strictmin/solvers/relax.h"
#include "strictmin/solvers/result.h"
#include "strictmin/tasks/method.h"
#include "linf_warm_start.h"

namespace strictmin {

class GlobalStep {
 public:
  // relax: one sweep per step (its rings in the kernel when no_flips); l2: one
  // factorization for every step; the other methods: a solve from the current map.
  // constrained_steps: linf and l2 steps on planar maps and tets stay inside the
  // orientation-preserving cones around the current map (no_flips_step.h; local-global's own
  // no_flips, not relax's);
  // warm_start: linf steps start from the previous step's dual (linf_warm_start.h).
  GlobalStep(const Problem& problem, const SolverOptions& solver, bool no_flips, bool constrained_steps,
             bool warm_start);
  // The step for the problem's current targets from the map X (#V by n). gap > 0 loosens a
  // linf solve's gap tolerance to it (an inexact early step).
  // expected_change: the last relative change of the maximum (NaN: unknown), how far above
  // the start's maximum a warm-started linf step begins.
  Result run(Problem& problem, const Eigen::MatrixXd& X, double gap, double expected_change) const;
  bool is_sweep() const { return static_cast<bool>(sweeper_); }
  // The next linf step starts cold (a centred point) instead of from the last dual.
  void forget_warm_start() const {
    if (warm_) *warm_ = LinfWarmStart();
  }

 private:
  SolverOptions solver_;
  bool constrained_steps_ = false;  // linf, l2: the step inside the orientation-preserving cones
  bool energy_cone_steps_ = false;  // l2 under constrained_steps_ where the cones apply (no L2 factorization)
  std::unique_ptr<L2Solver> l2_;
  std::unique_ptr<RelaxSweeper> sweeper_;
  // linf: the previous step's dual iterate, the next step's warm start (linf_warm_start.h).
  std::unique_ptr<LinfWarmStart> warm_;
};

}  // namespace strictmin
