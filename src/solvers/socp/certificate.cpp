#include "solvers/socp/certificate.h"

#include <cmath>
#include <limits>
#include <vector>

namespace strictmin::socp {

namespace {

// f(vertex row, vertex column, w_i <g_j1, g_j2>) for every pair of free corners of every
// element with row >= column (dof bases, vertex-major): the lower triangle of G^T W G's
// vertex matrix K (each entry summed over the elements).
template <class F>
void for_each_gram_entry(const ConeProgram& p, F&& f) {
  const int m = p.m, c = p.corners();
  for (int i = 0; i < p.num_element_cones(); ++i) {
    const double* g = p.grad.data() + static_cast<size_t>(i) * c * m;
    for (int j1 = 0; j1 < c; ++j1) {
      const int b1 = p.dof_base[i * c + j1];
      if (b1 < 0) continue;
      for (int j2 = 0; j2 < c; ++j2) {
        const int b2 = p.dof_base[i * c + j2];
        if (b2 < 0 || b2 > b1) continue;
        double gram = 0;
        for (int col = 0; col < m; ++col) gram += g[j1 * m + col] * g[j2 * m + col];
        f(b1, b2, p.weight[i] * gram);
      }
    }
  }
}

}  // namespace

WeightedLeastSquares::WeightedLeastSquares(const ConeProgram& p, bool with_equalities)
    : p_(p), cholesky_(/*amd_only=*/true), with_eq_(with_equalities && p.num_eq() > 0 && p.num_x > 0) {
  if (with_eq_) {
    factor_with_equalities();
    return;
  }
  const int n = p.n, F = p.num_x / n;
  if (F == 0) return;
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<size_t>(p.num_element_cones()) * p.corners() * p.corners());
  for_each_gram_entry(p, [&](int b1, int b2, double v) { triplets.emplace_back(b1 / n, b2 / n, v); });
  Eigen::SparseMatrix<double> K(F, F);
  K.setFromTriplets(triplets.begin(), triplets.end());
  cholesky_.analyze(K);
  ok_ = cholesky_.factorize(K);
}

void WeightedLeastSquares::factor_with_equalities() {
  // K (x) I_n + A^T A on every dof, lower triangle.
  const int n = p_.n;
  std::vector<Eigen::Triplet<double>> triplets;
  for_each_gram_entry(p_, [&](int b1, int b2, double v) {
    for (int d = 0; d < n; ++d) triplets.emplace_back(b1 + d, b2 + d, v);
  });
  const Eigen::SparseMatrix<double> ata = Eigen::SparseMatrix<double>(p_.A.transpose() * p_.A);
  for (int col = 0; col < ata.outerSize(); ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator it(ata, col); it; ++it)
      if (it.row() >= it.col()) triplets.emplace_back(static_cast<int>(it.row()), static_cast<int>(it.col()), it.value());
  Eigen::SparseMatrix<double> K(p_.num_x, p_.num_x);
  K.setFromTriplets(triplets.begin(), triplets.end());
  cholesky_.analyze(K);
  ok_ = cholesky_.factorize(K);
}

Eigen::VectorXd WeightedLeastSquares::solve(const Eigen::VectorXd& r) const {
  const int n = p_.n, F = p_.num_x / n;
  if (F == 0) return Eigen::VectorXd(0);
  if (with_eq_) return cholesky_.solve(r);
  using RowMat = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  const Eigen::MatrixXd B = Eigen::Map<const RowMat>(r.data(), F, n);
  const RowMat X = cholesky_.solve(B);
  return Eigen::Map<const Eigen::VectorXd>(X.data(), X.size());
}

Eigen::VectorXd WeightedLeastSquares::minimizer() const {
  const int tt = p_.t();
  Eigen::VectorXd wh(p_.h.size());
  for (int i = 0; i < p_.num_element_cones(); ++i)
    wh.segment(static_cast<Eigen::Index>(i) * tt, tt) = p_.weight[i] * p_.h.segment(static_cast<Eigen::Index>(i) * tt, tt);
  Eigen::VectorXd rhs;
  p_.apply_gt(wh.data(), tt, 0, rhs);
  if (with_eq_) rhs.noalias() += p_.A.transpose() * p_.beq;  // + ||A x - b||^2
  return solve(rhs);
}

double certified_lower_bound(const ConeProgram& p, const WeightedLeastSquares& ls, const Eigen::VectorXd& z,
                             const Eigen::VectorXd& y, Eigen::VectorXd* multipliers) {
  constexpr double minus_inf = -std::numeric_limits<double>::infinity();
  if (!p.has_k || p.has_quad() || !ls.ok()) return minus_inf;
  const int tt = p.t(), E = p.num_element_cones();
  // r = G^T z_tails + A^T y, and its correction.
  Eigen::VectorXd r;
  p.apply_gt(z.data(), tt + 1, 1, r);
  if (p.num_eq() > 0) r.noalias() += p.A.transpose() * y;
  Eigen::VectorXd delta, y_corrected = y;
  if (p.num_x > 0) {
    const Eigen::VectorXd u = ls.solve(r);
    p.apply_g(u, delta);
    for (int i = 0; i < E; ++i) delta.segment(static_cast<Eigen::Index>(i) * tt, tt) *= -p.weight[i];
    if (ls.with_equalities()) y_corrected.noalias() -= p.A * u;
  } else {
    delta.setZero(static_cast<Eigen::Index>(E) * tt);
  }
  double objective = 0, normalizer = 0;
  if (multipliers) multipliers->resize(E);
  for (int i = 0; i < E; ++i) {
    const Eigen::Index o = p.cone_offset(i);
    const auto d = delta.segment(static_cast<Eigen::Index>(i) * tt, tt);
    const auto tail = z.segment(o + 1, tt);
    // Head raised only as far as the corrected tail needs to stay in the cone (also covers
    // round-off in z): cones with slack absorb the correction for free.
    const double head = std::max(z[o], (tail + d).norm());
    if (multipliers) (*multipliers)[i] = head;
    objective += -p.head_b[i] * head + p.h.segment(static_cast<Eigen::Index>(i) * tt, tt).dot(tail + d);
    normalizer += p.head_a[i] * head;
  }
  if (p.has_scalar) {
    const double head = std::max(z[p.cone_offset(E)], 0.0);
    objective += -p.head_b[E] * head;
    normalizer += p.head_a[E] * head;
  }
  if (p.num_eq() > 0) objective += p.beq.dot(y_corrected);
  if (!(normalizer > 0) || !std::isfinite(objective)) return minus_inf;
  if (multipliers) *multipliers /= normalizer;
  return p.c_k * objective / normalizer;
}

}  // namespace strictmin::socp
