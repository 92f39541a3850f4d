// The status vocabulary (solvers/result.h): one decision per solver, inner shortfalls that
// propagate to the outer status, options that validate themselves.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>

#include "expect_input_error.h"
#include "strictmin/mesh/generators.h"
#include "strictmin/solvers/irls.h"
#include "strictmin/solvers/linf.h"
#include "strictmin/solvers/local_global.h"
#include "strictmin/solvers/lp.h"
#include "strictmin/solvers/relax.h"
#include "strictmin/solvers/strict.h"
#include "strictmin/tasks/deform.h"
#include "strictmin/tasks/method.h"
#include "test_meshes.h"

using namespace strictmin;
using test_support::expect_input_error;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

TEST(Status, NamesAndOrder) {
  EXPECT_EQ(status_name(SolveStatus::Solved), "solved");
  EXPECT_EQ(status_name(SolveStatus::AlmostSolved), "almost-solved");
  EXPECT_EQ(status_name(SolveStatus::MaxIterations), "max-iterations");
  EXPECT_EQ(status_name(SolveStatus::Stalled), "stalled");
  EXPECT_EQ(status_name(SolveStatus::NumericalError), "numerical-error");
  EXPECT_EQ(status_name(SolveStatus::Infeasible), "infeasible");
  EXPECT_EQ(worse_status(SolveStatus::Solved, SolveStatus::MaxIterations), SolveStatus::MaxIterations);
  EXPECT_EQ(worse_status(SolveStatus::Stalled, SolveStatus::AlmostSolved), SolveStatus::Stalled);
  EXPECT_TRUE(status_usable(SolveStatus::Stalled));
  EXPECT_FALSE(status_usable(SolveStatus::NumericalError));
  EXPECT_FALSE(status_usable(SolveStatus::Infeasible));
}

TEST(Status, DecidedInOrder) {
  StopState s;
  EXPECT_EQ(decide_status(s), SolveStatus::NumericalError);  // nothing known: no claim
  s.cap_reached = true;
  EXPECT_EQ(decide_status(s), SolveStatus::MaxIterations);
  s.stalled = true;
  EXPECT_EQ(decide_status(s), SolveStatus::Stalled);
  s.within_acceptable = true;
  EXPECT_EQ(decide_status(s), SolveStatus::AlmostSolved);
  s.failed = true;
  EXPECT_EQ(decide_status(s), SolveStatus::NumericalError);
  s.criterion_met = true;
  EXPECT_EQ(decide_status(s), SolveStatus::Solved);
  s.infeasible = true;
  EXPECT_EQ(decide_status(s), SolveStatus::Infeasible);
}

TEST(Status, UsableNeedsAFiniteMap) {
  Result r;
  r.positions = Eigen::MatrixXd::Zero(2, 2);
  r.status = SolveStatus::MaxIterations;
  EXPECT_TRUE(r.usable());
  r.positions(1, 1) = kNaN;
  EXPECT_FALSE(r.usable());
}

// Options that validate themselves: the values the CLI used to accept silently.
TEST(Options, OutOfRangeValuesAreRejectedWithTheirName) {
  std::string why;
  DirectOptions d;
  EXPECT_TRUE(d.is_valid(&why)) << why;
  for (double bad : {0.0, -1.0, kNaN}) {
    d.delta_k = bad;
    EXPECT_FALSE(d.is_valid(&why));
    EXPECT_NE(why.find("delta_k"), std::string::npos) << why;
  }
  d = {};
  d.level_gap = 2;
  EXPECT_FALSE(d.is_valid(&why));
  d.level_gap = -1;  // the default's sentinel
  EXPECT_TRUE(d.is_valid(&why));
  RelaxOptions r;
  r.sweeps = -5;
  EXPECT_FALSE(r.is_valid(&why));
  EXPECT_NE(why.find("sweeps"), std::string::npos) << why;
  LinfOptions l;
  EXPECT_TRUE(l.is_valid(&why)) << why;
  l.gap_tolerance = -1;
  EXPECT_FALSE(l.is_valid(&why));
  EXPECT_NE(why.find("gap_tolerance"), std::string::npos) << why;
  l = {};
  l.max_iterations = 0;
  EXPECT_FALSE(l.is_valid(&why));
  LpOptions lp;
  lp.p = 1.5;
  EXPECT_FALSE(lp.is_valid(&why));
  IrlsOptions irls;
  irls.iterations = -1;
  EXPECT_FALSE(irls.is_valid(&why));
  LocalGlobalOptions lg;
  lg.relative_change = kNaN;
  EXPECT_FALSE(lg.is_valid(&why));
  SolverOptions s;
  s.direct.delta_k = 0;
  EXPECT_FALSE(s.is_valid(&why));
  EXPECT_EQ(why.rfind("direct.delta_k", 0), 0u) << why;
  s = {};
  s.relax_init = Method::Direct;
  EXPECT_FALSE(s.is_valid(&why));
}

TEST(Options, SolversRefuseInvalidOptions) {
  const Problem p = test_support::random_target_bar();
  SolverOptions s;
  s.method = Method::Direct;
  s.direct.delta_k = -1;
  expect_input_error([&] { run_method(p, s); }, {"direct.delta_k", "> 0"});
  LinfOptions l;
  l.gap_tolerance = 0;
  expect_input_error([&] { solve_linf(p, l); }, {"gap_tolerance"});
  RelaxOptions r;
  r.accept_tolerance = 1;
  expect_input_error([&] { relax(p, p.positions, r); }, {"accept_tolerance"});
}

