#pragma once
// Assembly of sparse symmetric matrices sum_T B_T^T W_T B_T over the free dofs, where B_T
// (n*m by (m+1)*n) is the element's local Jacobian operator (vec(J_T) = B_T q_T, row-major
// vec as in problem.h) and W_T a symmetric n*m by n*m matrix per element (Newton Hessians of
// L_p, interior-point scalings). The sparsity pattern (the vertex adjacency with n by n
// blocks, lower triangle) and the scatter positions are computed once.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <functional>
#include <vector>

#include "strictmin/problem/problem.h"

namespace strictmin {

class ElementAssembler {
 public:
  explicit ElementAssembler(const Problem& problem);

  // Lower triangle of sum_T B_T^T W_T B_T, with W_T from weight(e, W) (W is n*m square,
  // zero on entry). The pattern is the same on every call (CHOLMOD's analysis stays valid).
  void assemble(const std::function<void(int, Eigen::Ref<Eigen::MatrixXd>)>& weight,
                Eigen::SparseMatrix<double>& out) const;

  // Local operator B_T of element e.
  Eigen::MatrixXd local_operator(int e) const;
  // out += B_T^T v (v has n*m entries) scattered on the free dofs.
  void add_transpose_product(int e, const Eigen::VectorXd& v, Eigen::VectorXd& out) const;

 private:
  const Problem& problem_;
  std::vector<int> free_index_;
  Eigen::SparseMatrix<double> pattern_;
  std::vector<int> scatter_;  // per element, per (i, j) local dof pair: value index or -1
  int local_dofs_ = 0;
};

}  // namespace strictmin
