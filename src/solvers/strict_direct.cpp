#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "strictmin/problem/check_problem.h"
#include "strictmin/problem/subproblem.h"
#include "strictmin/solvers/l2.h"
#include "strictmin/solvers/strict.h"
#include "strictmin/solvers/timing.h"
#include "option_check.h"
#include "strictmin/io/input_error.h"
#include "strictmin/solvers/interrupt.h"
#include "solvers/linf_warm_start.h"
#include "solvers/strict_constants.h"
#include "solvers/strict_pinning.h"

namespace strictmin {
namespace {

// One level on the region that can still change (DirectOptions::moving_rings): the vertices
// within that many rings of the free elements move, the others keep the previous level's
// map; pinned elements leave the program (strict_pinning.h).
Result solve_restricted_level(const Problem& p, const std::vector<char>& movable_element,
                              const Eigen::VectorXd& bounds, const Result& previous, const LinfOptions& linf,
                              const DirectOptions& options, const PinnedElements& pins, const LevelSolver& solve_level,
                              int& moved_vertices, std::vector<int>& immobile, Eigen::MatrixXd* duals,
                              Eigen::MatrixXd* level_duals) {
  std::vector<char> seeds(p.num_vertices, 0);
  for (int e = 0; e < p.num_elements(); ++e)
    if (movable_element[e] && bounds(e) < 0)
      for (int j = 0; j < p.corners(); ++j) seeds[p.elements(e, j)] = 1;
  const std::vector<char> moving = vertices_within_rings(p, seeds, options.moving_rings);
  const PinnedLevel level = pins.level_problem(p, moving, previous.positions);
  moved_vertices = level.sub.problem.num_free();
  return solve_on_level(p, level, bounds, previous, linf, solve_level, &immobile, duals, level_duals);
}

// The levels whose solve stopped short of its tolerance, for one summary at the end (a long
// run on a hard problem has hundreds of them: one message each would swamp the summary).
struct ShortLevels {
  explicit ShortLevels(double reduced_accuracy) : reduced_accuracy_gap(reduced_accuracy) {}
  double reduced_accuracy_gap;  // above this certified gap a level is of reduced accuracy
  int stalled = 0, iteration_limit = 0, reduced = 0, loose = 0;
  int worst_step = 0;
  double worst_gap = 0, worst_k = 0;
  SolveStatus reduced_status = SolveStatus::Solved;  // the worse of the reduced levels' statuses
  std::string first;  // the first one's message

  // A level that stopped short of its own tolerance (certified_gap NaN: it has no certificate).
  void add(int step, const Result& r, double k, double certified_gap) {
    if (r.status == SolveStatus::MaxIterations)
      ++iteration_limit;
    else
      ++stalled;
    if (first.empty()) first = "level " + std::to_string(step) + ": " + r.message;
    note_gap(step, r.status, k, certified_gap);
  }
  // A level that met its own tolerance, which was looser than delta_k / 4 (--gap or
  // --level-gap set so): its band is placed only to within its gap, and the run's criterion
  // (every level within delta_k / 4) is not met, though every level did what it was asked.
  void add_loose(int step, double k, double certified_gap) {
    if (!(certified_gap > reduced_accuracy_gap)) return;
    ++loose;
    note_gap(step, SolveStatus::AlmostSolved, k, certified_gap);
  }
  // The run's status: solved unless some level is of reduced accuracy, else the worse of
  // those levels' statuses (a cap shows as max-iterations): the map is complete, but those
  // levels are known only to within their gaps.
  SolveStatus status() const { return reduced > 0 ? reduced_status : SolveStatus::Solved; }
  std::string message(int levels) const {
    std::string loose_note;
    if (loose > 0) {
      char worst[200];
      std::snprintf(worst, sizeof worst,
                    "%d of %d levels met their own gap but it is above delta_k / 4 (--gap or --level-gap looser "
                    "than that; the largest certified gap %.3g at level %d)",
                    loose, levels, worst_gap, worst_step);
      loose_note = worst;
    }
    const int count = stalled + iteration_limit;
    if (count == 0) return loose_note;
    char worst[160];
    if (std::isinf(worst_gap))
      std::snprintf(worst, sizeof worst, "level %d (k = %.6g) has no certified gap", worst_step, worst_k);
    else
      std::snprintf(worst, sizeof worst, "the largest certified gap %.3g at level %d (k = %.6g)", worst_gap,
                    worst_step, worst_k);
    return std::to_string(count) + " of " + std::to_string(levels) + " levels stopped short of their tolerance (" +
           std::to_string(stalled) + " stalled or almost-solved, " + std::to_string(iteration_limit) +
           " max-iterations) and were used; " + std::to_string(reduced - loose) +
           " of them with reduced accuracy (no certified gap within delta_k / 4); " + worst + "; first: " + first +
           (loose_note.empty() ? "" : "; " + loose_note);
  }