// One LinfOptions for every method that solves L-infinity levels: direct's first level uses
// the solver's linf tolerance (a loose one gives a looser certified gap than the default).
TEST(Options, DirectUsesTheSolversLinfOptions) {
  const Problem p = test_support::random_target_bar();
  SolverOptions s;
  s.method = Method::Direct;
  s.direct.k_min = 0.3;
  s.linf.gap_tolerance = 1e-3;
  s.linf.active_set_bounds = false;
  const Result loose = run_method(p, s);
  s.linf.gap_tolerance = 1e-9;
  const Result tight = run_method(p, s);
  ASSERT_TRUE(loose.usable() && tight.usable());
  EXPECT_GT(loose.history.front().certified_gap, 1e-7);
  EXPECT_LE(loose.history.front().certified_gap, 1e-3);
  EXPECT_LE(tight.history.front().certified_gap, 1e-9);
}

// An interior-point cap is max-iterations with the best map so far, never solved.
TEST(Status, LinfAtItsCapSaysSo) {
  LinfOptions o;
  o.max_iterations = 3;
  const Result r = solve_linf(test_support::random_target_bar(), o);
  EXPECT_EQ(r.status, SolveStatus::MaxIterations) << r.message;
  EXPECT_TRUE(r.usable());
  EXPECT_NE(r.message.find("3 iterations"), std::string::npos) << r.message;
  for (const IterationRecord& h : r.history) {
    EXPECT_FALSE(std::isnan(h.certified_gap));
    EXPECT_TRUE(std::isnan(h.relative_change));
    EXPECT_TRUE(std::isnan(h.largest_move));
  }
}

TEST(Status, DirectAtItsLevelCapSaysSo) {
  DirectOptions o;
  o.max_steps = 2;
  o.k_min = 0;
  const Result r = solve_direct(test_support::random_target_bar(), o);
  EXPECT_EQ(r.status, SolveStatus::MaxIterations) << r.message;
  EXPECT_EQ(r.iterations, 2);
  EXPECT_TRUE(r.usable());
  EXPECT_NE(r.message.find("level cap"), std::string::npos) << r.message;
}

TEST(Status, RelaxWithAMoveToleranceItDoesNotReachHitsTheCap) {
  const Problem p = test_support::random_target_bar();
  RelaxOptions o;
  o.sweeps = 2;
  o.move_tolerance = 1e-14;
  const Result r = relax(p, p.positions, o);
  EXPECT_EQ(r.status, SolveStatus::MaxIterations) << r.message;
  for (const IterationRecord& h : r.history) EXPECT_GT(h.largest_move, 0);
  o.move_tolerance = 0;  // a fixed number of sweeps is the request itself
  EXPECT_EQ(relax(p, p.positions, o).status, SolveStatus::Solved);
}

// The rigid-handle tet case: every handle moved by one rigid motion. Each method reaches ARAP
// max below 1e-6 and says solved (a cap is checked by InnerCapPropagatesThroughLocalGlobal).
TEST(Status, RigidHandlesTetsConverge) {
  const Mesh m = make_tet_box(6, 2, 2, 3.0, 1.0, 1.0);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Vector3d t(0.3, -0.2, 0.5);
  std::vector<Handle> handles;
  for (int v = 0; v < m.V.rows(); ++v)
    if (m.V(v, 0) < 1e-9 || m.V(v, 0) > 3 - 1e-9) handles.push_back({v, R * m.V.row(v).transpose() + t});
  for (Method method : {Method::L2, Method::Linf, Method::Relax}) {
    DeformOptions o;
    o.measure = Measure::Arap;
    o.solver.method = method;
    o.local_global.max_iterations = 20;
    const DeformOutcome d = deform(m, handles, o);
    const double max = d.measured.stats.max;
    SCOPED_TRACE(method_name(method) + ": " + d.result.message);
    // The start is the handles' best rigid fit (deform_start.h): the map is rigid at once.
    EXPECT_EQ(d.result.status, SolveStatus::Solved);
    EXPECT_LT(max, 1e-6);
    for (const IterationRecord& h : d.result.history) EXPECT_TRUE(std::isnan(h.certified_gap));
  }
}

// An inner shortfall propagates: local-global whose global linf solves stop at their cap
// cannot call itself solved.
TEST(Status, InnerCapPropagatesThroughLocalGlobal) {
  const Problem p = test_support::random_target_bar();
  SolverOptions s;
  s.method = Method::Linf;
  s.linf.max_iterations = 2;
  LocalGlobalOptions o;
  o.max_iterations = 3;
  o.relative_change = 0.5;  // the loop's own criterion is easy to meet
  const Result r = local_global(p, p.positions, s, o);
  EXPECT_EQ(r.status, SolveStatus::MaxIterations) << r.message;
  EXPECT_NE(r.message.find("the last global step"), std::string::npos) << r.message;
}

}  // namespace

namespace {

// Reproducible: the same input, options and thread count give bitwise the same map, run
// after run (the parallel parts reduce in a fixed order).
TEST(Reproducible, DirectAndLinfGiveBitwiseTheSameMapTwice) {
  const Problem p = test_support::random_target_bar();
  DirectOptions o;
  o.k_min = 0;
  const Result a = solve_direct(p, o), b = solve_direct(p, o);
  ASSERT_EQ(a.distortion.size(), b.distortion.size());
  EXPECT_EQ(a.iterations, b.iterations);
  EXPECT_TRUE((a.positions.array() == b.positions.array()).all());
  EXPECT_TRUE((a.distortion.array() == b.distortion.array()).all());
  const Problem square = test_support::figure2(24, 0.2);
  const Result c = solve_linf(square), d = solve_linf(square);
  EXPECT_TRUE((c.positions.array() == d.positions.array()).all());
  EXPECT_EQ(c.lower_bound, d.lower_bound);
}

}  // namespace
