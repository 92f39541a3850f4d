#include "strictmin/problem/problem.h"

#include <Eigen/Dense>
#include <cmath>
#include <string>

#include "strictmin/io/input_error.h"
#include "strictmin/mesh/validate.h"
#include "problem/frame_axes.h"

namespace strictmin {

std::vector<int> Problem::free_index() const {
  std::vector<int> index(num_vertices, -1);
  int next = 0;
  for (int v = 0; v < num_vertices; ++v)
    if (!fixed[v]) index[v] = next++;
  return index;
}

int Problem::num_free() const {
  int count = 0;
  for (char f : fixed) count += f ? 0 : 1;
  return count;
}

Eigen::MatrixXd Problem::jacobian(int e, const Eigen::MatrixXd& X) const {
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(image_dim, domain_dim);
  const int c = corners();
  for (int j = 0; j < c; ++j)
    J.noalias() += X.row(elements(e, j)).transpose() * gradients.row(e * c + j);
  return J;
}

Eigen::SparseMatrix<double> Problem::jacobian_operator() const {
  const int n = image_dim, m = domain_dim, c = corners(), E = num_elements();
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<size_t>(E) * n * m * c);
  for (int e = 0; e < E; ++e)
    for (int j = 0; j < c; ++j)
      for (int r = 0; r < n; ++r)
        for (int k = 0; k < m; ++k)
          triplets.emplace_back(e * n * m + r * m + k, elements(e, j) * n + r, gradients(e * c + j, k));
  Eigen::SparseMatrix<double> op(E * n * m, num_vertices * n);
  op.setFromTriplets(triplets.begin(), triplets.end());
  return op;
}

Problem::Reduced Problem::reduced() const {
  const int n = image_dim, m = domain_dim, c = corners(), E = num_elements();
  const std::vector<int> index = free_index();
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<size_t>(E) * n * m * c);
  Reduced out;
  out.h.resize(static_cast<Eigen::Index>(E) * n * m);
  for (int e = 0; e < E; ++e) {
    for (int r = 0; r < n; ++r)
      for (int k = 0; k < m; ++k) out.h(e * n * m + r * m + k) = targets(e * n + r, k);
    for (int j = 0; j < c; ++j) {
      const int v = elements(e, j);
      for (int r = 0; r < n; ++r)
        for (int k = 0; k < m; ++k) {
          const double g = gradients(e * c + j, k);
          const int row = e * n * m + r * m + k;
          if (fixed[v])
            out.h(row) -= g * positions(v, r);
          else
            triplets.emplace_back(row, index[v] * n + r, g);
        }
    }
  }
  out.G.resize(E * n * m, num_free() * n);
  out.G.setFromTriplets(triplets.begin(), triplets.end());
  return out;
}

Eigen::VectorXd Problem::free_dofs(const Eigen::MatrixXd& X) const {
  Eigen::VectorXd x(static_cast<Eigen::Index>(num_free()) * image_dim);
  int f = 0;
  for (int v = 0; v < num_vertices; ++v)
    if (!fixed[v]) x.segment(image_dim * f++, image_dim) = X.row(v).transpose();
  return x;
}

Eigen::MatrixXd Problem::with_free_dofs(const Eigen::VectorXd& x) const {
  Eigen::MatrixXd X = positions;
  int f = 0;
  for (int v = 0; v < num_vertices; ++v)
    if (!fixed[v]) X.row(v) = x.segment(image_dim * f++, image_dim).transpose();
  return X;
}

void Problem::fix(const std::vector<Handle>& handles) {
  if (static_cast<int>(fixed.size()) != num_vertices || positions.rows() != num_vertices || positions.cols() != image_dim)
    throw InputError("fix: the problem's fixed flags and positions are not sized for its " +
                     std::to_string(num_vertices) + " vertices (make_problem sets them)");
  for (const Handle& h : handles) {
    if (h.vertex < 0 || h.vertex >= num_vertices)
      throw InputError("handle on vertex " + std::to_string(h.vertex) + ": the mesh has " +
                       std::to_string(num_vertices) + " vertices (indices are 0-based)");
    if (h.position.size() != image_dim)
      throw InputError("handle on vertex " + std::to_string(h.vertex) + " has " +
                       std::to_string(h.position.size()) + " coordinates, the map is " +
                       std::to_string(image_dim) + "D");
    fixed[h.vertex] = 1;
    positions.row(h.vertex) = h.position.transpose();
  }
}

