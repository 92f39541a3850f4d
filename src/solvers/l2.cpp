#include "strictmin/solvers/l2.h"
#include "strictmin/problem/check_problem.h"
#include "strictmin/solvers/timing.h"

#include <chrono>
#include <cmath>
#include <numeric>

#include "strictmin/io/input_error.h"
#include "strictmin/measures/field_deviation.h"
#include "solvers/l2_complex.h"
#include "strictmin/problem/parts.h"

namespace strictmin {

namespace {

// The problem's free-vertex index, after its contract is checked (free_index reads `fixed`).
std::vector<int> checked_free_index(const Problem& p) {
  check_problem(p, "l2");
  return p.free_index();
}

}  // namespace

L2Solver::L2Solver(const Problem& p, const L2Options& options)
    : free_index_(checked_free_index(p)), num_elements_(p.num_elements()) {
  if (p.has_equalities() && options.complex_equalities) {
    if (auto basis = complex_equality_basis(p)) {
      complex_ = std::make_shared<ComplexL2>(std::move(*basis));
      factorize_complex(p, p.weights);
      return;
    }
  }
  if (p.has_equalities()) {
    auto basis = std::make_shared<EqualityBasis>(equality_basis(p));
    message_ = equalities_contradiction(p, *basis);
    if (!message_.empty()) {
      status_ = SolveStatus::Infeasible;
      return;
    }
    basis_ = std::move(basis);
    assemble(p, p.weights);
    if (K_.rows() == 0) return;
    const auto t0 = std::chrono::steady_clock::now();
    cholesky_.analyze(K_);
    analyze_s_ = seconds_since(t0);
    factorize();
    if (status_ != SolveStatus::Solved)
      message_ = "the L2 system with the equalities is singular (is every part anchored by a fixed vertex?)";
    return;
  }
  assemble(p, p.weights);
  if (K_.rows() == 0) return;
  const std::vector<int> loose = unanchored_components(p);
  if (!loose.empty()) {
    status_ = SolveStatus::NumericalError;
    message_ = "the map is not determined: the part of the mesh containing vertex " + std::to_string(loose.front()) +
               " has no fixed vertex (" + std::to_string(loose.size()) + " such part(s))";
    return;
  }
  const auto t0 = std::chrono::steady_clock::now();
  cholesky_.analyze(K_);
  analyze_s_ = seconds_since(t0);
  factorize();
}

// The factorization indexes the construction's vertices and elements: another problem read
// out of bounds.
void L2Solver::check_same_size(const Problem& p) const {
  if (p.num_vertices != static_cast<int>(free_index_.size()) || p.num_elements() != num_elements_)
    throw InputError("l2: the solver was built for " + std::to_string(free_index_.size()) + " vertices and " +
                     std::to_string(num_elements_) + " elements, the problem has " + std::to_string(p.num_vertices) +
                     " and " + std::to_string(p.num_elements()));
}

bool L2Solver::reweight(const Problem& p, const Eigen::VectorXd& element_weights) {
  check_same_size(p);
  if (element_weights.size() != num_elements_)
    throw InputError("l2: " + std::to_string(element_weights.size()) + " element weights for " +
                     std::to_string(num_elements_) + " elements");
  if (complex_) return factorize_complex(p, element_weights);
  if (status_ != SolveStatus::Solved && !cholesky_.analyzed()) return false;
  assemble(p, element_weights);
  return K_.rows() == 0 || factorize();
}

// The energy separates by image coordinate with one scalar matrix K (see l2.h), so on the
// full dof vector it is K (x) I_n; the seams' rotations couple the coordinates only through Z.
void L2Solver::assemble_constrained(const Problem& p, const Eigen::VectorXd& element_weights) {
  const int c = p.corners(), n = p.image_dim;
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(static_cast<size_t>(p.num_elements()) * c * c * n);
  for (int e = 0; e < p.num_elements(); ++e) {
    const auto g = p.gradients.middleRows(e * c, c);
    for (int i = 0; i < c; ++i)
      for (int j = 0; j < c; ++j) {
        const double kij = element_weights(e) * g.row(i).dot(g.row(j));
        for (int r = 0; r < n; ++r) t.emplace_back(p.elements(e, i) * n + r, p.elements(e, j) * n + r, kij);
      }
  }
  Eigen::SparseMatrix<double> K_full(static_cast<Eigen::Index>(p.num_vertices) * n, static_cast<Eigen::Index>(p.num_vertices) * n);
  K_full.setFromTriplets(t.begin(), t.end());
  Zt_ = basis_->Z.transpose();
  const Eigen::SparseMatrix<double> KZ = K_full * basis_->Z;
  K_ = (Zt_ * KZ).pruned();
  Kz0_ = K_full * basis_->z0;
}

Eigen::MatrixXd L2Solver::solve_constrained(const Problem& p) const {
  const int c = p.corners(), n = p.image_dim, m = p.domain_dim;
  Eigen::MatrixXd X = p.positions;
  Eigen::VectorXd q = basis_->z0;
  if (K_.rows() > 0) {
    // b = sum_T A_T R_T g_i at the dofs of corner i, as in the unconstrained case.
    Eigen::VectorXd b = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(p.num_vertices) * n);
    for (int e = 0; e < p.num_elements(); ++e)
      for (int i = 0; i < c; ++i)
        for (int r = 0; r < n; ++r) {
          double sum = 0;
          for (int k = 0; k < m; ++k) sum += p.targets(e * n + r, k) * p.gradients(e * c + i, k);
          b(static_cast<Eigen::Index>(p.elements(e, i)) * n + r) += element_weights_(e) * sum;
        }
    const Eigen::MatrixXd y = cholesky_.solve(Zt_ * (b - Kz0_));
    q += basis_->Z * y.col(0);
  }
  for (int v = 0; v < p.num_vertices; ++v)
    for (int r = 0; r < n; ++r) X(v, r) = q(static_cast<Eigen::Index>(v) * n + r);
  return X;
}

