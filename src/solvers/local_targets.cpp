#include "local_targets.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Dense>
#include <algorithm>

#include "strictmin/measures/measures.h"
#include "measures/closest_rotation3.h"

namespace strictmin {
namespace {

template <int n, int m>
using Mat = Eigen::Matrix<double, n, m>;

template <int n, int m>
Mat<n, m> jacobian(const Problem& p, int e, const Eigen::MatrixXd& X) {
  Mat<n, m> J = Mat<n, m>::Zero();
  for (int j = 0; j < m + 1; ++j)
    J.noalias() += X.row(p.elements(e, j)).transpose() * p.gradients.row(e * (m + 1) + j);
  return J;
}

// 2x2: the closest rotation is the direction of the conformal part a = ((J00 + J11) / 2,
// (J10 - J01) / 2), the closest similarity the conformal part itself (docs/maths.md).
Mat<2, 2> target_2x2(const Mat<2, 2>& J, LocalStep step) {
  const double a0 = 0.5 * (J(0, 0) + J(1, 1)), a1 = 0.5 * (J(1, 0) - J(0, 1));
  double c = a0, s = a1;
  if (step == LocalStep::Rotation) {
    const double r = std::hypot(a0, a1);
    c = r > 0 ? a0 / r : 1.0;
    s = r > 0 ? a1 / r : 0.0;
  }
  Mat<2, 2> T;
  T << c, -s, s, c;
  return T;
}

// 3x3: the closest rotation by the polar iteration (measures/closest_rotation3.h), times
// s = <J, Q> / 3 clamped at 0 for a similarity.
Mat<3, 3> target_3x3(const Mat<3, 3>& J, LocalStep step) {
  Mat<3, 3> Q = closest_rotation3(J);
  if (step == LocalStep::Similarity) Q *= std::max(0.0, (Q.transpose() * J).trace() / 3.0);
  return Q;
}

// 3x2: U V^T from the SVD (proper rotation for square J: the smallest singular
// direction flipped when det < 0), times s = <J, Q> / m clamped at 0 for a similarity.
template <int n, int m>
Mat<n, m> target_svd(const Mat<n, m>& J, LocalStep step) {
  const Eigen::JacobiSVD<Mat<n, m>> svd(J, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Mat<n, n> U = svd.matrixU();
  const Mat<m, m>& V = svd.matrixV();
  Mat<n, m> Q = U.template leftCols<m>() * V.transpose();
  if (n == m && Q.determinant() < 0) {
    U.col(m - 1) *= -1.0;
    Q = U.template leftCols<m>() * V.transpose();
  }
  if (step == LocalStep::Similarity) Q *= std::max(0.0, (Q.transpose() * J).trace() / m);
  return Q;
}

template <int n, int m>
void pass(const Problem& p, const Eigen::MatrixXd& X, LocalStep step, Eigen::VectorXd& d, Eigen::MatrixXd* targets) {
  tbb::parallel_for(tbb::blocked_range<int>(0, p.num_elements(), 1024), [&](const tbb::blocked_range<int>& r) {
    for (int e = r.begin(); e != r.end(); ++e) {
      const Mat<n, m> J = jacobian<n, m>(p, e, X);
      Mat<n, m> T;
      if constexpr (n == 2 && m == 2) T = target_2x2(J, step);
      else if constexpr (n == 3 && m == 3) T = target_3x3(J, step);
      else T = target_svd<n, m>(J, step);
      d(e) = (J - T).norm();
      if (targets) targets->middleRows(e * n, n) = T;
    }
  });
}

template <int n, int m>
void extrapolate_pass(const Problem& p, const Eigen::MatrixXd& previous, double beta, LocalStep step,
                      Eigen::MatrixXd& targets) {
  tbb::parallel_for(tbb::blocked_range<int>(0, p.num_elements(), 1024), [&](const tbb::blocked_range<int>& r) {
    for (int e = r.begin(); e != r.end(); ++e) {
      const Mat<n, m> now = targets.middleRows(e * n, n);
      const Mat<n, m> before = previous.middleRows(e * n, n);
      const Mat<n, m> M = now + beta * (now - before);
      Mat<n, m> T;
      if constexpr (n == 2 && m == 2) T = target_2x2(M, step);
      else if constexpr (n == 3 && m == 3) T = target_3x3(M, step);
      else T = target_svd<n, m>(M, step);
      targets.middleRows(e * n, n) = T;
    }
  });
}

}  // namespace

bool extrapolate_targets(const Problem& p, const Eigen::MatrixXd& previous, double beta, const LocalGlobalOptions& o,
                         Eigen::MatrixXd& targets) {
  if (o.shapes.size() != 0 || previous.rows() != targets.rows() || previous.cols() != targets.cols()) return false;
  const int n = p.image_dim, m = p.domain_dim;
  if (n == 2 && m == 2) extrapolate_pass<2, 2>(p, previous, beta, o.local, targets);
  else if (n == 3 && m == 3) extrapolate_pass<3, 3>(p, previous, beta, o.local, targets);
  else if (n == 3 && m == 2) extrapolate_pass<3, 2>(p, previous, beta, o.local, targets);
  else return false;
  return true;
}

Eigen::VectorXd local_targets(const Problem& p, const Eigen::MatrixXd& X, const LocalGlobalOptions& o,
                              Eigen::MatrixXd* targets) {
  Eigen::VectorXd d(p.num_elements());
  if (targets) targets->resize(static_cast<Eigen::Index>(p.num_elements()) * p.image_dim, p.domain_dim);
  const int n = p.image_dim, m = p.domain_dim;
  if (o.shapes.size() == 0 && n == 2 && m == 2) {
    pass<2, 2>(p, X, o.local, d, targets);
  } else if (o.shapes.size() == 0 && n == 3 && m == 3) {
    pass<3, 3>(p, X, o.local, d, targets);
  } else if (o.shapes.size() == 0 && n == 3 && m == 2) {
    pass<3, 2>(p, X, o.local, d, targets);
  } else {
    // Shapes (interpolation): Q S with Q the rotation closest to J S^T.
    for (int e = 0; e < p.num_elements(); ++e) {
      const Eigen::MatrixXd J = p.jacobian(e, X);
      Eigen::MatrixXd T;
      if (o.local == LocalStep::Similarity) {
        T = closest_similarity(J);
      } else if (o.shapes.size() == 0) {
        T = closest_rotation(J);
      } else {
        const Eigen::MatrixXd S = o.shapes.middleRows(e * n, n);
        T = closest_rotation(J * S.transpose()) * S;
      }
      d(e) = (J - T).norm();
      if (targets) targets->middleRows(e * n, n) = T;
    }
  }
  return d;
}

}  // namespace strictmin
