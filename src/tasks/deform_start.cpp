#include "strictmin/tasks/deform_start.h"

#include <Eigen/Dense>

#include "strictmin/solvers/l2.h"

namespace strictmin {

Eigen::MatrixXd handles_best_rotation(const Eigen::MatrixXd& rest, const std::vector<Handle>& handles) {
  const int n = static_cast<int>(rest.cols());
  if (handles.size() < 2) return Eigen::MatrixXd::Identity(n, n);
  Eigen::VectorXd from_centre = Eigen::VectorXd::Zero(n), to_centre = Eigen::VectorXd::Zero(n);
  for (const Handle& h : handles) {
    from_centre += rest.row(h.vertex).transpose();
    to_centre += h.position;
  }
  from_centre /= static_cast<double>(handles.size());
  to_centre /= static_cast<double>(handles.size());
  // Kabsch: H = sum (p - p0)(y - y0)^T = U S V^T, R = V diag(1, .., det(V U^T)) U^T.
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(n, n);
  for (const Handle& h : handles)
    H += (rest.row(h.vertex).transpose() - from_centre) * (h.position - to_centre).transpose();
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(H, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::MatrixXd D = Eigen::MatrixXd::Identity(n, n);
  D(n - 1, n - 1) = (svd.matrixV() * svd.matrixU().transpose()).determinant() < 0 ? -1.0 : 1.0;
  return svd.matrixV() * D * svd.matrixU().transpose();
}

Eigen::MatrixXd deform_start(const Problem& problem, const Eigen::MatrixXd& rest, const std::vector<Handle>& handles,
                             const LocalGlobalOptions& options) {
  const Eigen::MatrixXd plain = solve_l2(problem).positions;
  const Eigen::MatrixXd R = handles_best_rotation(rest, handles);
  if ((R - Eigen::MatrixXd::Identity(R.rows(), R.cols())).norm() < 1e-14) return plain;
  Problem turned = problem;
  for (int e = 0; e < turned.num_elements(); ++e) turned.set_target(e, R * problem.target(e));
  const Eigen::MatrixXd rotated = solve_l2(turned).positions;
  const double plain_max = local_distortion(problem, plain, options).maxCoeff();
  const double rotated_max = local_distortion(problem, rotated, options).maxCoeff();
  return rotated_max < plain_max ? rotated : plain;
}

}  // namespace strictmin
