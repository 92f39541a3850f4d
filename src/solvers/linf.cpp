// L-infinity field deviation by our interior-point method (solvers/socp/), in phases:
//   1. check the options, classify the elements (free / bounded / constant), refuse what has
//      no answer (a constant element over its bound, a part of the mesh with no handle);
//   2. build the main program (linf_program.h) and start its symbolic analysis;
//   3. choose the start: the L2 map or the given positions, whichever is better;
//   4. phase 1 when the start misses some fixed bound (linf_phase1.h);
//   5. the main solve, min k, with the active-set policy near the optimum (linf_main_solve.h);
//   6. the status, decided from what the solve knows (result.h);
//   7. optionally (Section 5.1 (a)) the least L2 map among the optima.
// docs/maths.md section 3 has the program and its certificate.
#include "strictmin/solvers/linf.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

#include <tbb/task_group.h>

#include "linf_main_solve.h"
#include "solvers/join_on_exit.h"
#include "linf_phase1.h"
#include "linf_program.h"
#include "linf_warm_start.h"
#include "solvers/linf_relaxed_equalities.h"
#include "element_bounds_check.h"
#include "option_check.h"
#include "strictmin/problem/check_problem.h"
#include "strictmin/problem/equality_basis.h"
#include "strictmin/io/input_error.h"
#include "strictmin/measures/field_deviation.h"
#include "strictmin/problem/parts.h"
#include "strictmin/solvers/timing.h"
#include "solvers/socp/certificate.h"
#include "solvers/socp/fd_program.h"
#include "solvers/socp/ipm.h"
#include "solvers/socp/kkt.h"

