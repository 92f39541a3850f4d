#include "linf_main_solve.h"

#include <algorithm>
#include <cmath>

#include "linf_active_set_policy.h"
#include "solvers/socp/ipm.h"
#include "solvers/socp/soc.h"
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
// The warm start (linf_warm_start.h): k just above the start map's maximum, s from the new
// program at the start map (heads raised where it misses the cones), and the kept dual with
// every cone's head raised by gamma mu / s_i0 (mu = s^T z / nu): the kept dual is nearly zero
// on the cones that were inactive, and this lifts each cone's complementarity product s_i^T z_i
// to at least gamma mu, so that the first steps are not cut short. Raising heads changes the
// dual objective only through the rescaling that restores the k equation sum_i a_i z_i0 = c_k
// (free cones have no constant head), so the start's certified bound stays close to the last
// solve's. (Blending with the centred dual instead pulled the bound 10% of the way to the
// centred dual's poor one.)
// gamma: 0.1 took the fewest iterations on tests/test_linf_warm_start.cpp's bar (2; 0.01: 4,
// 0.3: 4, 1: 3).
constexpr double kWarmLift = 0.1;
// Direct's levels, warm by element (linf_warm_start.h): the band and the essential elements of
// the last level leave the k equation (they are bounded or pinned now), so the kept dual is
// further from the next level's; a lift of 1 kept cow's first 40 levels at 334 interior-point
// iterations (0.1: 393, cold: 411; docs/strict.md, "Warm levels").
constexpr double kElementWarmLift = 1.0;
// The cold start of a program with fixed bounds and equalities (the levels of gparam's
// direct): the bounded cones' heads kBoundedLift * margin above the bound (or the start map's
// distortion where it misses it) instead of the free cones' margin, so that their multipliers
// start about 1 / kBoundedLift times larger (docs/strict.md, "The start of a level"). Cow's
// gparam direct, first 25 levels: 1003 interior-point iterations with the full margin, 664
// with 0.1, 514 with 0.01; with 0.01 the 10k bar's levels became ill-conditioned (42 of 192
// stopped short). Planar programs keep the full margin: with 0.1 the 50k bar had 13 levels at
// the iteration cap against 5.
constexpr double kBoundedLift = 1e-1;

// The kept dual on this program's cones: as kept, or (by element) each element cone from its
// element's row, zero where the row is empty (the lift below makes it interior), y zero.
void kept_dual(const MainProgram& mp, const LinfWarmStart& warm, socp::IpmState& st) {
  if (!warm.by_element()) {
    st.z = warm.z;
    st.y = warm.y;
    return;
  }
  const socp::ConeProgram& prog = mp.prog;
  st.z = Eigen::VectorXd::Zero(prog.cone_size());
  for (int i = 0; i < prog.num_element_cones(); ++i) {
    const int d = prog.cone_dim(i);
    const auto row = warm.element_z.row(mp.elems[i]).head(d);
    if (row.allFinite()) st.z.segment(prog.cone_offset(i), d) = row.transpose();
  }
  st.y = Eigen::VectorXd::Zero(prog.num_eq());
}

void warm_initialize(const MainProgram& mp, const Candidate& start, const LinfWarmStart& warm, socp::IpmState& st) {
  const socp::ConeProgram& prog = mp.prog;
  const double rise = std::clamp(warm.expected_change, 1e-4, 1e-2);
  const double scale = std::max(std::abs(start.kmax), 1e-3);
  socp::initialize(prog, start.x, start.kmax + rise * scale, rise * scale, 1.0, st);
  kept_dual(mp, warm, st);
  const double lift = warm.by_element() ? kElementWarmLift : kWarmLift;
  const double nu = prog.num_cones();
  const double mu = std::max(st.s.dot(st.z), 0.0) / nu;
  double k_equation = 0;
  for (int i = 0; i < prog.num_cones(); ++i) {
    const Eigen::Index o = prog.cone_offset(i);
    const int d = prog.cone_dim(i);
    double* z = st.z.data() + o;
    const double* s = st.s.data() + o;
    z[0] = std::max(z[0], socp::tail_norm(z, d)) + lift * mu / s[0];
    k_equation += prog.head_a[i] * z[0];
  }
  if (prog.has_k && k_equation > 0) {
    st.z *= prog.c_k / k_equation;
    st.y *= prog.c_k / k_equation;
  }
}

}  // namespace

