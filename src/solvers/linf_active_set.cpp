#include "strictmin/solvers/linf_active_set.h"

#include <limits>
#include <numeric>

namespace strictmin {
namespace {

int find_root(std::vector<int>& parent, int v) {
  while (parent[v] != v) v = parent[v] = parent[parent[v]];
  return v;
}

// The problem over `elements` only (see the header): which vertices are held, which
// equalities are kept.
Problem restricted_problem(const Problem& p, const std::vector<int>& elements, const Eigen::MatrixXd& X) {
  const int V = p.num_vertices, c = p.corners(), n = p.image_dim, E = static_cast<int>(elements.size());
  Problem r;
  r.image_dim = n;
  r.domain_dim = p.domain_dim;
  r.num_vertices = V;
  r.elements.resize(E, c);
  r.gradients.resize(static_cast<Eigen::Index>(E) * c, p.domain_dim);
  r.weights.resize(E);
  r.targets.resize(static_cast<Eigen::Index>(E) * n, p.domain_dim);
  for (int j = 0; j < E; ++j) {
    const int e = elements[j];
    r.elements.row(j) = p.elements.row(e);
    r.gradients.middleRows(static_cast<Eigen::Index>(j) * c, c) = p.gradients.middleRows(static_cast<Eigen::Index>(e) * c, c);
    r.weights[j] = p.weights[e];
    r.targets.middleRows(static_cast<Eigen::Index>(j) * n, n) = p.targets.middleRows(static_cast<Eigen::Index>(e) * n, n);
  }
  r.positions = X;

  // Parts of the restriction (vertices joined through its elements) and their anchors.
  std::vector<int> parent(V);
  std::iota(parent.begin(), parent.end(), 0);
  std::vector<char> touched(V, 0);
  for (int j = 0; j < E; ++j)
    for (int a = 0; a < c; ++a) {
      touched[r.elements(j, a)] = 1;
      parent[find_root(parent, r.elements(j, a))] = find_root(parent, r.elements(j, 0));
    }
  std::vector<char> anchored(V, 0);
  for (int v = 0; v < V; ++v)
    if (touched[v] && p.fixed[v]) anchored[find_root(parent, v)] = 1;
  // Held: the original handles, every vertex the restriction does not touch, and one vertex
  // of each unanchored part (a translation of the part changes no distortion).
  r.fixed.assign(V, 1);
  std::vector<char> floating(V, 0), held_one(V, 0);
  for (int v = 0; v < V; ++v) {
    if (!touched[v] || p.fixed[v]) continue;
    const int root = find_root(parent, v);
    if (anchored[root]) {
      r.fixed[v] = 0;
      continue;
    }
    floating[v] = 1;
    if (held_one[root]) r.fixed[v] = 0;
    held_one[root] = 1;
  }

  // Equalities: the rows whose vertices are all original handles or anchored free vertices of
  // the restriction; the others are dropped (a relaxation).
  if (p.has_equalities()) {
    const Eigen::SparseMatrix<double, Eigen::RowMajor> A = p.eq_matrix;
    std::vector<Eigen::Triplet<double>> kept;
    std::vector<double> rhs;
    for (int row = 0; row < A.rows(); ++row) {
      bool keep = true;
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(A, row); it && keep; ++it) {
        const int v = static_cast<int>(it.col()) / n;
        keep = p.fixed[v] || (touched[v] && !floating[v]);
      }
      if (!keep) continue;
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(A, row); it; ++it)
        kept.emplace_back(static_cast<int>(rhs.size()), static_cast<int>(it.col()), it.value());
      rhs.push_back(p.eq_rhs[row]);
    }
    r.eq_matrix.resize(static_cast<Eigen::Index>(rhs.size()), p.eq_matrix.cols());
    r.eq_matrix.setFromTriplets(kept.begin(), kept.end());
    r.eq_rhs = Eigen::Map<const Eigen::VectorXd>(rhs.data(), static_cast<Eigen::Index>(rhs.size()));
  }
  return r;
}

}  // namespace

ActiveSetBound active_set_bound(const Problem& p, const std::vector<int>& elements, const Eigen::MatrixXd& X,
                                const Eigen::VectorXd& bounds, const LinfOptions& options) {
  ActiveSetBound out;
  out.lower_bound = -std::numeric_limits<double>::infinity();
  out.elements = static_cast<int>(elements.size());
  if (elements.empty()) return out;
  const Problem r = restricted_problem(p, elements, X);
  LinfOptions o = options;
  o.progress = nullptr;
  o.verbose = 0;
  o.minimize_l2_among_optimal = false;
  o.active_set_bounds = false;
  o.gap_tolerance = 0.1 * options.gap_tolerance;
  o.element_bounds.resize(0);
  if (bounds.size() > 0) {
    o.element_bounds.resize(out.elements);
    for (int j = 0; j < out.elements; ++j) o.element_bounds[j] = bounds[elements[j]];
  }
  const Result sub = solve_linf(r, o);
  out.iterations = sub.iterations;
  if (sub.status == SolveStatus::Infeasible || !std::isfinite(sub.lower_bound)) return out;
  out.lower_bound = sub.lower_bound;
  if (sub.multipliers.size() == out.elements) {
    out.multipliers = Eigen::VectorXd::Zero(p.num_elements());
    for (int j = 0; j < out.elements; ++j) out.multipliers[elements[j]] = sub.multipliers[j];
  }
  return out;
}

}  // namespace strictmin
