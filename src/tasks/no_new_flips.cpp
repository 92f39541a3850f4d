#include "tasks/no_new_flips.h"

#include <algorithm>
#include <chrono>
#include <string>

#include "solvers/no_flips_step.h"
#include "strictmin/io/input_error.h"
#include "strictmin/measures/field_deviation.h"
#include "strictmin/solvers/no_flips.h"
#include "strictmin/solvers/relax.h"
#include "strictmin/solvers/timing.h"

namespace strictmin {

void steps_without_new_flips(const Problem& problem, const Eigen::MatrixXd& start, StepObjective objective,
                             const LinfOptions& options, Result& result, int max_steps, double relative_change) {
  // Each step is one of a sequence around a moving map: its optimum is needed roughly only
  // (a step that stops short, still lower, is kept; the next one goes on from it).
  constexpr double kStepGap = 1e-2;
  const auto t0 = std::chrono::steady_clock::now();
  const double unconstrained_time = result.time_s;
  if (!result.usable() || flips_added(problem, start, result.positions) == 0) return;
  cut_back_result(problem, start, result);
  const std::string cut = result.message;
  const bool maximum = objective == StepObjective::Maximum;
  const char* measured = maximum ? "maximum" : "L2 energy";
  auto value = [&](const Eigen::VectorXd& d) {
    return maximum ? (d.size() ? d.maxCoeff() : 0.0) : weighted_energy(problem, d);
  };
  Eigen::MatrixXd X = result.positions;
  double current = value(result.distortion);
  SolveStatus status = SolveStatus::MaxIterations;
  std::string reason = "the cap of " + std::to_string(max_steps) + " steps";
  int steps = 0;
  double last_change = 1;
  while (steps < max_steps) {
    const double gap = std::max(options.gap_tolerance, std::min(kStepGap, 0.1 * last_change));
    // (No step's own bound: the sequence keeps the unconstrained solve's, which bounds every map.)
    const Result step = step_without_new_flips(problem, X, objective, gap, gap, /*certify=*/false);
    ++steps;
    const double next = value(step.distortion);
    const double change = current > 0 ? (current - next) / current : 0.0;
    X = step.positions;
    current = next;
    last_change = change;
    IterationRecord rec;
    rec.iteration = steps;
    rec.max_distortion = step.distortion.size() ? step.distortion.maxCoeff() : 0.0;
    if (maximum) rec.lower_bound = result.lower_bound;
    rec.relative_change = change;
    rec.inner_iterations = step.iterations;
    rec.time_s = unconstrained_time + seconds_since(t0);
    result.history.push_back(rec);
    if (options.progress) options.progress(rec);
    // A step that stopped short but lowered the objective is kept, and the next
    // one goes on from it; the steps end when one no longer lowers it (it
    // returns X when it cannot).
    if (!(change >= relative_change)) {
      const bool converged = step.status == SolveStatus::Solved;
      status = converged ? SolveStatus::Solved : SolveStatus::Stalled;
      reason = "the " + std::string(measured) + " changed by " + std::to_string(change) + " (relative, below " +
               std::to_string(relative_change) + ")" +
               (converged ? "" : " in a step that stopped short: " + step.message);
      break;
    }
  }
  result.positions = X;
  result.distortion = field_deviation(problem, X);
  result.status = status;
  result.iterations += steps;
  result.message =
      cut + "; then " + std::to_string(steps) + (maximum ? " L-infinity" : " L2") +
      " steps inside the orientation-preserving cones around the map, stopped "
      "by " +
      reason + " (maximum " + std::to_string(result.distortion.size() ? result.distortion.maxCoeff() : 0.0) +
      (maximum ? "; the unconstrained optimum's certified bound " + std::to_string(result.lower_bound) : "") + ")";
  result.time_s = unconstrained_time + seconds_since(t0);
}

void remove_added_flips(const Problem& problem, const Eigen::MatrixXd& start, Method method, const LinfOptions& options,
                        Result& result) {
  if (method == Method::Linf && linf_without_new_flips_applies(problem, options))
    steps_without_new_flips(problem, start, StepObjective::Maximum, options, result);
  else if (method == Method::L2 && steps_without_new_flips_apply(problem))
    steps_without_new_flips(problem, start, StepObjective::Energy, options, result);
  else
    cut_back_result(problem, start, result);
}

Result relax_after(const Problem& p, const SolverOptions& o, const Result& start) {
  if (!start.usable()) return start;
  Result r = relax(p, start.positions, o.relax);
  r.time_s += start.time_s;
  r.lower_bound = start.lower_bound;
  if (!start.ok()) {  // the start's shortfall stays visible
    r.status = worse_status(r.status, start.status);
    r.message = "initial " + method_name(o.relax_init) + ": " + start.message + "; " + r.message;
  }
  return r;
}

Result relax_without_new_flips(const Problem& p, const Eigen::MatrixXd& start_map, const SolverOptions& o) {
  if (o.relax_init == Method::Relax) throw InputError("relax cannot start from relax (--init l2|lp|irls|linf)");
  SolverOptions init = o;
  init.method = o.relax_init;
  Result start = run_method(p, init);
  if (!start.usable()) return start;
  SolverOptions sweeps = o;
  sweeps.relax.no_flips = true;
  // First the sweeps from the start method's own map, inside the kernels of its positive
  // elements: its flipped ones are free to turn back, and when none is left flipped (against
  // start_map) that map is the answer. It can be the better one: the steps below stay near
  // flip-free maps all the way (a squeezed, turned tet bar: 2.000 here, 2.457 there).
  if (flips_added(p, start_map, start.positions) > 0) {
    Result swept = relax_after(p, sweeps, start);
    if (swept.usable() && flips_added(p, start_map, swept.positions) == 0) {
      swept.message = "no flip left by the sweeps from the start method's map; " + swept.message;
      return swept;
    }
  }
  remove_added_flips(p, start_map, init.method, init.linf, start);
  Result r = relax_after(p, sweeps, start);
  // How the start was made flip-free (relax_after says it only for a start that fell short).
  if (start.ok()) r.message = "initial " + method_name(init.method) + ": " + start.message + "; " + r.message;
  return r;
}

Result run_method_without_new_flips(const Problem& p, const Eigen::MatrixXd& start_map, const SolverOptions& o) {
  if (o.method == Method::Relax) return relax_without_new_flips(p, start_map, o);
  Result r = run_method(p, o);
  remove_added_flips(p, start_map, o.method, o.linf, r);
  return r;
}

}  // namespace strictmin
