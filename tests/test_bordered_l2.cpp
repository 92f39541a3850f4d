// The integer-grid rounding's bordered L2 solves (src/tasks/bordered_l2.h) against fresh L2
// solves of the problem with the same rows as real equalities (the real form: its own
// elimination and factorization): the same map at the watched vertices, redundant rows
// accepted, contradictory ones refused, and rows taken back.
#include <gtest/gtest.h>

#include <Eigen/SparseCore>
#include <complex>
#include <random>

#include "tasks/bordered_l2.h"
#include "test_meshes.h"
#include "strictmin/mesh/polycube.h"
#include "strictmin/solvers/l2.h"

using namespace strictmin;
using Complex = std::complex<double>;

namespace {

// The problem with the rows appended as real equalities: a complex coefficient a = p + iq on
// vertex w is the block [p -q; q p] on (u_w, v_w).
Problem with_rows(const Problem& p, const std::vector<BorderedL2::Row>& rows) {
  Problem q = p;
  std::vector<Eigen::Triplet<double>> t;
  for (int k = 0; k < q.eq_matrix.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(q.eq_matrix, k); it; ++it)
      t.emplace_back(static_cast<int>(it.row()), static_cast<int>(it.col()), it.value());
  int first = static_cast<int>(q.eq_matrix.rows());
  q.eq_rhs.conservativeResize(first + 2 * static_cast<int>(rows.size()));
  for (const BorderedL2::Row& row : rows) {
    for (const auto& [w, a] : row.terms) {
      t.emplace_back(first, 2 * w, a.real());
      t.emplace_back(first, 2 * w + 1, -a.imag());
      t.emplace_back(first + 1, 2 * w, a.imag());
      t.emplace_back(first + 1, 2 * w + 1, a.real());
    }
    q.eq_rhs(first) = row.rhs.real();
    q.eq_rhs(first + 1) = row.rhs.imag();
    first += 2;
  }
  q.eq_matrix.resize(first, 2 * q.num_vertices);
  q.eq_matrix.setFromTriplets(t.begin(), t.end());
  return q;
}

double largest_difference(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, const std::vector<int>& rows) {
  double d = 0;
  for (int w : rows) d = std::max(d, (a.row(w) - b.row(w)).cwiseAbs().maxCoeff());
  return d;
}

}  // namespace

TEST(BorderedL2, MatchesFreshSolvesWithTheRowsAsEqualities) {
  const Problem p = test_support::seamless_problem(make_bulged_frame_surface(4, 7));
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> vertex(1, p.num_vertices - 1);
  std::vector<int> watched;
  for (int i = 0; i < 12; ++i) watched.push_back(vertex(rng));
  BorderedL2 bordered(p, watched);
  ASSERT_TRUE(bordered.ok());
  const double extent = solve_l2(p).positions.cwiseAbs().maxCoeff();
  const double tolerance = 1e-8 * extent;
  // No rows: the problem's own L2 map.
  const Result plain = solve_l2(p);
  auto none = bordered.solve(p, tolerance);
  ASSERT_TRUE(none.has_value());
  EXPECT_LT(largest_difference(*none, plain.positions, watched), 1e-9 * extent);
  EXPECT_TRUE(std::isnan((*none)(0, 0)) || watched.front() == 0);  // only the watched rows are formed
  // Rows of the rounding's two kinds: a vertex held, a difference turned by a quarter turn.
  std::vector<BorderedL2::Row> rows = {
      {{{watched[0], 1.0}}, Complex(0.5, -0.25) * extent},
      {{{watched[1], 1.0}, {watched[2], Complex(0, -1)}}, Complex(0.1, 0.3) * extent},
      {{{watched[3], 1.0}, {watched[4], -1.0}, {watched[0], Complex(-1, 1)}}, Complex(-0.2, 0.05) * extent},
  };
  for (const auto& row : rows) bordered.push(row);
  const Result fresh = solve_l2(with_rows(p, rows));
  ASSERT_EQ(fresh.status, SolveStatus::Solved) << fresh.message;
  auto X = bordered.solve(p, tolerance);
  ASSERT_TRUE(X.has_value());
  EXPECT_LT(largest_difference(*X, fresh.positions, watched), 1e-8 * extent);
  // A redundant row (the sum of the first two, with the sum of their right-hand sides): the
  // same map.
  BorderedL2::Row sum{{{watched[0], 1.0}, {watched[1], 1.0}, {watched[2], Complex(0, -1)}}, rows[0].rhs + rows[1].rhs};
  bordered.push(sum);
  auto redundant = bordered.solve(p, tolerance);
  ASSERT_TRUE(redundant.has_value());
  EXPECT_LT(largest_difference(*redundant, fresh.positions, watched), 1e-8 * extent);
  // The same row off by a hundredth of the extent contradicts them: refused, as the fresh
  // solve refuses it.
  bordered.truncate(3);
  BorderedL2::Row off = sum;
  off.rhs += 0.01 * extent;
  bordered.push(off);
  EXPECT_FALSE(bordered.solve(p, tolerance).has_value());
  rows.push_back(off);
  EXPECT_EQ(solve_l2(with_rows(p, rows)).status, SolveStatus::Infeasible);
  // Taken back, the rows before it hold again; other targets (the look-ahead's) give their own map.
  bordered.truncate(3);
  rows.pop_back();
  Problem moved = p;
  for (Eigen::Index r = 0; r < moved.targets.rows(); ++r) moved.targets(r, 0) += 0.2 * std::sin(static_cast<double>(r));
  auto Y = bordered.solve(moved, tolerance);
  ASSERT_TRUE(Y.has_value());
  Problem moved_with_rows = with_rows(p, rows);
  moved_with_rows.targets = moved.targets;
  const Result fresh_moved = solve_l2(moved_with_rows);
  ASSERT_EQ(fresh_moved.status, SolveStatus::Solved);
  EXPECT_LT(largest_difference(*Y, fresh_moved.positions, watched), 1e-8 * extent);
  EXPECT_GT(largest_difference(*Y, fresh.positions, watched), 1e-4 * extent);
}
