// L-infinity qc / iso by bisection with frame updates (conformal.h; paper Section 7).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "strictmin/problem/check_problem.h"
#include "strictmin/io/input_error.h"
#include "strictmin/solvers/conformal.h"
#include "solvers/element_bounds_check.h"
#include "solvers/option_check.h"
#include "solvers/qc/bisection.h"
#include "solvers/qc/iso_level.h"
#include "strictmin/solvers/timing.h"

namespace strictmin {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// The level of the first test when the start is not orientation-preserving: K (or S) = 1e6.
constexpr double kCap = 1e6;

void check_conformal_options(const ConformalOptions& o) {
  std::string why;
  if (!o.is_valid(&why)) throw InputError(measure_name(o.measure) + ": " + why);
}

void check_measure(Measure m) {
  if (m != Measure::Quasiconformal && m != Measure::Isometric)
    throw InputError("solve_conformal_linf minimizes qc or iso, not '" + measure_name(m) + "'");
}

// The bounds of the active elements (direct's fixed levels), -1 for free ones.
Eigen::VectorXd active_bounds(const qc::ConformalParts& parts, const Eigen::VectorXd& element_bounds) {
  Eigen::VectorXd b = Eigen::VectorXd::Constant(parts.count(), -1.0);
  if (element_bounds.size())
    for (int i = 0; i < parts.count(); ++i) {
      const double v = element_bounds[parts.element[i]];
      if (v >= 0) b[i] = v;  // finite: checked by check_element_bounds
    }
  return b;
}

// Frames for a start that is not orientation-preserving: the rest pose's (r_T = (1, 0), the
// identity's conformal part) on the elements where the start is flipped or degenerate.
Eigen::VectorXd start_frames(const qc::ConformalParts& parts, const Eigen::VectorXd& x) {
  Eigen::VectorXd r = qc::frames_of(parts, x);
  Eigen::VectorXd a, b;
  qc::evaluate_ab(parts, x, a, b);
  for (int i = 0; i < parts.count(); ++i)
    if (!(a.segment<2>(2 * i).norm() > b.segment<2>(2 * i).norm())) r.segment<2>(2 * i) << 1.0, 0.0;
  return r;
}

std::string no_orientation_preserving_map() {
  return "no orientation-preserving map meets the constraints within the frames' convex cones (certified at K = "
         "1e6, resp. S = 1e6); the handles may reverse the orientation of the mesh between them";
}

// The last bisection's bracket closed only at undecided levels: almost-solved (result.h).
std::string bracket_closed_undecided(const qc::BisectionOutcome& b, double tolerance) {
  char text[320];
  std::snprintf(text, sizeof text,
                "reduced accuracy: the last level's bracket [%.10g, %.10g] is within %.3g only through a level the "
                "feasibility test could not decide (the optimal slack is 0 there to the solver's accuracy); its "
                "certified lower end is %.10g",
                b.lower, b.value, tolerance, std::isnan(b.certified_lower) ? 1.0 : b.certified_lower);
  return text;
}

}  // namespace

Eigen::VectorXd conformal_distortion(const Problem& p, Measure m, const Eigen::MatrixXd& X) {
  check_problem(p, "conformal_distortion");
  check_map(p, X, "conformal_distortion");
  Eigen::VectorXd d(p.num_elements());
  const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(p.image_dim, p.domain_dim);
  for (int e = 0; e < p.num_elements(); ++e) d[e] = distortion(m, p.jacobian(e, X), I);
  return d;
}

bool ConformalOptions::is_valid(std::string* why) const {
  return OptionCheck(why)
      .positive("bisection_tolerance", bisection_tolerance)
      .positive("frame_tolerance", frame_tolerance)
      .at_least("max_bisection_steps", max_bisection_steps, 1)
      .at_least("max_frame_iterations", max_frame_iterations, 1)
      .at_least("max_ipm_iterations", max_ipm_iterations, 1)
      .ok();
}

