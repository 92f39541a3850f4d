// Relaxation-based strict minimization (paper Algorithm 3): the sweeper and the driver.
// The sweep itself is in relax_sweep.cpp.
#include "strictmin/solvers/relax.h"

#include <chrono>
#include <string>

#include "relax_copies.h"
#include "relax_sweep.h"
#include "strictmin/io/input_error.h"
#include "strictmin/solvers/l2.h"

namespace strictmin {

using namespace relax_detail;

struct RelaxSweeper::Impl : SweepData {};

RelaxSweeper::RelaxSweeper(const Problem& p, double accept_tolerance) : accept_tolerance_(accept_tolerance) {
  auto impl = std::make_shared<Impl>();
  build(p, *impl);
  impl_ = std::move(impl);
}

double RelaxSweeper::sweep(const Problem& problem, Eigen::MatrixXd& X) const { return sweep(problem, X, nullptr); }

double RelaxSweeper::sweep(const Problem& problem, Eigen::MatrixXd& X, double* max_distortion) const {
  if (X.rows() != problem.num_vertices || X.cols() != impl_->dim)
    throw InputError("relax: the map has " + std::to_string(X.rows()) + " by " + std::to_string(X.cols()) +
                     " entries, expected " + std::to_string(problem.num_vertices) + " by " +
                     std::to_string(impl_->dim));
  Deviations dev;
  return sweep_any(*impl_, problem, X, dev, accept_tolerance_, max_distortion);
}

int RelaxSweeper::num_colours() const { return impl_->colouring.num_colours; }

const VertexColouring& RelaxSweeper::colouring() const { return impl_->colouring; }

Result relax(const Problem& problem, const Eigen::MatrixXd& initial, const RelaxOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  const auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
  if (initial.rows() != problem.num_vertices || initial.cols() != problem.image_dim)
    throw InputError("relax: the initial map has " + std::to_string(initial.rows()) + " by " +
                     std::to_string(initial.cols()) + " entries, expected " + std::to_string(problem.num_vertices) +
                     " by " + std::to_string(problem.image_dim));
  if (problem.has_equalities() && problem.copy_base.size() == static_cast<size_t>(problem.num_vertices) &&
      problem.image_dim == 2) {
    Eigen::MatrixXd X = initial;
    for (int v = 0; v < problem.num_vertices; ++v)
      if (problem.fixed[v]) X.row(v) = problem.positions.row(v);
    return relax_with_copies(problem, X, options);
  }
  SweepData data;
  build(problem, data);
  Result result;
  Eigen::MatrixXd X = initial;
  for (int v = 0; v < problem.num_vertices; ++v)
    if (problem.fixed[v]) X.row(v) = problem.positions.row(v);
  if (!X.allFinite()) {
    result.positions = X;
    result.distortion = field_deviation(problem, X);
    result.status = SolveStatus::NumericalError;
    result.message = "relax: the initial map has non-finite coordinates";
    result.time_s = elapsed();
    return result;
  }
  Deviations dev;
  for (int s = 1; s <= options.sweeps; ++s) {
    IterationRecord record;
    record.iteration = s;
    if (dev.age >= kRefreshInterval) dev.age = -1;
    const double move = sweep_any(data, problem, X, dev, options.accept_tolerance, &record.max_distortion);
    record.time_s = elapsed();
    result.history.push_back(record);
    result.iterations = s;
    if (options.progress) options.progress(record);
    if (options.largest_move) options.largest_move(s, move);
    if (move < options.move_tolerance) break;
  }
  result.positions = std::move(X);
  result.distortion = field_deviation(problem, result.positions);
  result.status = SolveStatus::Solved;
  result.time_s = elapsed();
  return result;
}

}  // namespace strictmin