 private:
  void note_gap(int step, SolveStatus status, double k, double certified_gap) {
    // A level without a certified bound is of unknown accuracy: count it as the worst.
    const double gap = std::isnan(certified_gap) ? INFINITY : certified_gap;
    if (gap > reduced_accuracy_gap) {
      ++reduced;
      reduced_status = worse_status(reduced_status, status);
    }
    if (gap > worst_gap || worst_step == 0) {
      worst_step = step;
      worst_gap = gap;
      worst_k = k;
    }
  }
};

// DirectOptions::level_solver's usable result for the level's problem (the whole one or a
// restriction): one of another size was read by the problem's indices, out of bounds.
Result checked_level_result(const Problem& problem, Result r) {
  if (!status_usable(r.status)) return r;  // no map to read (level_map_usable stops the run)
  if (r.positions.rows() != problem.num_vertices || r.positions.cols() != problem.image_dim ||
      r.distortion.size() != problem.num_elements())
    throw InputError("direct: the level solver returned a map of " + std::to_string(r.positions.rows()) + " by " +
                     std::to_string(r.positions.cols()) + " with " + std::to_string(r.distortion.size()) +
                     " distortions for a level of " + std::to_string(problem.num_vertices) + " vertices and " +
                     std::to_string(problem.num_elements()) + " elements");
  return r;
}

// A level's result that the next levels can build on: usable, finite, the problem's size.
bool level_map_usable(const Problem& p, const Result& r, double reached) {
  return r.usable() && r.positions.rows() == p.num_vertices && r.positions.cols() == p.image_dim &&
         r.distortion.size() == p.num_elements() && r.distortion.allFinite() && std::isfinite(reached);
}

}  // namespace

bool DirectOptions::is_valid(std::string* why) const {
  return OptionCheck(why)
      .positive("delta_k", delta_k)
      .non_negative("k_min", k_min)
      .at_least("max_steps", max_steps, 1)
      .that(level_gap < 1, "level_gap must be < 1 (negative: delta_k / 100)")
      .at_least("moving_rings", moving_rings, 0)
      .that(pin_threshold > 0 && pin_threshold <= 1, "pin_threshold must be in (0, 1]")
      .ok();
}

Result solve_direct(const Problem& p, const DirectOptions& options, const LinfOptions& linf_options) {
  const auto t0 = std::chrono::steady_clock::now();
  std::string why;
  if (!options.is_valid(&why)) throw InputError("direct: " + why);
  if (!linf_options.is_valid(&why)) throw InputError("linf: " + why);
  check_problem(p, "direct");
  const std::vector<char> movable = movable_elements(p);
  Eigen::VectorXd bounds = Eigen::VectorXd::Constant(p.num_elements(), -1.0);
  const double constant_max = bound_constant_elements(p, movable, bounds);
  int fixed_total = 0, free_left = 0;
  for (char m : movable) free_left += m;
  LinfOptions linf = linf_options;
  linf.progress = nullptr;
  Result out;
  ShortLevels short_levels(0.25 * options.delta_k);
  std::string stop_message;  // a level that ended the run
  double k = INFINITY;
  out.positions = p.positions;
  if (free_left == 0) return unmovable_answer(p);
  Problem level = p;
  // Pinning needs the field deviation's strict convexity (not the local-global or frame
  // levels' measures); the problem's own equalities (seams) are written on each level.
  const bool pinning = options.pin_essential && !options.level_solver;
  PinnedElements pins(p);
  // Warm levels: the last dual iterate per element (LinfWarmStart::element_z), carried from
  // level to level; the level's solve reads and writes its own elements' rows (warm).
  const bool warm_levels = options.warm_levels && !options.level_solver;
  Eigen::MatrixXd duals;
  if (warm_levels) duals.setConstant(p.num_elements(), LinfWarmStart::kElementDualColumns, NAN);
  LinfWarmStart warm;
  for (int step = 1; free_left > 0 && k > options.k_min && step <= options.max_steps; ++step) {
    check_interrupt();  // solvers/interrupt.h
    linf.element_bounds = bounds;
    if (step == 2) {
      const double level_gap = options.level_gap >= 0 ? options.level_gap : 1e-2 * options.delta_k;
      linf.gap_tolerance = std::max(linf.gap_tolerance, level_gap);
      linf.acceptable_gap_tolerance = std::max(linf.acceptable_gap_tolerance, linf.gap_tolerance);
    }
    // Each level starts from the previous level's map: it meets every fixed bound (they are
    // widened to it below), so the solve needs no phase 1.
    const LevelSolver solve_level = [&](const Problem& problem, const LinfOptions& o, const Eigen::MatrixXd& X) -> Result {
      if (options.level_solver) return checked_level_result(problem, options.level_solver(problem, o, X));
      LinfWarmStart* w = warm_levels ? &warm : nullptr;
      if (&problem != &p) return solve_linf_warm(problem, o, w);  // a sub-problem: its positions are X
      level.positions = X;
      if (w) warm.element_z.swap(duals);  // the whole problem's rows are the level's: lent, not copied
      Result whole = solve_linf_warm(level, o, w);
      if (w) warm.element_z.swap(duals);
      return whole;
    };
    Result r;
    int moved_vertices = -1;
    std::vector<int> immobile;  // free elements that pinned groups hold (strict_pinning.h)
    if (pins.count() == 0 && (step == 1 || options.moving_rings <= 0)) {
      r = solve_level(p, linf, out.positions);
    } else {
      r = solve_restricted_level(p, movable, bounds, out, linf, options, pins, solve_level, moved_vertices, immobile,
                                 warm_levels ? &duals : nullptr, warm_levels ? &warm.element_z : nullptr);
    }
    // Free elements held by pinned groups are constants from now on: they are fixed at their
    // value below, and the level is the optimum over the others (the free elements here).
    std::vector<char> level_free(movable.size(), 0);
    for (int e = 0; e < p.num_elements(); ++e) level_free[e] = movable[e] && bounds(e) < 0;
    for (int e : immobile) level_free[e] = 0;
    // This level's k over its free elements, and how well the solve certified it (with none,
    // nothing moved: the level is exact).
    const bool any_level_free = std::find(level_free.begin(), level_free.end(), 1) != level_free.end();
    const bool sized = r.distortion.size() == p.num_elements();  // else level_map_usable stops below
    double reached = sized && r.distortion.size() ? 0.0 : INFINITY;
    for (int e = 0; sized && e < r.distortion.size(); ++e)
      if (level_free[e]) reached = std::max(reached, r.distortion(e));
    const double gap = any_level_free ? (reached - r.lower_bound) / std::max(1.0, std::abs(reached)) : 0.0;
    // Stop on a map that is not finite or not the problem's size (a level solver's, whatever
    // its status: a "solved" one was read out of bounds and reported solved) and on
    // infeasible (the bounds were met by the previous map: only round-off can say so, and its
    // map is no witness).
    if (!level_map_usable(p, r, reached)) {
      out.status = status_usable(r.status) ? SolveStatus::NumericalError : r.status;
      stop_message = "direct stopped at level " + std::to_string(step) + ": " +
                     (status_usable(r.status) ? "the level's map is not finite or not the problem's size; " : "") +
                     r.message;
      break;
    }
    if (r.status != SolveStatus::Solved) {
      // A level whose solve stopped short still leaves a map that meets every fixed bound
      // (the interior-point iterates stay feasible for them to the solver's tolerance, and
      // the bounds are widened to what it reached below): the levels after it remain
      // well-defined, only this level's value is known less precisely (its certified gap).
      // Use it and go on; the summary says how many and how far off.
      short_levels.add(step, r, reached, options.level_bound_certifies ? gap : NAN);
    } else {
      short_levels.add_loose(step, reached, gap);
    }
    // The largest distortion is at least the constants' (which the solves leave out).
    if (step == 1) out.lower_bound = std::max(r.lower_bound, constant_max);
    out.positions = r.positions;
    out.distortion = r.distortion;
    // The interior-point map meets the fixed bounds only to the solver's tolerance; widen
    // them to what it reached so that it stays an exact witness of feasibility.
    for (int e = 0; e < p.num_elements(); ++e)
      if (bounds(e) >= 0) bounds(e) = std::max(bounds(e), r.distortion(e));
    // k = the optimum of (1) over the level's free elements (with none: the held ones').
    k = 0;
    for (int e = 0; e < p.num_elements(); ++e)
      if (level_free[e] || (!any_level_free && movable[e] && bounds(e) < 0)) k = std::max(k, r.distortion(e));
    int fixed_now = 0;
    for (int e : immobile) {
      bounds(e) = r.distortion(e) * (1 + 1e-3 * options.delta_k);
      ++fixed_now;
    }
    for (int e = 0; e < p.num_elements(); ++e)
      if (level_free[e] && r.distortion(e) >= k - options.delta_k) {
        // Fix at the value reached (it is feasible for the map in hand), never below it.
        // A relative slack of delta_k / 1000 keeps an interior in the next level's feasible
        // set: bounds met with equality make the interior-point systems ill-conditioned
        // (the certified gap stalls at 1e-5..1e-3 after a few levels without it).
        bounds(e) = std::max(k, r.distortion(e)) * (1 + 1e-3 * options.delta_k);
        ++fixed_now;
      }
    fixed_total += fixed_now;
    free_left -= fixed_now;
    if (pinning && r.multipliers.size() == p.num_elements()) pins.pin_essential(bounds, r.multipliers, options.pin_threshold);
    out.iterations = step;
    IterationRecord rec;
    rec.iteration = step;
    rec.max_distortion = k;
    // A local-global level's bound is its last field-deviation step's, with the rotations
    // held: no bound on the level's own measure (DirectOptions::level_bound_certifies).
    rec.lower_bound = !options.level_bound_certifies ? NAN : any_level_free ? r.lower_bound : k;  // nothing moved: exact
    rec.certified_gap = options.level_bound_certifies ? gap : NAN;
    rec.inner_iterations = r.iterations;
    rec.time_s = seconds_since(t0);
    out.history.push_back(rec);
    if (options.progress) {
      StrictStep info;
      info.level_free_vertices = moved_vertices;
      info.step = step;
      info.k = k;
      info.fixed_now = fixed_now;
      info.fixed_total = fixed_total;
      info.solves = step;
      info.level_iterations = r.iterations;
      info.level_iteration_unit = options.level_iteration_unit;
      info.pinned_total = pins.count();
      info.time_s = rec.time_s;
      options.progress(info);
    }
  }
  // Direct's criterion: every element fixed or the level below k_min, every level certified
  // well enough to place its band (ShortLevels). Leaving the loop at max_steps is the cap.
  const bool finished = free_left == 0 || k <= options.k_min;
  if (out.status == SolveStatus::Solved && !finished) {
    out.status = SolveStatus::MaxIterations;
    stop_message = "reached the level cap (" + std::to_string(options.max_steps) + ") at k = " + std::to_string(k) +
                   " above k_min with " + std::to_string(free_left) + " elements still free";
  }
  if (out.status == SolveStatus::Solved) {
    out.status = short_levels.status();
    stop_message = free_left == 0 ? "every element fixed after " + std::to_string(out.iterations) + " levels"
                                  : "the level fell to k_min after " + std::to_string(out.iterations) + " levels";
    if (pins.count() > 0) stop_message += " (" + std::to_string(pins.count()) + " elements pinned)";
  }
  out.message = stop_message;
  const std::string levels = short_levels.message(out.iterations);
  if (!levels.empty()) out.message += (out.message.empty() ? "" : "; ") + levels;
  out.time_s = seconds_since(t0);
  return out;
}

double worst_level_gap(const Result& direct) {
  double worst = 0;
  for (const IterationRecord& rec : direct.history)
    worst = std::isnan(rec.certified_gap) ? INFINITY : std::max(worst, rec.certified_gap);
  return worst;
}

}  // namespace strictmin
