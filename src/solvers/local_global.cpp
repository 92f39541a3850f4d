#include "strictmin/solvers/local_global.h"
#include "strictmin/problem/check_problem.h"
#include "strictmin/solvers/timing.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>

#include "strictmin/io/input_error.h"
#include "strictmin/measures/measures.h"
#include "strictmin/measures/field_deviation.h"
#include "strictmin/solvers/l2.h"
#include "strictmin/solvers/no_flips.h"
#include "strictmin/solvers/relax.h"
#include "strictmin/solvers/interrupt.h"
#include "anderson.h"
#include "global_step.h"
#include "local_targets.h"
#include "relax_sweep.h"
#include "option_check.h"
#include "io/text_parse.h"

namespace strictmin {
namespace {

// The largest distortion over the elements without a fixed bound (all of them unless a
// direct level passes bounds): the quantity the global step minimizes.
double max_of(const Eigen::VectorXd& d, const Eigen::VectorXd& bounds) {
  double m = 0;
  for (Eigen::Index e = 0; e < d.size(); ++e)
    if (bounds.size() == 0 || !(bounds(e) >= 0)) m = std::max(m, d(e));
  return m;
}

// By how much the distortion exceeds the fixed bounds at worst (-inf: no bounded element).
double bound_excess(const Eigen::VectorXd& d, const Eigen::VectorXd& bounds) {
  double m = -std::numeric_limits<double>::infinity();
  for (Eigen::Index e = 0; e < bounds.size(); ++e)
    if (bounds(e) >= 0) m = std::max(m, d(e) - bounds(e));
  return m;
}

// A map whose distortion is zero to rounding (kZeroDistortion, field_deviation.h: a rigid or
// similar map reached exactly) ends local-global: the relative change is round-off there.

// The objective the safeguard compares: the area-weighted energy sum A_T D_T^2 for l2 (what
// its global step minimizes), the maximum otherwise.
double objective(const Problem& p, const Eigen::VectorXd& d, const Eigen::VectorXd& bounds, bool energy) {
  return energy ? p.weights.dot(d.cwiseProduct(d)) : max_of(d, bounds);
}

// relax's sweeps with local steps and --move-tolerance > 0: the sweep moved no vertex by the
// tolerance, relax's own criterion (relax.cpp); without a tolerance every sweep runs.
bool sweep_settled(const GlobalStep& step, const RelaxOptions& relax, const IterationRecord& record) {
  return step.is_sweep() && relax.move_tolerance > 0 && record.largest_move < relax.move_tolerance;
}

// Why relax's sweeps with local steps ended without settling: all ran, or (with
// --move-tolerance > 0) the cap came first, as relax without local steps says it.
std::string sweeps_run_reason(bool move_tolerance_given, int sweeps, StopState& stop) {
  if (!move_tolerance_given) {
    stop.criterion_met = true;
    return "ran the requested " + std::to_string(sweeps) + " sweeps with local steps";
  }
  stop.cap_reached = true;
  if (sweeps == 0) return "no sweep ran (--sweeps 0), so the move tolerance could not be checked";
  return "reached the sweep cap (" + std::to_string(sweeps) +
         ") with vertices still moving more than the move tolerance (sweeps with local steps)";
}

// The loose gap of an inexact early linf step: half the last relative change of the
// maximum, at most 1e-2 (the step's maximum is then within that of the step's optimum, so
// the change it reports is still meaningful).
double early_gap(double last_change) {
  if (std::isnan(last_change)) return 1e-2;
  return std::min(1e-2, 0.5 * last_change);
}

// A global step that stopped short of its own tolerance (an L-infinity solve whose Newton
// systems became too ill-conditioned: direct's ARAP levels, where many bounded elements sit
// at their bounds) does not end the loop while retries remain: the loop goes on with the
// next step from a cold start (a fresh centred point instead of the last dual, whose
// multipliers on the bounded cones were what grew), so that it ends on a step that met its
// tolerance. Cow's ARAP direct (Figure 17): level 5's last step stalled at a relative gap of
// 6.8e-5 warm and solved cold (docs/strict.md, "Global steps that stop short").
constexpr int kShortStepRetries = 2;

// True when the loop should take another step (steps_remain: the cap is not reached) after
// the step with status `status`; the retry's step then starts cold.
bool retry_short_step(SolveStatus status, bool steps_remain, const GlobalStep& step, int& retries_left) {
  if (status == SolveStatus::Solved || !steps_remain || retries_left <= 0) return false;
  --retries_left;
  step.forget_warm_start();
  return true;
}

// The local-global iterations from out.positions: local step, then one global step (one
// sweep for relax, a solve otherwise), optionally accelerated (Anderson, safeguarded) and cut
// back to add no flips, until the cap or a small relative change of the max.
// The status: the loop's own (converged, almost at the cap, or the cap) combined with the
// last global step's, so that a global solve that stopped short shows (result.h).
Result iterate(Problem& p, Result out, const SolverOptions& solver, const LocalGlobalOptions& o,
               std::chrono::steady_clock::time_point t0) {
  const GlobalStep step(p, solver, o.no_flips || solver.relax.no_flips, o.no_flips, o.warm_start);
  const Eigen::VectorXd& bounds = solver.linf.element_bounds;
  const bool fixed_count = o.relative_change < 0;  // relax sweeps: run them all
  const bool energy = solver.method == Method::L2;
  const bool accelerate = o.acceleration_window > 0 && !step.is_sweep();
  bool inexact = o.inexact_early_steps && solver.method == Method::Linf;
  Anderson anderson(std::max(1, o.acceleration_window));
  int accepted = 0, rejected = 0;
  // The targets of the current map (its local step) and its distortion, in one pass.
  const Eigen::VectorXd start_distortion = local_targets(p, out.positions, o, &p.targets);
  double previous = max_of(start_distortion, bounds);
  // The stopping test follows the method's own objective: the maximum, or l2's energy (its
  // maximum rises and falls from step to step, and stopping where two happened to agree made
  // the result depend on the vertex order).
  double previous_energy = energy ? objective(p, start_distortion, bounds, true) : 0.0;
  double last_cut_back = 1;  // --no-flips: the fraction of the last global step taken
  Eigen::MatrixXd targets;  // the local step of the candidate map
  // Extrapolated targets where the maximum is the objective the guarantee is about (linf and
  // direct's levels); l2's fixed point is reached faster by Anderson on its energy.
  // Interpolation's targets (rotations of blended shapes, o.shapes) are not extrapolated.
  const double beta = solver.method == Method::Linf && o.shapes.size() == 0 ? o.target_extrapolation : 0.0;
  Eigen::MatrixXd plain_targets = p.targets;  // the local step of the current map
  bool extrapolated = false;                  // p.targets are extrapolated from plain_targets
  int extrapolations_rejected = 0;
  double last_change = kNotApplicable;
  SolveStatus last_global = SolveStatus::Solved;
  std::string last_global_message;
  int short_step_retries = kShortStepRetries;
  StopState stop;
  std::string reason;
  if (previous <= kZeroDistortion) {
    stop.criterion_met = true;
    char max[32];
    std::snprintf(max, sizeof max, "%.3g", previous);
    reason = std::string("converged: the start's distortion is zero to rounding (max ") + max + ")";
  }
  for (int it = 1; it <= o.max_iterations && reason.empty(); ++it) {
    check_interrupt();  // solvers/interrupt.h
    const double gap = inexact ? early_gap(last_change) : 0.0;
    Result r = step.run(p, out.positions, gap, last_change);
    if (!r.usable()) {
      out.status = r.status;
      out.message = "global step " + std::to_string(it) + ": " + r.message;
      out.distortion = local_targets(p, out.positions, o, nullptr);
      out.time_s = seconds_since(t0);
      return out;
    }
    if (!step.is_sweep()) out.lower_bound = r.lower_bound;
    Eigen::MatrixXd next = std::move(r.positions);
    last_cut_back = 1;
    if (o.no_flips && !step.is_sweep()) next = cut_back_to_no_new_flips(p, out.positions, next, &last_cut_back);
    // The plain map's local step. l2 with acceleration may not need it (below), so it is formed
    // on demand there; the other methods judge the step by its maximum first.
    Eigen::VectorXd d;
    const auto plain = [&]() -> const Eigen::VectorXd& {
      if (d.size() == 0) d = local_targets(p, next, o, &targets);
      return d;
    };
    const bool plain_on_demand = energy && accelerate;  // l2: no extrapolation, no rise check
    double current = plain_on_demand ? previous : max_of(plain(), bounds);
    if (extrapolated && current > previous) {
      // The extrapolated targets led higher: the plain step instead (the guarantee).
      p.targets = plain_targets;
      extrapolated = false;
      ++extrapolations_rejected;
      continue;
    }
    // An L-infinity global step cannot raise the maximum beyond its tolerance; keep the
    // better map if rounding (or a loose early step) says otherwise.
    if (solver.method == Method::Linf && current > previous) {
      if (inexact) {
        inexact = false;  // repeat at the solver's own tolerance
        continue;
      }
      if (retry_short_step(r.status, it < o.max_iterations, step, short_step_retries)) continue;  // the same step, cold
      // The rise comes from the step's own tolerance: converged when that step met it,
      // otherwise the step's shortfall is the outcome.
      last_global = worse_status(last_global, r.status);
      if (r.status != SolveStatus::Solved) last_global_message = r.message;
      stop.criterion_met = true;
      reason = "converged: the maximum stopped decreasing";
      break;
    }
    if (accelerate) {
      // Anderson on the free dofs; taken only when no worse than the plain step (its maximum;
      // l2: its energy).
      const Eigen::VectorXd g = p.free_dofs(next);
      const Eigen::VectorXd mixed = anderson.mix(p.free_dofs(out.positions), g);
      if ((mixed - g).squaredNorm() > 0) {
        Eigen::MatrixXd X = p.with_free_dofs(mixed);
        Eigen::MatrixXd accelerated_targets;
        Eigen::VectorXd da = local_targets(p, X, o, &accelerated_targets);
        // A direct level's bounded elements: no further over their bounds than the plain step
        // (the maximum above is over the free elements only).
        const bool admissible =
            da.allFinite() && (!o.no_flips || flips_added(p, out.positions, X) == 0) &&
            (bounds.size() == 0 || bound_excess(da, bounds) <= std::max(0.0, bound_excess(plain(), bounds)));
        const double accelerated = objective(p, da, bounds, energy);
        // l2: first against the plain step's global objective sum A ||J - R||^2 for the step's
        // targets, an upper bound of its energy that needs no local step (the local step is most
        // of an l2 step on tets); the energy still never increases.
        bool take = admissible && energy && accelerated <= objective(p, field_deviation(p, next), bounds, true);
        if (!take) take = admissible && accelerated <= objective(p, plain(), bounds, energy);
        if (take) {
          next = std::move(X);
          d = std::move(da);
          targets.swap(accelerated_targets);
          ++accepted;
        } else {
          ++rejected;
        }
      }
    }
    current = max_of(plain(), bounds);
    last_global = r.status;
    last_global_message = r.message;
    out.positions = std::move(next);
    p.targets.swap(targets);  // the next global step's targets: the local step of the new map
    if (beta > 0) {
      Eigen::MatrixXd before = std::move(plain_targets);
      plain_targets = p.targets;
      extrapolated = extrapolate_targets(p, before, beta, o, p.targets);
    }
    out.iterations = it;
    last_change = previous > 0 ? std::abs(previous - current) / previous : 0.0;
    if (energy) {
      const double current_energy = objective(p, plain(), bounds, true);
      last_change = previous_energy > 0 ? std::abs(previous_energy - current_energy) / previous_energy : 0.0;
      previous_energy = current_energy;
    }
    IterationRecord rec;
    rec.iteration = it;
    rec.max_distortion = current;
    rec.lower_bound = r.lower_bound;
    rec.relative_change = last_change;
    if (step.is_sweep() && !r.history.empty()) rec.largest_move = r.history.back().largest_move;
    if (accelerate) {
      rec.accelerated_accepted = accepted;
      rec.accelerated_rejected = rejected;
    }
    rec.time_s = seconds_since(t0);
    out.history.push_back(rec);
    if (o.progress) o.progress(rec);
    previous = current;
    if (current <= kZeroDistortion) {
      stop.criterion_met = true;
      reason = "converged: the distortion is zero to rounding";
    } else if (sweep_settled(step, solver.relax, rec)) {
      stop.criterion_met = true;
      reason = "converged: no vertex moved more than the move tolerance in sweep " + std::to_string(it) +
               " (sweeps with local steps)";
    } else if (!fixed_count && last_change <= o.relative_change) {
      if (inexact) {
        inexact = false;  // the criterion met with a loose step: certify with a full one
        continue;
      }
      if (retry_short_step(r.status, it < o.max_iterations, step, short_step_retries)) continue;  // one more step, cold
      const std::string measured = energy ? "the L2 energy" : "the maximum";
      if (last_cut_back < 1) {
        // The steps are held back by elements that would flip, not settled at the method's
        // fixed point (l2 --no-flips on fish: Tutte's 26.1 to 25.8 against l2's 5.5).
        stop.stalled = true;
        reason = "stalled: the global steps were cut back to add no flips (the last to " + io_detail::exact_text(last_cut_back) +
                 " of its length), so the relative change of " + measured + " fell below " +
                 io_detail::exact_text(o.relative_change) + " without the local-global fixed point";
      } else {
        stop.criterion_met = true;
        reason = "converged: relative change of " + measured + " below " + io_detail::exact_text(o.relative_change);
      }
    }
  }
  if (fixed_count && reason.empty()) {
    reason = sweeps_run_reason(step.is_sweep() && solver.relax.move_tolerance > 0, o.max_iterations, stop);
  } else if (reason.empty()) {
    stop.cap_reached = true;
    // Almost: the last change within ten times the tolerance (docs/formats.md).
    stop.within_acceptable = last_change <= 10 * o.relative_change;
    reason = "reached the iteration cap (" + std::to_string(o.max_iterations) + "); last relative change " +
             std::to_string(last_change);
  }
  if (beta > 0) reason += "; extrapolated targets rejected " + std::to_string(extrapolations_rejected);
  if (accelerate)
    reason += "; accelerated steps taken " + std::to_string(accepted) + ", rejected " + std::to_string(rejected);
  out.status = worse_status(decide_status(stop), last_global);
  if (last_global != SolveStatus::Solved) reason += "; the last global step: " + last_global_message;
  out.message = reason;
  out.distortion = local_targets(p, out.positions, o, nullptr);
  out.time_s = seconds_since(t0);
  return out;
}

// LocalGlobalOptions::l2_start: l2 local-global from X, its map when its maximum is lower
// and it has no more flipped elements than X.
Eigen::MatrixXd l2_start(const Problem& problem, const Eigen::MatrixXd& X, const SolverOptions& solver,
                         const LocalGlobalOptions& o, std::string* note) {
  SolverOptions l2 = solver;
  l2.method = Method::L2;
  LocalGlobalOptions lo = o;
  lo.progress = nullptr;
  Problem p = problem;
  Result start;
  start.positions = X;
  const Result r = iterate(p, std::move(start), l2, lo, std::chrono::steady_clock::now());
  const Eigen::VectorXd& bounds = solver.linf.element_bounds;
  if (!r.usable() || !(max_of(r.distortion, bounds) < max_of(local_targets(problem, X, o, nullptr), bounds))) return X;
  // A map with more flipped elements than the start leads linf into another basin (cow_disk
  // from Tutte, flip-free: 0.79 instead of 0.567): keep the start then. Fewer is welcome (boy:
  // 11 instead of the L2 fd start's 125, and 9 linf steps instead of 61).
  const auto flipped = [&](const Eigen::MatrixXd& Y) {
    const Eigen::VectorXi positive = positively_oriented(problem, Y);
    return positive.size() - positive.sum();
  };
  const auto flips_l2 = flipped(r.positions), flips_start = flipped(X);
  if (flips_l2 > flips_start) {
    *note = "the l2 local-global map (max " + std::to_string(max_of(r.distortion, bounds)) + ") was not taken as the start: "
            "it has more flipped elements (" + std::to_string(flips_l2) + " against " + std::to_string(flips_start) + "); ";
    return X;
  }
  *note = "started from the l2 local-global map (" + std::to_string(r.iterations) + " steps, max " +
          std::to_string(max_of(r.distortion, bounds)) + "); ";
  return r.positions;
}

}  // namespace

namespace {

// The shapes are read per element: empty, or #E*n by m and finite (NaN shapes made every
// local distortion NaN, which the maximum skipped: "zero to rounding", solved).
void check_shapes(const Problem& p, const LocalGlobalOptions& o) {
  if (o.shapes.size() == 0) return;
  if (o.shapes.rows() != static_cast<Eigen::Index>(p.num_elements()) * p.image_dim || o.shapes.cols() != p.domain_dim)
    throw InputError("local-global: shapes has " + std::to_string(o.shapes.rows()) + " by " +
                     std::to_string(o.shapes.cols()) + " entries, the problem needs " +
                     std::to_string(p.num_elements() * p.image_dim) + " by " + std::to_string(p.domain_dim));
  if (!o.shapes.allFinite()) throw InputError("local-global: shapes is not finite");
}

// What the local step reads: the problem, a map of its size and the shapes.
void check_local_step_input(const Problem& p, const Eigen::MatrixXd& X, const LocalGlobalOptions& o) {
  check_problem(p, "local step");
  check_map(p, X, "local step");
  check_shapes(p, o);
}

}  // namespace

void local_step(Problem& p, const Eigen::MatrixXd& X, const LocalGlobalOptions& o) {
  check_local_step_input(p, X, o);
  local_targets(p, X, o, &p.targets);
}

Eigen::VectorXd local_distortion(const Problem& p, const Eigen::MatrixXd& X, const LocalGlobalOptions& o) {
  check_local_step_input(p, X, o);
  return local_targets(p, X, o, nullptr);
}

bool LocalGlobalOptions::is_valid(std::string* why) const {
  return OptionCheck(why)
      .at_least("max_iterations", max_iterations, 0)
      .that(acceleration_window >= 0 && acceleration_window <= 50,
            "acceleration_window must be in [0, 50] (got " + std::to_string(acceleration_window) + ")")
      .that(!std::isnan(relative_change), "relative_change must be a number (got nan)")
      .that(target_extrapolation >= 0 && target_extrapolation <= 1,
            "target_extrapolation must be in [0, 1] (got " + io_detail::number_text(target_extrapolation) + ")")
      .ok();
}

Result local_global(const Problem& problem, const Eigen::MatrixXd& X0, const SolverOptions& solver,
                    const LocalGlobalOptions& o) {
  const auto t0 = std::chrono::steady_clock::now();
  std::string why;
  if (!o.is_valid(&why)) throw InputError("local-global: " + why);
  check_problem(problem, "local-global");
  check_map(problem, X0, "local-global start");
  if (!solver.is_valid(&why)) throw InputError("invalid solver options: " + why);
  relax_detail::check_no_flips(problem, o.no_flips || solver.relax.no_flips, "local-global");
  check_shapes(problem, o);
  Problem p = problem;
  Result out;
  out.positions = X0;
  for (int v = 0; v < p.num_vertices; ++v)
    if (p.fixed[v]) out.positions.row(v) = p.positions.row(v);
  if (solver.method == Method::Exact)
    throw InputError("--method exact (the exact strict minimizer) is for --measure fd only; under arap or asap use "
                     "--method direct or relax");
  // No new flips: first without the constraint; when that map adds no flip it is the answer
  // (and the better one: the cut-back steps can stall where a step must pass through a flip
  // to get around, dragon from Tutte: 19.3 instead of 0.98). Otherwise run again with every
  // global step cut back. Relax keeps its own guarantee (moves inside the rings' kernels,
  // from its start method's map, which goes through here).
  if (o.no_flips && o.no_flips_try_unconstrained && solver.method != Method::Relax) {
    LocalGlobalOptions unconstrained = o;
    unconstrained.no_flips = false;
    Result free_run = local_global(p, out.positions, solver, unconstrained);
    if (free_run.usable() && flips_added(p, out.positions, free_run.positions) == 0) {
      free_run.message = "no flip added without the constraint; " + free_run.message;
      return free_run;
    }
  }
  std::string start_note;
  if (o.l2_start && solver.method != Method::L2 && solver.method != Method::Relax)
    out.positions = l2_start(p, out.positions, solver, o, &start_note);
  if (solver.method == Method::Relax) {
    // Algorithm 3 improves another method's result (--init, default linf): here that
    // method's own local-global solution. Sweeps alone from a far start stall like any
    // coordinate descent on a maximum (rigid handles end at ARAP ~6e-3 instead of 0).
    if (solver.relax_init == Method::Relax) throw InputError("relax cannot start from relax (--init l2|lp|irls|linf)");
    SolverOptions init = solver;
    init.method = solver.relax_init;
    Result start = local_global(p, out.positions, init, o);
    if (!start.usable()) {
      start.message = "relax start (" + method_name(init.method) + "): " + start.message;
      return start;
    }
    // Then every one of solver.relax.sweeps sweeps, each followed by a local step: relax
    // lowers the levels below the maximum, so the maximum's change says nothing here.
    LocalGlobalOptions sweeps = o;
    sweeps.max_iterations = solver.relax.sweeps;
    sweeps.relative_change = -1;
    out.positions = start.positions;
    Result r = iterate(p, std::move(out), solver, sweeps, t0);
    r.lower_bound = start.lower_bound;
    // The start's shortfall (its local-global cap, say) stays visible.
    if (start.status != SolveStatus::Solved) {
      r.status = worse_status(r.status, start.status);
      r.message = "relax start (" + method_name(init.method) + "): " + start.message + "; " + r.message;
    }
    for (IterationRecord& rec : r.history) rec.iteration += start.iterations;
    start.history.insert(start.history.end(), r.history.begin(), r.history.end());
    r.history = std::move(start.history);
    r.iterations += start.iterations;
    return r;
  }
  if (solver.method == Method::Direct) {
    // Every level of the direct algorithm runs local-global L-infinity iterations; bounds
    // fixed at earlier levels stay valid because the local step never raises a D_T.
    DirectOptions direct = solver.direct;
    // Per-element shapes (interpolation) are indexed by the whole problem's elements, which a
    // level restricted to its moving region renumbers: every level runs on the whole problem
    // (with the region, the tet bar's third level took other elements' shapes and was
    // declared infeasible).
    if (o.shapes.size() != 0) direct.moving_rings = 0;
    p.positions = out.positions;  // the first level starts here
    direct.level_iteration_unit = "local-global steps";
    direct.level_bound_certifies = false;  // a loop stopped short counts with its status (strict.h)
    direct.level_solver = [o](const Problem& level_problem, const LinfOptions& linf, const Eigen::MatrixXd& X) {
      SolverOptions inner;
      inner.method = Method::Linf;
      inner.linf = linf;
      LocalGlobalOptions lo = o;
      lo.progress = nullptr;
      lo.l2_start = false;  // done once, before the first level
      lo.no_flips_try_unconstrained = false;  // the whole run was tried unconstrained already
      return local_global(level_problem, X, inner, lo);
    };
    Result r = solve_direct(p, direct, solver.linf);
    r.message = start_note + r.message;
    r.time_s = seconds_since(t0);
    return r;
  }
  Result r = iterate(p, std::move(out), solver, o, t0);
  r.message = start_note + r.message;
  return r;
}

}  // namespace strictmin
