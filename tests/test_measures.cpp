// Every measure against an independent SVD-based reference on random matrices, plus
// closed-form values on hand-made maps.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <random>

#include "measures/closest_rotation3.h"
#include "strictmin/measures/measures.h"

using namespace strictmin;

namespace {

// Reference: full SVD J = U S V^T; proper rotation by flipping the last singular pair when
// det(U V^T) < 0, so the signed singular values are S with the last one negated.
struct Reference {
  Eigen::VectorXd s;  // signed
  Eigen::MatrixXd R;  // closest rotation
  explicit Reference(const Eigen::MatrixXd& J) {
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(J, Eigen::ComputeFullU | Eigen::ComputeFullV);
    Eigen::MatrixXd U = svd.matrixU();
    s = svd.singularValues();
    if ((U * svd.matrixV().transpose()).determinant() < 0) {
      U.col(U.cols() - 1) *= -1;
      s(s.size() - 1) *= -1;
    }
    R = U * svd.matrixV().transpose();
  }
  double arap() const { return (s.array() - 1.0).matrix().norm(); }
  double asap() const {
    const double mean = s.mean();
    return (s.array() - mean).matrix().norm();
  }
};

Eigen::MatrixXd random_matrix(std::mt19937& rng, int d) {
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::MatrixXd J(d, d);
  for (int i = 0; i < d; ++i)
    for (int j = 0; j < d; ++j) J(i, j) = normal(rng);
  return J;
}

class MeasuresRandom : public ::testing::TestWithParam<int> {};

TEST_P(MeasuresRandom, AgreeWithSvdReference) {
  const int d = GetParam();
  std::mt19937 rng(42 + d);
  for (int trial = 0; trial < 2000; ++trial) {
    const Eigen::MatrixXd J = random_matrix(rng, d);
    const Eigen::MatrixXd R = random_matrix(rng, d);
    const Reference ref(J);
    const double tol = 1e-10 * (1.0 + J.norm());
    EXPECT_NEAR(distortion(Measure::FieldDeviation, J, R), (J - R).norm(), tol);
    EXPECT_NEAR(distortion(Measure::Arap, J, R), ref.arap(), tol);
    EXPECT_NEAR(distortion(Measure::Asap, J, R), ref.asap(), tol) << J;
    const Eigen::VectorXd s = signed_singular_values(J);
    ASSERT_EQ(s.size(), d);
    for (int i = 0; i < d; ++i) EXPECT_NEAR(s(i), ref.s(i), tol);
    EXPECT_LT((closest_rotation(J) - ref.R).norm(), 1e-9);
    EXPECT_NEAR(closest_rotation(J).determinant(), 1.0, 1e-12);
    EXPECT_EQ(is_flipped(J), J.determinant() <= 0);
    if (ref.s(d - 1) > 0) {
      EXPECT_NEAR(distortion(Measure::Quasiconformal, J, R), ref.s(0) / ref.s(d - 1), 1e-8 * ref.s(0) / ref.s(d - 1));
      EXPECT_NEAR(distortion(Measure::Isometric, J, R), std::max(ref.s(0), 1.0 / ref.s(d - 1)), 1e-8 / ref.s(d - 1));
    } else {
      EXPECT_TRUE(std::isinf(distortion(Measure::Quasiconformal, J, R)));
      EXPECT_TRUE(std::isinf(distortion(Measure::Isometric, J, R)));
    }
    // The closest similarity is at ASAP distance, and no rotation is closer than ARAP's.
    EXPECT_NEAR((J - closest_similarity(J)).norm(), ref.asap(), tol);
  }
}

INSTANTIATE_TEST_SUITE_P(Dimensions, MeasuresRandom, ::testing::Values(2, 3));

TEST(Measures, LocalStepsNeverIncreaseDistortion) {
  // min over rotations <= distance to any given rotation (the local step of docs/maths.md).
  std::mt19937 rng(7);
  for (int d : {2, 3})
    for (int trial = 0; trial < 500; ++trial) {
      const Eigen::MatrixXd J = random_matrix(rng, d);
      const Eigen::MatrixXd Q = closest_rotation(random_matrix(rng, d));
      EXPECT_LE(distortion(Measure::Arap, J, Q), (J - Q).norm() + 1e-12);
      EXPECT_LE(distortion(Measure::Asap, J, Q), distortion(Measure::Arap, J, Q) + 1e-12);
    }
}

TEST(Measures, ClosedForms2d) {
  const double a = 0.7;
  Eigen::Matrix2d rot;
  rot << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
  const Eigen::Matrix2d I = Eigen::Matrix2d::Identity();
  // A rotation: no ARAP/ASAP distortion, qc = iso = 1, FD against I = 2 sqrt(2) sin(a/2).
  EXPECT_NEAR(distortion(Measure::Arap, rot, I), 0.0, 1e-15);
  EXPECT_NEAR(distortion(Measure::Asap, rot, I), 0.0, 1e-15);
  EXPECT_NEAR(distortion(Measure::Quasiconformal, rot, I), 1.0, 1e-15);
  EXPECT_NEAR(distortion(Measure::Isometric, rot, I), 1.0, 1e-15);
  EXPECT_NEAR(distortion(Measure::FieldDeviation, rot, I), 2 * std::sqrt(2.0) * std::sin(a / 2), 1e-15);
  // Scaling diag(2, 0.5): ARAP sqrt(1 + 0.25), ASAP 1.5/sqrt(2), qc 4, iso 2.
  const Eigen::Matrix2d S = Eigen::Vector2d(2.0, 0.5).asDiagonal();
  EXPECT_NEAR(distortion(Measure::Arap, S, I), std::sqrt(1.25), 1e-15);
  EXPECT_NEAR(distortion(Measure::Asap, S, I), 1.5 / std::sqrt(2.0), 1e-15);
  EXPECT_NEAR(distortion(Measure::Quasiconformal, S, I), 4.0, 1e-15);
  EXPECT_NEAR(distortion(Measure::Isometric, S, I), 2.0, 1e-15);
  // Uniform scaling 3: a similarity (ASAP 0, qc 1), ARAP sqrt(8).
  EXPECT_NEAR(distortion(Measure::Asap, 3 * I, I), 0.0, 1e-15);
  EXPECT_NEAR(distortion(Measure::Arap, 3 * I, I), std::sqrt(8.0), 1e-14);
  // A reflection is flipped: ARAP measures the distance to proper rotations = 2.
  const Eigen::Matrix2d M = Eigen::Vector2d(1.0, -1.0).asDiagonal();
  EXPECT_TRUE(is_flipped(M));
  EXPECT_NEAR(distortion(Measure::Arap, M, I), 2.0, 1e-15);
  EXPECT_TRUE(std::isinf(distortion(Measure::Quasiconformal, M, I)));
  // Shear [[1, s], [0, 1]]: sigma = s/2 +- sqrt(1 + s^2/4); ASAP = |s| / sqrt(2).
  Eigen::Matrix2d H;
  H << 1, 0.6, 0, 1;
  EXPECT_NEAR(distortion(Measure::Asap, H, I), 0.6 / std::sqrt(2.0), 1e-15);
  const double s1 = 0.3 + std::sqrt(1 + 0.09), s2 = -0.3 + std::sqrt(1 + 0.09);
  EXPECT_NEAR(distortion(Measure::Quasiconformal, H, I), s1 / s2, 1e-13);
}

TEST(Measures, ClosedForms3d) {
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d S = Eigen::Vector3d(2.0, 1.0, 0.5).asDiagonal();
  EXPECT_NEAR(distortion(Measure::Arap, S, I), std::sqrt(1.25), 1e-14);
  EXPECT_NEAR(distortion(Measure::Quasiconformal, S, I), 4.0, 1e-14);
  EXPECT_NEAR(distortion(Measure::Isometric, S, I), 2.0, 1e-14);
  // ASAP: s = 3.5/3, distance^2 = sum (s_i - s)^2.
  const double m = 3.5 / 3;
  EXPECT_NEAR(distortion(Measure::Asap, S, I), std::sqrt((2 - m) * (2 - m) + (1 - m) * (1 - m) + (0.5 - m) * (0.5 - m)),
              1e-14);
}

// A collapsed element (a tet with two vertices on one point: det J is 1e-17 of either sign by
// rounding) counts as flipped and has infinite qc, whichever sign rounding gave it; a thin but
// whole element keeps its finite qc.
TEST(Measures, CollapsedElementsAreFlippedWithInfiniteQc) {
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  for (double last : {1e-17, -1e-17, 0.0}) {
    const Eigen::Matrix3d J = Eigen::Vector3d(1.0, 0.7, last).asDiagonal();
    EXPECT_TRUE(is_flipped(J)) << last;
    EXPECT_TRUE(std::isinf(distortion(Measure::Quasiconformal, J, I))) << last;
  }
  // Collapsed onto a line through rounding: columns a, b, a + b.
  Eigen::Matrix3d J;
  J.col(0) = Eigen::Vector3d(0.1, 0.2, 0.3);
  J.col(1) = Eigen::Vector3d(0.7, -0.1, 0.3);
  J.col(2) = J.col(0) + J.col(1);
  EXPECT_TRUE(is_flipped(J));
  EXPECT_TRUE(std::isinf(distortion(Measure::Quasiconformal, J, I)));
  const Eigen::Matrix3d thin = Eigen::Vector3d(1.0, 1.0, 1e-9).asDiagonal();
  EXPECT_FALSE(is_flipped(thin));
  EXPECT_NEAR(distortion(Measure::Quasiconformal, thin, I), 1e9, 1e-3);
  const Eigen::Matrix2d flat = Eigen::Vector2d(2.0, 1e-14).asDiagonal();
  EXPECT_TRUE(is_flipped(flat));
  EXPECT_FALSE(is_flipped(Eigen::Matrix2d(Eigen::Vector2d(2.0, 1e-6).asDiagonal())));
}

TEST(Measures, Names) {
  for (Measure m : {Measure::FieldDeviation, Measure::Arap, Measure::Asap, Measure::Quasiconformal, Measure::Isometric})
    EXPECT_EQ(parse_measure(measure_name(m)), m);
  EXPECT_FALSE(parse_measure("stretch").has_value());
}

}  // namespace

