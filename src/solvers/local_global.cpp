#include "strictmin/solvers/local_global.h"
#include "strictmin/solvers/timing.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

#include "strictmin/io/input_error.h"
#include "strictmin/measures/measures.h"
#include "strictmin/solvers/l2.h"
#include "strictmin/solvers/relax.h"
#include "strictmin/solvers/interrupt.h"
#include "option_check.h"

namespace strictmin {
namespace {

Eigen::MatrixXd local_target(const Problem& p, int e, const Eigen::MatrixXd& J, const LocalGlobalOptions& o) {
  if (o.local == LocalStep::Similarity) return closest_similarity(J);
  if (o.shapes.size() == 0) return closest_rotation(J);
  const Eigen::MatrixXd S = o.shapes.middleRows(e * p.image_dim, p.image_dim);
  return closest_rotation(J * S.transpose()) * S;
}

// The largest distortion over the elements without a fixed bound (all of them unless a
// direct level passes bounds): the quantity the global step minimizes.
double max_of(const Eigen::VectorXd& d, const Eigen::VectorXd& bounds) {
  double m = 0;
  for (Eigen::Index e = 0; e < d.size(); ++e)
    if (bounds.size() == 0 || !(bounds(e) >= 0)) m = std::max(m, d(e));
  return m;
}

// The local-global iterations from out.positions: local step, then one global step (one
// sweep for relax, a solve otherwise), until the cap or a small relative change of the max.
// The status: the loop's own (converged, almost at the cap, or the cap) combined with the
// last global step's, so that a global solve that stopped short shows (result.h).
Result iterate(Problem& p, Result out, const SolverOptions& solver, const LocalGlobalOptions& o,
               std::chrono::steady_clock::time_point t0) {
  std::unique_ptr<RelaxSweeper> sweeper;
  if (solver.method == Method::Relax) sweeper = std::make_unique<RelaxSweeper>(p, solver.relax.accept_tolerance);
  const bool fixed_count = o.relative_change < 0;  // relax sweeps: run them all
  double previous = max_of(local_distortion(p, out.positions, o), solver.linf.element_bounds);
  double last_change = kNotApplicable;
  SolveStatus last_global = SolveStatus::Solved;
  std::string last_global_message;
  StopState stop;
  std::string reason;
  for (int it = 1; it <= o.max_iterations; ++it) {
    check_interrupt();  // solvers/interrupt.h
    local_step(p, out.positions, o);
    Result r;
    if (sweeper) {
      r.positions = out.positions;
      sweeper->sweep(p, r.positions);
    } else {
      r = run_method(p, solver);
      if (!r.usable()) {
        out.status = r.status;
        out.message = "global step " + std::to_string(it) + ": " + r.message;
        out.distortion = local_distortion(p, out.positions, o);
        out.time_s = seconds_since(t0);
        return out;
      }
      out.lower_bound = r.lower_bound;
    }
    const Eigen::VectorXd d = local_distortion(p, r.positions, o);
    const double current = max_of(d, solver.linf.element_bounds);
    // An L-infinity global step cannot raise the maximum beyond its tolerance; keep the
    // better map if rounding says otherwise.
    if (solver.method == Method::Linf && current > previous) {
      stop.criterion_met = true;
      reason = "converged: the maximum stopped decreasing";
      break;
    }
    last_global = r.status;
    last_global_message = r.message;
    out.positions = r.positions;
    out.iterations = it;
    last_change = previous > 0 ? std::abs(previous - current) / previous : 0.0;
    IterationRecord rec;
    rec.iteration = it;
    rec.max_distortion = current;
    rec.lower_bound = r.lower_bound;
    rec.relative_change = last_change;
    rec.time_s = seconds_since(t0);
    out.history.push_back(rec);
    if (o.progress) o.progress(rec);
    previous = current;
    if (!fixed_count && last_change <= o.relative_change) {
      stop.criterion_met = true;
      reason = "converged: relative change of the maximum below " + std::to_string(o.relative_change);
      break;
    }
  }
  if (fixed_count && reason.empty()) {
    stop.criterion_met = true;
    reason = "ran the requested " + std::to_string(o.max_iterations) + " sweeps with local steps";
  } else if (reason.empty()) {
    stop.cap_reached = true;
    // Almost: the last change within ten times the tolerance (docs/formats.md).
    stop.within_acceptable = last_change <= 10 * o.relative_change;
    reason = "reached the iteration cap (" + std::to_string(o.max_iterations) + "); last relative change " +
             std::to_string(last_change);
  }
  out.status = worse_status(decide_status(stop), last_global);
  if (last_global != SolveStatus::Solved) reason += "; the last global step: " + last_global_message;
  out.message = reason;
  out.distortion = local_distortion(p, out.positions, o);
  out.time_s = seconds_since(t0);
  return out;
}

}  // namespace

void local_step(Problem& p, const Eigen::MatrixXd& X, const LocalGlobalOptions& o) {
  for (int e = 0; e < p.num_elements(); ++e) p.set_target(e, local_target(p, e, p.jacobian(e, X), o));
}

Eigen::VectorXd local_distortion(const Problem& p, const Eigen::MatrixXd& X, const LocalGlobalOptions& o) {
  Eigen::VectorXd d(p.num_elements());
  for (int e = 0; e < p.num_elements(); ++e) {
    const Eigen::MatrixXd J = p.jacobian(e, X);
    d(e) = (J - local_target(p, e, J, o)).norm();
  }
  return d;
}

bool LocalGlobalOptions::is_valid(std::string* why) const {
  return OptionCheck(why)
      .at_least("max_iterations", max_iterations, 0)
      .that(!std::isnan(relative_change), "relative_change must be a number (got nan)")
      .ok();
}

Result local_global(const Problem& problem, const Eigen::MatrixXd& X0, const SolverOptions& solver,
                    const LocalGlobalOptions& o) {
  const auto t0 = std::chrono::steady_clock::now();
  std::string why;
  if (!o.is_valid(&why)) throw InputError("local-global: " + why);
  if (!solver.is_valid(&why)) throw InputError("invalid solver options: " + why);
  Problem p = problem;
  Result out;
  out.positions = X0;
  for (int v = 0; v < p.num_vertices; ++v)
    if (p.fixed[v]) out.positions.row(v) = p.positions.row(v);
  if (solver.method == Method::Exact) {
    out.status = SolveStatus::NumericalError;
    out.message = "the exact strict minimizer is for field deviation only; use direct or relax with ARAP/ASAP";
    out.distortion = local_distortion(p, out.positions, o);
    return out;
  }
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
    p.positions = out.positions;  // the first level starts here
    direct.level_solver = [o](const Problem& level_problem, const LinfOptions& linf, const Eigen::MatrixXd& X) {
      SolverOptions inner;
      inner.method = Method::Linf;
      inner.linf = linf;
      LocalGlobalOptions lo = o;
      lo.progress = nullptr;
      return local_global(level_problem, X, inner, lo);
    };
    Result r = solve_direct(p, direct, solver.linf);
    r.time_s = seconds_since(t0);
    return r;
  }
  return iterate(p, std::move(out), solver, o, t0);
}

}  // namespace strictmin
