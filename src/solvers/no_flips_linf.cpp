#include "solvers/no_flips_linf.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "strictmin/measures/field_deviation.h"
#include "strictmin/solvers/no_flips.h"
#include "strictmin/solvers/timing.h"
#include "solvers/qc/qc_program.h"
#include "solvers/qc/sparse_socp.h"

namespace strictmin {
namespace {

using qc::add_row;

// The program. Variables: y = x / parts.map_scale (the map's free dofs in rest-pose length
// units, as the qc programs), then k. Rows s = h - G (y, k), cone by cone.
struct StepProgram {
  qc::SparseSocp program;
  int k_index = 0;
};

// d0: the field deviation of every element at the start (the constant elements' enter k's floor).
StepProgram build(const Problem& p, const qc::ConformalParts& parts, const Eigen::VectorXd& x0,
                  const Eigen::VectorXd& d0) {
  const int E = parts.count(), n = parts.num_x;
  const double L = parts.map_scale;
  StepProgram out;
  out.k_index = n;
  std::vector<Eigen::Triplet<double>> t;
  std::vector<double> h;
  std::vector<int> dims;
  int row = 0;
  Eigen::VectorXd a, b;
  qc::evaluate_ab(parts, x0, a, b);
  const double root2 = std::sqrt(2.0);
  for (int i = 0; i < E; ++i) {
    // The target's parts r (conformal) and s (anticonformal).
    const Eigen::MatrixXd R = p.target(parts.element[i]);
    const double r0 = 0.5 * (R(0, 0) + R(1, 1)), r1 = 0.5 * (R(1, 0) - R(0, 1));
    const double s0 = 0.5 * (R(0, 0) - R(1, 1)), s1 = 0.5 * (R(1, 0) + R(0, 1));
    // sqrt(2) ||(a - r, b - s)|| <= k.
    t.emplace_back(row, n, -1.0);
    h.push_back(0.0);
    for (int j = 0; j < 2; ++j) {  // rows row+1, row+2: sqrt(2) (a - r)
      add_row(parts.A, 2 * i + j, -root2 * L, row + 1 + j, t);
      h.push_back(root2 * (parts.a0[2 * i + j] - (j == 0 ? r0 : r1)));
    }
    for (int j = 0; j < 2; ++j) {  // rows row+3, row+4: sqrt(2) (b - s)
      add_row(parts.B, 2 * i + j, -root2 * L, row + 3 + j, t);
      h.push_back(root2 * (parts.b0[2 * i + j] - (j == 0 ? s0 : s1)));
    }
    dims.push_back(5);
    row += 5;
    // |b| <= <a, f> where the element is positive at x0.
    const double na = std::hypot(a[2 * i], a[2 * i + 1]);
    if (!(na > std::hypot(b[2 * i], b[2 * i + 1]))) continue;
    const double f0 = a[2 * i] / na, f1 = a[2 * i + 1] / na;
    add_row(parts.A, 2 * i, -f0 * L, row, t);
    add_row(parts.A, 2 * i + 1, -f1 * L, row, t);
    h.push_back(f0 * parts.a0[2 * i] + f1 * parts.a0[2 * i + 1]);
    for (int j = 0; j < 2; ++j) {
      add_row(parts.B, 2 * i + j, -L, row + 1 + j, t);
      h.push_back(parts.b0[2 * i + j]);
    }
    dims.push_back(3);
    row += 3;
  }
  // k >= the constant elements' distortion (no free vertex: not in parts).
  std::vector<char> active(p.num_elements(), 0);
  for (int e : parts.element) active[e] = 1;
  double constant = 0;
  bool any_constant = false;
  for (int e = 0; e < p.num_elements(); ++e)
    if (!active[e]) constant = std::max(constant, d0[e]), any_constant = true;
  if (any_constant) {
    t.emplace_back(row, n, -1.0);
    h.push_back(-constant);
    dims.push_back(1);
    ++row;
  }
  out.program.G.resize(row, n + 1);
  out.program.G.setFromTriplets(t.begin(), t.end());
  out.program.h = Eigen::Map<const Eigen::VectorXd>(h.data(), static_cast<Eigen::Index>(h.size()));
  out.program.c = Eigen::VectorXd::Zero(n + 1);
  out.program.c[n] = 1.0;
  out.program.dims = std::move(dims);
  return out;
}

SolveStatus status_of(qc::SparseSocpStatus s) {
  switch (s) {
    case qc::SparseSocpStatus::Converged: return SolveStatus::Solved;
    case qc::SparseSocpStatus::MaxIterations: return SolveStatus::MaxIterations;
    case qc::SparseSocpStatus::Stopped: return SolveStatus::Stalled;
    case qc::SparseSocpStatus::NumericalError: return SolveStatus::NumericalError;
  }
  return SolveStatus::NumericalError;
}

}  // namespace

bool linf_without_new_flips_applies(const Problem& p, const LinfOptions& o) {
  return p.image_dim == 2 && p.domain_dim == 2 && !p.has_equalities() && o.element_bounds.size() == 0;
}

Result linf_without_new_flips(const Problem& problem, const Eigen::MatrixXd& X0, double gap_tolerance) {
  const auto t0 = std::chrono::steady_clock::now();
  Problem p = problem;
  p.positions = X0;
  const qc::ConformalParts parts = qc::conformal_parts(p);
  const Eigen::VectorXd x0 = p.free_dofs(X0);
  const Eigen::VectorXd d0 = field_deviation(p, X0);
  const StepProgram step = build(p, parts, x0, d0);
  // The start: X0 with k at its maximum (the solver lifts the slacks into the cones).
  Eigen::VectorXd v0(parts.num_x + 1);
  v0.head(parts.num_x) = x0 / parts.map_scale;
  v0[step.k_index] = d0.size() ? 1.01 * d0.maxCoeff() + 1e-12 : 0.0;
  qc::SparseSocpSettings settings;
  settings.gap_tolerance = gap_tolerance;
  qc::SparseCholeskyCache cache;
  const qc::SparseSocpOutcome r = qc::solve_sparse_socp(step.program, v0, settings, nullptr, &cache);
  Result out;
  out.status = status_of(r.status);
  out.iterations = r.iterations;
  const Eigen::MatrixXd X = p.with_free_dofs(r.x.head(parts.num_x) * parts.map_scale);
  // The solver's map when it is no worse than the start and adds no flip (it cannot, to
  // round-off; checked), else the start.
  const Eigen::VectorXd d = field_deviation(p, X);
  const bool better = r.x.allFinite() && d.size() && d.maxCoeff() <= d0.maxCoeff() && flips_added(p, X0, X) == 0;
  out.positions = better ? X : X0;
  out.distortion = better ? d : d0;
  out.lower_bound = r.status == qc::SparseSocpStatus::Converged ? qc::corrected_dual_bound(step.program, r.z, &cache)
                                                                 : -std::numeric_limits<double>::infinity();
  out.message = (out.status == SolveStatus::Solved ? "converged" : r.message) +
                std::string(" (the step inside the orientation-preserving cones, ") + std::to_string(r.iterations) +
                " interior-point iterations)";
  out.time_s = seconds_since(t0);
  return out;
}

}  // namespace strictmin
