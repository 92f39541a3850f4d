#pragma once
// The closest proper rotation to a 3x3 matrix (the ARAP local step on tets, docs/maths.md):
// for det J > 0 it is the orthogonal polar factor of J, reached here by Higham's scaled
// Newton iteration X <- (g X + X^{-T} / g) / 2 (quadratic convergence; about 5-8 steps of
// a cofactor inverse, several times cheaper than a 3x3 SVD); for det J <= 0 (a flipped or
// degenerate element) and on the rare J where the iteration does not settle, U V^T from the
// SVD with the smallest singular direction flipped.
#include <Eigen/Dense>
#include <cmath>

namespace strictmin {

inline Eigen::Matrix3d closest_rotation3_svd(const Eigen::Matrix3d& J) {
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(J, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d U = svd.matrixU();
  const Eigen::Matrix3d& V = svd.matrixV();
  if ((U * V.transpose()).determinant() < 0) U.col(2) *= -1.0;
  return U * V.transpose();
}

inline Eigen::Matrix3d closest_rotation3(const Eigen::Matrix3d& J) {
  // A determinant this small relative to |J|^3 leaves the polar factor ill-determined in
  // double precision: the SVD decides there.
  constexpr double kMinRelativeDet = 1e-10;
  // Stop once a step moves X by less than this (relative): X's error is then about its square
  // (quadratic convergence, ~1e-10), and the plain Newton step after the loop squares it again.
  constexpr double kSettled = 1e-5;
  constexpr int kMaxSteps = 30;
  const double scale = J.norm();
  if (!(scale > 0) || !std::isfinite(scale) || J.determinant() <= kMinRelativeDet * scale * scale * scale)
    return closest_rotation3_svd(J);
  Eigen::Matrix3d X = J / scale;
  for (int step = 0; step < kMaxSteps; ++step) {
    // X^{-T} = cofactor(X) / det X.
    Eigen::Matrix3d C;
    C.col(0) = X.col(1).cross(X.col(2));
    C.col(1) = X.col(2).cross(X.col(0));
    C.col(2) = X.col(0).cross(X.col(1));
    const double det = X.col(0).dot(C.col(0));
    const Eigen::Matrix3d inverse_transpose = C / det;
    const double g = std::sqrt(std::sqrt(inverse_transpose.squaredNorm() / X.squaredNorm()));
    const Eigen::Matrix3d next = 0.5 * (g * X + inverse_transpose / g);
    const double moved = (next - X).norm();
    X = next;
    if (moved <= kSettled * std::sqrt(3.0)) {
      // One plain Newton step more: the error after it is about moved^2.
      Eigen::Matrix3d D;
      D.col(0) = X.col(1).cross(X.col(2));
      D.col(1) = X.col(2).cross(X.col(0));
      D.col(2) = X.col(0).cross(X.col(1));
      return 0.5 * (X + D / X.col(0).dot(D.col(0)));
    }
  }
  return closest_rotation3_svd(J);
}

}  // namespace strictmin
