// L2 with complex-linear equalities (problem/complex_equality_basis.h, src/solvers/l2_complex.h):
// the complex basis meets the seams exactly, the complex form gives the real form's
// minimizer (an independent elimination, sparse products and the real supernodal Cholesky),
// equalities that are not complex-linear fall back to the real form, and the complex
// Cholesky's own factorization and substitutions solve like a dense factorization.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <filesystem>
#include <random>

#include "field/hermitian_cholesky.h"
#include "test_meshes.h"
#include "strictmin/io/mesh_io.h"
#include "strictmin/mesh/generators.h"
#include "strictmin/mesh/polycube.h"
#include "strictmin/problem/complex_equality_basis.h"
#include "strictmin/problem/equality_basis.h"
#include "strictmin/solvers/l2.h"
#include "strictmin/tasks/gparam.h"

using namespace strictmin;
using Complex = std::complex<double>;

namespace {

Eigen::VectorXd dofs(const Eigen::MatrixXd& X) {
  Eigen::VectorXd q(X.size());
  for (int v = 0; v < X.rows(); ++v)
    for (int c = 0; c < X.cols(); ++c) q[v * X.cols() + c] = X(v, c);
  return q;
}

// The complex and the real form's minimizers, with the problem's weights and with others.
void expect_same_minimizer(const Problem& p, const std::string& name) {
  ASSERT_TRUE(complex_equality_basis(p).has_value()) << name;
  const Result complex_form = solve_l2(p), real_form = solve_l2(p, L2Options{false});
  ASSERT_EQ(complex_form.status, SolveStatus::Solved) << name;
  ASSERT_EQ(real_form.status, SolveStatus::Solved) << name;
  const double extent = real_form.positions.cwiseAbs().maxCoeff();
  EXPECT_LT((complex_form.positions - real_form.positions).cwiseAbs().maxCoeff(), 1e-9 * extent) << name;
  EXPECT_LT((p.eq_matrix * dofs(complex_form.positions)).lpNorm<Eigen::Infinity>(), 1e-10 * extent) << name;
  EXPECT_EQ(complex_form.positions.row(0).norm(), 0.0) << name;  // the pinned wedge
  // Reweighted (IRLS): both forms refactor with the new weights.
  Eigen::VectorXd w = p.weights;
  for (Eigen::Index e = 0; e < w.size(); ++e) w(e) *= 1.0 + 0.5 * std::sin(3.0 * static_cast<double>(e));
  L2Solver a(p), b(p, L2Options{false});
  ASSERT_TRUE(a.reweight(p, w)) << name;
  ASSERT_TRUE(b.reweight(p, w)) << name;
  const Eigen::MatrixXd xa = a.solve(p), xb = b.solve(p);
  EXPECT_LT((xa - xb).cwiseAbs().maxCoeff(), 1e-9 * xb.cwiseAbs().maxCoeff()) << name;
  EXPECT_GT((xa - real_form.positions).cwiseAbs().maxCoeff(), 1e-6 * extent) << name;  // the weights mattered
}

}  // namespace

// Any complex y gives a map meeting every seam exactly; the unknowns are as many as the real
// elimination's (each complex node two real ones); every coefficient is a multiple of 1/4 in
// both parts (quarter turns, and halves at singular vertices).
TEST(ComplexEqualityBasis, EliminatesSeamsExactly) {
  const Problem p = test_support::seamless_problem(make_bulged_frame_surface(4, 7));
  const auto b = complex_equality_basis(p);
  ASSERT_TRUE(b.has_value());
  EXPECT_EQ(2 * b->num_nodes, equality_basis(p).num_independent());
  for (Complex c : b->coefficient) {
    EXPECT_EQ(4.0 * c.real(), std::round(4.0 * c.real())) << c;
    EXPECT_EQ(4.0 * c.imag(), std::round(4.0 * c.imag())) << c;
  }
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::VectorXcd y(b->num_nodes);
  for (Eigen::Index i = 0; i < y.size(); ++i) y(i) = Complex(u(rng), u(rng));
  Eigen::MatrixXd X(p.num_vertices, 2);
  for (int w = 0; w < p.num_vertices; ++w) {
    Complex z = b->z0(w);
    for (int t = b->offset[w]; t < b->offset[w + 1]; ++t) z += b->coefficient[t] * y(b->node[t]);
    X(w, 0) = z.real();
    X(w, 1) = z.imag();
  }
  EXPECT_LT((p.eq_matrix * dofs(X)).lpNorm<Eigen::Infinity>(), 1e-12);
  EXPECT_EQ(X.row(0).norm(), 0.0);
}