// The local step's 3x3 closest rotation (polar iteration, measures/closest_rotation3.h)
// against U V^T of the SVD (last singular pair flipped when det < 0), on random matrices of
// every kind: well and badly conditioned, nearly singular, reflections, scaled far from 1.
TEST(Measures, ClosestRotation3MatchesSvd) {
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> log_scale(-6.0, 6.0);
  const auto random_rotation = [&] {
    Eigen::Matrix3d M;
    for (int i = 0; i < 9; ++i) M(i) = normal(rng);
    Eigen::HouseholderQR<Eigen::Matrix3d> qr(M);
    Eigen::Matrix3d Q = qr.householderQ();
    if (Q.determinant() < 0) Q.col(0) *= -1.0;
    return Q;
  };
  double worst = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    // J = U diag(s) V^T with singular values spread over up to 12 decades, one of them
    // negative in a quarter of the trials (a flipped element).
    Eigen::Vector3d s;
    for (int i = 0; i < 3; ++i) s(i) = std::pow(10.0, log_scale(rng) * (trial % 3 == 0 ? 1.0 : 0.1));
    if (trial % 4 == 1) s(2) = -s(2);
    const double global = std::pow(10.0, log_scale(rng));
    const Eigen::Matrix3d J = global * random_rotation() * s.asDiagonal() * random_rotation().transpose();
    const Eigen::Matrix3d fast = closest_rotation3(J);
    const Eigen::Matrix3d reference = closest_rotation3_svd(J);
    ASSERT_NEAR(fast.determinant(), 1.0, 1e-12) << "trial " << trial;
    ASSERT_LT((fast.transpose() * fast - Eigen::Matrix3d::Identity()).norm(), 1e-12) << "trial " << trial;
    // The polar factor is well determined when the two smallest |singular values| are apart
    // relative to the matrix; compare there, and compare the objective <J, R> everywhere.
    Eigen::Vector3d a = s.cwiseAbs();
    std::sort(a.data(), a.data() + 3);
    if (a(0) + a(1) > 1e-6 * a(2)) {
      const double error = (fast - reference).norm();
      worst = std::max(worst, error);
      ASSERT_LT(error, 1e-9) << "trial " << trial << " singular values " << s.transpose();
    }
    ASSERT_GE((fast.transpose() * J).trace(), (reference.transpose() * J).trace() - 1e-12 * J.norm())
        << "trial " << trial;
  }
  RecordProperty("worst_difference", std::to_string(worst));
}
