// The L2 solver: its solution satisfies the normal equations of sum_T A_T ||J_T - R_T||^2
// (checked with the independently built operator Problem::reduced()), reproduces affine
// maps exactly when the handles come from one, and reports undetermined problems.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <vector>

#include "strictmin/measures/measures.h"
#include "strictmin/mesh/generators.h"
#include "strictmin/problem/parts.h"
#include "strictmin/solvers/l2.h"
#include "strictmin/solvers/sparse_cholesky.h"

using namespace strictmin;

namespace {

Eigen::VectorXd row_weights(const Problem& p) {
  Eigen::VectorXd w(p.num_elements() * p.jacobian_size());
  for (int e = 0; e < p.num_elements(); ++e) w.segment(e * p.jacobian_size(), p.jacobian_size()).setConstant(p.weights(e));
  return w;
}

void expect_normal_equations(const Problem& p, const Eigen::MatrixXd& X) {
  const auto red = p.reduced();
  const Eigen::VectorXd x = p.free_dofs(X);
  const Eigen::VectorXd grad = red.G.transpose() * (row_weights(p).asDiagonal() * (red.G * x - red.h));
  const Eigen::VectorXd scale = red.G.transpose() * (row_weights(p).asDiagonal() * red.h);
  EXPECT_LT(grad.norm(), 1e-10 * (1.0 + scale.norm())) << "gradient of the L2 energy at the solution";
}

Eigen::Matrix2d random_rotation2(std::mt19937& rng) {
  const double a = std::uniform_real_distribution<double>(-3, 3)(rng);
  Eigen::Matrix2d R;
  R << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
  return R;
}

TEST(L2, SatisfiesNormalEquationsWithRandomTargets) {
  Problem p = make_problem(make_grid(12, 9, 1.3, 1.0));
  std::mt19937 rng(11);
  for (int e = 0; e < p.num_elements(); ++e) p.set_target(e, random_rotation2(rng));
  p.fix({{0, Eigen::Vector2d(0, 0)}, {50, Eigen::Vector2d(0.5, 0.7)}, {129, Eigen::Vector2d(1.5, 1.1)}});
  const Result r = solve_l2(p);
  ASSERT_TRUE(r.ok()) << r.message;
  expect_normal_equations(p, r.positions);
  EXPECT_EQ(r.distortion.size(), p.num_elements());
}

TEST(L2, TetsSatisfyNormalEquations) {
  Problem p = make_problem(make_tet_box(4, 3, 2));
  p.fix({{0, Eigen::Vector3d(0, 0, 0)}, {59, Eigen::Vector3d(1.2, 1.1, 1.3)}});
  const Result r = solve_l2(p);
  ASSERT_TRUE(r.ok()) << r.message;
  expect_normal_equations(p, r.positions);
}

TEST(L2, ReproducesAffineMapsFromTheirHandles) {
  const Mesh mesh = make_grid(10, 10);
  Eigen::Matrix2d A;
  A << 1.3, 0.4, -0.2, 0.8;
  const Eigen::Vector2d b(0.5, -0.25);
  Problem p = make_problem(mesh);
  std::vector<Handle> handles;
  // The whole boundary follows the affine map. Inside, a constant J = A has zero energy
  // gradient (sum_T A_T g_v = 0 over a closed 1-ring), so the minimizer is the affine map.
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    const Eigen::Vector2d x = mesh.V.row(v);
    if (x.minCoeff() == 0.0 || x.maxCoeff() == 1.0) handles.push_back({v, A * x + b});
  }
  p.fix(handles);
  const Result r = solve_l2(p);
  ASSERT_TRUE(r.ok());
  for (int v = 0; v < mesh.num_vertices(); ++v)
    EXPECT_LT((r.positions.row(v).transpose() - (A * mesh.V.row(v).transpose() + b)).norm(), 1e-10);
  EXPECT_NEAR(r.distortion.maxCoeff(), (A - Eigen::Matrix2d::Identity()).norm(), 1e-10);
  EXPECT_NEAR(r.distortion.minCoeff(), (A - Eigen::Matrix2d::Identity()).norm(), 1e-10);
}

