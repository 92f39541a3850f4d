#include "solvers/element_assembly.h"

#include <algorithm>

namespace strictmin {

ElementAssembler::ElementAssembler(const Problem& p) : problem_(p), free_index_(p.free_index()) {
  const int n = p.image_dim, c = p.corners();
  local_dofs_ = c * n;
  auto dof = [&](int e, int i) {  // local dof i = corner * n + coordinate
    const int f = free_index_[p.elements(e, i / n)];
    return f < 0 ? -1 : f * n + i % n;
  };
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(static_cast<size_t>(p.num_elements()) * local_dofs_ * local_dofs_);
  for (int e = 0; e < p.num_elements(); ++e)
    for (int i = 0; i < local_dofs_; ++i)
      for (int j = 0; j < local_dofs_; ++j) {
        const int a = dof(e, i), b = dof(e, j);
        if (a >= 0 && b >= 0 && a >= b) t.emplace_back(a, b, 1.0);
      }
  const int N = p.num_free() * n;
  pattern_.resize(N, N);
  pattern_.setFromTriplets(t.begin(), t.end());
  pattern_.makeCompressed();
  // Position of every (row, col) entry in the compressed value array.
  scatter_.assign(static_cast<size_t>(p.num_elements()) * local_dofs_ * local_dofs_, -1);
  for (int e = 0; e < p.num_elements(); ++e)
    for (int i = 0; i < local_dofs_; ++i)
      for (int j = 0; j < local_dofs_; ++j) {
        const int a = dof(e, i), b = dof(e, j);
        if (a < 0 || b < 0 || a < b) continue;
        const int* rows = pattern_.innerIndexPtr();
        const int begin = pattern_.outerIndexPtr()[b], end = pattern_.outerIndexPtr()[b + 1];
        const int* hit = std::lower_bound(rows + begin, rows + end, a);
        scatter_[(static_cast<size_t>(e) * local_dofs_ + i) * local_dofs_ + j] = static_cast<int>(hit - rows);
      }
}

Eigen::MatrixXd ElementAssembler::local_operator(int e) const {
  const Problem& p = problem_;
  const int n = p.image_dim, m = p.domain_dim, c = p.corners();
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(n * m, c * n);
  for (int j = 0; j < c; ++j)
    for (int r = 0; r < n; ++r)
      for (int k = 0; k < m; ++k) B(r * m + k, j * n + r) = p.gradients(e * c + j, k);
  return B;
}

void ElementAssembler::assemble(const std::function<void(int, Eigen::Ref<Eigen::MatrixXd>)>& weight,
                                Eigen::SparseMatrix<double>& out) const {
  const Problem& p = problem_;
  const int nm = p.jacobian_size();
  out = pattern_;
  double* values = out.valuePtr();
  std::fill(values, values + out.nonZeros(), 0.0);
  Eigen::MatrixXd W(nm, nm);
  for (int e = 0; e < p.num_elements(); ++e) {
    W.setZero();
    weight(e, W);
    const Eigen::MatrixXd B = local_operator(e);
    const Eigen::MatrixXd H = B.transpose() * W * B;
    const int* s = &scatter_[static_cast<size_t>(e) * local_dofs_ * local_dofs_];
    for (int i = 0; i < local_dofs_; ++i)
      for (int j = 0; j < local_dofs_; ++j)
        if (s[i * local_dofs_ + j] >= 0) values[s[i * local_dofs_ + j]] += H(i, j);
  }
}

void ElementAssembler::add_transpose_product(int e, const Eigen::VectorXd& v, Eigen::VectorXd& out) const {
  const Problem& p = problem_;
  const int n = p.image_dim, m = p.domain_dim, c = p.corners();
  for (int j = 0; j < c; ++j) {
    const int f = free_index_[p.elements(e, j)];
    if (f < 0) continue;
    for (int r = 0; r < n; ++r) {
      double sum = 0;
      for (int k = 0; k < m; ++k) sum += p.gradients(e * c + j, k) * v(r * m + k);
      out(f * n + r) += sum;
    }
  }
}

}  // namespace strictmin
