#pragma once
// Polar decomposition and rotation logarithms for shape interpolation (docs/maths.md
// section 6): J = R Y with R a proper rotation and Y symmetric.
#include <Eigen/Core>

namespace strictmin {

struct Polar {
  Eigen::MatrixXd R;  // d by d proper rotation (det +1)
  Eigen::MatrixXd Y;  // d by d symmetric (positive definite when det J > 0)
};

// J square (2x2: closed form through the conformal part; 3x3: SVD with the sign of the
// smallest singular direction flipped when det < 0).
Polar polar_decomposition(const Eigen::MatrixXd& J);

// Angle of a 2D rotation in (-pi, pi], and the rotation of an angle.
double rotation_angle(const Eigen::MatrixXd& R);
Eigen::MatrixXd rotation_2d(double angle);

// Rotation vector (axis * angle, angle in [0, pi]) of a 3D rotation, and its exponential.
Eigen::Vector3d rotation_log(const Eigen::Matrix3d& R);
Eigen::Matrix3d rotation_exp(const Eigen::Vector3d& w);

}  // namespace strictmin
