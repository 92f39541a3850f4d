// Algorithm 1 with exact essential sets. At a level with optimal value k, an element is
// essential when no optimal solution lowers it. Candidates are the free elements at k
// (within tolerance) in the level's solution.
//
// First the level's own certificate settles what it can, without further solves: its dual
// multipliers lambda give, for every map meeting the fixed bounds with the other free
// elements at most k, lambda_i D_i + (1 - lambda_i) k >= lower bound, so candidate i cannot
// drop below k - (k - lower bound) / lambda_i (result.h). Their sum is 1, so this always
// finds an essential element when the gap is small (Proposition 1's argument, made
// quantitative), and it needs no solve with a feasible set that has no interior.
//
// The other candidates are tested by minimizing D_i with every other free element bounded
// by k. Any solution that lowers some candidates proves them all non-essential (the
// optimal set is convex, so one solution lowers them all at once), which lets one solve
// settle several. These test solves are the delicate part: their feasible set is the
// level's optimal set (no interior), and the level values can be extremely sensitive to the
// fixed bounds (on a 16 x 4 bar with random rotation targets, relaxing the bounds of level 6
// by 1e-9 lowers its optimum by 2e-2: the levels compose square-root-like sensitivities). A
// test can therefore lower an essential element by the solver's feasibility tolerance
// amplified; such an element stays free and is fixed at the next level instead, whose
// optimum it then sets. The default tolerance (the paper's delta-k, 1e-3) keeps the tests
// above the ordinary noise.
#include <chrono>
#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "strictmin/problem/check_problem.h"
#include "strictmin/io/input_error.h"
#include "strictmin/solvers/strict.h"
#include "strictmin/solvers/timing.h"
#include "strictmin/solvers/interrupt.h"
#include "option_check.h"
#include "solvers/strict_constants.h"
#include "solvers/strict_pinning.h"

