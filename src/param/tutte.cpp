#include "strictmin/param/tutte.h"

#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <utility>

#include "strictmin/solvers/sparse_cholesky.h"

namespace strictmin {

Eigen::MatrixXd tutte_embedding(const Mesh& mesh, const std::vector<int>& boundary) {
  const int nv = mesh.num_vertices();
  Eigen::MatrixXd X = Eigen::MatrixXd::Zero(nv, 2);
  // Boundary on the unit circle, counter-clockwise along the loop, spaced by arc length.
  const int nb = static_cast<int>(boundary.size());
  std::vector<double> s(nb + 1, 0.0);
  for (int i = 0; i < nb; ++i)
    s[i + 1] = s[i] + (mesh.V.row(boundary[(i + 1) % nb]) - mesh.V.row(boundary[i])).norm();
  std::vector<char> on_boundary(nv, 0);
  for (int i = 0; i < nb; ++i) {
    const double angle = 2 * std::numbers::pi * s[i] / s[nb];
    X.row(boundary[i]) << std::cos(angle), std::sin(angle);
    on_boundary[boundary[i]] = 1;
  }
  // Uniform graph Laplacian over the interior vertices.
  std::vector<std::pair<int, int>> edges;
  edges.reserve(static_cast<size_t>(mesh.num_elements()) * 3);
  for (int f = 0; f < mesh.num_elements(); ++f)
    for (int j = 0; j < 3; ++j) {
      const int a = mesh.F(f, j), b = mesh.F(f, (j + 1) % 3);
      edges.emplace_back(std::min(a, b), std::max(a, b));
    }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  std::vector<int> index(nv, -1);
  std::vector<char> used(nv, 0);
  for (const auto& [a, b] : edges) used[a] = used[b] = 1;
  int ni = 0;
  for (int v = 0; v < nv; ++v)
    if (used[v] && !on_boundary[v]) index[v] = ni++;
  if (ni == 0) return X;
  std::vector<Eigen::Triplet<double>> triplets;
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(ni, 2);
  for (const auto& [a, b] : edges) {
    const int ia = index[a], ib = index[b];
    if (ia >= 0) triplets.emplace_back(ia, ia, 1.0);
    if (ib >= 0) triplets.emplace_back(ib, ib, 1.0);
    if (ia >= 0 && ib >= 0) {
      triplets.emplace_back(ia, ib, -1.0);
      triplets.emplace_back(ib, ia, -1.0);
    } else if (ia >= 0) {
      rhs.row(ia) += X.row(b);
    } else if (ib >= 0) {
      rhs.row(ib) += X.row(a);
    }
  }
  Eigen::SparseMatrix<double> L(ni, ni);
  L.setFromTriplets(triplets.begin(), triplets.end());
  SparseCholesky chol;
  chol.analyze(L);
  if (!chol.factorize(L)) throw std::runtime_error("Tutte embedding: the Laplacian factorization failed");
  const Eigen::MatrixXd interior = chol.solve(rhs);
  for (int v = 0; v < nv; ++v)
    if (index[v] >= 0) X.row(v) = interior.row(index[v]);
  return X;
}

}  // namespace strictmin
