// The integer linear algebra of the integer-grid rounding's exact check
// (src/solvers/integer_hermite.h, src/tasks/grid_completion.h): closed cases, and small
// random systems against brute force over a box.
#include <gtest/gtest.h>

#include <functional>
#include <random>

#include "solvers/integer_hermite.h"
#include "tasks/grid_completion.h"

using namespace strictmin;

namespace {

IntegerMatrix matrix(int rows, int cols, const std::vector<long>& by_rows) {
  IntegerMatrix A(rows, cols);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) A(r, c) = by_rows[static_cast<std::size_t>(r * cols + c)];
  return A;
}

IntegerVector vec(const std::vector<long>& v) { return IntegerVector(v.begin(), v.end()); }

IntegerVector times(const IntegerMatrix& A, const IntegerVector& x) {
  IntegerVector out(static_cast<std::size_t>(A.rows));
  for (int c = 0; c < A.cols(); ++c)
    for (int r = 0; r < A.rows; ++r) out[static_cast<std::size_t>(r)] += A(r, c) * x[static_cast<std::size_t>(c)];
  return out;
}

// The determinant by fraction-free (Bareiss) elimination, exact.
mpz_class determinant(IntegerMatrix M) {
  const int n = M.cols();
  mpz_class previous = 1;
  int sign = 1;
  for (int k = 0; k < n; ++k) {
    int p = k;
    while (p < n && sgn(M(k, p)) == 0) ++p;
    if (p == n) return 0;
    if (p != k) {
      std::swap(M.columns[static_cast<std::size_t>(p)], M.columns[static_cast<std::size_t>(k)]);
      sign = -sign;
    }
    for (int i = k + 1; i < n; ++i)
      for (int j = k + 1; j < n; ++j) M(i, j) = (M(i, j) * M(k, k) - M(i, k) * M(k, j)) / previous;
    previous = M(k, k);
  }
  return sign * M(n - 1, n - 1);
}

// Every x in [-box, box]^n, until `visit` returns true.
bool any_in_box(int n, int box, const std::function<bool(const IntegerVector&)>& visit) {
  IntegerVector x(static_cast<std::size_t>(n), -box);
  while (true) {
    if (visit(x)) return true;
    int k = 0;
    while (k < n && x[static_cast<std::size_t>(k)] == box) x[static_cast<std::size_t>(k++)] = -box;
    if (k == n) return false;
    ++x[static_cast<std::size_t>(k)];
  }
}

// Whether some integer x with the given coordinates fixed (-1: free) and the free ones in
// [-box, box] solves A x = 0 (machine integers: the entries are small).
bool any_small_completion(const IntegerMatrix& A, const std::vector<long>& fixed, const std::vector<char>& is_fixed,
                          int box) {
  const int n = A.cols();
  std::vector<long> x(static_cast<std::size_t>(n));
  std::vector<int> free;
  for (int c = 0; c < n; ++c) {
    if (is_fixed[static_cast<std::size_t>(c)]) {
      x[static_cast<std::size_t>(c)] = fixed[static_cast<std::size_t>(c)];
    } else {
      free.push_back(c);
      x[static_cast<std::size_t>(c)] = -box;
    }
  }
  while (true) {
    bool solves = true;
    for (int r = 0; r < A.rows && solves; ++r) {
      long sum = 0;
      for (int c = 0; c < n; ++c) sum += A(r, c).get_si() * x[static_cast<std::size_t>(c)];
      solves = sum == 0;
    }
    if (solves) return true;
    std::size_t k = 0;
    while (k < free.size() && x[static_cast<std::size_t>(free[k])] == box) x[static_cast<std::size_t>(free[k++])] = -box;
    if (k == free.size()) return false;
    ++x[static_cast<std::size_t>(free[k])];
  }
}

// The normal form's properties: A U = H, U unimodular, H in column echelon form with
// positive pivots and reduced entries left of them, zero after the rank.
void expect_hermite_form(const IntegerMatrix& A) {
  const ColumnHermiteForm f = column_hermite_form(A);
  for (int c = 0; c < A.cols(); ++c) EXPECT_EQ(times(A, f.U.columns[static_cast<std::size_t>(c)]), f.H.columns[static_cast<std::size_t>(c)]);
  EXPECT_EQ(abs(determinant(f.U)), 1);
  for (int k = 0; k < A.cols(); ++k)
    for (int r = 0; r < A.rows; ++r) {
      if (k >= f.rank()) {
        EXPECT_EQ(f.H(r, k), 0);
        continue;
      }
      const int pr = f.pivot_rows[static_cast<std::size_t>(k)];
      if (r < pr) {
        EXPECT_EQ(f.H(r, k), 0);
      }
      if (r == pr) {
        EXPECT_GT(f.H(r, k), 0);
      }
    }
  for (int k = 0; k < f.rank(); ++k) {
    const int pr = f.pivot_rows[static_cast<std::size_t>(k)];
    if (k > 0) {
      EXPECT_GT(pr, f.pivot_rows[static_cast<std::size_t>(k - 1)]);
    }
    for (int j = 0; j < k; ++j) {
      EXPECT_GE(f.H(pr, j), 0);
      EXPECT_LT(f.H(pr, j), f.H(pr, k));
    }
  }
}

}  // namespace

