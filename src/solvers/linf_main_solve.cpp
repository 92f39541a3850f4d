#include "linf_main_solve.h"

#include <algorithm>
#include <cmath>

#include "linf_active_set_policy.h"
#include "solvers/socp/ipm.h"
#include "strictmin/solvers/timing.h"

namespace strictmin::linf_detail {
namespace {

// The certificate costs a least-squares solve and three passes over the cones. Unless someone
// watches the progress it is formed only once the method's dual objective or its own gap is
// within kCertifyNear tolerances of the best k, or its Newton directions have become
// unreliable (relative residual above kUnreliableDirections); before, it could not end the
// solve. The last iterate is certified after the method in any case.
constexpr double kCertifyNear = 1e4;
constexpr double kUnreliableDirections = 1e-3;
// Stalled: the certified gap has not shrunk by kProgress (to 90%) in kStallIterations
// iterations while the directions are unreliable; in 1 iteration once the method's own gap is
// below the tolerance (its dual iterates then only degrade).
constexpr double kProgress = 0.9;
constexpr int kStallIterations = 4;

}  // namespace

MainSolve solve_main(const MainProgram& mp, const socp::WeightedLeastSquares& ls, const Candidate& start,
                     const Eigen::VectorXd& effective_bounds, socp::NormalEquations* normal_equations,
                     std::vector<IterationRecord>& history, std::chrono::steady_clock::time_point t0) {
  const LinfOptions& options = mp.options;
  MainSolve ms;
  BestSoFar& best = ms.best;
  best.x = start.x;
  socp::IpmState st;
  const double k0 = start_above(start.kmax);
  socp::initialize(mp.prog, start.x, k0, 1e-2 * (1.0 + std::abs(k0)), 1.0, st);
  ActiveSetPolicy active_set(mp, effective_bounds);
  double last_progress_gap = kInf;
  int last_progress_iteration = 0;
  bool last_certified = true;

  auto certify = [&](const socp::IpmState& s) {
    Eigen::VectorXd lambda;
    const double lb = socp::certified_lower_bound(mp.prog, ls, s.z, s.y, &lambda);
    best.iterate_bound = std::max(best.iterate_bound, lb);
    if (lb > best.lower_bound) {
      best.lower_bound = lb;
      best.multipliers = std::move(lambda);
      best.element_multipliers.resize(0);
    }
  };
  auto record = [&](int iteration, double k) {
    IterationRecord rec;
    rec.iteration = iteration;
    rec.max_distortion = std::min(k, best.k);  // the active-set map may be better than the iterate
    rec.lower_bound = best.lower_bound;
    rec.certified_gap = (rec.max_distortion - best.lower_bound) / std::max(1.0, std::abs(rec.max_distortion));
    rec.time_s = seconds_since(t0);
    history.push_back(rec);
    if (options.progress) options.progress(rec);
  };
  // Returns true to stop: the certified gap within tolerance, or a stall.
  auto judge = [&](const socp::IpmIteration& info) {
    const double best_gap = best.k - best.lower_bound;
    if (!std::isfinite(best_gap)) return false;  // no iterate meets the constraints yet
    if (best_gap <= options.gap_tolerance * std::max(1.0, std::abs(best.k))) return true;
    const bool ipm_converged = info.gap <= options.gap_tolerance * std::max(1.0, std::abs(info.pobj));
    if (best_gap < kProgress * last_progress_gap) {
      last_progress_gap = best_gap;
      last_progress_iteration = info.iteration;
    } else if (info.iteration - last_progress_iteration >= (ipm_converged ? 1 : kStallIterations) &&
               info.kkt_residual > kUnreliableDirections) {
      ms.stalled = true;
      return true;
    }
    return false;
  };

  ms.outcome = socp::run_ipm(mp.prog, st, ipm_settings(options), [&](const socp::IpmState& s,
                                                                          const socp::Residuals& r,
                                                                          const socp::IpmIteration& info) {
    // 1. The iterate: kept when it is the best map meeting every constraint.
    const Eigen::VectorXd& d = r.tail_norms;  // the distortions at s.x
    const double k = mp.max_free(d);
    if (k < best.k && mp.bounds_met(d) && mp.equalities_met(s.x)) {
      best.k = k;
      best.x = s.x;
    }
    // 2. Its certificate (and the active-set solves) when it can matter.
    const double near = kCertifyNear * options.gap_tolerance * std::max(1.0, std::abs(best.k));
    const bool certified = options.progress || info.iteration == 0 || !std::isfinite(best.k) ||
                           best.k - info.dobj <= near || info.gap <= near || info.kkt_residual > kUnreliableDirections;
    if (certified) {
      certify(s);
      active_set.consider(s, d, k, info, best);
    }
    best.previous_k = k;
    last_certified = certified;
    // 3. The record, and whether to stop.
    record(info.iteration, k);
    if (!certified) {  // no new bound: nothing to judge progress by
      last_progress_iteration = info.iteration;
      return false;
    }
    return judge(info);
  }, normal_equations);
  if (!last_certified) certify(st);
  return ms;
}

}  // namespace strictmin::linf_detail
