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
Problem restricted_problem(const Problem& p, const std::vector<int>& elements, const Eigen::MatrixXd& X,
                           bool hold_rim) {
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
  // The rim: vertices that other elements touch too (held in a restriction of the problem).
  std::vector<char> rim(V, 0);
  if (hold_rim) {
    std::vector<char> chosen(p.num_elements(), 0);
    for (int e : elements) chosen[e] = 1;
    for (int e = 0; e < p.num_elements(); ++e)
      if (!chosen[e])
        for (int a = 0; a < c; ++a) rim[p.elements(e, a)] = 1;
  }
  std::vector<char> anchored(V, 0);
  for (int v = 0; v < V; ++v)
    if (touched[v] && (p.fixed[v] || rim[v])) anchored[find_root(parent, v)] = 1;
  // Held: the original handles, every vertex the restriction does not touch, and one vertex
  // of each unanchored part (a translation of the part changes no distortion).
  r.fixed.assign(V, 1);
  std::vector<char> floating(V, 0), held_one(V, 0);
  for (int v = 0; v < V; ++v) {
    if (!touched[v] || p.fixed[v] || rim[v]) continue;
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
        keep = hold_rim || p.fixed[v] || (touched[v] && !floating[v]);
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

ActiveSetSolve solve_restricted(const Problem& p, const std::vector<int>& elements, const Eigen::MatrixXd& X,
                                const Eigen::VectorXd& bounds, const LinfOptions& options, bool hold_rim) {
  ActiveSetSolve out;
  out.lower_bound = -std::numeric_limits<double>::infinity();
  out.elements = static_cast<int>(elements.size());
  if (elements.empty()) return out;
  const Problem r = restricted_problem(p, elements, X, hold_rim);
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
  if (sub.status == SolveStatus::Infeasible) return out;
  out.positions = sub.positions;
  if (hold_rim || !std::isfinite(sub.lower_bound)) return out;  // a restriction bounds nothing
  out.lower_bound = sub.lower_bound;
  if (sub.multipliers.size() == out.elements) {
    out.multipliers = Eigen::VectorXd::Zero(p.num_elements());
    for (int j = 0; j < out.elements; ++j) out.multipliers[elements[j]] = sub.multipliers[j];
  }
  return out;
}

}  // namespace

ActiveSetSolve active_set_bound(const Problem& p, const std::vector<int>& elements, const Eigen::MatrixXd& X,
                                const Eigen::VectorXd& bounds, const LinfOptions& options) {
  return solve_restricted(p, elements, X, bounds, options, false);
}

ActiveSetSolve active_set_map(const Problem& p, const std::vector<int>& elements, const Eigen::MatrixXd& X,
                              const Eigen::VectorXd& bounds, const LinfOptions& options) {
  return solve_restricted(p, elements, X, bounds, options, true);
}

std::vector<int> widen_by_rings(const Problem& p, const std::vector<int>& elements, int rings, double max_growth) {
  std::vector<int> out = elements;
  std::vector<char> in(p.num_elements(), 0), touched(p.num_vertices, 0);
  for (int e : out) in[e] = 1;
  const double limit = max_growth * static_cast<double>(elements.size());
  for (int ring = 0; ring < rings; ++ring) {
    for (int e : out)
      for (int a = 0; a < p.corners(); ++a) touched[p.elements(e, a)] = 1;
    std::vector<int> next;
    for (int e = 0; e < p.num_elements(); ++e) {
      if (in[e]) continue;
      for (int a = 0; a < p.corners(); ++a)
        if (touched[p.elements(e, a)]) {
          next.push_back(e);
          break;
        }
    }
    if (static_cast<double>(out.size() + next.size()) > limit) break;
    for (int e : next) in[e] = 1;
    out.insert(out.end(), next.begin(), next.end());
  }
  return out;
}

}  // namespace strictmin
