// The bordered L2 solves of the integer-grid rounding (src/tasks/bordered_l2.h).
#include "tasks/bordered_l2.h"

#include <Eigen/QR>
#include <cmath>
#include <limits>

#include "solvers/l2_complex.h"
#include "strictmin/io/input_error.h"
#include "strictmin/problem/complex_equality_basis.h"

namespace strictmin {

// S = G K^-1 G^H for the rows as they are, decomposed with column pivoting: dependent rows
// give pivots at round-off, below kRank times the largest, which count as zero.
struct BorderedL2::Decomposition {
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXcd> s;
};

namespace {
constexpr double kRank = 1e-10;
}

BorderedL2::BorderedL2(const Problem& p, const std::vector<int>& watched) : watched_(watched) {
  std::optional<ComplexEqualityBasis> basis = complex_equality_basis(p);
  if (!basis) return;
  auto l2 = std::make_unique<ComplexL2>(std::move(*basis));
  if (!l2->factorize(p, p.weights)) return;
  l2->prepare_many_solves();
  const ComplexEqualityBasis& z = l2->basis();
  local_of_node_.assign(static_cast<std::size_t>(z.num_nodes), -1);
  for (int w : watched_)
    for (int t = z.offset[w]; t < z.offset[w + 1]; ++t)
      if (local_of_node_[z.node[t]] < 0) {
        local_of_node_[z.node[t]] = static_cast<int>(nodes_.size());
        nodes_.push_back(z.node[t]);
      }
  l2_ = std::move(l2);
}

BorderedL2::~BorderedL2() = default;

void BorderedL2::push(const Row& row) {
  const ComplexEqualityBasis& z = l2_->basis();
  Eigen::SparseVector<Complex> g(z.num_nodes);
  Complex c = row.rhs;
  for (const auto& [w, a] : row.terms) {
    c -= a * z.z0(w);
    for (int t = z.offset[w]; t < z.offset[w + 1]; ++t) {
      if (local_of_node_[z.node[t]] < 0) throw std::logic_error("BorderedL2: a row names a vertex not watched");
      g.coeffRef(z.node[t]) += a * z.coefficient[t];
    }
  }
  std::vector<std::pair<int, Complex>> local;
  for (Eigen::SparseVector<Complex>::InnerIterator it(g); it; ++it)
    local.emplace_back(local_of_node_[it.index()], it.value());
  g_.push_back(std::move(local));
  g_full_.push_back(std::move(g));
  c_.push_back(c);
  cached_.reset();
}

void BorderedL2::truncate(std::size_t count) {
  if (count >= c_.size()) return;
  g_.resize(count);
  g_full_.resize(count);
  c_.resize(count);
  w_rows_ = std::min<Eigen::Index>(w_rows_, static_cast<Eigen::Index>(count));
  cached_.reset();
}

void BorderedL2::solve_new_rows() const {
  const Eigen::Index rows = static_cast<Eigen::Index>(g_.size()), count = rows - w_rows_;
  if (count <= 0) return;
  Eigen::MatrixXcd W(l2_->basis().num_nodes, count);
  for (Eigen::Index j = 0; j < count; ++j) W.col(j) = Eigen::VectorXcd(g_full_[w_rows_ + j]).conjugate();
  l2_->solve_reduced_many(W);  // one pass over the factor for the step's rows
  if (w_.cols() < rows) w_.conservativeResize(static_cast<Eigen::Index>(nodes_.size()), std::max(rows, 2 * w_.cols()));
  for (Eigen::Index j = 0; j < count; ++j)
    for (std::size_t k = 0; k < nodes_.size(); ++k) w_(static_cast<Eigen::Index>(k), w_rows_ + j) = W(nodes_[k], j);
  w_rows_ = rows;
}

Eigen::VectorXcd BorderedL2::rows_times(const Eigen::VectorXcd& y_local) const {
  Eigen::VectorXcd out(static_cast<Eigen::Index>(g_.size()));
  for (std::size_t i = 0; i < g_.size(); ++i) {
    Complex sum(0, 0);
    for (const auto& [k, value] : g_[i]) sum += value * y_local(k);
    out(static_cast<Eigen::Index>(i)) = sum;
  }
  return out;
}

const BorderedL2::Decomposition& BorderedL2::decomposition() const {
  if (cached_) return *cached_;
  solve_new_rows();
  const Eigen::Index m = static_cast<Eigen::Index>(g_.size());
  Eigen::MatrixXcd S = Eigen::MatrixXcd::Zero(m, m);
  for (Eigen::Index i = 0; i < m; ++i)
    for (const auto& [k, value] : g_[static_cast<std::size_t>(i)])
      S.row(i) += value * w_.row(k).head(m);
  cached_ = std::make_unique<Decomposition>();
  cached_->s.setThreshold(kRank);
  cached_->s.compute(S);
  return *cached_;
}

std::optional<Eigen::MatrixXd> BorderedL2::solve(const Problem& p, double tolerance) const {
  const Eigen::VectorXcd y0 = l2_->solve_reduced(l2_->reduced_rhs(p));
  Eigen::VectorXcd y(static_cast<Eigen::Index>(nodes_.size()));
  for (std::size_t k = 0; k < nodes_.size(); ++k) y(static_cast<Eigen::Index>(k)) = y0(nodes_[k]);
  const Eigen::Index m = static_cast<Eigen::Index>(g_.size());
  if (m > 0) {
    Eigen::VectorXcd miss = rows_times(y);
    for (Eigen::Index i = 0; i < m; ++i) miss(i) -= c_[static_cast<std::size_t>(i)];
    const Decomposition& d = decomposition();
    y -= w_.leftCols(m) * d.s.solve(miss);
    const Eigen::VectorXcd met = rows_times(y);
    for (Eigen::Index i = 0; i < m; ++i)
      if (!(std::abs(met(i) - c_[static_cast<std::size_t>(i)]) <= tolerance)) return std::nullopt;
  }
  const ComplexEqualityBasis& z = l2_->basis();
  Eigen::MatrixXd X = Eigen::MatrixXd::Constant(p.num_vertices, 2, std::numeric_limits<double>::quiet_NaN());
  for (int w : watched_) {
    Complex q = z.z0(w);
    for (int t = z.offset[w]; t < z.offset[w + 1]; ++t) q += z.coefficient[t] * y(local_of_node_[z.node[t]]);
    X(w, 0) = q.real();
    X(w, 1) = q.imag();
  }
  return X;
}

}  // namespace strictmin
