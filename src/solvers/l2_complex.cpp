#include "solvers/l2_complex.h"

#include <algorithm>

#include "solvers/serial_cholmod_scope.h"

namespace strictmin {
namespace {

using Complex = std::complex<double>;

// conj(a) * k * b, written out (std::complex's product guards against infinities with a
// library call per product).
Complex conj_product(Complex a, double k, Complex b) {
  const double re = a.real() * b.real() + a.imag() * b.imag(), im = a.real() * b.imag() - a.imag() * b.real();
  return {k * re, k * im};
}

struct Entry {
  int row, col;
  Complex value;
};

// The lower triangle's entries (row >= col) of Z^H K Z, one per element, corner pair and term
// pair, plus a zero on every diagonal (HermitianLower keeps the diagonal first).
std::vector<Entry> entries(const Problem& p, const ComplexEqualityBasis& z, const Eigen::VectorXd& weights) {
  const int c = p.corners();
  std::vector<Entry> out;
  out.reserve(static_cast<size_t>(p.num_elements()) * c * (c + 1) / 2 * 2 + z.num_nodes);
  for (int n = 0; n < z.num_nodes; ++n) out.push_back({n, n, Complex(0, 0)});
  for (int e = 0; e < p.num_elements(); ++e) {
    const auto g = p.gradients.middleRows(e * c, c);
    for (int i = 0; i < c; ++i)
      for (int j = 0; j < c; ++j) {
        const double kij = weights(e) * g.row(i).dot(g.row(j));
        const int wi = p.elements(e, i), wj = p.elements(e, j);
        for (int ti = z.offset[wi]; ti < z.offset[wi + 1]; ++ti)
          for (int tj = z.offset[wj]; tj < z.offset[wj + 1]; ++tj)
            if (z.node[ti] >= z.node[tj])
              out.push_back({z.node[ti], z.node[tj], conj_product(z.coefficient[ti], kij, z.coefficient[tj])});
      }
  }
  return out;
}

// The entries summed into columns (counting sort by column, then rows sorted per column).
HermitianLower compress(const std::vector<Entry>& entries, int n) {
  std::vector<int> start(n + 1, 0);
  for (const Entry& x : entries) ++start[x.col + 1];
  for (int k = 0; k < n; ++k) start[k + 1] += start[k];
  std::vector<std::pair<int, Complex>> sorted(entries.size());
  std::vector<int> next(start.begin(), start.end() - 1);
  for (const Entry& x : entries) sorted[next[x.col]++] = {x.row, x.value};
  HermitianLower A;
  A.n = n;
  A.start.assign(n + 1, 0);
  A.row.reserve(entries.size());
  A.value.reserve(entries.size());
  for (int col = 0; col < n; ++col) {
    const auto first = sorted.begin() + start[col], last = sorted.begin() + start[col + 1];
    std::sort(first, last, [](const auto& a, const auto& b) { return a.first < b.first; });
    for (auto it = first; it != last; ++it) {
      if (static_cast<int>(A.row.size()) > A.start[col] && A.row.back() == it->first) {
        A.value.back() += it->second;
      } else {
        A.row.push_back(it->first);
        A.value.push_back(it->second);
      }
    }
    A.start[col + 1] = static_cast<int>(A.row.size());
  }
  return A;
}

}  // namespace

bool ComplexL2::factorize(const Problem& p, const Eigen::VectorXd& element_weights) {
  weights_ = element_weights;
  if (basis_.num_nodes == 0) return true;
  SerialCholmodScope serial;  // one BLAS thread: supernodes of a few columns (serial_cholmod_scope.h)
  return cholesky_.factorize(compress(entries(p, basis_, weights_), basis_.num_nodes));
}

Eigen::VectorXcd ComplexL2::reduced_rhs(const Problem& p) const {
  const int c = p.corners(), m = p.domain_dim;
  const ComplexEqualityBasis& z = basis_;
  // b - K z0 per vertex: b_w = sum_T A_T (R_T g_w) as u + iv; K z0 from the fixed vertices.
  Eigen::VectorXcd r = Eigen::VectorXcd::Zero(p.num_vertices);
  for (int e = 0; e < p.num_elements(); ++e) {
    const auto g = p.gradients.middleRows(e * c, c);
    for (int i = 0; i < c; ++i) {
      double u = 0, v = 0;
      for (int k = 0; k < m; ++k) {
        u += p.targets(e * 2, k) * g(i, k);
        v += p.targets(e * 2 + 1, k) * g(i, k);
      }
      Complex sum(u, v);
      for (int j = 0; j < c; ++j) {
        const Complex zj = z.z0(p.elements(e, j));
        if (zj != Complex(0, 0)) sum -= g.row(i).dot(g.row(j)) * zj;
      }
      r(p.elements(e, i)) += weights_(e) * sum;
    }
  }
  // Z^H r.
  Eigen::VectorXcd rhs = Eigen::VectorXcd::Zero(z.num_nodes);
  for (int w = 0; w < p.num_vertices; ++w)
    for (int t = z.offset[w]; t < z.offset[w + 1]; ++t) rhs(z.node[t]) += std::conj(z.coefficient[t]) * r(w);
  return rhs;
}

Eigen::VectorXcd ComplexL2::solve_reduced(const Eigen::VectorXcd& rhs) const {
  return basis_.num_nodes > 0 ? cholesky_.solve(rhs) : rhs;
}

void ComplexL2::solve_reduced_many(Eigen::MatrixXcd& rhs) const {
  if (basis_.num_nodes > 0) cholesky_.solve_many_in_place(rhs);
}

Eigen::MatrixXd ComplexL2::positions(const Eigen::VectorXcd& y) const {
  const ComplexEqualityBasis& z = basis_;
  const Eigen::Index num_vertices = z.z0.size();
  Eigen::MatrixXd X(num_vertices, 2);
  for (Eigen::Index w = 0; w < num_vertices; ++w) {
    Complex q = z.z0(w);
    for (int t = z.offset[w]; t < z.offset[w + 1]; ++t) q += z.coefficient[t] * y(z.node[t]);
    X(w, 0) = q.real();
    X(w, 1) = q.imag();
  }
  return X;
}

Eigen::MatrixXd ComplexL2::solve(const Problem& p) const { return positions(solve_reduced(reduced_rhs(p))); }

}  // namespace strictmin