TEST(IntegerHermite, ClosedCases) {
  EXPECT_FALSE(integer_solution(matrix(1, 1, {2}), vec({1})));                  // 2x = 1
  EXPECT_TRUE(integer_solution(matrix(1, 1, {2}), vec({4})));                   // 2x = 4
  EXPECT_TRUE(integer_solution(matrix(1, 2, {1, 1}), vec({1})));                // x + y = 1
  EXPECT_TRUE(integer_solution(matrix(1, 2, {6, 10}), vec({2})));               // gcd 2 divides 2
  EXPECT_FALSE(integer_solution(matrix(1, 2, {6, 10}), vec({3})));
  EXPECT_FALSE(integer_solution(matrix(2, 2, {1, 1, 1, -1}), vec({1, 0})));     // x = y = 1/2
  EXPECT_TRUE(integer_solution(matrix(2, 2, {1, 1, 1, -1}), vec({2, 0})));
  EXPECT_FALSE(integer_solution(matrix(2, 1, {1, 1}), vec({1, 2})));            // x = 1, x = 2
  EXPECT_TRUE(integer_solution(matrix(2, 2, {0, 0, 0, 0}), vec({0, 0})));
  EXPECT_FALSE(integer_solution(matrix(2, 2, {0, 0, 0, 0}), vec({0, 1})));
  // (I - R) f = t, R a quarter turn: t = (1, 0) needs f = (1/2, 1/2); (1, 1) has f = (0, 1).
  const IntegerMatrix I_minus_R = matrix(2, 2, {1, 1, -1, 1});
  EXPECT_FALSE(integer_solution(I_minus_R, vec({1, 0})));
  const auto f = integer_solution(I_minus_R, vec({1, 1}));
  ASSERT_TRUE(f);
  EXPECT_EQ(times(I_minus_R, *f), vec({1, 1}));
  // The kernel of x + y + z = 0 has rank 2; of [1 1; 1 -1], rank 0.
  EXPECT_EQ(integer_kernel(matrix(1, 3, {1, 1, 1})).cols(), 2);
  EXPECT_EQ(integer_kernel(matrix(2, 2, {1, 1, 1, -1})).cols(), 0);
  // Entries far beyond 64 bits are fine.
  IntegerMatrix big(1, 2);
  big(0, 0) = mpz_class("123456789012345678901234567890");
  big(0, 1) = mpz_class("987654321098765432109876543210");
  // gcd = 9000000000900000000090: 7 gcd is reached, gcd + 1 is not.
  const auto x = integer_solution(big, IntegerVector{mpz_class("63000000006300000000630")});
  ASSERT_TRUE(x);
  EXPECT_EQ(times(big, *x)[0], mpz_class("63000000006300000000630"));
  EXPECT_FALSE(integer_solution(big, IntegerVector{mpz_class("9000000000900000000091")}));
  expect_hermite_form(big);
}

// Random m by n systems (entries -3..3, right-hand sides -4..4): whenever a box search finds
// an integer solution, integer_solution finds one, and what it returns solves the system;
// the kernel's columns solve A x = 0, and every kernel vector of the box is an integer
// combination of them.
TEST(IntegerHermite, RandomSystemsAgainstBruteForce) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> entry(-3, 3), rhs(-4, 4), size(1, 3);
  int solvable = 0, unsolvable = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const int m = size(rng), n = size(rng);
    IntegerMatrix A(m, n);
    for (int r = 0; r < m; ++r)
      for (int c = 0; c < n; ++c) A(r, c) = entry(rng);
    IntegerVector b(static_cast<std::size_t>(m));
    for (auto& x : b) x = rhs(rng);
    if (trial % 3 == 0) {  // half-solvable by construction: b = A x for a random x
      IntegerVector x(static_cast<std::size_t>(n));
      for (auto& v : x) v = entry(rng);
      b = times(A, x);
    }
    expect_hermite_form(A);
    const auto x = integer_solution(A, b);
    if (x) {
      EXPECT_EQ(times(A, *x), b) << "trial " << trial;
    }
    bool found = false;
    any_in_box(n, 8, [&](const IntegerVector& y) { return found = times(A, y) == b; });
    if (found) {
      EXPECT_TRUE(x) << "trial " << trial << ": the box has a solution";
    }
    (x ? solvable : unsolvable) += 1;
    const IntegerMatrix K = integer_kernel(A);
    for (const IntegerVector& k : K.columns) EXPECT_EQ(times(A, k), IntegerVector(static_cast<std::size_t>(m))) << trial;
    any_in_box(n, 3, [&](const IntegerVector& y) {
      if (times(A, y) == IntegerVector(static_cast<std::size_t>(m)) && K.cols() > 0) {
        EXPECT_TRUE(integer_solution(K, y)) << "trial " << trial << ": a kernel vector outside the basis' span";
      }
      return false;
    });
  }
  EXPECT_GT(solvable, 100);
  EXPECT_GT(unsolvable, 50);
}