namespace strictmin {
namespace {

using namespace linf_detail;


// Step 3: the L2 map or the given positions, whichever misses the bounds less (then has the
// lower maximum). The L2 map ignores the equalities (or meets them by a penalty): it is moved
// onto them first, since the iterates keep what a start misses of them to the method's
// tolerance only (gparam's levels with pinned elements, whose programs have no bounded
// cones left for the previous map to win by: seams to 1e-7 instead of round-off).
Candidate choose_start(const MainProgram& mp, const socp::WeightedLeastSquares& ls) {
  Candidate start = mp.evaluate(onto_equalities(mp.prog, ls.minimizer()));
  const Candidate given = mp.evaluate(mp.problem.free_dofs(mp.problem.positions));
  if (given.x.allFinite() && (given.excess < start.excess || (given.excess == start.excess && given.kmax < start.kmax)))
    start = given;
  return start;
}

// A map kept within the feasibility tolerance of the fixed bounds can end below the certified
// bound, which is for the bounds exactly: where the bounds' multipliers are large (the
// unpinned levels of direct, exact's test solves) a few 1e-9 over them are worth 1e-4 of k
// (docs/strict.md, "Levels within the feasibility tolerance"). Said, with both figures, when
// it is more than round-off.
std::string below_bound_note(const MainProgram& mp, const BestSoFar& best) {
  const double below = best.lower_bound - best.k;
  if (!(below > 1e-12 * std::max(1.0, std::abs(best.k))) || best.x.size() == 0) return "";
  const Eigen::VectorXd d = socp::cone_distortions(mp.prog, best.x);
  double over = 0;
  for (int i = mp.num_free_cones; i < mp.prog.num_element_cones(); ++i) over = std::max(over, d[i] - mp.prog.head_b[i]);
  return "; k is " + format(below) + " below the certified bound of the fixed bounds as given: the map meets them to "
         "the feasibility tolerance (over them by at most " + format(over) + "), and the optimum is that sensitive to them";
}

// Step 6: the status and the stop reason of the main solve.
void decide(const MainProgram& mp, const MainSolve& ms, const LinfOptions& options, double widened, Result& result) {
  const BestSoFar& best = ms.best;
  const double gap = best.k - best.lower_bound;
  const double rel_gap = std::isfinite(gap) ? gap / std::max(1.0, std::abs(best.k)) : kInf;
  StopState stop;
  stop.criterion_met = rel_gap <= options.gap_tolerance;
  stop.within_acceptable = rel_gap <= options.acceptable_gap_tolerance;
  stop.cap_reached = ms.outcome.status == socp::IpmStatus::MaxIterations;
  const bool ipm_failed = ms.outcome.status == socp::IpmStatus::NumericalError;
  // A stall or a failed Newton system still leaves the best map found, which meets every
  // constraint: stalled. Only without any such map is it a numerical error.
  stop.stalled = ms.stalled || ipm_failed;
  stop.failed = ipm_failed && !std::isfinite(best.k);
  result.status = decide_status(stop);

  const std::string figures = "k = " + format(best.k) + ", certified lower bound " + format(best.lower_bound) +
                              ", relative gap " + format(rel_gap);
  const std::string stall = "the certified gap stopped improving (the Newton systems are too ill-conditioned)";
  if (result.status == SolveStatus::Solved)
    result.message = "converged: certified relative gap within " + format(options.gap_tolerance) + " (" + figures + ")";
  else if (result.status == SolveStatus::AlmostSolved)
    result.message = "reduced accuracy: certified relative gap within " + format(options.acceptable_gap_tolerance) +
                     " but not " + format(options.gap_tolerance) + "; " + (ms.stalled ? stall : ms.outcome.message) +
                     " (" + figures + ")";
  else
    result.message = (ms.stalled ? stall : ms.outcome.message) + " (" + figures + ")";
  if (widened > 0) result.message += "; fixed bounds relaxed by " + format(widened) + " (missed by that much at best)";
  result.message += below_bound_note(mp, best);
}

// Step 7 (Section 5.1 (a)): min sum A_T D_T^2 s.t. D_T <= k* + slack; the L-infinity map X
// stays when the second solve stops short.
void polish_least_l2(const MainProgram& mp, const Eigen::VectorXd& x_star, double kstar, Result& result,
                     Eigen::MatrixXd& X, std::chrono::steady_clock::time_point t0) {
  const Problem& p = mp.problem;
  const LinfOptions& options = mp.options;
  const double slack = options.l2_slack * std::max(1.0, kstar);
  socp::ConeProgram q = socp::element_program(p, mp.elems, mp.vertex_dof, mp.num_x, p.positions);
  q.has_k = false;
  q.c_k = 0.0;
  q.head_a.setZero();
  for (int i = 0; i < q.num_element_cones(); ++i)
    q.head_b[i] = (i < mp.num_free_cones ? kstar : mp.prog.head_b[i]) + slack;
  q.quad_weight = q.weight / q.weight.sum();
  socp::restrict_equalities(p, mp.vertex_dof, mp.num_x, p.positions, p.fixed, q);
  socp::IpmState st;
  const double margin = 0.05 * std::max(kstar, 1e-3);
  socp::initialize(q, x_star, 0.0, margin, 2.0 * margin * std::max(kstar, 1e-3) / q.num_cones(), st);
  const socp::IpmSettings settings = ipm_settings(options);
  const int offset = result.history.empty() ? 0 : result.history.back().iteration;
  const auto out = socp::run_ipm(q, st, settings, [&](const socp::IpmState&, const socp::Residuals& r,
                                                      const socp::IpmIteration& info) {
    const double k = mp.max_free(r.tail_norms);
    IterationRecord rec;
    rec.iteration = offset + info.iteration;
    rec.max_distortion = k;
    rec.lower_bound = result.lower_bound;
    rec.certified_gap = (k - result.lower_bound) / std::max(1.0, std::abs(k));
    rec.time_s = seconds_since(t0);
    result.history.push_back(rec);
    if (options.progress) options.progress(rec);
    return socp::default_converged(r, settings);
  });
  result.iterations += out.iterations;
  if (out.status == socp::IpmStatus::MonitorStopped) {
    X = p.with_free_dofs(st.x);
    // The message so far describes the L-infinity map; say what the returned map is.
    result.message += "; then the least L2 map among those within " + format(slack) + " of k* = " + format(kstar) +
                      " (its maximum " + format(mp.evaluate(st.x).kmax) + ")";
  } else {
    // The L-infinity map stays: a usable result whose second criterion was not met.
    result.status = out.status == socp::IpmStatus::MaxIterations ? SolveStatus::MaxIterations : SolveStatus::Stalled;
    result.message = "minimize_l2_among_optimal: " + out.message + " (the L-infinity map is returned)";
  }
}

}  // namespace

bool LinfOptions::is_valid(std::string* why) const {
  return OptionCheck(why)
      .below_one("gap_tolerance", gap_tolerance)
      .below_one("feasibility_tolerance", feasibility_tolerance)
      .at_least("max_iterations", max_iterations, 1)
      .below_one("infeasibility_tolerance", infeasibility_tolerance)
      .positive("l2_slack", l2_slack)
      .below_one("acceptable_gap_tolerance", acceptable_gap_tolerance)
      .below_one("step_fraction", step_fraction)
      .non_negative("regularization", regularization)
      .at_least("refinement_steps", refinement_steps, 0)
      .between("verbose", verbose, 0, 2)
      .ok();
}

Result solve_linf(const Problem& p, const LinfOptions& options) { return solve_linf_warm(p, options, nullptr); }

Result solve_linf_warm(const Problem& p, const LinfOptions& options, LinfWarmStart* warm) {
  const auto t0 = std::chrono::steady_clock::now();
  // 1. Options, element classes, the cases without an answer.
  std::string why;
  if (!options.is_valid(&why)) throw InputError("linf: " + why);
  check_problem(p, "linf");
  const int E = p.num_elements();
  check_element_bounds(options.element_bounds, E, "linf");
  Result result;
  auto finish = [&](const Eigen::MatrixXd& X) {
    result.positions = X;
    result.distortion = field_deviation(p, X);
    result.time_s = seconds_since(t0);
    return result;
  };
  const Eigen::VectorXd& bounds = options.element_bounds;
  const socp::ElementClasses cls = socp::classify_elements(p, bounds);
  if (cls.constant_excess_element >= 0 &&
      cls.constant_excess > options.infeasibility_tolerance * std::max(1.0, bounds[cls.constant_excess_element])) {
    result.status = SolveStatus::Infeasible;
    result.message = "element " + std::to_string(cls.constant_excess_element) +
                     " has every vertex fixed and exceeds its bound k_T by " + format(cls.constant_excess);
    return finish(p.positions);
  }
  // Parts without a fixed vertex may still be held by the equalities (an active-set
  // relaxation's, linf_relaxed_equalities.h); the least squares then includes them.
  const std::vector<int> unanchored = unanchored_components(p);
  const bool held_by_equalities = !unanchored.empty() && p.has_equalities();
  const std::vector<int> loose = held_by_equalities ? free_translations(p) : unanchored;
  if (!loose.empty()) {
    result.status = SolveStatus::NumericalError;
    result.message = "the map is not determined: the part of the mesh containing vertex " + std::to_string(loose.front()) +
                     " has no fixed vertex";
    return finish(p.positions);
  }
  if (p.num_free() == 0 || (cls.free_elements.empty() && cls.bounded_elements.empty())) {
    const double k = cls.constant_max;
    result.lower_bound = k;
    IterationRecord rec;
    rec.max_distortion = k;
    rec.lower_bound = k;
    rec.certified_gap = 0.0;
    rec.time_s = seconds_since(t0);
    result.history.push_back(rec);
    result.message = "nothing to optimise: every vertex is fixed";
    return finish(p.positions);
  }

  // 2. The main program. Its normal equations' ordering and analysis (a third of a second at
  // 100k elements) run on another thread while this one builds the least-squares factor and
  // the start, and the main solve's first certificate. They read only the program's structure,
  // which stays fixed from here (phase 1 and the widening of bounds change bounds only); the
  // wait comes before phase 1 and before any active-set solve, which would compete with it
  // for the cores. (Their orderings may run beside it: METIS calls take turns, ordering.h.)
  MainProgram mp(p, options, cls);
  const socp::IpmSettings settings = ipm_settings(options);  // the normal equations keep a reference
  std::unique_ptr<socp::NormalEquations> normal_equations;
  tbb::task_group analysis;
  const bool prepare = mp.num_x > 0 && mp.has_k;
  if (prepare)
    analysis.run([&] { normal_equations = std::make_unique<socp::NormalEquations>(mp.prog, settings); });
  const JoinOnExit join_on_exit(analysis, prepare);  // every way out waits for the task (it references locals)
  socp::WeightedLeastSquares ls(mp.prog, held_by_equalities);
  if (!ls.ok()) {
    result.status = SolveStatus::NumericalError;
    result.message = "the L2 system is not positive definite (degenerate elements?)";
    return finish(p.positions);
  }

  // 3. The start. One that misses the equalities after its projection onto them may mean
  // that they cannot hold at all: decided exactly, as L2 does, rather than by a solve that
  // could only fail.
  Candidate start = choose_start(mp, ls);
  if (!mp.equalities_met(start.x)) {
    result.message = equalities_contradiction(p, equality_basis(p));
    if (!result.message.empty()) {
      result.status = SolveStatus::Infeasible;
      return finish(p.with_free_dofs(start.x));
    }
  }

  // 4. Phase 1, or the widening of barely missed bounds: a start that misses them by
  // round-off only (the strict minimizers pass maps that met them when evaluated on the whole
  // mesh, and bounds widened to exactly those values) keeps its place, the bounds widened by
  // that excess instead; a phase 1 from such a start ends no closer and costs a solve.
  double widened = 0;
  std::string phase1_note;
  if (!cls.bounded_elements.empty() && start.excess > 0 && start.excess <= 1e-12 * mp.bound_scale()) {
    widened = start.excess;
  } else if (!cls.bounded_elements.empty() && start.excess > 0) {
    analysis.wait();
    const Phase1 ph = run_phase1(p, cls, bounds, p.with_free_dofs(start.x), options);
    result.iterations += ph.iterations;
    if (ph.feasible) {
      start = mp.evaluate(p.free_dofs(ph.X));
      widened = std::max(0.0, start.excess);
    } else if (ph.restricted && mp.has_k) {
      // Undecided only because phase 1 held the seam partners: the main method starts from
      // the map that misses the bounds instead (its bounded cones' heads raised, a primal
      // residual it removes), moving every vertex; its maps count once they meet them.
      // (Without a free element there is no main method to do that: undecided.)
      phase1_note = "phase 1 could not meet the fixed bounds with the vertices outside the bounded elements held "
                    "(the equalities tie some to them); the main solve started from a map that misses them";
    } else {
      result.status = ph.certified ? SolveStatus::Infeasible : SolveStatus::NumericalError;
      result.message = ph.message;
      return finish(ph.X);
    }
  }
  if (widened > 0) mp.widen_bounds(widened);
  if (!mp.has_k) {
    // Every non-constant element is bounded: the feasible map is the answer.
    result.message = "no free element: returned a map that meets the fixed bounds";
    return finish(p.with_free_dofs(start.x));
  }

  // 5. The main solve.
  Eigen::VectorXd effective_bounds = bounds;
  for (Eigen::Index e = 0; e < effective_bounds.size(); ++e)
    if (socp::has_bound(bounds, static_cast<int>(e))) effective_bounds[e] += widened;
  LinfWarmStart* fitting = warm && warm_start_applies(mp, *warm) ? warm : nullptr;
  // The analysis is waited for after the start's first certificate (solve_main).
  MainSolve ms = solve_main(mp, ls, start, effective_bounds, [&] {
    analysis.wait();
    return normal_equations.get();
  }, result.history, t0, fitting);
  analysis.wait();
  socp::IpmSettings penalty = settings;  // the fallback's (the normal equations keep a reference)
  penalty.eliminate_equalities = false;
  std::string fallback_note;
  if (ms.outcome.status == socp::IpmStatus::NumericalError && normal_equations &&
      normal_equations->eliminates_equalities()) {
    // The eliminated Newton systems could not be factored even with the largest
    // regularization (not seen since an element with two corners on one unknown counts its
    // cross pairs twice, docs/linf.md): solve again with the equalities' penalty (kkt.h).
    const int first_iterations = ms.outcome.iterations;
    normal_equations = std::make_unique<socp::NormalEquations>(mp.prog, penalty);
    ms = solve_main(mp, ls, start, effective_bounds, [&] { return normal_equations.get(); }, result.history, t0,
                    nullptr);
    result.iterations += first_iterations;
    fallback_note = "the eliminated Newton systems could not be factored after " + std::to_string(first_iterations) +
                    " iterations; solved again with the equalities' penalty";
  }
  if (warm) keep_dual(mp, ms, *warm);  // the next solve's warm start, unless this one failed
  const BestSoFar& best = ms.best;
  result.iterations += ms.outcome.iterations;
  // Every distortion is a norm, so 0 bounds the optimum too (a dual bound of -4e-30 on a map
  // of zero distortion is round-off).
  result.lower_bound = std::max(0.0, std::min(best.lower_bound, best.k));
  if (best.element_multipliers.size() == E) {
    result.multipliers = best.element_multipliers;
  } else if (best.multipliers.size() > 0) {
    result.multipliers = Eigen::VectorXd::Zero(E);
    for (size_t i = 0; i < mp.elems.size(); ++i)
      result.multipliers[mp.elems[i]] = best.multipliers[static_cast<Eigen::Index>(i)];
  }

  // 6. The status. Without any iterate meeting the bounds, the start (which meets them up to
  // the widening) is the map.
  decide(mp, ms, options, widened, result);
  if (!fallback_note.empty()) result.message += "; " + fallback_note;
  if (!phase1_note.empty()) result.message += "; " + phase1_note;
  Eigen::MatrixXd X = p.with_free_dofs(std::isfinite(best.k) ? best.x : start.x);

  // 7. The least L2 map among the optima.
  if (options.minimize_l2_among_optimal && result.status == SolveStatus::Solved)
    polish_least_l2(mp, best.x, best.k, result, X, t0);
  return finish(X);
}

}  // namespace strictmin
