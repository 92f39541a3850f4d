// L-infinity field deviation by our interior-point method (solvers/socp/): the phases.
//   1. classify elements (free / bounded / constant), check the constants;
//   2. start from the L2 map (or the given positions, whichever is better);
//   3. phase 1 when the start misses some fixed bound: min t s.t. D_T <= k_T + t;
//   4. min k s.t. D_T <= k (free), D_T <= k_T (bounded), k >= constant elements' D_T;
//   5. optionally (Section 5.1 (a)) min sum A_T D_T^2 s.t. D_T <= k* (+ slack).
#include "strictmin/solvers/linf.h"
#include "strictmin/solvers/timing.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <sstream>

#include <tbb/task_group.h>

#include "strictmin/io/input_error.h"
#include "strictmin/problem/parts.h"
#include "strictmin/solvers/l2.h"
#include "strictmin/solvers/linf_active_set.h"
#include "strictmin/solvers/socp/certificate.h"
#include "strictmin/solvers/socp/kkt.h"
#include "strictmin/solvers/socp/fd_program.h"
#include "strictmin/solvers/socp/ipm.h"
#include "option_check.h"

namespace strictmin {
namespace {

using socp::ConeProgram;
constexpr double kInf = std::numeric_limits<double>::infinity();

std::string format(double v) {
  std::ostringstream os;
  os.precision(6);
  os << v;
  return os.str();
}

socp::IpmSettings ipm_settings(const LinfOptions& o) {
  socp::IpmSettings s;
  s.max_iterations = o.max_iterations;
  s.gap_tolerance = o.gap_tolerance;
  s.feasibility_tolerance = o.feasibility_tolerance;
  s.step_fraction = o.step_fraction;
  s.regularization = o.regularization;
  s.refinement_steps = o.refinement_steps;
  s.verbose = o.verbose;
  return s;
}

// A starting k above every value: max + 10% + 1% of the scale.
double start_above(double max_value) { return max_value + 0.1 * std::abs(max_value) + 1e-2 * (1.0 + std::abs(max_value)); }

struct Phase1 {
  bool feasible = true;
  double t = -kInf;          // max_T (D_T - k_T) at the returned x
  double lower_bound = -kInf; // certified: no map does better than this t
  Eigen::MatrixXd X;          // the map (vertices outside the bounded elements unchanged)
  int iterations = 0;
  std::string message;
};

// min t s.t. ||G_T x - h_T|| <= k_T + t over the bounded elements only (always feasible).
// Vertices of no bounded element stay where X0 has them; a part of the bounded elements
// without any fixed vertex is anchored at one vertex (D_T is translation invariant).
Phase1 run_phase1(const Problem& p, const socp::ElementClasses& cls, const Eigen::VectorXd& bounds,
                  const Eigen::MatrixXd& X0, const LinfOptions& options) {
  const int n = p.image_dim;
  const std::vector<int>& elems = cls.bounded_elements;
  std::vector<char> bounded(p.num_elements(), 0), held(p.fixed.begin(), p.fixed.end());
  for (int e : elems) bounded[e] = 1;
  const ElementParts parts = element_parts(p, &bounded);
  if (!p.has_equalities())
    for (int v : unanchored_parts(parts, p.fixed)) held[v] = 1;
  std::vector<int> vertex_dof(p.num_vertices, -1);
  int num_x = 0;
  for (int v = 0; v < p.num_vertices; ++v) {
    if (parts.part[v] < 0) held[v] = 1;  // outside: constant here
    if (!held[v]) {
      vertex_dof[v] = num_x;
      num_x += n;
    }
  }
  ConeProgram prog = socp::element_program(p, elems, vertex_dof, num_x, X0);
  for (size_t i = 0; i < elems.size(); ++i) prog.head_b[static_cast<Eigen::Index>(i)] = bounds[elems[i]];
  socp::restrict_equalities(p, vertex_dof, num_x, X0, held, prog);

  Eigen::VectorXd x0(num_x);
  for (int v = 0; v < p.num_vertices; ++v)
    if (vertex_dof[v] >= 0) x0.segment(vertex_dof[v], n) = X0.row(v).transpose();

  Phase1 out;
  auto excess_at = [&](const Eigen::VectorXd& x) {
    const Eigen::VectorXd d = socp::cone_distortions(prog, x);
    double t = -kInf;
    for (int i = 0; i < prog.num_element_cones(); ++i) t = std::max(t, d[i] - prog.head_b[i]);
    return t;
  };
  const double scale = std::max(1.0, prog.head_b.maxCoeff());
  const double tol = options.infeasibility_tolerance * scale;
  double best_t = excess_at(x0), best_lb = -kInf;
  Eigen::VectorXd best_x = x0;
  socp::WeightedLeastSquares ls(prog);
  socp::IpmState st;
  socp::initialize(prog, x0, start_above(best_t), 1e-2 * scale, 1.0, st);
  const socp::IpmSettings settings = ipm_settings(options);
  const auto outcome = socp::run_ipm(prog, st, settings, [&](const socp::IpmState& s, const socp::Residuals&,
                                                             const socp::IpmIteration&) {
    const double t = excess_at(s.x);
    if (t < best_t) {
      best_t = t;
      best_x = s.x;
    }
    best_lb = std::max(best_lb, socp::certified_lower_bound(prog, ls, s.z, s.y));
    // Done when strictly feasible, certainly infeasible, or converged.
    return best_t < 0 || best_lb > tol || best_t - best_lb <= options.gap_tolerance * scale;
  });
  out.iterations = outcome.iterations;
  out.t = best_t;
  out.lower_bound = best_lb;
  out.X = X0;
  for (int v = 0; v < p.num_vertices; ++v)
    if (vertex_dof[v] >= 0) out.X.row(v) = best_x.segment(vertex_dof[v], n).transpose();
  if (best_lb > tol || (outcome.status == socp::IpmStatus::MonitorStopped && best_t > tol)) {
    out.feasible = false;
    out.message = "the fixed bounds cannot all be met: some bounded element exceeds its bound k_T by at least " +
                  format(std::max(best_lb, 0.0)) + " (best map found: " + format(best_t) + ")";
  } else if (best_t > tol) {
    out.feasible = false;
    out.message = "could not decide whether the fixed bounds can be met (phase 1: " + outcome.message +
                  "; excess " + format(best_t) + ", bound " + format(best_lb) + ")";
  }
  return out;
}

struct MainSolve {
  Eigen::VectorXd x;
  double k = kInf, lower_bound = -kInf;
  socp::IpmOutcome outcome;
  double last_progress_gap = kInf;
  int last_progress_iteration = 0;
  Eigen::VectorXd multipliers;  // per element cone, of the best certificate
  Eigen::VectorXd element_multipliers;  // or per element, when it came from an active-set bound
  int active_set_attempts = 0, active_set_iteration = -1;
  double active_set_bound = -kInf;  // of the last restriction tried
  double iterate_bound = -kInf;     // the best of the iterates' own certificates
  int active_set_maps = 0;
  size_t active_set_elements = 0;  // in the last restriction tried
  double previous_k = kInf;        // max distortion of the previous iterate
  bool stalled = false;
  bool last_certified = true;  // the monitor formed the certificate of the last iterate
};

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

Result solve_linf(const Problem& p, const LinfOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  std::string why;
  if (!options.is_valid(&why)) throw InputError("linf: " + why);
  const int E = p.num_elements(), n = p.image_dim;
  if (options.element_bounds.size() != 0 && options.element_bounds.size() != E)
    throw InputError("element_bounds has " + std::to_string(options.element_bounds.size()) + " entries, the problem has " +
                     std::to_string(E) + " elements");
  Result result;
  auto finish = [&](const Eigen::MatrixXd& X) {
    result.positions = X;
    result.distortion = field_deviation(p, X);
    result.time_s = seconds_since(t0);
    return result;
  };
  const Eigen::VectorXd& bounds = options.element_bounds;
  const socp::ElementClasses cls = socp::classify_elements(p, bounds);

  // Constant elements: their bounds must hold as they are.
  if (cls.constant_excess_element >= 0 &&
      cls.constant_excess > options.infeasibility_tolerance * std::max(1.0, bounds[cls.constant_excess_element])) {
    result.status = SolveStatus::Infeasible;
    result.message = "element " + std::to_string(cls.constant_excess_element) +
                     " has every vertex fixed and exceeds its bound k_T by " + format(cls.constant_excess);
    return finish(p.positions);
  }
  const std::vector<int> loose = unanchored_components(p);
  if (!loose.empty()) {
    result.status = SolveStatus::NumericalError;
    result.message = "the map is not determined: the part of the mesh containing vertex " + std::to_string(loose.front()) +
                     " has no fixed vertex";
    return finish(p.positions);
  }
  if (p.num_free() == 0 || (cls.free_elements.empty() && cls.bounded_elements.empty())) {
    // Nothing to optimise: the map is the fixed positions.
    result.iterations = 0;
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

  // The main program: free elements (k), bounded elements (k_T), constant free elements (k >= kmin).
  std::vector<int> elems = cls.free_elements;
  elems.insert(elems.end(), cls.bounded_elements.begin(), cls.bounded_elements.end());
  const int num_free_cones = static_cast<int>(cls.free_elements.size());
  std::vector<int> vertex_dof(p.num_vertices, -1);
  {
    const std::vector<int> fi = p.free_index();
    for (int v = 0; v < p.num_vertices; ++v)
      if (fi[v] >= 0) vertex_dof[v] = fi[v] * n;
  }
  const int num_x = p.num_free() * n;
  ConeProgram prog = socp::element_program(p, elems, vertex_dof, num_x, p.positions);
  const bool has_kmin = cls.constant_max > -kInf;
  for (int i = num_free_cones; i < prog.num_element_cones(); ++i) {
    prog.head_a[i] = 0.0;
    prog.head_b[i] = bounds[elems[i]];
  }
  if (has_kmin) {
    prog.has_scalar = true;
    prog.head_a.conservativeResize(prog.num_cones());
    prog.head_b.conservativeResize(prog.num_cones());
    prog.head_a[prog.num_cones() - 1] = 1.0;
    prog.head_b[prog.num_cones() - 1] = -cls.constant_max;
  }
  const bool has_k = num_free_cones > 0 || has_kmin;
  socp::restrict_equalities(p, vertex_dof, num_x, p.positions, p.fixed, prog);
  const socp::IpmSettings settings = ipm_settings(options);

  // The normal equations' ordering and analysis (a third of a second at 100k elements) run on
  // another thread while this one builds the least-squares factor and the start. They read
  // only the program's structure, which stays fixed from here (phase 1 and the relaxation of
  // bounds change bounds only); the wait comes before phase 1, whose own analysis uses METIS
  // too (its random generator is global: no two orderings at once).
  std::unique_ptr<socp::NormalEquations> normal_equations;
  tbb::task_group analysis;
  const bool prepare = num_x > 0 && (num_free_cones > 0 || has_kmin);
  if (prepare) analysis.run([&] { normal_equations = std::make_unique<socp::NormalEquations>(prog, settings); });
  struct JoinOnExit {  // every return path waits for the task (it references locals)
    tbb::task_group& g;
    bool active;
    ~JoinOnExit() {
      if (active) g.wait();
    }
  } join_on_exit{analysis, prepare};

  socp::WeightedLeastSquares ls(prog);
  if (!ls.ok()) {
    result.status = SolveStatus::NumericalError;
    result.message = "the L2 system is not positive definite (degenerate elements?)";
    return finish(p.positions);
  }

  // Start: the L2 map or the given positions, whichever misses the bounds less (then has
  // the lower maximum).
  struct Candidate {
    Eigen::VectorXd x;
    double kmax = -kInf, excess = -kInf;
  };
  auto evaluate = [&](const Eigen::VectorXd& x) {
    Candidate cd;
    cd.x = x;
    const Eigen::VectorXd d = socp::cone_distortions(prog, x);
    for (int i = 0; i < prog.num_element_cones(); ++i) {
      if (i < num_free_cones)
        cd.kmax = std::max(cd.kmax, d[i]);
      else
        cd.excess = std::max(cd.excess, d[i] - prog.head_b[i]);
    }
    if (has_kmin) cd.kmax = std::max(cd.kmax, cls.constant_max);
    return cd;
  };
  Candidate start = evaluate(ls.minimizer());
  {
    const Candidate given = evaluate(p.free_dofs(p.positions));
    if (given.x.allFinite() && (given.excess < start.excess || (given.excess == start.excess && given.kmax < start.kmax)))
      start = given;
  }
  int total_iterations = 0;

  // Phase 1 and relaxation of barely missed bounds. A start that misses them by round-off
  // only (the strict minimizers pass maps that met them when evaluated on the whole mesh,
  // and bounds widened to exactly those values) keeps its place: the bounds are widened by
  // that excess instead. A phase 1 from such a start ends no closer and costs a solve.
  double relax = 0;
  double bound_scale = 1.0;
  for (int i = num_free_cones; i < prog.num_element_cones(); ++i) bound_scale = std::max(bound_scale, prog.head_b[i]);
  if (!cls.bounded_elements.empty() && start.excess > 0 && start.excess <= 1e-12 * bound_scale) {
    relax = start.excess;
  } else if (!cls.bounded_elements.empty() && start.excess > 0) {
    analysis.wait();
    Phase1 ph = run_phase1(p, cls, bounds, p.with_free_dofs(start.x), options);
    total_iterations += ph.iterations;
    if (!ph.feasible) {
      result.status = SolveStatus::Infeasible;
      result.message = ph.message;
      result.iterations = total_iterations;
      return finish(ph.X);
    }
    start = evaluate(p.free_dofs(ph.X));
    relax = std::max(0.0, start.excess);
  }
  if (relax > 0)
    for (int i = num_free_cones; i < prog.num_element_cones(); ++i) prog.head_b[i] += relax;
  if (!has_k) {
    // Every non-constant element is bounded: the feasible map is the answer.
    result.iterations = total_iterations;
    result.message = "no free element: returned a map that meets the fixed bounds";
    return finish(p.with_free_dofs(start.x));
  }

  // Phase 2: min k.
  MainSolve ms;
  ms.x = start.x;
  auto bound_ok = [&](const Eigen::VectorXd& d) {
    for (int i = num_free_cones; i < prog.num_element_cones(); ++i)
      if (d[i] - prog.head_b[i] > options.feasibility_tolerance * std::max(1.0, prog.head_b[i])) return false;
    return true;
  };
  // k of a map: the largest distortion of a free element (constant ones included).
  auto max_free = [&](const Eigen::VectorXd& d) {
    double k = has_kmin ? cls.constant_max : -kInf;
    for (int i = 0; i < num_free_cones; ++i) k = std::max(k, d[i]);
    return k;
  };
  auto equalities_ok = [&](const Eigen::VectorXd& x) {
    if (prog.num_eq() == 0) return true;
    const double scale = std::max(1.0, prog.beq.cwiseAbs().maxCoeff());
    return (prog.A * x - prog.beq).cwiseAbs().maxCoeff() <= options.feasibility_tolerance * scale;
  };
  socp::IpmState st;
  const double k0 = start_above(start.kmax);
  socp::initialize(prog, start.x, k0, 1e-2 * (1.0 + std::abs(k0)), 1.0, st);
  auto certify_iterate = [&](const socp::IpmState& s) {
    Eigen::VectorXd lambda;
    const double lb = socp::certified_lower_bound(prog, ls, s.z, s.y, &lambda);
    ms.iterate_bound = std::max(ms.iterate_bound, lb);
    if (lb > ms.lower_bound) {
      ms.lower_bound = lb;
      ms.multipliers = std::move(lambda);
      ms.element_multipliers.resize(0);
    }
  };
  // The active-set solves (linf_active_set.h), for tight tolerances, once the method is near
  // (see try_active_set): the bound from the elements within reach of the maximum (reach 1e3
  // times the iterates' certified gap, ten times more on each retry; at most three tries),
  // and the map from the same elements widened, tried again at a later iterate while k stays
  // above a bound within 1e2 tolerances of it (at most two maps).
  Eigen::VectorXd effective_bounds = bounds;
  for (Eigen::Index e = 0; e < effective_bounds.size(); ++e)
    if (socp::has_bound(bounds, static_cast<int>(e))) effective_bounds[e] += relax;
  // The elements within reach of the maximum (bounded ones: of their bound), the reach cut
  // tenfold until at most max(1000, 5%) of the elements remain.
  auto near_maximum = [&](const Eigen::VectorXd& d, double k, double reach, double tol) {
    const size_t cap = std::max<size_t>(1000, E / 20);
    std::vector<int> chosen;
    for (;; reach *= 0.1) {
      chosen.clear();
      for (int i = 0; i < prog.num_element_cones(); ++i) {
        const double top = i < num_free_cones ? k : prog.head_b[i];
        if (d[i] >= top - reach) chosen.push_back(elems[i]);
      }
      for (size_t j = 0; j < cls.constant_elements.size(); ++j)
        if (!socp::has_bound(bounds, cls.constant_elements[j]) && cls.constant_distortion[j] >= k - reach)
          chosen.push_back(cls.constant_elements[j]);
      if (chosen.size() <= cap || reach < 1e-3 * tol) return chosen;
    }
  };
  // The map: the elements and up to two rings around them (while at most three times as
  // many), the rest held; kept if it lowers k (checked on the whole problem).
  auto try_map = [&](const std::vector<int>& chosen, const Eigen::MatrixXd& X) {
    ++ms.active_set_maps;
    const ActiveSetSolve m = active_set_map(p, widen_by_rings(p, chosen, 2, 3.0), X, effective_bounds, options);
    if (options.verbose)
      std::fprintf(stderr, "linf: active-set map from %d elements (%d iterations)\n", m.elements, m.iterations);
    if (m.positions.size() == 0 || !m.positions.allFinite()) return;
    const Eigen::VectorXd x2 = p.free_dofs(m.positions);
    const Eigen::VectorXd d2 = socp::cone_distortions(prog, x2);
    const double k2 = max_free(d2);
    if (k2 < ms.k && bound_ok(d2) && equalities_ok(x2)) {
      ms.k = k2;
      ms.x = x2;
    }
  };
  auto try_active_set = [&](const socp::IpmState& s, const Eigen::VectorXd& d, double k, const socp::IpmIteration& info) {
    const double scale = std::max(1.0, std::abs(ms.k));
    const double tol = options.gap_tolerance * scale;
    // Not for loose tolerances (the strict minimizers' later levels): the iterates' own
    // certificate reaches them about as soon, and a restriction tried early costs more.
    if (!options.active_set_bounds || options.gap_tolerance > 1e-6) return;
    if (!std::isfinite(ms.k) || ms.k - ms.lower_bound <= tol) return;
    // Near: the method's gap or dual objective within 1e3 tolerances of k, or within 1e4 with
    // the maps settled (the last step lowered k by under 1% of the certified gap: the gap is
    // the dual's lag).
    const bool near = ms.k - info.dobj <= 1e3 * tol || info.gap <= 1e3 * tol;
    const bool settled = ms.k - ms.lower_bound <= 1e4 * tol && ms.previous_k - k <= 1e-2 * (ms.k - ms.lower_bound);
    if (!near && !settled) return;
    // A restriction tried before that misses part of the dual's support gives a bound below
    // the optimum: retried (with a wider reach) only once the iterates' own dual objective
    // passes that bound, or their gap falls well below the gap left to it. Otherwise, with
    // the bound in place and k still above it, only the map is tried again.
    const bool retry = ms.active_set_attempts == 0 || info.dobj > ms.active_set_bound + tol ||
                       info.gap < 0.1 * (ms.k - ms.active_set_bound);
    // The map only helps to finish when the bound is about there (it missed no support).
    const auto bound_close = [&] { return ms.k - ms.active_set_bound <= 1e2 * tol; };
    if (!retry || ms.active_set_attempts >= 3 || info.iteration == ms.active_set_iteration) {
      if (bound_close() && ms.active_set_maps < 2 && info.iteration != ms.active_set_iteration)
        try_map(near_maximum(d, k, 1e3 * std::max(ms.k - ms.iterate_bound, tol), tol), p.with_free_dofs(s.x));
      return;
    }
    const double reach = 1e3 * std::max(ms.k - ms.iterate_bound, tol) * std::pow(10.0, ms.active_set_attempts);
    const std::vector<int> chosen = near_maximum(d, k, reach, tol);
    ++ms.active_set_attempts;
    ms.active_set_iteration = info.iteration;
    // A retry that the size cap keeps to about the same elements cannot do better: the last.
    if (chosen.size() < 1.2 * ms.active_set_elements) {
      ms.active_set_attempts = 3;
      return;
    }
    ms.active_set_elements = chosen.size();
    const Eigen::MatrixXd X = p.with_free_dofs(s.x);
    const ActiveSetSolve b = active_set_bound(p, chosen, X, effective_bounds, options);
    if (options.verbose)
      std::fprintf(stderr, "linf: active-set bound %.12g from %d elements (%d iterations)\n", b.lower_bound, b.elements,
                   b.iterations);
    ms.active_set_bound = b.lower_bound;
    if (b.lower_bound > ms.lower_bound) {
      ms.lower_bound = b.lower_bound;
      ms.element_multipliers = b.multipliers;
    }
    if (bound_close() && ms.k - ms.lower_bound > tol) try_map(chosen, X);
  };

  analysis.wait();
  ms.outcome = socp::run_ipm(prog, st, settings, [&](const socp::IpmState& s, const socp::Residuals& r,
                                                     const socp::IpmIteration& info) {
    const Eigen::VectorXd& d = r.tail_norms;  // the distortions at s.x
    const double k = max_free(d);
    if (k < ms.k && bound_ok(d) && equalities_ok(s.x)) {
      ms.k = k;
      ms.x = s.x;
    }
    // The certificate costs a least-squares solve and three passes over the cones. Without
    // anyone watching the progress it is formed only once the method's dual objective or its
    // own gap is within 10^4 times the tolerance of the best k, or its directions have become
    // unreliable (a stall ends the solve on the best bound so far); before, it could not end
    // the solve. The last iterate is certified after the method in any case.
    const double scale = std::max(1.0, std::abs(ms.k));
    const double near = 1e4 * options.gap_tolerance * scale;
    const bool certify = options.progress || info.iteration == 0 || !std::isfinite(ms.k) ||
                         ms.k - info.dobj <= near || info.gap <= near || info.kkt_residual > 1e-3;
    if (certify) {
      certify_iterate(s);
      try_active_set(s, d, k, info);
    }
    ms.previous_k = k;
    ms.last_certified = certify;
    IterationRecord rec;
    rec.iteration = info.iteration;
    rec.max_distortion = std::min(k, ms.k);  // the active-set map may be better than the iterate
    rec.lower_bound = ms.lower_bound;
    rec.certified_gap = (rec.max_distortion - ms.lower_bound) / std::max(1.0, std::abs(rec.max_distortion));
    rec.time_s = seconds_since(t0);
    result.history.push_back(rec);
    if (options.progress) options.progress(rec);
    const double best_gap = ms.k - ms.lower_bound;
    if (!certify) {  // no new bound: nothing to judge progress by
      ms.last_progress_iteration = info.iteration;
      return false;
    }
    if (!std::isfinite(best_gap)) return false;  // no iterate meets the constraints yet
    if (best_gap <= options.gap_tolerance * std::max(1.0, std::abs(ms.k))) return true;
    // Stalled: the certified gap has not shrunk by 10% in 4 iterations while the Newton
    // directions are unreliable (round-off dominates); 1 iteration once the method's own
    // gap is below the tolerance (its dual iterates then only degrade: bimba_89k's dual
    // residual grows from 5e-7 to 4e-5 over the iterations after that).
    const bool ipm_converged = info.gap <= options.gap_tolerance * std::max(1.0, std::abs(info.pobj));
    if (best_gap < 0.9 * ms.last_progress_gap) {
      ms.last_progress_gap = best_gap;
      ms.last_progress_iteration = info.iteration;
    } else if (info.iteration - ms.last_progress_iteration >= (ipm_converged ? 1 : 4) && info.kkt_residual > 1e-3) {
      ms.stalled = true;
      return true;
    }
    return false;
  }, normal_equations.get());
  if (!ms.last_certified) certify_iterate(st);
  total_iterations += ms.outcome.iterations;
  result.iterations = total_iterations;
  result.lower_bound = std::min(ms.lower_bound, ms.k);
  if (ms.element_multipliers.size() == E) {
    result.multipliers = ms.element_multipliers;
  } else if (ms.multipliers.size() > 0) {
    result.multipliers = Eigen::VectorXd::Zero(E);
    for (size_t i = 0; i < elems.size(); ++i) result.multipliers[elems[i]] = ms.multipliers[static_cast<Eigen::Index>(i)];
  }
  const double gap = ms.k - ms.lower_bound;
  const double rel_gap = std::isfinite(gap) ? gap / std::max(1.0, std::abs(ms.k)) : kInf;
  // The status, decided in one place from what the solve knows (result.h).
  StopState stop;
  stop.criterion_met = rel_gap <= options.gap_tolerance;
  stop.within_acceptable = rel_gap <= options.acceptable_gap_tolerance;
  stop.cap_reached = ms.outcome.status == socp::IpmStatus::MaxIterations;
  const bool ipm_failed = ms.outcome.status == socp::IpmStatus::NumericalError;
  // A stall or a failed Newton system still leaves the best map found, which meets every
  // constraint: stalled. Only without any such map is it a numerical error.
  stop.stalled = ms.stalled || ipm_failed;
  stop.failed = ipm_failed && !std::isfinite(ms.k);
  result.status = decide_status(stop);
  const std::string figures = "k = " + format(ms.k) + ", certified lower bound " + format(ms.lower_bound) +
                              ", relative gap " + format(rel_gap);
  if (result.status == SolveStatus::Solved)
    result.message = "converged: certified relative gap within " + format(options.gap_tolerance) + " (" + figures + ")";
  else if (result.status == SolveStatus::AlmostSolved)
    result.message = "reduced accuracy: certified relative gap within " + format(options.acceptable_gap_tolerance) +
                     " but not " + format(options.gap_tolerance) + "; " +
                     (ms.stalled ? std::string("the certified gap stopped improving (the Newton systems are too "
                                               "ill-conditioned)")
                                 : ms.outcome.message) +
                     " (" + figures + ")";
  else if (ms.stalled)
    result.message = "the certified gap stopped improving (the Newton systems are too ill-conditioned) (" + figures + ")";
  else
    result.message = ms.outcome.message + " (" + figures + ")";
  if (relax > 0) result.message += "; fixed bounds relaxed by " + format(relax) + " (missed by that much at best)";
  if (!std::isfinite(ms.k)) {
    // No iterate met the bounds: return the start (which meets them up to `relax`).
    ms.x = start.x;
  }
  Eigen::MatrixXd X = p.with_free_dofs(ms.x);

  // Section 5.1 (a): the least area-weighted L2 field deviation among the minimizers.
  if (options.minimize_l2_among_optimal && result.status == SolveStatus::Solved) {
    const double kstar = ms.k;
    const double slack = options.l2_slack * std::max(1.0, kstar);
    ConeProgram q = socp::element_program(p, elems, vertex_dof, num_x, p.positions);
    q.has_k = false;
    q.c_k = 0.0;
    q.head_a.setZero();
    for (int i = 0; i < q.num_element_cones(); ++i) q.head_b[i] = (i < num_free_cones ? kstar : prog.head_b[i]) + slack;
    q.quad_weight = q.weight / q.weight.sum();
    socp::restrict_equalities(p, vertex_dof, num_x, p.positions, p.fixed, q);
    socp::IpmState st2;
    const double margin = 0.05 * std::max(kstar, 1e-3);
    socp::initialize(q, ms.x, 0.0, margin, 2.0 * margin * std::max(kstar, 1e-3) / q.num_cones(), st2);
    Eigen::VectorXd best_x;
    socp::IpmSettings s2 = settings;
    const int offset = result.history.empty() ? 0 : result.history.back().iteration;
    const auto out2 = socp::run_ipm(q, st2, s2, [&](const socp::IpmState&, const socp::Residuals& r,
                                                    const socp::IpmIteration& info) {
      const Eigen::VectorXd& d = r.tail_norms;  // the distortions at s.x
      const double k = max_free(d);
      IterationRecord rec;
      rec.iteration = offset + info.iteration;
      rec.max_distortion = k;
      rec.lower_bound = result.lower_bound;
      rec.certified_gap = (k - result.lower_bound) / std::max(1.0, std::abs(k));
      rec.time_s = seconds_since(t0);
      result.history.push_back(rec);
      if (options.progress) options.progress(rec);
      return socp::default_converged(r, s2);
    });
    result.iterations += out2.iterations;
    if (out2.status == socp::IpmStatus::MonitorStopped) {
      X = p.with_free_dofs(st2.x);
    } else {
      // The L-infinity map stays: a usable result whose second criterion was not met.
      result.status = out2.status == socp::IpmStatus::MaxIterations ? SolveStatus::MaxIterations : SolveStatus::Stalled;
      result.message = "minimize_l2_among_optimal: " + out2.message + " (the L-infinity map is returned)";
    }
  }
  return finish(X);
}

}  // namespace strictmin
