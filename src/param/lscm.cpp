#include "strictmin/param/lscm.h"

#include <Eigen/SparseCore>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "strictmin/problem/problem.h"
#include "strictmin/solvers/sparse_cholesky.h"

namespace strictmin {
namespace {

// Boundaries up to this many vertices get their exact farthest pair (b^2 / 2 distances:
// 0.05 s at 10,000); longer ones two sweeps.
constexpr size_t kExactFarthestPairBoundary = 10000;

// u before v in the vertices' coordinates (x, then y, then z): an order that does not depend
// on the numbering.
bool coordinates_before(const Mesh& mesh, int u, int v) {
  for (int c = 0; c < mesh.V.cols(); ++c)
    if (mesh.V(v, c) != mesh.V(u, c)) return mesh.V(u, c) < mesh.V(v, c);
  return false;
}

// Whether the pair (a, b) is farther apart than (c, d) (distance d2 against best), ties going to the
// pair whose first vertex, then second, comes first in coordinates.
bool better_pair(const Mesh& mesh, double d2, int a, int b, double best, int c, int d) {
  if (d2 != best) return d2 > best;
  if (a != c) return coordinates_before(mesh, a, c);
  return coordinates_before(mesh, b, d);
}

// The boundary vertex farthest (in 3D) from the point `from`, ties by coordinates.
int farthest(const Mesh& mesh, const std::vector<int>& boundary, const Eigen::RowVectorXd& from) {
  int best = boundary.front();
  double d = -1;
  for (int v : boundary) {
    const double dv = (mesh.V.row(v) - from).squaredNorm();
    if (dv > d || (dv == d && coordinates_before(mesh, v, best))) d = dv, best = v;
  }
  return best;
}

// The two boundary vertices farthest apart, the first before the second in coordinates,
// whatever the vertex numbering: exactly, or on long boundaries by two sweeps from the
// vertex farthest from the boundary's centroid.
std::pair<int, int> farthest_pair(const Mesh& mesh, const std::vector<int>& boundary) {
  const auto ordered = [&](int a, int b) { return coordinates_before(mesh, b, a) ? std::make_pair(b, a) : std::make_pair(a, b); };
  if (boundary.size() > kExactFarthestPairBoundary) {
    Eigen::RowVectorXd centroid = Eigen::RowVectorXd::Zero(mesh.V.cols());
    for (int v : boundary) centroid += mesh.V.row(v);
    centroid /= static_cast<double>(boundary.size());
    const int a = farthest(mesh, boundary, centroid);
    const int b = farthest(mesh, boundary, mesh.V.row(a));
    return ordered(farthest(mesh, boundary, mesh.V.row(b)), b);
  }
  std::pair<int, int> best = ordered(boundary[0], boundary[boundary.size() > 1 ? 1 : 0]);
  double best_d2 = -1;
  for (size_t i = 0; i < boundary.size(); ++i)
    for (size_t j = i + 1; j < boundary.size(); ++j) {
      const auto [a, b] = ordered(boundary[i], boundary[j]);
      const double d2 = (mesh.V.row(a) - mesh.V.row(b)).squaredNorm();
      if (better_pair(mesh, d2, a, b, best_d2, best.first, best.second)) best = {a, b}, best_d2 = d2;
    }
  return best;
}

}  // namespace

Eigen::MatrixXd lscm(const Mesh& mesh, const std::vector<int>& boundary) {
  const Problem p = make_problem(mesh);  // per-triangle isometric frames, gradients, areas
  const int nv = mesh.num_vertices(), nf = p.num_elements();
  const auto [a, b] = farthest_pair(mesh, boundary);
  Eigen::MatrixXd X = Eigen::MatrixXd::Zero(nv, 2);
  X.row(b) << (mesh.V.row(b) - mesh.V.row(a)).norm(), 0.0;
  // Free vertices: used by a face, not pinned.
  std::vector<int> index(nv, -1);
  std::vector<char> used(nv, 0);
  for (int f = 0; f < nf; ++f)
    for (int j = 0; j < 3; ++j) used[p.elements(f, j)] = 1;
  int n = 0;
  for (int v = 0; v < nv; ++v)
    if (used[v] && v != a && v != b) index[v] = n++;
  // Two rows per triangle, sqrt(A_T) (u_x - v_y) and sqrt(A_T) (u_y + v_x); dof (v, r) = 2 index + r.
  std::vector<Eigen::Triplet<double>> triplets;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(2 * nf);
  for (int f = 0; f < nf; ++f) {
    const double w = std::sqrt(p.weights(f));
    for (int j = 0; j < 3; ++j) {
      const int v = p.elements(f, j);
      const double gx = w * p.gradients(f * 3 + j, 0), gy = w * p.gradients(f * 3 + j, 1);
      // row 2f: u gx - v gy; row 2f+1: u gy + v gx
      if (index[v] >= 0) {
        triplets.emplace_back(2 * f, 2 * index[v], gx);
        triplets.emplace_back(2 * f, 2 * index[v] + 1, -gy);
        triplets.emplace_back(2 * f + 1, 2 * index[v], gy);
        triplets.emplace_back(2 * f + 1, 2 * index[v] + 1, gx);
      } else {
        rhs(2 * f) -= X(v, 0) * gx - X(v, 1) * gy;
        rhs(2 * f + 1) -= X(v, 0) * gy + X(v, 1) * gx;
      }
    }
  }
  if (n == 0) return X;
  Eigen::SparseMatrix<double> A(2 * nf, 2 * n);
  A.setFromTriplets(triplets.begin(), triplets.end());
  const Eigen::SparseMatrix<double> N = A.transpose() * A;
  SparseCholesky chol;
  chol.analyze(N);
  if (!chol.factorize(N)) throw std::runtime_error("LSCM: the normal matrix factorization failed");
  const Eigen::VectorXd x = chol.solve(A.transpose() * rhs);
  for (int v = 0; v < nv; ++v)
    if (index[v] >= 0) X.row(v) << x(2 * index[v]), x(2 * index[v] + 1);
  return X;
}

}  // namespace strictmin