void L2Solver::assemble(const Problem& p, const Eigen::VectorXd& element_weights) {
  element_weights_ = element_weights;
  if (basis_) return assemble_constrained(p, element_weights);
  const int c = p.corners(), F = p.num_free();
  std::vector<Eigen::Triplet<double>> free_t, fixed_t;
  free_t.reserve(static_cast<size_t>(p.num_elements()) * c * c);
  for (int e = 0; e < p.num_elements(); ++e) {
    const auto g = p.gradients.middleRows(e * c, c);
    for (int i = 0; i < c; ++i) {
      const int fi = free_index_[p.elements(e, i)];
      if (fi < 0) continue;
      for (int j = 0; j < c; ++j) {
        const double kij = element_weights(e) * g.row(i).dot(g.row(j));
        const int vj = p.elements(e, j), fj = free_index_[vj];
        if (fj >= 0) {
          if (fj <= fi) free_t.emplace_back(fi, fj, kij);  // lower triangle
        } else {
          fixed_t.emplace_back(fi, vj, kij);
        }
      }
    }
  }
  K_.resize(F, F);
  K_.setFromTriplets(free_t.begin(), free_t.end());
  K_fixed_.resize(F, p.num_vertices);
  K_fixed_.setFromTriplets(fixed_t.begin(), fixed_t.end());
}

bool L2Solver::factorize() {
  const auto t0 = std::chrono::steady_clock::now();
  const bool ok = cholesky_.factorize(K_);
  factorize_s_ = seconds_since(t0);
  status_ = ok ? SolveStatus::Solved : SolveStatus::NumericalError;
  message_ = ok ? "" : "the L2 system is not positive definite (degenerate elements?)";
  return ok;
}

bool L2Solver::factorize_complex(const Problem& p, const Eigen::VectorXd& element_weights) {
  const bool ok = complex_->factorize(p, element_weights);
  analyze_s_ = complex_->analyze_s();
  factorize_s_ = complex_->factorize_s();
  status_ = ok ? SolveStatus::Solved : SolveStatus::NumericalError;
  message_ = ok ? "" : "the L2 system with the equalities is singular (is every part anchored by a fixed vertex?)";
  return ok;
}

Eigen::MatrixXd L2Solver::solve(const Problem& p) const {
  check_same_size(p);
  if (complex_) return status_ == SolveStatus::Solved ? complex_->solve(p) : p.positions;
  if (basis_ && status_ == SolveStatus::Solved) return solve_constrained(p);
  Eigen::MatrixXd X = p.positions;
  if (status_ != SolveStatus::Solved || K_.rows() == 0 || basis_) return X;
  const int c = p.corners(), n = p.image_dim;
  // B_i = sum_T A_T R_T g_i (one row per free vertex, one column per image coordinate),
  // minus the couplings to the fixed vertices.
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(K_.rows(), n);
  const int m = p.domain_dim;
  for (int e = 0; e < p.num_elements(); ++e) {
    for (int i = 0; i < c; ++i) {
      const int fi = free_index_[p.elements(e, i)];
      if (fi < 0) continue;
      for (int r = 0; r < n; ++r) {
        double sum = 0;  // (R_T g_i)_r
        for (int k = 0; k < m; ++k) sum += p.targets(e * n + r, k) * p.gradients(e * c + i, k);
        B(fi, r) += element_weights_(e) * sum;
      }
    }
  }
  B.noalias() -= K_fixed_ * p.positions;
  const Eigen::MatrixXd Q = cholesky_.solve(B);
  for (int v = 0; v < p.num_vertices; ++v)
    if (free_index_[v] >= 0) X.row(v) = Q.row(free_index_[v]);
  return X;
}

Result solve_l2(const Problem& p, const L2Options& options) {
  const auto t0 = std::chrono::steady_clock::now();
  Result r;
  const L2Solver solver(p, options);
  r.status = solver.status();
  r.message = solver.message();
  if (r.message.empty())
    r.message = "least squares: one factorization and solve (" + std::to_string(p.num_free()) + " free vertices)";
  r.positions = solver.solve(p);
  r.distortion = field_deviation(p, r.positions);
  r.iterations = 1;
  if (r.status == SolveStatus::Solved && !(r.positions.allFinite() && r.distortion.allFinite())) {
    r.status = SolveStatus::NumericalError;
    r.message = "least squares: the solve gave a map that is not finite";
  }
  r.time_s = seconds_since(t0);
  return r;
}

}  // namespace strictmin