TEST(ComplexL2, SameMinimizerAsTheRealFormOnTheBulgedFrame) {
  expect_same_minimizer(test_support::seamless_problem(make_bulged_frame_surface(4, 7)), "bulged frame");
}

TEST(ComplexL2, SameMinimizerAsTheRealFormOnCow) {
  const std::filesystem::path file = std::filesystem::path(STRICTMIN_SHARED_DATA) / "closed" / "cow.obj";
  if (!std::filesystem::exists(file)) GTEST_SKIP() << "no " << file;
  expect_same_minimizer(test_support::seamless_problem(read_mesh(file.string())), "cow");
}

// An equality on u alone (not a rotation-scaling block) and one with a right-hand side are
// not complex-linear: the real form solves them and meets them.
TEST(ComplexEqualityBasis, LeavesOtherEqualitiesToTheRealForm) {
  Problem p = make_problem(make_grid(6, 6));
  p.fix({Handle{0, Eigen::Vector2d::Zero()}});
  std::vector<Eigen::Triplet<double>> t = {{0, 2 * 5, 1.0}, {0, 2 * 30, -1.0}, {1, 2 * 7 + 1, 1.0}};
  p.eq_matrix.resize(2, 2 * p.num_vertices);
  p.eq_matrix.setFromTriplets(t.begin(), t.end());
  p.eq_rhs = Eigen::Vector2d(0.0, 0.25);
  EXPECT_FALSE(complex_equality_basis(p).has_value());
  const Result r = solve_l2(p);
  ASSERT_EQ(r.status, SolveStatus::Solved);
  EXPECT_LT((p.eq_matrix * dofs(r.positions) - p.eq_rhs).lpNorm<Eigen::Infinity>(), 1e-12);
}

// The complex Cholesky against a dense one: our numeric factorization (on this grid both its
// loops and its BLAS paths: a 47-column root supernode, wide updates), the supernodal
// substitutions and those with the compact copy of the factor, on a Hermitian positive
// definite matrix with complex couplings.
TEST(HermitianCholeskyTest, SolvesLikeADenseFactorization) {
  const int side = 24, n = side * side;
  Eigen::MatrixXcd dense = Eigen::MatrixXcd::Zero(n, n);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j) {
      const int a = i * side + j;
      for (int b : {i + 1 < side ? a + side : -1, j + 1 < side ? a + 1 : -1, (i + 1 < side && j + 1 < side) ? a + side + 1 : -1}) {
        if (b < 0) continue;
        const Complex w = std::polar(1.0 + 0.5 * u(rng), 3.0 * u(rng));
        dense(a, a) += std::abs(w);
        dense(b, b) += std::abs(w);
        dense(b, a) -= w;
        dense(a, b) -= std::conj(w);
      }
      dense(a, a) += 0.01;
    }
  HermitianLower A;
  A.n = n;
  A.start.assign(n + 1, 0);
  for (int col = 0; col < n; ++col) {
    for (int row = col; row < n; ++row)
      if (row == col || dense(row, col) != Complex(0, 0)) {
        A.row.push_back(row);
        A.value.push_back(dense(row, col));
      }
    A.start[col + 1] = static_cast<int>(A.row.size());
  }
  HermitianCholesky chol;
  ASSERT_TRUE(chol.factorize(A));
  Eigen::VectorXcd b(n);
  for (int k = 0; k < n; ++k) b(k) = Complex(u(rng), u(rng));
  const Eigen::VectorXcd expected = dense.llt().solve(b);
  for (const bool compact : {false, true}) {  // the supernodal and the compact substitutions
    if (compact) chol.compact_for_solves();
    const Eigen::VectorXcd x = chol.solve(b);
    EXPECT_LT((x - expected).norm(), 1e-10 * expected.norm()) << compact;
    EXPECT_LT((dense * x - b).norm(), 1e-12 * b.norm() * dense.cwiseAbs().maxCoeff()) << compact;
  }
}
