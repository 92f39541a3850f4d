#include "strictmin/measures/polar.h"

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>

#include "strictmin/measures/measures.h"

namespace strictmin {

Polar polar_decomposition(const Eigen::MatrixXd& J) {
  Polar p;
  // closest_rotation is the polar factor (2D closed form, 3D SVD with the det fix), so
  // Y = R^T J; symmetrize away rounding.
  p.R = closest_rotation(J);
  const Eigen::MatrixXd Y = p.R.transpose() * J;
  p.Y = 0.5 * (Y + Y.transpose());
  return p;
}

double rotation_angle(const Eigen::MatrixXd& R) {
  if (R.rows() != 2 || R.cols() != 2) throw std::invalid_argument("rotation_angle: a 2 by 2 rotation is needed");
  return std::atan2(R(1, 0), R(0, 0));
}

Eigen::MatrixXd rotation_2d(double angle) {
  Eigen::Matrix2d R;
  R << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
  return R;
}

Eigen::Vector3d rotation_log(const Eigen::Matrix3d& R) {
  const Eigen::AngleAxisd aa(R);
  return aa.angle() * aa.axis();
}

Eigen::Matrix3d rotation_exp(const Eigen::Vector3d& w) {
  const double angle = w.norm();
  if (angle == 0.0) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, w / angle).toRotationMatrix();
}

}  // namespace strictmin
