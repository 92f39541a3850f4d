#include "strictmin/solvers/irls.h"

#include <chrono>
#include <cmath>

#include "strictmin/problem/check_problem.h"
#include "strictmin/measures/field_deviation.h"
#include "strictmin/solvers/l2.h"
#include "strictmin/io/input_error.h"
#include "strictmin/solvers/interrupt.h"
#include "option_check.h"

namespace strictmin {

bool IrlsOptions::is_valid(std::string* why) const {
  return OptionCheck(why).at_least("iterations", iterations, 1).ok();
}

Result solve_irls(const Problem& p, const IrlsOptions& options) {
  std::string why;
  if (!options.is_valid(&why)) throw InputError("irls: " + why);
  check_problem(p, "irls");
  const auto t0 = std::chrono::steady_clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
  Result r;
  L2Solver solver(p);
  r.positions = solver.solve(p);
  if (solver.status() != SolveStatus::Solved) {
    r.status = solver.status();
    r.message = solver.message();
    r.distortion = field_deviation(p, r.positions);
    return r;
  }
  Eigen::VectorXd w = Eigen::VectorXd::Ones(p.num_elements());
  r.distortion = field_deviation(p, r.positions);
  for (int it = 1; it <= options.iterations; ++it) {
    check_interrupt();  // solvers/interrupt.h
    // Lawson's update; a floor keeps K positive definite when some D_T reach 0.
    w = w.cwiseProduct(r.distortion);
    const double total = p.weights.dot(w);
    if (!std::isfinite(total)) {
      r.status = SolveStatus::NumericalError;
      r.message = "IRLS: the map's distortion is not finite";
      break;
    }
    if (!(total > 0)) break;  // every element at zero distortion: nothing to improve
    w /= total;
    w = w.cwiseMax(1e-12 * w.maxCoeff());
    if (!solver.reweight(p, p.weights.cwiseProduct(w))) {
      // The last solve's map stays: usable, but the reweighting stopped.
      r.status = SolveStatus::Stalled;
      r.message = "IRLS: " + solver.message();
      break;
    }
    r.positions = solver.solve(p);
    r.distortion = field_deviation(p, r.positions);
    r.iterations = it;
    IterationRecord rec;
    rec.iteration = it;
    rec.max_distortion = r.distortion.maxCoeff();
    rec.time_s = elapsed();
    r.history.push_back(rec);
    if (options.progress) options.progress(rec);
  }
  if (r.status == SolveStatus::Solved)
    r.message = "ran " + std::to_string(r.iterations) + " of the requested " + std::to_string(options.iterations) +
                " reweighted solves" + (r.iterations < options.iterations ? " (every element at zero distortion)" : "");
  r.time_s = elapsed();
  return r;
}

}  // namespace strictmin
