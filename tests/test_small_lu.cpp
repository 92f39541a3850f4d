// The 1-ring solver's small dense solve (src/solvers/small_lu.h) against Eigen's
// PartialPivLU, whose operations it repeats: bitwise the same answer on random systems of
// size 1 to 3, with ties between pivot candidates, exactly zero pivot columns (non-finite
// answers, as Eigen's), and badly scaled rows; and a residual check that does not depend on
// Eigen.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstring>
#include <random>

#include "solvers/small_lu.h"

using namespace strictmin;

namespace {

using Small = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 3, 3>;
using SmallVec = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 3, 1>;

bool same_bits(double x, double y) { return std::memcmp(&x, &y, sizeof x) == 0; }

// Our solve of (A, b) beside Eigen's: every entry bitwise equal (NaNs compared as NaN).
void expect_as_eigen(const double (&A)[3][3], const double (&b)[3], int m) {
  Small J(m, m);
  SmallVec r(m);
  for (int i = 0; i < m; ++i) {
    r(i) = b[i];
    for (int j = 0; j < m; ++j) J(i, j) = A[i][j];
  }
  const SmallVec expected = J.partialPivLu().solve(r);
  double LU[3][3], x[3];
  std::memcpy(LU, A, sizeof LU);
  std::memcpy(x, b, sizeof x);
  small_lu_solve<3>(LU, x, m);
  for (int i = 0; i < m; ++i) {
    if (std::isnan(expected(i))) {
      EXPECT_TRUE(std::isnan(x[i])) << "m " << m << " entry " << i;
    } else {
      EXPECT_TRUE(same_bits(x[i], expected(i))) << "m " << m << " entry " << i << ": " << x[i] << " vs " << expected(i);
    }
  }
}

TEST(SmallLu, BitwiseAsEigenOnRandomSystems) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_int_distribution<int> scale(-8, 8);
  for (int trial = 0; trial < 20000; ++trial) {
    const int m = 1 + trial % 3;
    double A[3][3] = {}, b[3] = {};
    for (int i = 0; i < m; ++i) {
      const double row_scale = std::ldexp(1.0, scale(rng));
      b[i] = u(rng) * row_scale;
      for (int j = 0; j < m; ++j) A[i][j] = u(rng) * row_scale;
    }
    if (trial % 7 == 0 && m > 1) A[1][0] = -A[0][0];  // a tie for the first pivot
    if (trial % 11 == 0 && m > 2) A[2][1] = A[1][1];  // a possible tie for the second
    expect_as_eigen(A, b, m);
  }
}

TEST(SmallLu, ZeroPivotColumnsAsEigen) {
  const double A2[3][3] = {{0, 1, 0}, {0, 2, 0}, {0, 0, 0}};
  const double b[3] = {1, 2, 0};
  expect_as_eigen(A2, b, 2);
  const double A3[3][3] = {{1, 2, 3}, {2, 4, 6}, {1, 0, 1}};  // second pivot column zero after elimination
  expect_as_eigen(A3, b, 3);
  const double A1[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
  expect_as_eigen(A1, b, 1);
}

TEST(SmallLu, SolvesToRounding) {
  // A known answer: A x = b with x = (1, -2, 0.5) and a first pivot that needs a swap.
  const double A[3][3] = {{1e-3, 2, 1}, {4, -1, 3}, {2, 5, -7}};
  const double x_true[3] = {1, -2, 0.5};
  double b[3], LU[3][3];
  for (int i = 0; i < 3; ++i) b[i] = A[i][0] * x_true[0] + A[i][1] * x_true[1] + A[i][2] * x_true[2];
  std::memcpy(LU, A, sizeof LU);
  small_lu_solve<3>(LU, b, 3);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(b[i], x_true[i], 1e-14) << i;
}

}  // namespace
