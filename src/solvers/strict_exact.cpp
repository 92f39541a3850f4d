// Algorithm 1 with exact essential sets. At a level with optimal value k, an element is
// essential when no optimal solution lowers it. Candidates are the free elements at k
// (within tolerance) in the level's solution; candidate i is tested by minimizing D_i with
// every other free element bounded by k. Any solution that lowers some candidates proves
// them all non-essential (the optimal set is convex, so one solution lowers them all at
// once), which lets one solve settle several candidates.
//
// Numerically the levels are delicate: where an essential set is essential only to second
// order (the symmetric square of the paper's Figure 2 is such a case), the optimum of the
// next level moves like the square root of the error in the fixed bounds, so interior-point
// accuracy of 1e-8 shows up as ~1e-4 in the levels below. The default tolerance (the
// paper's delta-k, 1e-3) keeps the tests of essentiality above that noise.
#include <chrono>
#include <algorithm>
#include <cmath>
#include <vector>

#include "strictmin/io/input_error.h"
#include "strictmin/solvers/strict.h"

namespace strictmin {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

Result solve_exact(const Problem& p, const ExactOptions& options) {
  if (p.num_elements() > options.max_elements)
    throw InputError("the exact strict minimizer needs up to one L-infinity solve per element and level; " +
                     std::to_string(p.num_elements()) + " elements is above its limit of " +
                     std::to_string(options.max_elements) + " (use --method direct or relax)");
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<char> movable(p.num_elements(), 0);
  int undecided = 0;
  for (int e = 0; e < p.num_elements(); ++e) {
    for (int j = 0; j < p.corners(); ++j) movable[e] |= p.fixed[p.elements(e, j)] ? 0 : 1;
    undecided += movable[e];
  }
  const double tol = options.tolerance;
  Eigen::VectorXd bounds = Eigen::VectorXd::Constant(p.num_elements(), -1.0);
  LinfOptions linf = options.linf;
  linf.progress = nullptr;
  Result out;
  int solves = 0, fixed_total = 0;
  auto fail = [&](const Result& r, const std::string& where) {
    out.status = r.status;
    out.message = where + ": " + r.message;
  };
  for (int level = 1; undecided > 0; ++level) {
    linf.element_bounds = bounds;
    const Result r = solve_linf(p, linf);
    ++solves;
    if (level == 1) out.lower_bound = r.lower_bound;
    out.positions = r.positions;
    out.distortion = r.distortion;
    if (r.status != SolveStatus::Solved) {
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
    for (int i = 0; i < p.num_elements(); ++i) {
      if (!candidate[i]) continue;
      // min D_i subject to the fixed bounds and D_j <= k for every other free element.
      Eigen::VectorXd test = bounds;
      for (int e = 0; e < p.num_elements(); ++e)
        if (movable[e] && bounds(e) < 0 && e != i) test(e) = k;
      linf.element_bounds = test;
      const Result t = solve_linf(p, linf);
      ++solves;
      if (t.status != SolveStatus::Solved) {
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
    for (int e : essential) bounds(e) = k;
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
  out.time_s = seconds_since(t0);
  return out;
}

}  // namespace strictmin
