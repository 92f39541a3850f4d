#include "solvers/no_flips_step.h"

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "solvers/qc/qc_program.h"
#include "solvers/qc/sparse_socp.h"
#include "strictmin/measures/field_deviation.h"
#include "strictmin/solvers/no_flips.h"
#include "strictmin/solvers/timing.h"

namespace strictmin {
namespace {

using qc::add_row;

// The program. Variables: y = x / map_scale (the map's free dofs in rest-pose
// length units, as the qc programs), then k (Maximum) or one t_T per element
// with a free vertex (Energy). Rows s = h - G (y, ...), cone by cone.
struct StepProgram {
  qc::SparseSocp program;
  int num_x = 0;  // the first objective variable's index
  double map_scale = 1;
  std::vector<int> element;  // Energy: the element of each t
};

// Collects the rows, and gives each element's distortion cone its head: k >=
// ||tail|| (Maximum) or the rotated cone ((t + 1) / 2, (t - 1) / 2, tail), i.e.
// t >= ||tail||^2 (Energy).
class Rows {
 public:
  Rows(StepObjective objective, int num_x) : objective_(objective), n_(num_x) {}
  // Appends the head of element e's distortion cone; its tail rows follow at
  // the returned row.
  int head(int e) {
    if (objective_ == StepObjective::Maximum) {
      t.emplace_back(row, n_, -1.0);
      h.push_back(0.0);
      return row + 1;
    }
    const int column = n_ + static_cast<int>(element.size());
    element.push_back(e);
    t.emplace_back(row, column, -0.5);
    h.push_back(0.5);
    t.emplace_back(row + 1, column, -0.5);
    h.push_back(-0.5);
    return row + 2;
  }
  int head_rows() const { return objective_ == StepObjective::Maximum ? 1 : 2; }
  // Ends a cone of `dim` rows that started at `row`.
  void close(int dim) {
    dims.push_back(dim);
    row += dim;
  }
  // Maximum: k >= the constant elements' distortion (elements without a free
  // vertex, active[e] == 0; d0 holds every element's at the start), when there
  // are any. (They are constant terms of the energy.)
  void constant_floor(const std::vector<char>& active, const Eigen::VectorXd& d0) {
    if (objective_ != StepObjective::Maximum) return;
    double constant = 0;
    bool any_constant = false;
    for (int e = 0; e < static_cast<int>(active.size()); ++e)
      if (!active[e]) constant = std::max(constant, d0[e]), any_constant = true;
    if (!any_constant) return;
    t.emplace_back(row, n_, -1.0);
    h.push_back(-constant);
    close(1);
  }
  // The program: minimize k, or sum_T w_T t_T / sum_T w_T.
  void finish(const Problem& p, StepProgram& out) {
    const int columns = n_ + (objective_ == StepObjective::Maximum ? 1 : static_cast<int>(element.size()));
    out.program.G.resize(row, columns);
    out.program.G.setFromTriplets(t.begin(), t.end());
    out.program.h = Eigen::Map<const Eigen::VectorXd>(h.data(), static_cast<Eigen::Index>(h.size()));
    out.program.c = Eigen::VectorXd::Zero(columns);
    if (objective_ == StepObjective::Maximum) {
      out.program.c[n_] = 1.0;
    } else {
      double total = 0;
      for (int e : element) total += p.weights[e];
      for (size_t i = 0; i < element.size(); ++i)
        out.program.c[n_ + i] = p.weights[element[i]] / std::max(total, 1e-300);
    }
    out.program.dims = std::move(dims);
    out.element = std::move(element);
  }

  std::vector<Eigen::Triplet<double>> t;
  std::vector<double> h;
  int row = 0;

