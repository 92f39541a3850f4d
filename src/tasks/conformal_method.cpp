#include "strictmin/tasks/conformal_method.h"

#include <algorithm>
#include <string>

#include "strictmin/io/input_error.h"

namespace strictmin {

bool is_conformal_measure(Measure m) { return m == Measure::Quasiconformal || m == Measure::Isometric; }

Result run_conformal_method(const Problem& problem, const Eigen::MatrixXd& start, Measure measure,
                            const SolverOptions& options, ConformalStats* stats) {
  std::string why;
  if (!options.is_valid(&why)) throw InputError("invalid solver options: " + why);  // as run_method (NaN gap, 0 frames)
  // 1. The options of the bisection from the L-infinity ones (--gap: the bracket's width).
  ConformalOptions c;
  c.measure = measure;
  c.bisection_tolerance = std::max(options.linf.gap_tolerance, 1e-10);
  c.max_frame_iterations = options.frame_iterations;
  c.max_ipm_iterations = options.linf.max_iterations;  // --max-iterations: each program's cap
  c.progress = options.linf.progress;
  // 2. The method.
  switch (options.method) {
    case Method::L2: {
      Result r;
      r.positions = start;
      r.distortion = conformal_distortion(problem, measure, start);
      r.message = "l2 with --measure " + measure_name(measure) + " is the starting map, not a minimizer";
      return r;
    }
    case Method::Linf:
      return solve_conformal_linf(problem, start, c, stats);
    case Method::Direct:
      return solve_conformal_direct(problem, start, c, options.direct, stats);
    default:
      throw InputError("--measure " + measure_name(measure) + " supports --method l2 (the starting map), linf and " +
                       "direct; '" + method_name(options.method) + "' is not available for it" +
                       (options.method == Method::Relax
                            ? " (relax has no exact 1-ring step for a measure that is convex only for fixed frames)"
                            : ""));
  }
}

}  // namespace strictmin
