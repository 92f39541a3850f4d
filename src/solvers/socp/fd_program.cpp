#include "solvers/socp/fd_program.h"

#include <cmath>

#include "strictmin/measures/field_deviation.h"

namespace strictmin::socp {

ElementClasses classify_elements(const Problem& p, const Eigen::VectorXd& bounds) {
  ElementClasses out;
  const int c = p.corners();
  for (int e = 0; e < p.num_elements(); ++e) {
    bool constant = true;
    for (int j = 0; j < c; ++j) constant = constant && p.fixed[p.elements(e, j)];
    if (constant) {
      const double d = field_deviation(p, p.positions, e);
      out.constant_elements.push_back(e);
      out.constant_distortion.push_back(d);
      if (has_bound(bounds, e)) {
        if (d - bounds[e] > out.constant_excess) {
          out.constant_excess = d - bounds[e];
          out.constant_excess_element = e;
        }
      } else {
        out.constant_max = std::max(out.constant_max, d);
      }
    } else if (has_bound(bounds, e)) {
      out.bounded_elements.push_back(e);
    } else {
      out.free_elements.push_back(e);
    }
  }
  return out;
}

ConeProgram element_program(const Problem& p, const std::vector<int>& elements, const std::vector<int>& vertex_dof,
                            int num_x, const Eigen::MatrixXd& X) {
  ConeProgram out;
  out.n = p.image_dim;
  out.m = p.domain_dim;
  out.num_x = num_x;
  const int n = out.n, m = out.m, c = out.corners(), tt = out.t(), E = static_cast<int>(elements.size());
  out.element = elements;
  out.dof_base.resize(static_cast<size_t>(E) * c);
  out.grad.resize(static_cast<size_t>(E) * c * m);
  out.h.resize(static_cast<Eigen::Index>(E) * tt);
  out.weight.resize(E);
  for (int i = 0; i < E; ++i) {
    const int e = elements[i];
    out.weight[i] = p.weights[e];
    double* hi = out.h.data() + static_cast<Eigen::Index>(i) * tt;
    for (int r = 0; r < n; ++r)
      for (int col = 0; col < m; ++col) hi[r * m + col] = p.targets(e * n + r, col);
    for (int j = 0; j < c; ++j) {
      const int v = p.elements(e, j);
      out.dof_base[i * c + j] = vertex_dof[v];
      for (int col = 0; col < m; ++col) out.grad[(static_cast<size_t>(i) * c + j) * m + col] = p.gradients(e * c + j, col);
      if (vertex_dof[v] < 0)
        for (int r = 0; r < n; ++r)
          for (int col = 0; col < m; ++col) hi[r * m + col] -= X(v, r) * p.gradients(e * c + j, col);
    }
  }
  out.head_a = Eigen::VectorXd::Ones(E);
  out.head_b = Eigen::VectorXd::Zero(E);
  out.finalize();
  return out;
}

void restrict_equalities(const Problem& p, const std::vector<int>& vertex_dof, int num_x, const Eigen::MatrixXd& X,
                         const std::vector<char>& held, ConeProgram& out) {
  if (!p.has_equalities()) return;
  const int n = p.image_dim;
  const Eigen::SparseMatrix<double, Eigen::RowMajor> A = p.eq_matrix;
  std::vector<Eigen::Triplet<double>> triplets;
  std::vector<double> rhs;
  for (int row = 0; row < A.rows(); ++row) {
    bool keep = true, any = false;
    double b = p.eq_rhs[row];
    std::vector<Eigen::Triplet<double>> entries;
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(A, row); it; ++it) {
      const int v = static_cast<int>(it.col()) / n, r = static_cast<int>(it.col()) % n;
      if (vertex_dof[v] >= 0) {
        entries.emplace_back(static_cast<int>(rhs.size()), vertex_dof[v] + r, it.value());
        any = true;
      } else if (held[v]) {
        b -= it.value() * X(v, r);
      } else {
        keep = false;
      }
    }
    if (!keep || !any) continue;
    triplets.insert(triplets.end(), entries.begin(), entries.end());
    rhs.push_back(b);
  }
  out.A.resize(static_cast<Eigen::Index>(rhs.size()), num_x);
  out.A.setFromTriplets(triplets.begin(), triplets.end());
  out.beq = Eigen::Map<const Eigen::VectorXd>(rhs.data(), static_cast<Eigen::Index>(rhs.size()));
}

Eigen::VectorXd cone_distortions(const ConeProgram& p, const Eigen::VectorXd& x) {
  Eigen::VectorXd tails;
  p.apply_g(x, tails);
  tails -= p.h;
  const int tt = p.t();
  Eigen::VectorXd d(p.num_element_cones());
  for (int i = 0; i < p.num_element_cones(); ++i) d[i] = tails.segment(static_cast<Eigen::Index>(i) * tt, tt).norm();
  return d;
}

}  // namespace strictmin::socp