namespace strictmin {
namespace {
// A solve (a level's after the first, or a test's) that stopped short of its own criterion (a
// relative gap of 1e-8) still decides when its certified gap is at most this fraction of the
// tolerance: far finer than the decisions, which compare values with k - tol, need (a value
// known within tol / 10 is misplaced only where it lies within tol / 10 of k - tol). At 1e-2
// before: with OpenBLAS's Cooperlake kernels (an AMD EPYC VM, 2026-11-26) the 58th and last
// level of the seamed bulged frame (k = 0.0051) stalls at a certified gap of 4.7e-7, tol / 21.
constexpr double kDecidingGap = 1e-1;
}  // namespace

bool ExactOptions::is_valid(std::string* why) const {
  return OptionCheck(why).positive("tolerance", tolerance).at_least("max_elements", max_elements, 1).ok();
}

Result solve_exact(const Problem& p, const ExactOptions& options, const LinfOptions& linf_options) {
  std::string why;
  if (!options.is_valid(&why)) throw InputError("exact: " + why);
  if (!linf_options.is_valid(&why)) throw InputError("linf: " + why);
  check_problem(p, "exact");
  if (p.num_elements() > options.max_elements)
    throw InputError("the exact strict minimizer needs up to one L-infinity solve per element and level; " +
                     std::to_string(p.num_elements()) + " elements is above its limit of " +
                     std::to_string(options.max_elements) +
                     " (ExactOptions::max_elements: --exact-max-elements on the command line, exact_max_elements in "
                     "Python; use the method direct or relax, or raise that limit)");
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<char> movable = movable_elements(p);
  int undecided = 0;
  for (char m : movable) undecided += m;
  const double tol = options.tolerance;
  Eigen::VectorXd bounds = Eigen::VectorXd::Constant(p.num_elements(), -1.0);
  const double constant_max = bound_constant_elements(p, movable, bounds);
  LinfOptions linf = linf_options;
  linf.progress = nullptr;
  Result out;
  if (undecided == 0) return unmovable_answer(p);
  int solves = 0, fixed_total = 0;
  // Essential elements are pinned (strict_pinning.h) on problems without equalities: every
  // solve after the first runs on the level's problem, from the map in hand.
  const bool pinning = options.pin_essential && !p.has_equalities();
  PinnedElements pins(p);
  const std::vector<char> every_vertex(p.num_vertices, 1);
  const LevelSolver plain = [](const Problem& level, const LinfOptions& o, const Eigen::MatrixXd&) {
    return solve_linf(level, o);
  };
  // The problem of the solves from the map `from` (built once for the level's solve and once
  // for all its test solves): the whole problem until something is pinned.
  auto level_problem = [&](const Result& from) {
    return pins.count() == 0 ? std::optional<PinnedLevel>() : pins.level_problem(p, every_vertex, from.positions);
  };
  // Unpinned solves run from the map in hand, which meets every fixed bound: the problem's
  // own start (the first map) misses the new ones and would need a phase 1 (which on seamed
  // problems declared the bulged frame's second level infeasible). One copy, its start reset.
  Problem from_map = p;
  auto solve = [&](const std::optional<PinnedLevel>& level, const Eigen::VectorXd& element_bounds,
                   const Result& from) {
    if (!level) {
      linf.element_bounds = element_bounds;
      from_map.positions = from.positions.rows() == p.num_vertices ? from.positions : p.positions;
      return solve_linf(from_map, linf);
    }
    return solve_on_level(p, *level, element_bounds, from, linf, plain);
  };
  // A solve that stopped short of its own gap (1e-8 relative) still decides the level or a
  // test when its certified gap is far inside the tolerance: the decisions compare values
  // with k - tol. Counted in the message; the status stays the decisions'.
  int short_solves = 0;
  auto within_deciding_gap = [&](const Result& r) {
    const bool ok = r.usable() && std::isfinite(r.lower_bound) && r.distortion.size() == p.num_elements() &&
                    r.history.size() > 0 && r.history.back().max_distortion - r.lower_bound <= kDecidingGap * tol;
    short_solves += ok;
    return ok;
  };
  auto fail = [&](const Result& r, const std::string& where) {
    out.status = r.status;
    out.message = where + ": " + r.message;
  };
  for (int level = 1; undecided > 0; ++level) {
    check_interrupt();  // solvers/interrupt.h
    const Result r = solve(level_problem(out), bounds, out);
    ++solves;
    if (level == 1) out.lower_bound = std::max(r.lower_bound, constant_max);  // the constants are left out
    out.positions = r.positions;
    out.distortion = r.distortion;
    if (r.status != SolveStatus::Solved && !(level > 1 && within_deciding_gap(r))) {
      fail(r, "exact level " + std::to_string(level));
      break;
    }
    // The interior-point solution meets the fixed bounds only to the solver's tolerance;
    // widen them to what it reached, so that this level's map is an exact witness of
    // feasibility for every test below (tiny infeasibilities are amplified by the levels).
    for (int e = 0; e < p.num_elements(); ++e)
      if (bounds(e) >= 0) bounds(e) = std::max(bounds(e), r.distortion(e));
    double k = 0;
    for (int e = 0; e < p.num_elements(); ++e)
      if (movable[e] && bounds(e) < 0) k = std::max(k, r.distortion(e));
    std::vector<char> candidate(p.num_elements(), 0);
    for (int e = 0; e < p.num_elements(); ++e)
      candidate[e] = movable[e] && bounds(e) < 0 && r.distortion(e) >= k - tol;
    std::vector<int> essential;
    // Certified by the level's dual multipliers (see the top of the file).
    const double gap = std::max(0.0, k - r.lower_bound);
    if (r.multipliers.size() == p.num_elements()) {
      int strongest = -1;
      for (int i = 0; i < p.num_elements(); ++i) {
        if (!candidate[i]) continue;
        if (strongest < 0 || r.multipliers[i] > r.multipliers[strongest]) strongest = i;
        if (r.multipliers[i] > 0 && gap <= tol * r.multipliers[i]) {
          essential.push_back(i);
          candidate[i] = 0;
        }
      }
      // The certificate's largest multiplier among the candidates: essential to within
      // gap / lambda, which the tolerance test above can miss only when the gap is large.
      if (essential.empty() && strongest >= 0 && r.multipliers[strongest] > 0) {
        essential.push_back(strongest);
        candidate[strongest] = 0;
      }
    }
    const std::optional<PinnedLevel> tests_level = level_problem(r);
    for (int i = 0; i < p.num_elements(); ++i) {
      if (!candidate[i]) continue;
      // min D_i subject to the fixed bounds and D_j <= k for every other free element.
      Eigen::VectorXd test = bounds;
      for (int e = 0; e < p.num_elements(); ++e)
        if (movable[e] && bounds(e) < 0 && e != i) test(e) = k;
      const Result t = solve(tests_level, test, r);
      ++solves;
      // A test solve that stopped short of its own gap still decides the test when its
      // certified gap is far inside the test's tolerance: the decision compares D_i with
      // k - tol, and the certified bound brackets min D_i within that gap.
      if (t.status != SolveStatus::Solved && !within_deciding_gap(t)) {
        fail(t, "exact level " + std::to_string(level) + ", element " + std::to_string(i));
        break;
      }
      if (t.distortion(i) >= k - tol) {
        essential.push_back(i);
        candidate[i] = 0;
      }
      for (int e = 0; e < p.num_elements(); ++e)
        if (candidate[e] && t.distortion(e) < k - tol) candidate[e] = 0;
    }
    if (out.status != SolveStatus::Solved) break;
    for (int e : essential) {
      bounds(e) = k;
      if (pinning) pins.pin(e);
    }
    fixed_total += static_cast<int>(essential.size());
    undecided -= static_cast<int>(essential.size());
    out.iterations = level;
    IterationRecord rec;
    rec.iteration = level;
    rec.max_distortion = k;
    rec.lower_bound = r.lower_bound;
    rec.time_s = seconds_since(t0);
    out.history.push_back(rec);
    if (options.progress) options.progress({level, k, static_cast<int>(essential.size()), fixed_total, solves, rec.time_s});
    if (essential.empty()) {  // Proposition 1 says this cannot happen for exact optima
      out.status = SolveStatus::NumericalError;
      out.message = "exact level " + std::to_string(level) + ": no essential element found within tolerance";
      break;
    }
  }
  if (out.status == SolveStatus::Solved && out.message.empty())
    out.message = "every level's essential elements found: " + std::to_string(out.iterations) + " levels, " +
                  std::to_string(solves) + " solves";
  if (short_solves > 0) {
    const std::string note = std::to_string(short_solves) + " of " + std::to_string(solves) +
                             " solves stopped short of their gap but within tolerance / 10 and decided their level or test";
    out.message = out.message.empty() ? note : out.message + "; " + note;
  }
  out.time_s = seconds_since(t0);
  return out;
}

}  // namespace strictmin
