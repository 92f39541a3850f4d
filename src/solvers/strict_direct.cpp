#include <chrono>
#include <cmath>

#include "strictmin/solvers/l2.h"
#include "strictmin/solvers/strict.h"

namespace strictmin {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Elements with a vertex that is free: the others are constants of the problem.
std::vector<char> movable_elements(const Problem& p) {
  std::vector<char> movable(p.num_elements(), 0);
  for (int e = 0; e < p.num_elements(); ++e)
    for (int j = 0; j < p.corners(); ++j) movable[e] |= p.fixed[p.elements(e, j)] ? 0 : 1;
  return movable;
}

}  // namespace

Result solve_direct(const Problem& p, const DirectOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<char> movable = movable_elements(p);
  Eigen::VectorXd bounds = Eigen::VectorXd::Constant(p.num_elements(), -1.0);
  int fixed_total = 0, free_left = 0;
  for (char m : movable) free_left += m;
  LinfOptions linf = options.linf;
  linf.progress = nullptr;
  Result out;
  double k = INFINITY;
  out.positions = options.start.size() ? options.start : p.positions;
  for (int step = 1; free_left > 0 && k > options.k_min && step <= options.max_steps; ++step) {
    linf.element_bounds = bounds;
    Result r = options.level_solver ? options.level_solver(p, linf, out.positions) : solve_linf(p, linf);
    if (step == 1) out.lower_bound = r.lower_bound;
    out.positions = r.positions;
    out.distortion = r.distortion;
    if (r.status != SolveStatus::Solved) {
      out.status = r.status;
      out.message = "direct step " + std::to_string(step) + ": " + r.message;
      // A step that stops short still leaves a valid map; keep going only if it is usable.
      if (r.status != SolveStatus::MaxIterations) break;
    }
    // The interior-point map meets the fixed bounds only to the solver's tolerance; widen
    // them to what it reached so that it stays an exact witness of feasibility.
    for (int e = 0; e < p.num_elements(); ++e)
      if (bounds(e) >= 0) bounds(e) = std::max(bounds(e), r.distortion(e));
    // k = the optimum of (1) over the elements still free.
    k = 0;
    for (int e = 0; e < p.num_elements(); ++e)
      if (movable[e] && bounds(e) < 0) k = std::max(k, r.distortion(e));
    int fixed_now = 0;
    for (int e = 0; e < p.num_elements(); ++e)
      if (movable[e] && bounds(e) < 0 && r.distortion(e) >= k - options.delta_k) {
        // Fix at the value reached (it is feasible for the map in hand), never below it.
        bounds(e) = std::max(k, r.distortion(e));
        ++fixed_now;
      }
    fixed_total += fixed_now;
    free_left -= fixed_now;
    out.iterations = step;
    IterationRecord rec;
    rec.iteration = step;
    rec.max_distortion = k;
    rec.lower_bound = r.lower_bound;
    rec.time_s = seconds_since(t0);
    out.history.push_back(rec);
    if (options.progress) options.progress({step, k, fixed_now, fixed_total, step, rec.time_s});
  }
  out.time_s = seconds_since(t0);
  return out;
}

}  // namespace strictmin