Result solve_conformal_linf(const Problem& problem, const Eigen::MatrixXd& start, const ConformalOptions& options,
                            ConformalStats* stats) {
  const auto t0 = std::chrono::steady_clock::now();
  check_measure(options.measure);
  check_conformal_options(options);
  check_problem(problem, measure_name(options.measure));
  check_map(problem, start, measure_name(options.measure) + " start");
  check_element_bounds(options.element_bounds, problem.num_elements(), measure_name(options.measure));
  // 1. The cones' affine parts and the start.
  const qc::ConformalParts parts = qc::conformal_parts(problem);
  Eigen::VectorXd x = problem.free_dofs(start);
  qc::SparseCholeskyCache cache;
  qc::BisectionSetup setup;
  setup.measure = options.measure;
  setup.parts = &parts;
  setup.bounds = active_bounds(parts, options.element_bounds);
  setup.ipm = qc::feasibility_settings(options.max_ipm_iterations);
  setup.ipm.verbose = std::getenv("STRICTMIN_QC_VERBOSE") != nullptr;  // one line per iteration
  setup.cache = &cache;
  setup.frames = start_frames(parts, x);
  setup.slack_scale = qc::slack_scales(options.measure, parts, x);
  ConformalStats local;
  ConformalStats& st = stats ? *stats : local;
  Result out;
  // 2. Elements with every vertex fixed are constants: a flipped one has no cure.
  const Eigen::VectorXd fixed_values = conformal_distortion(problem, options.measure, start);
  std::vector<char> active(problem.num_elements(), 0);
  for (int e : parts.element) active[e] = 1;
  for (int e = 0; e < problem.num_elements(); ++e)
    if (!active[e] && !std::isfinite(fixed_values[e])) {
      out.status = SolveStatus::Infeasible;
      out.positions = start;
      out.distortion = fixed_values;
      out.message = "element " + std::to_string(e) +
                    " has every vertex fixed and the handles flip it (or make it degenerate): no "
                    "orientation-preserving map exists";
      out.time_s = seconds_since(t0);
      return out;
    }
  // Every element a constant (every vertex fixed): nothing to optimise, as for linf. The frame
  // loop ran to its cap over an empty program and ended max-iterations "while still lowering".
  if (parts.count() == 0) {
    out.positions = start;
    out.distortion = fixed_values;
    out.message = "nothing to optimise: every element has all its vertices fixed";
    out.time_s = seconds_since(t0);
    return out;
  }
  double current = qc::free_max(setup, x);  // with frames from x: the measure itself
  // 3. A start that is not orientation-preserving, for iso: first any orientation-preserving
  //    map, by qc's well-scaled cones at K = 1e6 (iso's at S = 1e6 would mix 1e6 and 1e-6 in
  //    one program); iso then starts from it, where its value is finite.
  if (!std::isfinite(current) && options.measure == Measure::Isometric) {
    qc::BisectionSetup phase1 = setup;
    phase1.measure = Measure::Quasiconformal;
    phase1.bounds = Eigen::VectorXd::Constant(parts.count(), -1.0);
    const qc::FeasibilityTest t = qc::test_level(phase1, kCap, x);
    ++st.bisection_steps;
    st.ipm_iterations += t.ipm_iterations;
    if (t.verdict != qc::Verdict::Feasible) {
      out.status = t.verdict == qc::Verdict::Infeasible ? SolveStatus::Infeasible : SolveStatus::NumericalError;
      out.message = t.verdict == qc::Verdict::Infeasible ? no_orientation_preserving_map()
                                                          : "could not decide whether an orientation-preserving map "
                                                            "exists: " + t.message;
      out.positions = start;
      out.distortion = fixed_values;
      out.time_s = seconds_since(t0);
      return out;
    }
    x = t.x;
    setup.frames = qc::frames_of(parts, x);
    setup.slack_scale = qc::slack_scales(options.measure, parts, x);
    current = qc::free_max(setup, x);
  }
  bool converged = false, closed_undecided = false;
  int capped_tests = 0;  // of the last bisection
  double last_improvement = 1.0;  // relative, of the last frame iteration
  std::string message;
  // 4. Frame iterations: bisection for the frames of the current map, then new frames.
  for (int f = 1; f <= options.max_frame_iterations; ++f) {
    const auto tf = std::chrono::steady_clock::now();
    // The bracket needs to be only a little narrower than the frames' last improvement: coarse
    // while they move the maximum a lot, the final tolerance once they settle (an improvement
    // below frame_tolerance: this iteration decides convergence).
    const double tolerance = last_improvement <= options.frame_tolerance
                                 ? options.bisection_tolerance
                                 : std::max(options.bisection_tolerance, std::min(1e-3, 0.1 * last_improvement));
    qc::BisectionOutcome b =
        options.measure == Measure::Isometric && options.iso_one_program && std::isfinite(current)
            ? qc::minimize_iso_level(setup, x, tolerance)
            : qc::bisect(setup, x, 1.0, kCap, tolerance, options.max_bisection_steps);
    st.bisection_steps += b.steps;
    st.ipm_iterations += b.ipm_iterations;
    st.bisection_time_s += seconds_since(tf);
    if (!b.feasible) {
      const bool certified = !std::isnan(b.certified_lower);
      out.status = certified ? SolveStatus::Infeasible : SolveStatus::NumericalError;
      message = certified ? no_orientation_preserving_map() : "could not decide whether an orientation-preserving map "
                                                              "meets the constraints: " + b.message;
      break;
    }
    ++st.frame_iterations;
    st.frames_lower_bound = b.certified_lower;
    const Eigen::VectorXd x_new = b.x;
    setup.frames = qc::frames_of(parts, x_new);
    setup.slack_scale = qc::slack_scales(options.measure, parts, x_new);
    const double next = qc::free_max(setup, x_new);  // the measure of the new map
    // Monotone: the previous map stays feasible under frames taken from it.
    if (std::isfinite(current) && next > current * (1 + 1e-12) + 1e-12) {
      out.status = SolveStatus::NumericalError;
      message = "a frame iteration raised the maximum (" + std::to_string(current) + " -> " + std::to_string(next) +
                "): round-off in the feasibility test";
      break;
    }
    const double improvement = std::isfinite(current) ? current - next : kInf;
    x = x_new;
    current = next;
    message = b.converged ? "" : b.closed_undecided ? bracket_closed_undecided(b, tolerance) : "bisection stopped at its step limit: " + b.message;  // of the last one
    IterationRecord rec;
    rec.iteration = f;
    rec.max_distortion = current;
    rec.time_s = seconds_since(t0);
    out.history.push_back(rec);
    if (options.progress) options.progress(rec);
    st.frame_time_s += seconds_since(tf);
    last_improvement = std::isfinite(improvement) ? improvement / current : 1.0;
    if (improvement <= options.frame_tolerance * current && tolerance <= options.bisection_tolerance) {
      converged = b.converged;
      closed_undecided = b.closed_undecided;
      capped_tests = b.capped_tests;
      break;
    }
  }
  // 5. The result: the measure per element, the status by the stopping criterion met.
  out.positions = problem.with_free_dofs(x);
  out.distortion = conformal_distortion(problem, options.measure, out.positions);
  out.iterations = st.frame_iterations;
  if (out.status == SolveStatus::Solved && !converged) {
    StopState stop;
    // The bracket closed, but not by a certificate: within the looser tolerance, unless tests
    // were left undecided by the interior-point cap (--max-iterations), which is a cap.
    stop.within_acceptable = closed_undecided && capped_tests == 0;
    stop.cap_reached = !stop.within_acceptable;
    out.status = decide_status(stop);
    if (capped_tests > 0)
      message += "; " + std::to_string(capped_tests) + " feasibility tests of the last bisection stopped at the "
                 "interior-point cap (" + std::to_string(options.max_ipm_iterations) + ")";
    if (message.empty()) message = "frame iterations stopped at their limit while still lowering the maximum";
  }
  if (out.status == SolveStatus::Solved && message.empty()) {
    char text[200];
    std::snprintf(text, sizeof text,
                  "converged: the last frame iteration lowered the maximum by less than %g relative, its bracket "
                  "certified within the tolerance (%d frame iterations)",
                  options.frame_tolerance, st.frame_iterations);
    message = text;
  }
  out.message = message;
  out.time_s = seconds_since(t0);
  return out;
}