// The completion of a quarter turn's relation t = (I - R) f: t is completable exactly on the
// index-2 lattice t_x + t_y even; fixing f fixes t.
TEST(GridCompletion, QuarterTurnRelation) {
  // Values: f (0), t (1); relation (I - R) f - t = 0 with R = [0 -1; 1 0].
  GridCompletion c(matrix(2, 4, {1, 1, -1, 0, -1, 1, 0, -1}));
  const GridCoset t = c.coset(1);
  EXPECT_FALSE(t.contains({1, 0}));
  EXPECT_TRUE(t.contains({1, 1}));
  EXPECT_TRUE(t.contains({-3, 5}));
  EXPECT_EQ(t.nearest({0.6, 0.3}), Eigen::Vector2d(0, 0));
  EXPECT_EQ(t.nearest({0.9, 0.2}), Eigen::Vector2d(1, 1));  // not the nearest grid point (1, 0)
  EXPECT_EQ(t.nearest({10.4, 0.45}), Eigen::Vector2d(10, 0));
  EXPECT_EQ(t.nearest({10.6, 0.55}), Eigen::Vector2d(11, 1));
  EXPECT_FALSE(c.fix(1, {1, 0}));
  ASSERT_TRUE(c.fix(0, {1, 0}));
  const GridCoset fixed = c.coset(1);
  EXPECT_TRUE(fixed.contains({1, -1}));
  EXPECT_FALSE(fixed.contains({1, 1}));
  EXPECT_EQ(fixed.nearest({40, 7}), Eigen::Vector2d(1, -1));
  EXPECT_TRUE(c.fix(1, {1, -1}));
  c.truncate(1);
  EXPECT_FALSE(c.fix(1, {3, 3}));
  c.truncate(0);
  EXPECT_TRUE(c.fix(1, {3, 3}));  // then f = (0, 3), the one f with (I - R) f = (3, 3)
  EXPECT_TRUE(c.coset(0).contains({0, 3}));
  EXPECT_FALSE(c.coset(0).contains({1, 3}));
}

// Random relations among three 2D values: fixing values one after another succeeds exactly
// when the relations with those values held have an integer solution (decided independently
// by integer_solution on the stacked system, and confirmed by a box search when it has one
// there); the coset's nearest point is the nearest completable point of a window around y.
TEST(GridCompletion, RandomRelationsAgainstIntegerSolutionsAndBruteForce) {
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> entry(-2, 2), point(-3, 3), rows(1, 3);
  std::uniform_real_distribution<double> real(-4, 4);
  int refused = 0, accepted = 0;
  for (int trial = 0; trial < 150; ++trial) {
    const int m = rows(rng);
    IntegerMatrix A(m, 6);
    for (int r = 0; r < m; ++r)
      for (int c = 0; c < 6; ++c) A(r, c) = entry(rng);
    GridCompletion completion(A);
    std::vector<std::pair<int, Eigen::Vector2d>> held;
    for (int value : {1, 0, 2}) {
      // The nearest point of the coset against a window search over completable points.
      const Eigen::Vector2d y(real(rng), real(rng));
      const GridCoset coset = completion.coset(value);
      const Eigen::Vector2d nearest = coset.nearest(y);
      EXPECT_TRUE(coset.contains(nearest));
      for (int i = -12; i <= 12; ++i)
        for (int j = -12; j <= 12; ++j)
          if (coset.contains({i, j})) {
            EXPECT_LE((nearest - y).norm(), (Eigen::Vector2d(i, j) - y).norm() + 1e-12) << trial;
          }
      const Eigen::Vector2d v(point(rng), point(rng));
      // The stacked system: A x = 0 and the held coordinates.
      auto with = held;
      with.emplace_back(value, v);
      IntegerMatrix S(m + 2 * static_cast<int>(with.size()), 6);
      IntegerVector rhs(static_cast<std::size_t>(S.rows));
      std::vector<long> coordinates(6, 0);
      std::vector<char> is_fixed(6, 0);
      for (int r = 0; r < m; ++r)
        for (int c = 0; c < 6; ++c) S(r, c) = A(r, c);
      for (std::size_t k = 0; k < with.size(); ++k)
        for (int d = 0; d < 2; ++d) {
          const int r = m + 2 * static_cast<int>(k) + d, c = 2 * with[k].first + d;
          S(r, c) = 1;
          rhs[static_cast<std::size_t>(r)] = static_cast<long>(with[k].second(d));
          coordinates[static_cast<std::size_t>(c)] = static_cast<long>(with[k].second(d));
          is_fixed[static_cast<std::size_t>(c)] = 1;
        }
      const bool solvable = integer_solution(S, rhs).has_value();
      if (any_small_completion(A, coordinates, is_fixed, 6)) {
        EXPECT_TRUE(solvable) << trial;
      }
      EXPECT_EQ(coset.contains(v), solvable) << trial;
      const bool fixed = completion.fix(value, v);
      EXPECT_EQ(fixed, solvable) << trial;
      if (fixed) {
        held = with;
        ++accepted;
      } else {
        ++refused;
      }
    }
  }
  EXPECT_GT(accepted, 50);
  EXPECT_GT(refused, 50);
}
