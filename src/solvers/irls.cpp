#include "strictmin/solvers/irls.h"

#include <chrono>

#include "strictmin/solvers/l2.h"

namespace strictmin {

Result solve_irls(const Problem& p, const IrlsOptions& options) {
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
    // Lawson's update; a floor keeps K positive definite when some D_T reach 0.
    w = w.cwiseProduct(r.distortion);
    const double total = p.weights.dot(w);
    if (!(total > 0)) break;  // every element at zero distortion: nothing to improve
    w /= total;
    w = w.cwiseMax(1e-12 * w.maxCoeff());
    if (!solver.reweight(p, p.weights.cwiseProduct(w))) {
      r.status = SolveStatus::NumericalError;
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
  r.time_s = elapsed();
  return r;
}

}  // namespace strictmin
