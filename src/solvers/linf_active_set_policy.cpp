#include "linf_active_set_policy.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <tbb/task_group.h>

#include "solvers/join_on_exit.h"
#include "solvers/linf_active_set.h"
#include "solvers/socp/fd_program.h"
#include "strictmin/solvers/timing.h"

namespace strictmin::linf_detail {

ActiveSetPolicy::ActiveSetPolicy(const MainProgram& mp, const Eigen::VectorXd& effective_bounds)
    : mp_(mp), effective_bounds_(effective_bounds) {}

void ActiveSetPolicy::consider(const socp::IpmState& s, const Eigen::VectorXd& d, double k,
                               const socp::IpmIteration& info, BestSoFar& best) {
  const LinfOptions& options = mp_.options;
  const double tol = options.gap_tolerance * std::max(1.0, std::abs(best.k));
  if (!options.active_set_bounds || options.gap_tolerance > kTightestLooseTolerance) return;
  if (!std::isfinite(best.k) || best.k - best.lower_bound <= tol) return;
  // Settled is judged on the iterates' own certificate (and the attempts' bounds below):
  // a probe's bound closes the certified gap by itself and would hold the attempts back.
  const double certified_gap = best.k - (attempts_ > 0 ? best.lower_bound : best.iterate_bound);
  const bool near = best.k - info.dobj <= kNear * tol || info.gap <= kNear * tol;
  const bool settled = certified_gap <= kSettled * tol && best.previous_k - k <= kSettledStep * certified_gap;
  if (!near && !settled) {
    if (due_iteration_ == info.iteration) probe(s, tol, best);
    return;
  }
  // A restriction tried before that misses part of the dual's support gives a bound below
  // the optimum: retried (wider) only once the iterates' dual objective passes that bound or
  // their gap falls well below the gap left to it. Otherwise only the map is tried again.
  const bool retry = attempts_ == 0 || info.dobj > bound_ + tol || info.gap < kRetryGapFraction * (best.k - bound_);
  const double iterate_gap = std::max(best.k - best.iterate_bound, tol);
  if (!retry || attempts_ >= kMaxBoundAttempts || info.iteration == last_iteration_) {
    const bool bound_close = best.k - bound_ <= kBoundClose * tol;
    if (bound_close && maps_ < kMaxMaps && info.iteration != last_iteration_)
      try_map(near_maximum(d, k, kReach * iterate_gap, tol), mp_.problem.with_free_dofs(s.x), best);
    return;
  }
  const double reach = kReach * iterate_gap * std::pow(kReachGrowth, attempts_);
  const std::vector<int> chosen = near_maximum(d, k, reach, tol);
  ++attempts_;
  last_iteration_ = info.iteration;
  if (chosen.size() < kSameElements * elements_) {
    attempts_ = kMaxBoundAttempts;
    return;
  }
  elements_ = chosen.size();
  try_bound(chosen, mp_.problem.with_free_dofs(s.x), tol, best);
}

bool ActiveSetPolicy::probes_left() const {
  const LinfOptions& options = mp_.options;
  return options.active_set_bounds && options.active_set_probes && options.gap_tolerance <= kTightestLooseTolerance &&
         mp_.prog.num_eq() > 0 && probes_ < kMaxProbes && attempts_ == 0;
}

bool ActiveSetPolicy::probe_due(const Eigen::VectorXd& x, const Eigen::VectorXd& d, double k,
                                const socp::IpmIteration& info) {
  if (!probes_left() || !(info.gap <= kProbeGap * std::max(1.0, std::abs(info.pobj)))) return false;
  const double tol = mp_.options.gap_tolerance * std::max(1.0, std::abs(k));
  const size_t limit = static_cast<size_t>(mp_.problem.num_elements()) / kProbeDivisor;
  heading_ = previous_x_.size() == x.size() ? Eigen::VectorXd(2 * x - previous_x_) : x;
  heading_distortions_ = socp::cone_distortions(mp_.prog, heading_);
  const double heading_top = std::min(k, mp_.max_free(heading_distortions_));
  const std::vector<int> near_iterate = near_maximum(d, k, kReach * std::max(info.gap, tol), tol);
  double reach = kHeadingReach * std::max(info.gap, tol);
  for (int halving = 0; halving <= kHeadingHalvings; ++halving, reach *= 0.5) {
    heading_elements_ = near_maximum(heading_distortions_, heading_top, reach, tol);
    probe_elements_ = near_iterate;
    probe_elements_.insert(probe_elements_.end(), heading_elements_.begin(), heading_elements_.end());
    std::sort(probe_elements_.begin(), probe_elements_.end());
    probe_elements_.erase(std::unique(probe_elements_.begin(), probe_elements_.end()), probe_elements_.end());
    if (probe_elements_.size() <= limit) {
      due_iteration_ = info.iteration;
      return true;
    }
  }
  return false;
}

void ActiveSetPolicy::remember(const Eigen::VectorXd& x) {
  if (probes_left()) previous_x_ = x;
}

void ActiveSetPolicy::probe(const socp::IpmState& s, double tol, BestSoFar& best) {
  ++probes_;
  due_iteration_ = -1;
  // The map's region depends on the bound (below), but it is usually the heading's elements
  // with rings: that map is solved beside the bound (the restricted solves are small and
  // mostly serial, so the other core is idle) and kept when the region turns out the same.
  const Eigen::MatrixXd heading = mp_.problem.with_free_dofs(heading_);
  const std::vector<int> early_region = probe_map_region(heading_elements_);
  const bool beside = !early_region.empty();
  ActiveSetSolve early_map;
  tbb::task_group map_beside;
  const JoinOnExit join_map(map_beside);  // an exception from the bound's solve waits for the map
  if (beside) map_beside.run([&] { early_map = solve_map(early_region, heading); });
  const double bound = restricted_bound(probe_elements_, mp_.problem.with_free_dofs(s.x), best);
  map_beside.wait();
  // A restriction whose bound is below the iterates' own certificate misses the dual's
  // support: its map would not reach the optimum either.
  if (!(bound > best.iterate_bound) || best.k - best.lower_bound <= tol) return;
  // The map holds every vertex outside its elements, among them (through the seams'
  // equalities) the cones' places, which move the whole parametrization. An early iterate
  // has them off, and its map misses (horse, iteration 10: 1e-5 above the optimum). Held
  // where the iterates are heading (the last step once more: it meets the equalities, as
  // both iterates do), the same map lands 2e-8 above, and around the heading's own elements
  // 4e-10. Of the multiples 0.3-3 of the last step, 1-1.1 did best.
  // The map moves only its own elements' vertices, so every element outside it keeps its
  // distortion: it can reach the bound only if it holds every element above the bound.
  std::vector<int> elements = heading_elements_;
  std::vector<char> in(mp_.problem.num_elements(), 0);
  for (int e : elements) in[e] = 1;
  for (int i = 0; i < mp_.num_free_cones; ++i)
    if (heading_distortions_[i] >= bound - tol && !in[mp_.elems[i]]) elements.push_back(mp_.elems[i]);
  if (beside && elements.size() == heading_elements_.size()) {  // nothing added: the early map's region
    keep_map(early_map, best);
    return;
  }
  const std::vector<int> region = probe_map_region(elements);  // empty: too many elements
  if (!region.empty()) restricted_map(region, heading, best);
}

std::vector<int> ActiveSetPolicy::probe_map_region(const std::vector<int>& elements) const {
  const size_t limit = static_cast<size_t>(mp_.problem.num_elements()) / kProbeMapDivisor;
  if (elements.empty() || elements.size() > limit) return {};
  const double growth = static_cast<double>(limit) / static_cast<double>(elements.size());
  return widen_by_rings(mp_.problem, elements, kProbeMapRings, growth, kMapRings, kMapMinElements);
}


std::vector<int> ActiveSetPolicy::near_maximum(const Eigen::VectorXd& d, double k, double reach, double tol) const {
  const MainProgram& mp = mp_;
  const size_t cap = std::max<size_t>(kCapMin, mp.problem.num_elements() / kCapDivisor);
  const Eigen::VectorXd& bounds = mp.options.element_bounds;
  std::vector<int> chosen;
  for (;; reach *= 0.1) {
    chosen.clear();
    for (int i = 0; i < mp.prog.num_element_cones(); ++i) {
      const double top = i < mp.num_free_cones ? k : mp.prog.head_b[i];
      if (d[i] >= top - reach) chosen.push_back(mp.elems[i]);
    }
    for (size_t j = 0; j < mp.cls.constant_elements.size(); ++j)
      if (!socp::has_bound(bounds, mp.cls.constant_elements[j]) && mp.cls.constant_distortion[j] >= k - reach)
        chosen.push_back(mp.cls.constant_elements[j]);
    // Below a thousandth of the tolerance a smaller reach changes nothing that matters.
    if (chosen.size() <= cap || reach < 1e-3 * tol) return chosen;
  }
}


std::vector<int> ActiveSetPolicy::map_region(const std::vector<int>& chosen) const {
  double growth = kMapGrowth;
  if (mp_.prog.num_eq() > 0 && !chosen.empty())
    growth = std::max(growth, static_cast<double>(kMapMinElements) / static_cast<double>(chosen.size()));
  return widen_by_rings(mp_.problem, chosen, kMapRings, growth);
}

void ActiveSetPolicy::try_map(const std::vector<int>& chosen, const Eigen::MatrixXd& X, BestSoFar& best) {
  ++maps_;
  restricted_map(map_region(chosen), X, best);
}

void ActiveSetPolicy::restricted_map(const std::vector<int>& region, const Eigen::MatrixXd& X, BestSoFar& best) const {
  keep_map(solve_map(region, X), best);
}

ActiveSetSolve ActiveSetPolicy::solve_map(const std::vector<int>& region, const Eigen::MatrixXd& X) const {
  const auto t0 = std::chrono::steady_clock::now();
  ActiveSetSolve m = active_set_map(mp_.problem, region, X, effective_bounds_, mp_.options);
  if (mp_.options.verbose)
    std::fprintf(stderr, "linf: active-set map from %d elements (%d iterations, %.3f s)\n", m.elements, m.iterations,
                 seconds_since(t0));
  return m;
}

void ActiveSetPolicy::keep_map(const ActiveSetSolve& m, BestSoFar& best) const {
  const Problem& p = mp_.problem;
  if (m.positions.size() == 0 || !m.positions.allFinite()) return;
  // Kept when it lowers k and meets every constraint, checked on the whole problem.
  const Eigen::VectorXd x2 = onto_equalities(mp_.prog, p.free_dofs(m.positions));
  const Eigen::VectorXd d2 = socp::cone_distortions(mp_.prog, x2);
  const double k2 = mp_.max_free(d2);
  if (k2 < best.k && mp_.bounds_met(d2) && mp_.equalities_met(x2)) {
    best.k = k2;
    best.x = x2;
  }
}

void ActiveSetPolicy::try_bound(const std::vector<int>& chosen, const Eigen::MatrixXd& X, double tol,
                                BestSoFar& best) {
  // The map, needed when the bound comes close, is solved beside it (the restricted solves
  // are small and mostly serial, and their METIS calls take turns: ordering.h).
  const std::vector<int> region = map_region(chosen);
  ActiveSetSolve early_map;
  tbb::task_group map_beside;
  const JoinOnExit join_map(map_beside);  // an exception from the bound's solve waits for the map
  map_beside.run([&] { early_map = solve_map(region, X); });
  bound_ = restricted_bound(chosen, X, best);
  map_beside.wait();
  if (!(best.k - bound_ <= kBoundClose * tol && best.k - best.lower_bound > tol)) return;
  ++maps_;
  keep_map(early_map, best);
}

double ActiveSetPolicy::restricted_bound(const std::vector<int>& chosen, const Eigen::MatrixXd& X,
                                         BestSoFar& best) const {
  const auto t0 = std::chrono::steady_clock::now();
  const ActiveSetSolve b = active_set_bound(mp_.problem, chosen, X, effective_bounds_, mp_.options);
  if (mp_.options.verbose)
    std::fprintf(stderr, "linf: active-set bound %.12g from %d elements (%d iterations, %.3f s)\n", b.lower_bound,
                 b.elements, b.iterations, seconds_since(t0));
  if (b.lower_bound > best.lower_bound) {
    best.lower_bound = b.lower_bound;
    best.element_multipliers = b.multipliers;
  }
  return b.lower_bound;
}

}  // namespace strictmin::linf_detail