 private:
  StepObjective objective_;
  int n_;
  std::vector<int> dims;
  std::vector<int> element;
};

// Planar maps (docs/arap.md): Lipman's cone in the conformal parts. d0: the
// field deviation of every element at the start.
StepProgram build_planar(const Problem& p, const Eigen::VectorXd& x0, const Eigen::VectorXd& d0,
                         StepObjective objective) {
  const qc::ConformalParts parts = qc::conformal_parts(p);
  const int E = parts.count(), n = parts.num_x;
  const double L = parts.map_scale;
  StepProgram out;
  out.num_x = n;
  out.map_scale = L;
  Rows rows(objective, n);
  auto& t = rows.t;
  auto& h = rows.h;
  Eigen::VectorXd a, b;
  qc::evaluate_ab(parts, x0, a, b);
  const double root2 = std::sqrt(2.0);
  for (int i = 0; i < E; ++i) {
    // The target's parts r (conformal) and s (anticonformal).
    const Eigen::MatrixXd R = p.target(parts.element[i]);
    const double r0 = 0.5 * (R(0, 0) + R(1, 1)), r1 = 0.5 * (R(1, 0) - R(0, 1));
    const double s0 = 0.5 * (R(0, 0) - R(1, 1)), s1 = 0.5 * (R(1, 0) + R(0, 1));
    // ||J - R|| = sqrt(2) ||(a - r, b - s)||: the tail.
    const int tail = rows.head(parts.element[i]);
    for (int j = 0; j < 2; ++j) {  // sqrt(2) (a - r)
      add_row(parts.A, 2 * i + j, -root2 * L, tail + j, t);
      h.push_back(root2 * (parts.a0[2 * i + j] - (j == 0 ? r0 : r1)));
    }
    for (int j = 0; j < 2; ++j) {  // sqrt(2) (b - s)
      add_row(parts.B, 2 * i + j, -root2 * L, tail + 2 + j, t);
      h.push_back(root2 * (parts.b0[2 * i + j] - (j == 0 ? s0 : s1)));
    }
    rows.close(rows.head_rows() + 4);
    // |b| <= <a, f> where the element is positive at x0.
    const double na = std::hypot(a[2 * i], a[2 * i + 1]);
    if (!(na > std::hypot(b[2 * i], b[2 * i + 1]))) continue;
    const double f0 = a[2 * i] / na, f1 = a[2 * i + 1] / na;
    const int row = rows.row;
    add_row(parts.A, 2 * i, -f0 * L, row, t);
    add_row(parts.A, 2 * i + 1, -f1 * L, row, t);
    h.push_back(f0 * parts.a0[2 * i] + f1 * parts.a0[2 * i + 1]);
    for (int j = 0; j < 2; ++j) {
      add_row(parts.B, 2 * i + j, -L, row + 1 + j, t);
      h.push_back(parts.b0[2 * i + j]);
    }
    rows.close(3);
  }
  std::vector<char> active(p.num_elements(), 0);
  for (int e : parts.element) active[e] = 1;
  rows.constant_floor(active, d0);
  rows.finish(p, out);
  return out;
}

// For det J > 0: V (a rotation) and sigma > 0 from J^T J = V diag(sigma^2) V^T,
// and U = J V diag(sigma)^-1, so J = U diag(sigma) V^T with det U > 0. (The
// cones need only det U det V > 0 to keep det J >= 0, and U^T J V close to
// diag(sigma) for X0 to lie well inside them: round-off in U is harmless.)
void proper_svd(const Eigen::Matrix3d& J, Eigen::Matrix3d& U, Eigen::Vector3d& sigma, Eigen::Matrix3d& V) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(J.transpose() * J);
  V = eig.eigenvectors();
  if (V.determinant() < 0) V.col(0) *= -1;
  sigma = eig.eigenvalues().cwiseMax(0).cwiseSqrt();
  sigma = sigma.cwiseMax(1e-12 * sigma.maxCoeff());
  U = J * V * sigma.cwiseInverse().asDiagonal();
}

// Tets: the field deviation's cone ||J_T - R_T||_F <= k (10 rows), and where
// det J_T(X0) > 0 a convex set of orientation-preserving J around J_T(X0) = U
// diag(sigma) V^T: with S = sym(C U^T J V C), C = diag(sigma)^(-1/2), every row
// diagonally dominant,
//   S_ii >= sqrt(2) ||(S_ij, S_il)||  (j, l the other two; three 3-cones),
// so S is positive semidefinite, the eigenvalues of U^T J V have non-negative
// real parts, and det J = det(U^T J V) >= 0 (> 0 inside the cones). At X0, S =
// I: strictly inside.
StepProgram build_tets(const Problem& p, const Eigen::VectorXd& x0, const Eigen::VectorXd& d0,
                       StepObjective objective) {
  const Problem::Reduced red = p.reduced();
  const Eigen::SparseMatrix<double, Eigen::RowMajor> G = red.G;
  const int n = static_cast<int>(G.cols()), E = p.num_elements();
  double sum = 0;
  for (Eigen::Index i = 0; i < G.nonZeros(); ++i) sum += G.valuePtr()[i] * G.valuePtr()[i];
  StepProgram out;
  out.num_x = n;
  out.map_scale = sum > 0 ? 1.0 / std::sqrt(sum / static_cast<double>(G.nonZeros())) : 1.0;
  const double L = out.map_scale;
  const Eigen::VectorXd j0 = G * x0 - red.h;  // vec(J - R) at x0
  Rows rows(objective, n);
  auto& t = rows.t;
  auto& h = rows.h;
  std::vector<char> active(E, 0);
  for (int e = 0; e < E; ++e) {
    for (int r = 0; r < 9; ++r)
      active[e] = active[e] || G.outerIndexPtr()[9 * e + r + 1] > G.outerIndexPtr()[9 * e + r];
    if (!active[e]) continue;
    // The tail vec(J - R) = G_e x - h_e.
    const int tail = rows.head(e);
    for (int r = 0; r < 9; ++r) {
      qc::add_row(G, 9 * e + r, -L, tail + r, t);
      h.push_back(-red.h[9 * e + r]);
    }
    rows.close(rows.head_rows() + 9);
    const Eigen::Matrix3d R = p.target(e);
    const Eigen::Matrix3d J0 = R + Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(j0.data() + 9 * e);
    if (!(J0.determinant() > 0)) continue;
    Eigen::Matrix3d U, V;
    Eigen::Vector3d sigma;
    proper_svd(J0, U, sigma, V);
    const Eigen::Vector3d c = sigma.cwiseSqrt().cwiseInverse();
    // S_ab = sum_rc w_rc J_rc, w_rc = c_a c_b (U_ra V_cb + U_rb V_ca) / 2, J =
    // (G_e x - h_e) + R.
    auto add_entry = [&](int a, int b, double scale, int row) {
      double offset = 0;
      for (int r = 0; r < 3; ++r)
        for (int col = 0; col < 3; ++col) {
          const double w = scale * c[a] * c[b] * 0.5 * (U(r, a) * V(col, b) + U(r, b) * V(col, a));
          if (w == 0) continue;
          qc::add_row(G, 9 * e + 3 * r + col, -w * L, row, t);
          offset += w * (R(r, col) - red.h[9 * e + 3 * r + col]);
        }
      h.push_back(offset);
    };
    for (int a = 0; a < 3; ++a) {
      int row = rows.row;
      add_entry(a, a, 1.0, row++);
      for (int b = 0; b < 3; ++b)
        if (b != a) add_entry(a, b, std::sqrt(2.0), row++);
      rows.close(3);
    }
  }
  rows.constant_floor(active, d0);
  rows.finish(p, out);
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
  return steps_without_new_flips_apply(p) && o.element_bounds.size() == 0;
}

bool steps_without_new_flips_apply(const Problem& p) {
  const bool planar = p.image_dim == 2 && p.domain_dim == 2, tets = p.image_dim == 3 && p.domain_dim == 3;
  return (planar || tets) && !p.has_equalities();
}

double weighted_energy(const Problem& p, const Eigen::VectorXd& distortion) {
  const double total = p.weights.sum();
  return total > 0 ? p.weights.dot(distortion.cwiseAbs2()) / total : 0.0;
}

Result step_without_new_flips(const Problem& problem, const Eigen::MatrixXd& X0, StepObjective objective,
                              double gap_tolerance, double feasibility_tolerance, bool certify) {
  const auto t0 = std::chrono::steady_clock::now();
  const bool maximum = objective == StepObjective::Maximum;
  Problem p = problem;
  p.positions = X0;
  const Eigen::VectorXd x0 = p.free_dofs(X0);
  const Eigen::VectorXd d0 = field_deviation(p, X0);
  const StepProgram step = p.domain_dim == 3 ? build_tets(p, x0, d0, objective) : build_planar(p, x0, d0, objective);
  // The start: X0 with k at its maximum, or each t at its element's square (the
  // solver lifts the slacks into the cones).
  Eigen::VectorXd v0(step.program.c.size());
  v0.head(step.num_x) = x0 / step.map_scale;
  if (maximum)
    v0[step.num_x] = d0.size() ? 1.01 * d0.maxCoeff() + 1e-12 : 0.0;
  else
    for (size_t i = 0; i < step.element.size(); ++i)
      v0[step.num_x + i] = 1.01 * d0[step.element[i]] * d0[step.element[i]] + 1e-12;
  qc::SparseSocpSettings settings;
  settings.gap_tolerance = gap_tolerance;
  settings.feasibility_tolerance = feasibility_tolerance;
  qc::SparseCholeskyCache cache;
  const qc::SparseSocpOutcome r = qc::solve_sparse_socp(step.program, v0, settings, nullptr, &cache);
  Result out;
  // The map returned is X0 or a checked improvement on it either way: a cone program that
  // failed (numerical-error) leaves a usable map, a step that stopped short (stalled).
  out.status = r.status == qc::SparseSocpStatus::NumericalError ? SolveStatus::Stalled : status_of(r.status);
  out.iterations = r.iterations;
  const Eigen::MatrixXd X = p.with_free_dofs(r.x.head(step.num_x) * step.map_scale);
  // The solver's map when it is no worse than the start for the objective and
  // adds no flip (it cannot, to round-off; checked), else the start.
  const Eigen::VectorXd d = field_deviation(p, X);
  const bool no_worse =
      maximum ? d.size() && d.maxCoeff() <= d0.maxCoeff() : weighted_energy(p, d) <= weighted_energy(p, d0);
  const bool better = r.x.allFinite() && no_worse && flips_added(p, X0, X) == 0;
  out.positions = better ? X : X0;
  out.distortion = better ? d : d0;
  out.lower_bound = certify && maximum && r.status == qc::SparseSocpStatus::Converged
                        ? qc::corrected_dual_bound(step.program, r.z, &cache)
                        : -std::numeric_limits<double>::infinity();
  out.message = (out.status == SolveStatus::Solved ? "converged" : r.message) +
                std::string(" (the step inside the orientation-preserving cones, ") + std::to_string(r.iterations) +
                " interior-point iterations)";
  out.time_s = seconds_since(t0);
  return out;
}

Result linf_without_new_flips(const Problem& problem, const Eigen::MatrixXd& X0, double gap_tolerance,
                              double feasibility_tolerance) {
  return step_without_new_flips(problem, X0, StepObjective::Maximum, gap_tolerance, feasibility_tolerance);
}

}  // namespace strictmin
