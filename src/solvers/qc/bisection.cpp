#include "solvers/qc/bisection.h"

#include <algorithm>
#include <cmath>

namespace strictmin::qc {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Levels of every active element for a free level.
Eigen::VectorXd levels(const BisectionSetup& s, double free_level) {
  Eigen::VectorXd l(s.parts->count());
  for (int i = 0; i < l.size(); ++i) l[i] = s.bounds.size() && s.bounds[i] >= 0 ? s.bounds[i] : free_level;
  return l;
}

// True when x meets every level (a witness); `value` = its largest free frame value.
bool meets(const BisectionSetup& s, const Eigen::VectorXd& level, const Eigen::VectorXd& x, double& value) {
  const Eigen::VectorXd v = frame_values(s.measure, *s.parts, s.frames, x);
  value = 0;
  bool ok = true;
  for (int i = 0; i < v.size(); ++i) {
    ok = ok && v[i] <= level[i];
    if (!(s.bounds.size() && s.bounds[i] >= 0)) value = std::max(value, v[i]);
  }
  return ok;
}

// The midpoint of a bracket: geometric while it spans a large ratio (the first bracket of a
// flipped start reaches up to the cap).
double midpoint(double lo, double hi) { return hi > 4 * lo && lo > 0 ? std::sqrt(lo * hi) : 0.5 * (lo + hi); }

}  // namespace

double free_max(const BisectionSetup& s, const Eigen::VectorXd& x) {
  const Eigen::VectorXd v = frame_values(s.measure, *s.parts, s.frames, x);
  double m = 0;
  for (int i = 0; i < v.size(); ++i)
    if (!(s.bounds.size() && s.bounds[i] >= 0)) m = std::max(m, v[i]);
  return m;
}

FeasibilityTest test_level(const BisectionSetup& s, double free_level, const Eigen::VectorXd& x_start) {
  // 1. The slack program at these levels, started from the last feasible map.
  const Eigen::VectorXd level = levels(s, free_level);
  const SparseSocp program = slack_program(s.measure, *s.parts, s.frames, level, 1.0, s.slack_scale);
  const int nx = s.parts->num_x;
  FeasibilityTest out;
  // 2. Stop on the first iterate that settles the question: a witness map, or a positive
  //    dual bound on the slack with a small dual residual.
  auto monitor = [&](const SparseSocpIterate& it) {
    double value = 0;
    const Eigen::VectorXd x = s.parts->map_scale * it.x->head(nx);
    if (meets(s, level, x, value)) {
      out.verdict = Verdict::Feasible;
      out.x = x;
      out.value = value;
      return true;
    }
    // A positive dual bound, certified after correcting the dual iterate to exact
    // feasibility (its residual would otherwise leave the bound unproven); tried once the
    // slack is positive and the gap below it (the raw dual bound may still be negative).
    if (it.pobj > 0 && it.gap < it.pobj && it.dres <= 1e-4 && corrected_dual_bound(program, *it.z, s.cache) > 0) {
      out.verdict = Verdict::Infeasible;
      return true;
    }
    return false;
  };
  const SparseSocpOutcome r =
      solve_sparse_socp(program, slack_start(s.measure, *s.parts, x_start), s.ipm, monitor, s.cache);
  out.ipm_iterations = r.iterations;
  // 3. Otherwise the optimum slack's sign decides, when the solve converged away from 0.
  if (out.verdict == Verdict::Undecided && r.pobj > 0 && corrected_dual_bound(program, r.z, s.cache) > 0)
    out.verdict = Verdict::Infeasible;
  if (out.verdict == Verdict::Undecided) {
    out.message = r.message;
    out.capped = r.status == SparseSocpStatus::MaxIterations;
  }
  return out;
}

SparseSocpSettings feasibility_settings(int max_iterations) {
  SparseSocpSettings st;
  st.max_iterations = max_iterations;
  st.gap_tolerance = 1e-12;
  st.refinement_steps = 10;  // the dual iterate's accuracy near the optimum decides the certificate
  return st;
}

FeasibilityTest test_into(const BisectionSetup& s, double level, BisectionOutcome& out) {
  FeasibilityTest t = test_level(s, level, out.x);
  ++out.steps;
  out.ipm_iterations += t.ipm_iterations;
  out.capped_tests += t.capped ? 1 : 0;
  if (t.verdict == Verdict::Feasible) {
    out.x = t.x;
    out.value = std::min(t.value, level);
    out.feasible = true;
  }
  return t;
}

BisectionOutcome bisect(const BisectionSetup& s, const Eigen::VectorXd& x0, double floor, double cap,
                        double tolerance, int max_steps) {
  BisectionOutcome out;
  out.x = x0;
  out.value = free_max(s, x0);
  out.feasible = std::isfinite(out.value);
  // The bracket [lo, value]: value a witness's own value; below it, lo_certified (the floor or
  // a level with a positive corrected dual bound) and lo (>= lo_certified: also undecided
  // levels, where the optimal slack is 0 to the solver's accuracy, so that the optimum is
  // there to that accuracy: the bisection steers by lo, the convergence is measured by
  // lo_certified).
  double lo = floor, lo_certified = floor;
  auto width = [&] { return tolerance * std::max(1.0, out.value); };
  // One test at `level`: a feasible one lowers the upper end to the witness's own value,
  // any other raises the lower end (certified only when infeasible).
  auto step = [&](double level) {
    const FeasibilityTest t = test_into(s, level, out);
    if (t.verdict == Verdict::Feasible) {
      if (lo >= out.value) lo = lo_certified;  // an undecided level above a witness: not the optimum
    } else {
      lo = std::max(lo, level);
      if (t.verdict == Verdict::Infeasible) {
        lo_certified = std::max(lo_certified, level);
        out.certified_lower = std::isnan(out.certified_lower) ? level : std::max(out.certified_lower, level);
      } else if (out.message.empty()) {
        out.message = "undecided at level " + std::to_string(level) + (t.message.empty() ? "" : ": " + t.message);
      }
    }
    return t.verdict;
  };
  // 1. Without a feasible start: first a level near the cap (an orientation-preserving map).
  if (!out.feasible) {
    if (step(cap) != Verdict::Feasible) {
      out.lower = lo;
      return out;
    }
  }
  // 2. Gallop down from the upper end (frame updates usually lower it a little), then bisect.
  double d = std::max(1e-3 * (out.value - lo), width());
  bool bracketed = false;
  while (!bracketed && out.value - lo > width() && out.steps < max_steps) {
    const double level = out.value - d;
    if (level <= lo) break;
    bracketed = step(level) != Verdict::Feasible;
    d *= 4;
  }
  // 3. Bisect [lo, value] down to the tolerance. A bracket closed by an undecided lower end
  //    (the optimum sits there to the solver's accuracy) is then closed by a certified level
  //    as far below the optimum as the tolerance allows, value - 0.999 w (w the tolerance's
  //    width); when that is undecided too, a witness between it and the upper end lowers the
  //    upper end, and with it the next closing level (at most kClosingSteps such tests).
  constexpr int kClosingSteps = 2;
  int closing_steps = 0;
  while (out.value - lo_certified > width() && out.steps < max_steps) {
    if (out.value - lo > width()) {
      step(midpoint(lo, out.value));
      continue;
    }
    if (closing_steps++ >= kClosingSteps) break;
    const double close = out.value - 0.999 * width();
    step(lo < close ? close : midpoint(lo, out.value));
  }
  out.converged = out.value - lo_certified <= width();
  out.closed_undecided = !out.converged && out.value - lo <= width();
  out.lower = lo;
  return out;
}

}  // namespace strictmin::qc
