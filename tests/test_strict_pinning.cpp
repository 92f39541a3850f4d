// Pinned elements of the strict minimizers (src/solvers/strict_pinning.h, docs/strict.md
// "Pinned elements"): the level problem they leave (translations of free groups, held
// groups, members outside the level following their group), and what pinning buys on a
// problem whose levels are extremely sensitive to the bounds' slack.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cstdio>
#include <functional>
#include <random>
#include <set>
#include <vector>

#include "solvers/strict_pinning.h"
#include "strictmin/mesh/generators.h"
#include "strictmin/solvers/linf.h"
#include "strictmin/solvers/strict.h"
#include "test_meshes.h"

namespace strictmin {
namespace {

// A 6 x 6 grid of the unit square, boundary fixed, random rotation targets, the interior
// vertices moved at random (the map the level starts from).
struct Grid {
  Problem p;
  Eigen::MatrixXd X;
};

Grid make_problem_grid(int cells = 6) {
  const Mesh mesh = make_grid(cells, cells);
  Grid g{make_problem(mesh), {}};
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> angle(-0.3, 0.3), shift(-0.02, 0.02);
  for (int e = 0; e < g.p.num_elements(); ++e) g.p.set_target(e, Eigen::Rotation2Dd(angle(rng)).toRotationMatrix());
  std::vector<Handle> boundary;
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    const Eigen::Vector2d x = mesh.V.row(v).head<2>().transpose();
    if (x.x() == 0 || x.y() == 0 || x.x() == 1 || x.y() == 1) boundary.push_back({v, x});
  }
  g.p.fix(boundary);
  g.X = g.p.positions;
  for (int v = 0; v < g.p.num_vertices; ++v)
    if (!g.p.fixed[v]) g.X.row(v) += Eigen::RowVector2d(shift(rng), shift(rng));
  return g;
}

int vertex_at(const Mesh& mesh, double x, double y) {
  for (int v = 0; v < mesh.num_vertices(); ++v)
    if (std::abs(mesh.V(v, 0) - x) < 1e-12 && std::abs(mesh.V(v, 1) - y) < 1e-12) return v;
  return -1;
}

// The level's problem solved by solve_linf from the map X, every element free (no bounds).
Result solve_free_level(const Problem& p, const PinnedLevel& level, const Eigen::MatrixXd& X) {
  Result previous;
  previous.positions = X;
  previous.distortion = Eigen::VectorXd(p.num_elements());
  for (int e = 0; e < p.num_elements(); ++e) previous.distortion[e] = (p.jacobian(e, X) - p.target(e)).norm();
  const LevelSolver solve = [](const Problem& level_problem, const LinfOptions& o, const Eigen::MatrixXd&) {
    return solve_linf(level_problem, o);
  };
  const Eigen::VectorXd bounds = Eigen::VectorXd::Constant(p.num_elements(), -1.0);
  return solve_on_level(p, level, bounds, previous, LinfOptions{}, solve);
}

std::vector<int> elements_around(const Problem& p, int v) {
  std::vector<int> around;
  for (int e = 0; e < p.num_elements(); ++e)
    for (int j = 0; j < p.corners(); ++j)
      if (p.elements(e, j) == v) around.push_back(e);
  return around;
}

// Every element around an interior vertex pinned (a free group whose centre is outside the
// level's problem) and one element at the boundary (a held group): the level moves the free
// group by one translation, the centre follows it, the held group stays, and every pinned
// element keeps its Jacobian.
TEST(PinnedElements, FreeGroupsTranslateHeldGroupsStay) {
  const Mesh mesh = make_grid(6, 6);
  Grid g = make_problem_grid();
  const Problem& p = g.p;
  const int centre = vertex_at(mesh, 0.5, 0.5);
  const int corner = vertex_at(mesh, 1.0 / 6, 1.0 / 6);
  ASSERT_GE(centre, 0);
  ASSERT_GE(corner, 0);
  PinnedElements pins(p);
  const std::vector<int> star = elements_around(p, centre);
  for (int e : star) pins.pin(e);
  const int at_boundary = elements_around(p, corner).front();
  pins.pin(at_boundary);
  EXPECT_EQ(pins.count(), static_cast<int>(star.size()) + 1);

  const std::vector<char> every_vertex(p.num_vertices, 1);
  const PinnedLevel level = pins.level_problem(p, every_vertex, g.X);
  // The pinned elements are out; the centre (only pinned elements around it) too; the ring
  // around it is one free group: one root and an n-row equality per other member.
  const std::set<int> kept(level.sub.element.begin(), level.sub.element.end());
  for (int e : star) EXPECT_EQ(kept.count(e), 0u);
  EXPECT_EQ(kept.count(at_boundary), 0u);
  EXPECT_EQ(std::count(level.sub.vertex.begin(), level.sub.vertex.end(), centre), 0);
  ASSERT_EQ(level.groups.size(), 1u);
  EXPECT_EQ(level.groups[0].outside, std::vector<int>{centre});
  EXPECT_EQ(level.sub.problem.eq_matrix.rows(), 2 * (static_cast<Eigen::Index>(star.size()) - 1));
  // The held group: every vertex of the boundary element is fixed in the level.
  for (size_t i = 0; i < level.sub.vertex.size(); ++i)
    for (int j = 0; j < 3; ++j) {
      if (level.sub.vertex[i] == p.elements(at_boundary, j)) {
        EXPECT_TRUE(level.sub.problem.fixed[i]);
      }
    }

  const Result r = solve_free_level(p, level, g.X);
  ASSERT_TRUE(r.ok()) << r.message;
  for (int e : star) EXPECT_LT((p.jacobian(e, r.positions) - p.jacobian(e, g.X)).norm(), 1e-9) << e;
  for (int j = 0; j < 3; ++j) {
    const int v = p.elements(at_boundary, j);
    EXPECT_EQ(r.positions.row(v), g.X.row(v)) << v;
  }
  const Eigen::RowVector2d moved = r.positions.row(centre) - g.X.row(centre);
  EXPECT_GT(moved.norm(), 1e-4);  // the group did move (its ring is not where the optimum wants it)
  for (int e : star)
    for (int j = 0; j < 3; ++j) {
      const int v = p.elements(e, j);
      EXPECT_LT((r.positions.row(v) - g.X.row(v) - moved).norm(), 1e-9) << v;
    }
  // The distortion of the pinned elements is carried over, their multipliers are 0, and the
  // result's distortion is the map's.
  for (int e = 0; e < p.num_elements(); ++e)
    EXPECT_NEAR(r.distortion[e], (p.jacobian(e, r.positions) - p.target(e)).norm(), 1e-9) << e;
  for (int e : star) EXPECT_EQ(r.multipliers[e], 0.0);
}

// The problem's own equalities (gparam's seams) with pinned elements: groups touching
// their vertices translate like the others, the equalities written on the level (a member
// outside the level's problem through its group's root), then the translation rows. Here
// q_a - q_b = X_a - X_b with a the centre of a pinned star (outside the level's problem) and
// b a free vertex: the level's map keeps every pinned Jacobian, moves each group by one
// translation and meets the equality exactly, so b follows a's group.
TEST(PinnedElements, GroupsOnTheProblemsEqualitiesTranslateAndMeetThem) {
  const Mesh mesh = make_grid(8, 8);
  Grid g = make_problem_grid(8);
  Problem& p = g.p;
  const int centre = vertex_at(mesh, 0.25, 0.25), seam_a = vertex_at(mesh, 0.75, 0.75);
  const int seam_b = vertex_at(mesh, 0.25, 0.75);
  ASSERT_GE(centre, 0);
  ASSERT_GE(seam_a, 0);
  ASSERT_GE(seam_b, 0);
  std::vector<Eigen::Triplet<double>> t;
  for (int r = 0; r < 2; ++r) {
    t.emplace_back(r, 2 * seam_a + r, 1.0);
    t.emplace_back(r, 2 * seam_b + r, -1.0);
  }
  p.eq_matrix.resize(2, 2 * p.num_vertices);
  p.eq_matrix.setFromTriplets(t.begin(), t.end());
  p.eq_rhs = (g.X.row(seam_a) - g.X.row(seam_b)).transpose();

  PinnedElements pins(p);
  const std::vector<int> star = elements_around(p, centre), seam_star = elements_around(p, seam_a);
  for (int e : star) pins.pin(e);
  for (int e : seam_star) pins.pin(e);
  const std::vector<char> every_vertex(p.num_vertices, 1);
  const PinnedLevel level = pins.level_problem(p, every_vertex, g.X);
  ASSERT_EQ(level.groups.size(), 2u);
  for (const PinnedLevel::Group& group : level.groups) EXPECT_EQ(group.outside.size(), 1u);
  // The equality's two rows first (on a's root and b), then n rows per other member in the level.
  const Problem& q = level.sub.problem;
  const Eigen::Index ties = 2 * (static_cast<Eigen::Index>(star.size()) - 1 + static_cast<Eigen::Index>(seam_star.size()) - 1);
  ASSERT_EQ(q.eq_matrix.rows(), 2 + ties);
  const Eigen::MatrixXd A = Eigen::MatrixXd(q.eq_matrix);
  for (Eigen::Index r = 0; r < A.rows(); ++r) EXPECT_EQ(A.row(r).cwiseAbs().sum(), 2.0) << r;

  const Result r = solve_free_level(p, level, g.X);
  ASSERT_TRUE(r.ok()) << r.message;
  Eigen::VectorXd x(2 * p.num_vertices);
  for (int v = 0; v < p.num_vertices; ++v) x.segment<2>(2 * v) = r.positions.row(v).transpose();
  EXPECT_LT((p.eq_matrix * x - p.eq_rhs).cwiseAbs().maxCoeff(), 1e-12);
  for (const auto& [pinned, middle] : {std::pair{star, centre}, std::pair{seam_star, seam_a}}) {
    const Eigen::RowVector2d moved = r.positions.row(middle) - g.X.row(middle);
    EXPECT_GT(moved.norm(), 1e-4) << middle;  // the group did move
    for (int e : pinned) {
      EXPECT_LT((p.jacobian(e, r.positions) - p.jacobian(e, g.X)).norm(), 1e-9) << e;
      for (int j = 0; j < 3; ++j) {
        const int v = p.elements(e, j);
        EXPECT_LT((r.positions.row(v) - g.X.row(v) - moved).norm(), 1e-9) << v;
      }
    }
  }
}

// A free element whose corners all belong to held groups cannot move: the level's lower
// bound is at least its distortion, and with nothing left to move the map in hand is the
// level's optimum.
TEST(PinnedElements, AnElementThatCannotMoveBoundsTheLevel) {
  Grid g = make_problem_grid();
  const Problem& p = g.p;
  PinnedElements pins(p);
  for (int e = 1; e < p.num_elements(); ++e) pins.pin(e);
  const std::vector<char> every_vertex(p.num_vertices, 1);
  const PinnedLevel level = pins.level_problem(p, every_vertex, g.X);
  EXPECT_EQ(level.sub.problem.num_free(), 0);
  Result previous;
  previous.positions = g.X;
  previous.distortion = Eigen::VectorXd::Constant(p.num_elements(), 0.1);
  previous.distortion[0] = 0.7;
  Eigen::VectorXd bounds = Eigen::VectorXd::Constant(p.num_elements(), 1.0);
  bounds[0] = -1;
  const LevelSolver solve = [](const Problem&, const LinfOptions&, const Eigen::MatrixXd&) -> Result {
    ADD_FAILURE() << "no solve expected";
    return {};
  };
  const Result r = solve_on_level(p, level, bounds, previous, LinfOptions{}, solve);
  EXPECT_TRUE(r.ok());
  EXPECT_EQ(r.lower_bound, 0.7);
  EXPECT_EQ(r.positions, g.X);
}

// On the random-target bar (levels extremely sensitive to the fixed bounds: test_strict.cpp)
// the pinned levels are a property of the problem far more than of the tolerances: direct
// with the default tolerances and with first-level gap 1e-12, level gap 1e-11 agree at every
// rank to 1.1e-4 (measured; the same number of levels). Unpinned, the same two runs differed
// by 1.1e-2 (70 and 66 levels; docs/strict.md): the bounds' slack set the lower levels.
TEST(PinnedElements, DirectLevelsDoNotDependOnTheTolerances) {
  const Problem p = test_support::random_target_bar();
  DirectOptions o;
  o.delta_k = 1e-5;
  o.k_min = 0;
  const Result loose = solve_direct(p, o);
  ASSERT_TRUE(loose.ok()) << loose.message;
  LinfOptions tight_linf;
  tight_linf.gap_tolerance = 1e-12;
  o.level_gap = 1e-11;
  const Result tight = solve_direct(p, o, tight_linf);
  ASSERT_TRUE(tight.ok()) << tight.message;
  const Eigen::VectorXd a = test_support::sorted_down(loose.distortion), b = test_support::sorted_down(tight.distortion);
  // A pinned Jacobian is known to about the square root of its level's gap (about 5e-4 at the
  // default level gap 1e-7 here; docs/strict.md, "Limits"), which bounds how far the later
  // levels can move; the measured difference is well inside that.
  for (int i = 0; i < a.size(); ++i) EXPECT_NEAR(a[i], b[i], 3e-4) << "rank " << i;
  EXPECT_EQ(loose.iterations, tight.iterations);
  std::printf("%d levels each; largest difference at any rank %.3g\n", loose.iterations,
              (a - b).cwiseAbs().maxCoeff());
}

// Warm levels (DirectOptions::warm_levels, docs/strict.md): each level's interior-point method
// starts from the previous level's dual, element by element. The levels are the same problems
// solved to the same certified gap, so the run differs from the cold one only in which of a
// level's tied optima it returns (the band's membership at delta-k); it takes fewer iterations.
TEST(PinnedElements, WarmLevelsMatchColdLevelsInFewerIterations) {
  const Problem p = test_support::random_target_bar();
  DirectOptions o;
  o.k_min = 0;
  int iterations = 0;
  o.progress = [&](const StrictStep& s) { iterations += s.level_iterations; };
  const Result warm = solve_direct(p, o);
  const int warm_iterations = iterations;
  iterations = 0;
  o.warm_levels = false;
  const Result cold = solve_direct(p, o);
  const int cold_iterations = iterations;
  ASSERT_EQ(warm.status, SolveStatus::Solved) << warm.message;
  ASSERT_EQ(cold.status, SolveStatus::Solved) << cold.message;
  // The first level has no dual to start from: the same solve.
  EXPECT_EQ(warm.history[0].max_distortion, cold.history[0].max_distortion);
  EXPECT_EQ(warm.lower_bound, cold.lower_bound);
  for (const IterationRecord& rec : warm.history) EXPECT_LE(rec.certified_gap, 1e-2 * o.delta_k) << rec.iteration;
  const Eigen::VectorXd a = test_support::sorted_down(warm.distortion), b = test_support::sorted_down(cold.distortion);
  double largest = 0;
  for (int i = 0; i < a.size(); ++i) largest = std::max(largest, std::abs(a[i] - b[i]));
  std::printf("warm %d levels, %d iterations; cold %d levels, %d iterations; largest difference at a rank %.3g\n",
              warm.iterations, warm_iterations, cold.iterations, cold_iterations, largest);
  EXPECT_LT(largest, 2 * o.delta_k);  // measured 4.9e-4: the band's membership at delta-k
  EXPECT_LT(warm_iterations, cold_iterations);
}

}  // namespace
}  // namespace strictmin
