#include "strictmin/measures/field_deviation.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace strictmin {

double field_deviation(const Problem& p, const Eigen::MatrixXd& X, int e) {
  const int n = p.image_dim, m = p.domain_dim, c = p.corners();
  double sum = 0;  // ||sum_j q_j g_j^T - R_T||_F^2, entry by entry
  for (int r = 0; r < n; ++r)
    for (int k = 0; k < m; ++k) {
      double J = -p.targets(e * n + r, k);
      for (int j = 0; j < c; ++j) J += X(p.elements(e, j), r) * p.gradients(e * c + j, k);
      sum += J * J;
    }
  return std::sqrt(sum);
}

Eigen::VectorXd field_deviation(const Problem& p, const Eigen::MatrixXd& X) {
  if (X.rows() != p.num_vertices || X.cols() != p.image_dim)
    throw std::invalid_argument("field_deviation: the map is " + std::to_string(X.rows()) + " by " +
                                std::to_string(X.cols()) + ", the problem's vertices " +
                                std::to_string(p.num_vertices) + " by " + std::to_string(p.image_dim));
  Eigen::VectorXd d(p.num_elements());
  for (int e = 0; e < p.num_elements(); ++e) d(e) = field_deviation(p, X, e);
  return d;
}

}  // namespace strictmin
