#include "strictmin/param/lscm.h"

#include <Eigen/SparseCore>
#include <cmath>
#include <stdexcept>

#include "strictmin/problem/problem.h"
#include "strictmin/solvers/sparse_cholesky.h"

namespace strictmin {
namespace {

// The boundary vertex farthest (in 3D) from `from`.
int farthest(const Mesh& mesh, const std::vector<int>& boundary, int from) {
  int best = boundary.front();
  double d = -1;
  for (int v : boundary) {
    const double dv = (mesh.V.row(v) - mesh.V.row(from)).squaredNorm();
    if (dv > d) d = dv, best = v;
  }
  return best;
}

}  // namespace

Eigen::MatrixXd lscm(const Mesh& mesh, const std::vector<int>& boundary) {
  const Problem p = make_problem(mesh);  // per-triangle isometric frames, gradients, areas
  const int nv = mesh.num_vertices(), nf = p.num_elements();
  const int a = farthest(mesh, boundary, boundary.front());
  const int b = farthest(mesh, boundary, a);
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
