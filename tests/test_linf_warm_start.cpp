// Local-global's cheaper linf global steps (docs/arap.md, "Fewer and cheaper global steps"):
// the warm start from the previous step's dual, the extrapolated targets, and the memo of
// fill-reducing orderings. Each must leave the answers as they were: the same certified
// optimum, the maximum never increasing, the same orderings.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <vector>

#include "strictmin/mesh/generators.h"
#include "test_meshes.h"
#include "strictmin/problem/problem.h"
#include "strictmin/solvers/l2.h"
#include "strictmin/solvers/linf.h"
#include "strictmin/solvers/local_global.h"
#include "solvers/linf_warm_start.h"
#include "solvers/socp/ordering.h"

using namespace strictmin;

namespace {

// A 16 x 4 bar of [0, 4] x [0, 1], its ends turned by -+0.6 rad about their centres.
Problem bent_bar() { return test_support::bent_bar(16, 4, 4.0, 1.0, 0.6); }

// Every target turned by a small angle varying along the bar: the next global step's problem.
void turn_targets(Problem& p, double scale) {
  for (int e = 0; e < p.num_elements(); ++e) {
    const double angle = scale * std::sin(0.7 * e);
    p.set_target(e, Eigen::Rotation2Dd(angle).toRotationMatrix() * p.target(e));
  }
}

}  // namespace

// The warm start from a neighbouring program's dual (the same mesh, its targets turned by up
// to 1e-3 rad, as between late local-global steps) reaches the same certified optimum as a
// cold start (the dual does not depend on the targets), in at most half the interior-point
// iterations.
TEST(LinfWarmStart, SameOptimumInFewerIterations) {
  Problem p = bent_bar();
  LocalGlobalOptions lo;
  const Eigen::MatrixXd X = solve_l2(p).positions;
  local_step(p, X, lo);
  p.positions = X;
  LinfWarmStart warm;
  const Result first = solve_linf_warm(p, {}, &warm);
  ASSERT_EQ(first.status, SolveStatus::Solved) << first.message;
  ASSERT_GT(warm.z.size(), 0);

  Problem next = p;
  turn_targets(next, 1e-3);
  next.positions = first.positions;
  warm.expected_change = 1e-3;
  const Result cold = solve_linf(next, {});
  const Result hot = solve_linf_warm(next, {}, &warm);
  ASSERT_EQ(cold.status, SolveStatus::Solved) << cold.message;
  ASSERT_EQ(hot.status, SolveStatus::Solved) << hot.message;
  const double k_cold = cold.distortion.maxCoeff(), k_hot = hot.distortion.maxCoeff();
  // Both certified within the default gap (1e-8, relative): the same optimum to that.
  EXPECT_NEAR(k_hot, k_cold, 2e-8 * std::max(1.0, k_cold));
  EXPECT_LE(hot.lower_bound, k_hot);
  EXPECT_GE(hot.lower_bound, k_cold - 2e-8 * std::max(1.0, k_cold));
  // Measured: 2 against 7 (4 against 10 on an 80 x 20 bar).
  EXPECT_LE(2 * hot.iterations, cold.iterations) << "warm " << hot.iterations << ", cold " << cold.iterations;
  std::printf("k %.10f: cold %d iterations, warm %d\n", k_hot, cold.iterations, hot.iterations);
}

// A warm start whose shape does not fit the program (another mesh) is ignored, not misused.
TEST(LinfWarmStart, IgnoredWhenTheProgramDiffers) {
  Problem p = bent_bar();
  LinfWarmStart warm;
  warm.z = Eigen::VectorXd::Ones(7);
  warm.cone_size = 7;
  warm.num_eq = 0;
  const Result cold = solve_linf(p, {});
  const Result r = solve_linf_warm(p, {}, &warm);
  EXPECT_EQ(r.status, SolveStatus::Solved) << r.message;
  EXPECT_EQ(r.iterations, cold.iterations);
  EXPECT_DOUBLE_EQ(r.distortion.maxCoeff(), cold.distortion.maxCoeff());
  EXPECT_NE(warm.cone_size, 7);  // replaced by this solve's
}

// With extrapolated targets (beta up to 1) and the warm start, the maximum still never
// increases from one global step to the next, and the fixed point is the plain run's: both
// converge to the same maximum (to 1e-6).
TEST(LinfWarmStart, ExtrapolatedTargetsKeepTheGuarantee) {
  for (double beta : {0.5, 1.0}) {
    Problem p = bent_bar();
    SolverOptions s;
    s.method = Method::Linf;
    LocalGlobalOptions o;
    o.max_iterations = 400;
    o.relative_change = 1e-10;
    o.target_extrapolation = beta;
    const Eigen::MatrixXd X0 = solve_l2(p).positions;
    const Result fast = local_global(p, X0, s, o);
    ASSERT_GE(fast.history.size(), 2u) << fast.message;
    for (size_t i = 1; i < fast.history.size(); ++i)
      EXPECT_LE(fast.history[i].max_distortion, fast.history[i - 1].max_distortion * (1 + 1e-9))
          << "beta " << beta << ", step " << fast.history[i].iteration;
    o.target_extrapolation = 0;
    o.warm_start = false;
    o.acceleration_window = 0;
    const Result plain = local_global(p, X0, s, o);
    EXPECT_TRUE(fast.ok()) << fast.message;
    EXPECT_TRUE(plain.ok()) << plain.message;
    EXPECT_NEAR(fast.distortion.maxCoeff(), plain.distortion.maxCoeff(), 1e-6)
        << fast.message << " / " << plain.message;
    std::printf("beta %.1f: max %.9f in %d steps; plain %.9f in %d\n", beta, fast.distortion.maxCoeff(),
                fast.iterations, plain.distortion.maxCoeff(), plain.iterations);
  }
}

TEST(LinfWarmStart, ExtrapolationOutOfRangeIsRefused) {
  LocalGlobalOptions o;
  o.target_extrapolation = 1.5;
  std::string why;
  EXPECT_FALSE(o.is_valid(&why));
  EXPECT_NE(why.find("target_extrapolation"), std::string::npos) << why;
  o.target_extrapolation = -0.1;
  EXPECT_FALSE(o.is_valid(&why));
}

// The memo returns what a fresh ordering computes, for both functions and a second graph.
TEST(OrderingMemo, SameAsAFreshOrdering) {
  for (int size : {80, 120}) {
    // A size x size grid graph (large enough for METIS).
    const int n = size * size;
    std::vector<int> offset(1, 0), adj;
    for (int v = 0; v < n; ++v) {
      const int i = v / size, j = v % size;
      if (i > 0) adj.push_back(v - size);
      if (j > 0) adj.push_back(v - 1);
      if (j + 1 < size) adj.push_back(v + 1);
      if (i + 1 < size) adj.push_back(v + size);
      offset.push_back(static_cast<int>(adj.size()));
    }
    const std::vector<int> fresh = socp::compute_ordering(offset, adj, 5000);
    EXPECT_EQ(socp::vertex_ordering(offset, adj), fresh);
    EXPECT_EQ(socp::vertex_ordering(offset, adj), fresh);  // from the memo
    const std::vector<int> part = socp::compute_bisection(offset, adj);
    EXPECT_EQ(socp::vertex_bisection(offset, adj), part);
    EXPECT_EQ(socp::vertex_bisection(offset, adj), part);
  }
}
