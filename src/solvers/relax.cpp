// Relaxation-based strict minimization (paper Algorithm 3): the sweeper and the driver.
// The sweep itself is in relax_sweep.cpp.
#include "strictmin/solvers/relax.h"

#include <chrono>
#include <string>

#include "relax_copies.h"
#include "relax_sweep.h"
#include "strictmin/problem/check_problem.h"
#include "strictmin/io/input_error.h"
#include "strictmin/measures/field_deviation.h"
#include "strictmin/solvers/interrupt.h"
#include "option_check.h"
#include "io/text_parse.h"

namespace strictmin {

using namespace relax_detail;

// A seamless problem (copies of a vertex related by the seams' transitions) sweeps its groups
// of copies (relax_copies.h); every other problem its vertices (relax_sweep.h).
struct RelaxSweeper::Impl : SweepData {
  std::unique_ptr<CopiesSweeper> copies;
  int num_vertices = 0, num_elements = 0;  // of the problem it was built for
};

namespace {
bool sweeps_copies(const Problem& p) {
  return p.has_equalities() && p.copy_base.size() == static_cast<size_t>(p.num_vertices) && p.image_dim == 2;
}

void check_no_flips_with_copies(const Problem& p, bool no_flips) {
  if (no_flips && sweeps_copies(p))
    throw InputError("relax: --no-flips is not available with seams (seamless problems) yet");
}
}  // namespace

RelaxSweeper::RelaxSweeper(const Problem& p, double accept_tolerance, bool no_flips)
    : accept_tolerance_(accept_tolerance) {
  RelaxOptions options;  // the range of RelaxOptions::accept_tolerance (a NaN never accepted a move: endless sweeps)
  options.accept_tolerance = accept_tolerance;
  std::string why;
  if (!options.is_valid(&why)) throw InputError("relax: " + why);
  check_problem(p, "relax");
  check_no_flips_with_copies(p, no_flips);
  check_no_flips(p, no_flips);
  auto impl = std::make_shared<Impl>();
  if (sweeps_copies(p)) {
    impl->copies = std::make_unique<CopiesSweeper>(p);
    impl->colouring = impl->copies->colouring();
  } else {
    build(p, *impl);
  }
  impl->no_flips = no_flips;
  impl->num_vertices = p.num_vertices;
  impl->num_elements = p.num_elements();
  impl_ = std::move(impl);
}

double RelaxSweeper::sweep(const Problem& problem, Eigen::MatrixXd& X) const { return sweep(problem, X, nullptr); }

double RelaxSweeper::sweep(const Problem& problem, Eigen::MatrixXd& X, double* max_distortion) const {
  // The rings index the construction's vertices and elements: another mesh read out of bounds.
  if (problem.num_vertices != impl_->num_vertices || problem.num_elements() != impl_->num_elements)
    throw InputError("relax: the sweeper was built for " + std::to_string(impl_->num_vertices) + " vertices and " +
                     std::to_string(impl_->num_elements) + " elements, the problem has " +
                     std::to_string(problem.num_vertices) + " and " + std::to_string(problem.num_elements()));
  if (X.rows() != problem.num_vertices || X.cols() != impl_->dim)
    throw InputError("relax: the map has " + std::to_string(X.rows()) + " by " + std::to_string(X.cols()) +
                     " entries, expected " + std::to_string(problem.num_vertices) + " by " +
                     std::to_string(impl_->dim));
  if (impl_->copies) return impl_->copies->sweep(problem, X, accept_tolerance_, max_distortion);
  Deviations dev;
  return sweep_any(*impl_, problem, X, dev, accept_tolerance_, max_distortion);
}

int RelaxSweeper::num_colours() const { return impl_->colouring.num_colours; }

const VertexColouring& RelaxSweeper::colouring() const { return impl_->colouring; }

namespace relax_detail {

void set_relax_status(Result& result, const RelaxOptions& options, bool moves_settled) {
  StopState stop;
  stop.criterion_met = options.move_tolerance > 0 ? moves_settled : true;
  stop.cap_reached = !stop.criterion_met;
  result.status = decide_status(stop);
  if (moves_settled)
    result.message = "converged: no vertex moved more than the move tolerance in sweep " + std::to_string(result.iterations);
  else if (stop.criterion_met)
    result.message = "ran the requested " + std::to_string(options.sweeps) + " sweeps";
  else if (options.sweeps == 0)
    result.message = "no sweep ran (--sweeps 0), so the move tolerance could not be checked";
  else
    result.message = "reached the sweep cap (" + std::to_string(options.sweeps) +
                     ") with vertices still moving more than the move tolerance";
}

bool record_sweep(Result& result, const RelaxOptions& options, const IterationRecord& record) {
  result.history.push_back(record);
  result.iterations = record.iteration;
  if (options.progress) options.progress(record);
  return record.largest_move < options.move_tolerance;
}

}  // namespace relax_detail

bool RelaxOptions::is_valid(std::string* why) const {
  return OptionCheck(why)
      .at_least("sweeps", sweeps, 0)
      .non_negative("move_tolerance", move_tolerance)
      .that(accept_tolerance >= 0 && accept_tolerance < 1,
            "accept_tolerance must be in [0, 1) (got " + io_detail::number_text(accept_tolerance) + ")")
      .ok();
}

Result relax(const Problem& problem, const Eigen::MatrixXd& initial, const RelaxOptions& options) {
  std::string why;
  if (!options.is_valid(&why)) throw InputError("relax: " + why);
  check_problem(problem, "relax");
  check_map(problem, initial, "relax start");
  const auto t0 = std::chrono::steady_clock::now();
  const auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
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
  if (sweeps_copies(problem)) {
    check_no_flips_with_copies(problem, options.no_flips);
    return relax_with_copies(problem, X, options);
  }
  check_no_flips(problem, options.no_flips);
  SweepData data;
  build(problem, data);
  data.no_flips = options.no_flips;
  Deviations dev;
  bool moves_settled = false;
  for (int s = 1; s <= options.sweeps; ++s) {
    check_interrupt();  // solvers/interrupt.h
    IterationRecord record;
    record.iteration = s;
    if (dev.age >= kRefreshInterval) dev.age = -1;
    const double move = sweep_any(data, problem, X, dev, options.accept_tolerance, &record.max_distortion);
    record.largest_move = move;
    record.time_s = elapsed();
    if ((moves_settled = record_sweep(result, options, record))) break;
  }
  result.positions = std::move(X);
  result.distortion = field_deviation(problem, result.positions);
  set_relax_status(result, options, moves_settled);
  result.time_s = elapsed();
  return result;
}

}  // namespace strictmin
