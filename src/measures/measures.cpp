#include "strictmin/measures/measures.h"

#include "measures/closest_rotation3.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace strictmin {
namespace {

// 2x2: J = A + B with A conformal, B anticonformal (docs/maths.md section 7):
// a = ((J00 + J11)/2, (J10 - J01)/2), b = ((J00 - J11)/2, (J10 + J01)/2),
// sigma_1 = |a| + |b|, signed sigma_2 = |a| - |b| (negative exactly when det J < 0).
struct Conformal2 {
  double a0, a1, b0, b1;
  explicit Conformal2(const Eigen::MatrixXd& J)
      : a0(0.5 * (J(0, 0) + J(1, 1))), a1(0.5 * (J(1, 0) - J(0, 1))),
        b0(0.5 * (J(0, 0) - J(1, 1))), b1(0.5 * (J(1, 0) + J(0, 1))) {}
  double norm_a() const { return std::hypot(a0, a1); }
  double norm_b() const { return std::hypot(b0, b1); }
};

bool is_2x2(const Eigen::MatrixXd& J) { return J.rows() == 2 && J.cols() == 2; }

}  // namespace

std::string measure_name(Measure m) {
  switch (m) {
    case Measure::FieldDeviation: return "fd";
    case Measure::Arap: return "arap";
    case Measure::Asap: return "asap";
    case Measure::Quasiconformal: return "qc";
    case Measure::Isometric: return "iso";
  }
  return "?";
}

std::optional<Measure> parse_measure(const std::string& name) {
  if (name == "fd" || name == "field-deviation") return Measure::FieldDeviation;
  if (name == "arap") return Measure::Arap;
  if (name == "asap") return Measure::Asap;
  if (name == "qc" || name == "quasiconformal") return Measure::Quasiconformal;
  if (name == "iso" || name == "isometric") return Measure::Isometric;
  return std::nullopt;
}

Eigen::VectorXd signed_singular_values(const Eigen::MatrixXd& J) {
  if (J.size() == 0) throw std::invalid_argument("signed_singular_values: an empty matrix");
  if (is_2x2(J)) {
    const Conformal2 c(J);
    return Eigen::Vector2d(c.norm_a() + c.norm_b(), c.norm_a() - c.norm_b());
  }
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(J);
  Eigen::VectorXd s = svd.singularValues();
  if (J.rows() == J.cols() && J.determinant() < 0) s(s.size() - 1) = -s(s.size() - 1);
  return s;
}

Eigen::MatrixXd closest_rotation(const Eigen::MatrixXd& J) {
  if (J.size() == 0) throw std::invalid_argument("closest_rotation: an empty matrix");
  if (is_2x2(J)) {
    // R = rot(atan2(c - b, a + d)) for J = [[a, b], [c, d]]: the direction of a.
    const Conformal2 c(J);
    const double r = c.norm_a();
    const double cs = r > 0 ? c.a0 / r : 1.0, sn = r > 0 ? c.a1 / r : 0.0;
    Eigen::Matrix2d R;
    R << cs, -sn, sn, cs;
    return R;
  }
  if (J.rows() == 3 && J.cols() == 3) return closest_rotation3(Eigen::Matrix3d(J));
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(J, Eigen::ComputeThinU | Eigen::ComputeThinV);
  Eigen::MatrixXd U = svd.matrixU();
  const Eigen::MatrixXd& V = svd.matrixV();
  if (J.rows() == J.cols() && (U * V.transpose()).determinant() < 0) U.col(U.cols() - 1) *= -1.0;
  return U * V.transpose();
}

Eigen::MatrixXd closest_similarity(const Eigen::MatrixXd& J) {
  if (is_2x2(J)) {
    const Conformal2 c(J);  // the conformal part A is the closest similarity
    Eigen::Matrix2d S;
    S << c.a0, -c.a1, c.a1, c.a0;
    return S;
  }
  // s Q with Q the closest rotation and s = <J, Q> / d (clamped at 0).
  const Eigen::MatrixXd Q = closest_rotation(J);
  const double s = std::max(0.0, (Q.transpose() * J).trace() / static_cast<double>(J.cols()));
  return s * Q;
}

namespace {
// From a square J's signed singular values (the last one negative when det J < 0): flipped,
// or collapsed (the smallest at most kCollapsedRatio times the largest).
bool flipped_or_collapsed(const Eigen::VectorXd& s) { return s(s.size() - 1) <= kCollapsedRatio * s(0); }
}  // namespace

double distortion(Measure m, const Eigen::MatrixXd& J, const Eigen::MatrixXd& R) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  switch (m) {
    case Measure::FieldDeviation: return (J - R).norm();
    case Measure::Arap: {
      if (is_2x2(J)) {
        const Eigen::VectorXd s = signed_singular_values(J);
        return std::hypot(s(0) - 1.0, s(1) - 1.0);
      }
      return (J - closest_rotation(J)).norm();
    }
    case Measure::Asap: {
      if (is_2x2(J)) return Conformal2(J).norm_b() * std::sqrt(2.0);  // (s1 - s2)/sqrt(2)
      return (J - closest_similarity(J)).norm();
    }
    case Measure::Quasiconformal: {
      const Eigen::VectorXd s = signed_singular_values(J);
      const double smin = s(s.size() - 1);
      if (J.rows() == J.cols() && flipped_or_collapsed(s)) return inf;
      return smin > 0 ? s(0) / smin : inf;
    }
    case Measure::Isometric: {
      const Eigen::VectorXd s = signed_singular_values(J);
      const double smin = s(s.size() - 1);
      if (smin <= 0) return inf;
      return std::max(s(0), 1.0 / smin);
    }
  }
  return inf;
}

bool is_flipped(const Eigen::MatrixXd& J) {
  return J.rows() == J.cols() && flipped_or_collapsed(signed_singular_values(J));
}

}  // namespace strictmin
