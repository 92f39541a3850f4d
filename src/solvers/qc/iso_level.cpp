#include "solvers/qc/iso_level.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "solvers/qc/qc_program.h"

namespace strictmin::qc {
namespace {

// True when x meets the bounded elements' levels to a relative 1e-9 (the interior-point
// iterate meets its cones to its primal residual only).
bool meets_bounds(const BisectionSetup& s, const Eigen::VectorXd& x) {
  if (!s.bounds.size()) return true;
  const Eigen::VectorXd v = frame_values(s.measure, *s.parts, s.frames, x);
  for (int i = 0; i < v.size(); ++i)
    if (s.bounds[i] >= 0 && !(v[i] <= s.bounds[i] * (1 + 1e-9))) return false;
  return true;
}

}  // namespace

BisectionOutcome minimize_iso_level(const BisectionSetup& s, const Eigen::VectorXd& x0, double tolerance) {
  // 1. The program for these frames and bounds, started from x0.
  BisectionOutcome out;
  out.x = x0;
  out.value = free_max(s, x0);
  out.feasible = std::isfinite(out.value);
  const IsoProgram prog = iso_program(*s.parts, s.frames, s.bounds);
  SparseSocpSettings settings = s.ipm;
  settings.gap_tolerance = 0.5 * tolerance;  // relative to max(1, S): the bracket's own measure
  // 2. Stop on the first iterate whose map is within the tolerance of a certified lower
  //    bound (the dual iterate corrected to exact feasibility: its own residual is not zero),
  //    tried once the gap is below the tolerance; keep the best map and bound seen.
  const int nx = s.parts->num_x;
  double bound = -std::numeric_limits<double>::infinity();
  auto monitor = [&](const SparseSocpIterate& it) {
    if (!(it.gap <= tolerance * std::max(1.0, std::abs(it.pobj)) && it.pres <= 1e-8 && it.dres <= 1e-5))
      return false;
    const Eigen::VectorXd x = s.parts->map_scale * it.x->head(nx);
    const double value = free_max(s, x);
    if (std::isfinite(value) && value < out.value && meets_bounds(s, x)) {
      out.x = x;
      out.value = value;
      out.feasible = true;
    }
    // The heads are bounded on the maps with S <= S_max (IsoProgram::head_bounds); with S_max
    // the best value the corrected bound holds for every map that could beat it, hence for
    // the optimum (min(bound, S_max) covers the case that none can).
    const double s_max = out.value;
    bound = std::max(bound, std::min(s_max, corrected_dual_bound(prog.program, *it.z, s.cache, prog.head_bounds(s_max))));
    return out.value - bound <= tolerance * std::max(1.0, out.value);
  };
  const SparseSocpOutcome r = solve_sparse_socp(prog.program, iso_start(prog, *s.parts, s.frames, x0, out.value),
                                                settings, monitor, s.cache);
  out.steps = 1;
  out.ipm_iterations = r.iterations;
  if (std::isfinite(bound)) {
    out.certified_lower = std::max(bound, 1.0);
    out.lower = out.certified_lower;
  }
  out.converged = out.feasible && out.value - bound <= tolerance * std::max(1.0, out.value);
  if (std::getenv("STRICTMIN_QC_VERBOSE"))
    std::fprintf(stderr, "iso level: status %d its %d value %.12g bound %.12g tol %.2e %s\n", static_cast<int>(r.status),
                 r.iterations, out.value, bound, tolerance, r.message.c_str());
  if (out.converged) return out;
  // 3. Otherwise the bisection's closing tests: a level just inside the tolerance below the
  //    best map's value, certified infeasible, closes the bracket; a witness there lowers the
  //    value and the next closing level (kClosingTests at most); undecided levels leave the
  //    bracket closed only through them (almost-solved, as the bisection's).
  constexpr int kClosingTests = 2;
  for (int k = 0; k < kClosingTests && !out.converged; ++k) {
    const double level = out.value - 0.999 * tolerance * std::max(1.0, out.value);
    if (std::isfinite(bound) && level <= bound) break;
    const FeasibilityTest t = test_into(s, level, out);
    if (t.verdict == Verdict::Feasible) continue;
    out.lower = std::max(std::isfinite(out.lower) ? out.lower : 1.0, level);
    if (t.verdict == Verdict::Infeasible) {
      bound = std::max(bound, level);
      out.certified_lower = std::max(bound, 1.0);
      out.converged = true;
    } else {
      out.closed_undecided = true;
      out.message = "undecided at level " + std::to_string(level) + (t.message.empty() ? "" : ": " + t.message);
    }
    break;
  }
  if (!out.converged && !out.closed_undecided && out.message.empty())
    out.message = "the iso level program stopped short of a certified optimum: " +
                  (r.message.empty() ? std::string("its corrected dual bound is too far below") : r.message);
  return out;
}

}  // namespace strictmin::qc