Eigen::Matrix<double, 3, 2> local_frame_coordinates(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                                    const Eigen::Vector3d& p2) {
  // Edges far from unit length are measured scaled by an exact power of two (frame_axes.h).
  const double s = frame_edge_scale(p1 - p0, p2 - p0);
  const Eigen::Vector3d e1 = (p1 - p0) * s, e2 = (p2 - p0) * s;
  const Eigen::Matrix<double, 3, 2> axes = frame_axes_of_edges(e1, e2);  // x along e1, y in-plane
  Eigen::Matrix<double, 3, 2> P;
  P << 0.0, 0.0, e1.norm(), 0.0, e2.dot(axes.col(0)), e2.dot(axes.col(1));
  return P / s;
}

namespace {

// Barycentric gradients of a simplex with corners P (d+1 by d): with E = [p_1 - p_0, ...]
// (d by d, edges as columns), grad(phi_j) for j >= 1 are the rows of E^{-1}, and
// grad(phi_0) = -sum of the others. Returns the gradients as rows and the signed measure.
template <int d>
double simplex_gradients(const Eigen::Matrix<double, d + 1, d>& P, Eigen::Matrix<double, d + 1, d>& grads) {
  Eigen::Matrix<double, d, d> E;
  for (int j = 0; j < d; ++j) E.col(j) = (P.row(j + 1) - P.row(0)).transpose();
  const Eigen::Matrix<double, d, d> inv = E.inverse();
  grads.bottomRows(d) = inv;
  grads.row(0) = -inv.colwise().sum();
  return E.determinant() / (d == 2 ? 2.0 : 6.0);
}

}  // namespace

namespace {

Problem problem_in_frames(const Mesh& mesh, bool flat_surfaces_in_the_plane) {
  check_mesh_structure(mesh, "make_problem");
  if (mesh.F.rows() == 0) throw InputError("make_problem: the mesh has no elements (no triangle or tetrahedron to map)");
  Problem p;
  const bool tets = mesh.element_type() == ElementType::Tetrahedron;
  const bool planar = !tets && (mesh.dim() == 2 || (flat_surfaces_in_the_plane && mesh.is_planar()));
  const Mesh src = planar ? to_planar(mesh) : mesh;
  p.domain_dim = tets ? 3 : 2;
  p.image_dim = p.domain_dim;
  p.num_vertices = src.num_vertices();
  p.elements = src.F;
  const int E = src.num_elements(), c = p.corners(), n = p.image_dim;
  p.gradients.resize(static_cast<Eigen::Index>(E) * c, p.domain_dim);
  p.weights.resize(E);
  p.targets.resize(static_cast<Eigen::Index>(E) * n, p.domain_dim);
  for (int e = 0; e < E; ++e) {
    p.targets.middleRows(e * n, n).setIdentity();
    if (tets) {
      Eigen::Matrix<double, 4, 3> P, g;
      for (int j = 0; j < 4; ++j) P.row(j) = src.V.row(src.F(e, j));
      p.weights(e) = std::abs(simplex_gradients<3>(P, g));
      p.gradients.middleRows(e * 4, 4) = g;
    } else {
      Eigen::Matrix<double, 3, 2> P, g;
      if (planar) {
        for (int j = 0; j < 3; ++j) P.row(j) = src.V.row(src.F(e, j));
      } else {
        P = local_frame_coordinates(src.V.row(src.F(e, 0)).transpose(), src.V.row(src.F(e, 1)).transpose(),
                                    src.V.row(src.F(e, 2)).transpose());
      }
      p.weights(e) = std::abs(simplex_gradients<2>(P, g));
      p.gradients.middleRows(e * 3, 3) = g;
    }
  }
  p.fixed.assign(p.num_vertices, 0);
  p.positions = (planar || tets) ? Eigen::MatrixXd(src.V) : Eigen::MatrixXd::Zero(p.num_vertices, n);
  // Vertices used by no element are not part of the map: keep them where they are.
  std::vector<char> used(p.num_vertices, 0);
  for (int e = 0; e < E; ++e)
    for (int j = 0; j < c; ++j) used[p.elements(e, j)] = 1;
  for (int v = 0; v < p.num_vertices; ++v)
    if (!used[v]) p.fixed[v] = 1;
  return p;
}

}  // namespace

Problem make_problem(const Mesh& mesh) { return problem_in_frames(mesh, true); }

Problem make_surface_problem(const Mesh& mesh) { return problem_in_frames(mesh, false); }

}  // namespace strictmin
