#include "strictmin/problem/subproblem.h"

#include <vector>

namespace strictmin {

Subproblem restrict_to_movable(const Problem& p, const std::vector<char>& movable, const Eigen::MatrixXd& X,
                               const std::vector<char>* elements) {
  const int V = p.num_vertices, E = p.num_elements(), c = p.corners(), n = p.image_dim;
  auto moves = [&](int v) { return movable[v] && !p.fixed[v]; };
  Subproblem out;
  std::vector<int> local(V, -1);
  for (int e = 0; e < E; ++e) {
    if (elements && !(*elements)[e]) continue;
    bool keep = false;
    for (int j = 0; j < c && !keep; ++j) keep = moves(p.elements(e, j));
    if (!keep) continue;
    out.element.push_back(e);
    for (int j = 0; j < c; ++j) {
      const int v = p.elements(e, j);
      if (local[v] < 0) {
        local[v] = static_cast<int>(out.vertex.size());
        out.vertex.push_back(v);
      }
    }
  }
  const int SV = static_cast<int>(out.vertex.size()), SE = static_cast<int>(out.element.size());
  Problem& s = out.problem;
  s.image_dim = p.image_dim;
  s.domain_dim = p.domain_dim;
  s.num_vertices = SV;
  s.elements.resize(SE, c);
  s.gradients.resize(static_cast<Eigen::Index>(SE) * c, p.domain_dim);
  s.weights.resize(SE);
  s.targets.resize(static_cast<Eigen::Index>(SE) * n, p.domain_dim);
  for (int i = 0; i < SE; ++i) {
    const int e = out.element[i];
    for (int j = 0; j < c; ++j) s.elements(i, j) = local[p.elements(e, j)];
    s.gradients.middleRows(i * c, c) = p.gradients.middleRows(e * c, c);
    s.weights[i] = p.weights[e];
    s.targets.middleRows(i * n, n) = p.targets.middleRows(e * n, n);
  }
  s.fixed.resize(SV);
  s.positions.resize(SV, n);
  for (int i = 0; i < SV; ++i) {
    s.fixed[i] = moves(out.vertex[i]) ? 0 : 1;
    s.positions.row(i) = X.row(out.vertex[i]);
  }
  if (p.has_equalities()) {
    // Columns of vertices that stay where X has them become part of the right-hand side.
    const Eigen::SparseMatrix<double, Eigen::RowMajor> A = p.eq_matrix;
    std::vector<Eigen::Triplet<double>> triplets;
    std::vector<double> rhs;
    for (int row = 0; row < A.rows(); ++row) {
      double b = p.eq_rhs[row];
      std::vector<Eigen::Triplet<double>> kept;
      bool has_movable = false;
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(A, row); it; ++it) {
        const int v = static_cast<int>(it.col()) / n, r = static_cast<int>(it.col()) % n;
        if (local[v] >= 0) {
          kept.emplace_back(static_cast<int>(rhs.size()), local[v] * n + r, it.value());
          has_movable = has_movable || moves(v);
        } else {
          b -= it.value() * X(v, r);
        }
      }
      if (!has_movable) continue;
      triplets.insert(triplets.end(), kept.begin(), kept.end());
      rhs.push_back(b);
    }
    s.eq_matrix.resize(static_cast<Eigen::Index>(rhs.size()), static_cast<Eigen::Index>(SV) * n);
    s.eq_matrix.setFromTriplets(triplets.begin(), triplets.end());
    s.eq_rhs = Eigen::Map<const Eigen::VectorXd>(rhs.data(), static_cast<Eigen::Index>(rhs.size()));
  }
  return out;
}

std::vector<char> vertices_within_rings(const Problem& p, const std::vector<char>& seeds, int rings) {
  const int V = p.num_vertices, E = p.num_elements(), c = p.corners();
  if (rings <= 0) return std::vector<char>(V, 1);
  std::vector<char> in = seeds;
  for (int ring = 1; ring < rings; ++ring) {
    std::vector<char> next = in;
    bool grew = false;
    for (int e = 0; e < E; ++e) {
      bool touches = false;
      for (int j = 0; j < c && !touches; ++j) touches = in[p.elements(e, j)];
      if (touches)
        for (int j = 0; j < c; ++j) {
          grew |= !next[p.elements(e, j)];
          next[p.elements(e, j)] = 1;
        }
    }
    in.swap(next);
    if (!grew) break;  // every further ring is the same set (a huge `rings` ran this loop on)
  }
  return in;
}

}  // namespace strictmin