Result solve_conformal_direct(const Problem& problem, const Eigen::MatrixXd& start, const ConformalOptions& options,
                              const DirectOptions& direct, ConformalStats* stats) {
  check_measure(options.measure);
  check_conformal_options(options);
  ConformalStats local;
  ConformalStats& st = stats ? *stats : local;
  DirectOptions d = direct;
  Problem from_start = problem;  // Algorithm 2 starts from the problem's positions
  from_start.positions = start;
  // Each level: the bisection with the fixed elements' bounds as their own cone levels
  // (paper Section 7: "binary-search L-infinity optimization in the direct strict solver").
  d.level_iteration_unit = "frame iterations";
  d.level_solver = [&](const Problem& level, const LinfOptions& o, const Eigen::MatrixXd& X) {
    ConformalOptions c = options;
    c.element_bounds = o.element_bounds;
    // Levels after the first need their value to a fraction of delta_k only (solve_direct
    // raises the gap to DirectOptions::level_gap from the second level): so does the bracket.
    c.bisection_tolerance = std::max(options.bisection_tolerance, o.gap_tolerance);
    c.progress = nullptr;
    ConformalStats s;
    Result r = solve_conformal_linf(level, X, c, &s);
    st.bisection_steps += s.bisection_steps;
    st.frame_iterations += s.frame_iterations;
    st.ipm_iterations += s.ipm_iterations;
    st.bisection_time_s += s.bisection_time_s;
    st.frame_time_s += s.frame_time_s;
    return r;
  };
  return solve_direct(from_start, d);
}

}  // namespace strictmin