TEST(L2, AffineTetMap) {
  const Mesh mesh = make_tet_box(3, 3, 3);
  const Eigen::Matrix3d A = Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()).toRotationMatrix() * 1.2;
  Problem p = make_problem(mesh);
  std::vector<Handle> handles;
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    const Eigen::Vector3d x = mesh.V.row(v);
    if (x.minCoeff() == 0.0 || x.maxCoeff() == 1.0) handles.push_back({v, A * x});
  }
  p.fix(handles);
  const Result r = solve_l2(p);
  ASSERT_TRUE(r.ok());
  for (int v = 0; v < mesh.num_vertices(); ++v)
    EXPECT_LT((r.positions.row(v).transpose() - A * mesh.V.row(v).transpose()).norm(), 1e-10);
}

TEST(L2, RepeatedSolvesReuseTheFactorization) {
  Problem p = make_problem(make_grid(8, 8));
  p.fix({{0, Eigen::Vector2d(0, 0)}});
  const L2Solver solver(p);
  ASSERT_EQ(solver.status(), SolveStatus::Solved);
  // With targets = a rotation Q and one vertex pinned at the origin, the solution is Q x.
  const double a = 1.1;
  Eigen::Matrix2d Q;
  Q << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
  for (int e = 0; e < p.num_elements(); ++e) p.set_target(e, Q);
  const Eigen::MatrixXd X = solver.solve(p);
  const Eigen::MatrixXd rest = make_grid(8, 8).V;
  EXPECT_LT((X - rest * Q.transpose()).norm(), 1e-10);
}

TEST(L2, ReportsAPartWithoutHandles) {
  Problem p = make_problem(make_grid(3, 3));
  const Result r = solve_l2(p);
  EXPECT_EQ(r.status, SolveStatus::NumericalError);
  EXPECT_NE(r.message.find("no fixed vertex"), std::string::npos) << r.message;
  EXPECT_EQ(unanchored_components(p), std::vector<int>{0});
}

}  // namespace

// SparseCholesky (CHOLMOD's supernodal factor, our own substitutions) against a dense LLT on
// a random sparse SPD matrix with several right-hand sides, entries over 8 orders of
// magnitude, and a factor with wide supernodes (a dense block).
TEST(SparseCholeskyTest, SolvesLikeADenseFactorisation) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int n = 400;
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) {
    const double scale = std::pow(10.0, 8.0 * i / n - 4.0);
    t.emplace_back(i, i, scale * (4.0 + u(rng)));
    for (int j : {i + 1, i + 7, i + 31})
      if (j < n) {
        const double v = 0.3 * std::sqrt(scale) * u(rng);
        t.emplace_back(i, j, v * std::pow(10.0, 4.0 * j / n - 2.0));
        t.emplace_back(j, i, v * std::pow(10.0, 4.0 * j / n - 2.0));
      }
  }
  for (int i = n - 40; i < n; ++i)  // a dense trailing block: wide supernodes
    for (int j = n - 40; j < i; ++j) {
      const double v = 0.01 * u(rng);
      t.emplace_back(i, j, v);
      t.emplace_back(j, i, v);
    }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  Eigen::MatrixXd dense = Eigen::MatrixXd(A);
  dense = 0.5 * (dense + dense.transpose()).eval();
  const Eigen::LLT<Eigen::MatrixXd> reference(dense);
  ASSERT_EQ(reference.info(), Eigen::Success);
  SparseCholesky chol;
  ASSERT_TRUE(chol.factorize(A));
  const Eigen::MatrixXd B = Eigen::MatrixXd::NullaryExpr(n, 3, [&] { return u(rng); });
  const Eigen::MatrixXd X = chol.solve(B), Y = reference.solve(B);
  EXPECT_LT((X - Y).norm() / Y.norm(), 1e-10);
  EXPECT_LT((dense * X - B).norm() / B.norm(), 1e-12);
}