bool warm_start_applies(const MainProgram& mp, const LinfWarmStart& warm) {
  if (!warm.by_element()) return warm.fits(mp.prog.cone_size(), mp.prog.num_eq()) && warm.close_enough();
  if (warm.element_z.rows() != mp.problem.num_elements() || mp.prog.num_cones() != mp.prog.num_element_cones())
    return false;
  int kept = 0;
  for (int i = 0; i < mp.prog.num_element_cones(); ++i)
    kept += warm.element_z.row(mp.elems[i]).head(mp.prog.cone_dim(i)).allFinite() ? 1 : 0;
  return 2 * kept >= mp.prog.num_element_cones();
}

void keep_dual(const MainProgram& mp, MainSolve& ms, LinfWarmStart& warm) {
  const bool sound = ms.outcome.status != socp::IpmStatus::NumericalError && !ms.stalled && ms.final_z.allFinite();
  if (!warm.by_element()) {
    warm.z = sound ? std::move(ms.final_z) : Eigen::VectorXd();
    warm.y = sound ? std::move(ms.final_y) : Eigen::VectorXd();
    warm.cone_size = sound ? mp.prog.cone_size() : -1;
    warm.num_eq = sound ? mp.prog.num_eq() : -1;
    return;
  }
  warm.element_z.setConstant(NAN);
  if (!sound || ms.final_z.size() != mp.prog.cone_size()) return;
  for (int i = 0; i < mp.prog.num_element_cones(); ++i) {
    const int d = mp.prog.cone_dim(i);
    warm.element_z.row(mp.elems[i]).head(d) = ms.final_z.segment(mp.prog.cone_offset(i), d).transpose();
  }
}

MainSolve solve_main(const MainProgram& mp, const socp::WeightedLeastSquares& ls, const Candidate& start,
                     const Eigen::VectorXd& effective_bounds, const socp::NormalEquationsSource& normal_equations,
                     std::vector<IterationRecord>& history, std::chrono::steady_clock::time_point t0,
                     const LinfWarmStart* warm) {
  const LinfOptions& options = mp.options;
  MainSolve ms;
  BestSoFar& best = ms.best;
  best.x = start.x;
  socp::IpmState st;
  if (warm)
    warm_initialize(mp, start, *warm, st);
  else {
    const double margin = 1e-2 * (1.0 + std::abs(start_above(start.kmax)));
    const double bounded_margin = mp.prog.num_eq() > 0 ? kBoundedLift * margin : 0.0;
    socp::initialize(mp.prog, start.x, start_above(start.kmax), margin, 1.0, st, bounded_margin);
  }
  ActiveSetPolicy active_set(mp, effective_bounds);
  // The normal equations, once their analysis is done (it may still run on another thread
  // through the first certificate). The active-set solves wait for it too, rather than
  // compete with it for the cores.
  socp::NormalEquations* analysed = nullptr;
  bool waited = false;
  auto wait_for_analysis = [&] {
    if (!waited) analysed = normal_equations ? normal_equations() : nullptr;
    waited = true;
    return analysed;
  };
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
    const bool probe = active_set.probe_due(s.x, d, k, info);
    const bool certified = probe || options.progress || info.iteration == 0 || !std::isfinite(best.k) ||
                           best.k - info.dobj <= near || info.gap <= near || info.kkt_residual > kUnreliableDirections;
    if (certified) {
      certify(s);
      wait_for_analysis();
      active_set.consider(s, d, k, info, best);
    }
    best.previous_k = k;
    active_set.remember(s.x);
    last_certified = certified;
    // 3. The record, and whether to stop.
    record(info.iteration, k);
    if (!certified) {  // no new bound: nothing to judge progress by
      last_progress_iteration = info.iteration;
      return false;
    }
    return judge(info);
  }, wait_for_analysis);
  if (!last_certified) certify(st);
  ms.final_z = std::move(st.z);
  ms.final_y = std::move(st.y);
  return ms;
}

}  // namespace strictmin::linf_detail
