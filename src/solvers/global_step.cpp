#include "global_step.h"
#include "no_flips_step.h"

#include <algorithm>
#include <cmath>

namespace strictmin {
namespace {
// The l2 step inside the cones: its energy to this relative gap (and residuals).
constexpr double kEnergyStepGap = 1e-6;
}  // namespace

GlobalStep::GlobalStep(const Problem& p, const SolverOptions& solver, bool no_flips, bool constrained_steps,
                       bool warm_start)
    : solver_(solver),
      constrained_steps_(constrained_steps),
      energy_cone_steps_(solver.method == Method::L2 && constrained_steps && steps_without_new_flips_apply(p)) {
  if (solver.method == Method::Relax)
    sweeper_ = std::make_unique<RelaxSweeper>(p, solver.relax.accept_tolerance, no_flips);
  else if (solver.method == Method::L2 && !p.has_equalities() && !energy_cone_steps_)  // (unused by cone steps)
    l2_ = std::make_unique<L2Solver>(p);
  else if (solver.method == Method::Linf && warm_start)
    warm_ = std::make_unique<LinfWarmStart>();
}

Result GlobalStep::run(Problem& p, const Eigen::MatrixXd& X, double gap, double expected_change) const {
  Result r;
  if (sweeper_) {
    r.positions = X;
    IterationRecord sweep;
    sweep.iteration = 1;
    sweep.largest_move = sweeper_->sweep(p, r.positions);
    r.history.push_back(sweep);
    r.iterations = 1;
    return r;
  }
  // l2 under --no-flips: the least energy inside the orientation-preserving cones around X
  // (no_flips_step.h), where cutting the plain step back stalled (fish from Tutte: 26.09 ->
  // 25.79, against 5.53 without the constraint).
  if (energy_cone_steps_) return step_without_new_flips(p, X, StepObjective::Energy, kEnergyStepGap);
  if (l2_) {
    r.status = l2_->status();
    r.message = l2_->message();
    r.positions = l2_->solve(p);
    r.iterations = 1;
    return r;
  }
  // Start from the current map (solve_linf takes it when it beats the L2 map).
  p.positions = X;
  SolverOptions s = solver_;
  if (s.method == Method::Linf && gap > s.linf.gap_tolerance) {
    s.linf.gap_tolerance = gap;
    s.linf.acceptable_gap_tolerance = std::max(s.linf.acceptable_gap_tolerance, gap);
  }
  if (s.method == Method::Linf && constrained_steps_ && linf_without_new_flips_applies(p, s.linf))
    return linf_without_new_flips(p, X, s.linf.gap_tolerance);
  if (s.method != Method::Linf || !warm_) return run_method(p, s);
  if (!std::isnan(expected_change)) warm_->expected_change = expected_change;
  return solve_linf_warm(p, s.linf, warm_.get());
}

}  // namespace strictmin
