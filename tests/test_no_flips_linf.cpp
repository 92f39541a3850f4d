// The linf global step inside the orientation-preserving cones (solvers/no_flips_step.h),
// against the field-deviation L-infinity solver (an independent program and solver): where
// the cones do not bind, the same optimum; where they do, no better, and no flip added.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <vector>

#include "strictmin/measures/field_deviation.h"
#include "strictmin/mesh/generators.h"
#include "strictmin/problem/problem.h"
#include "strictmin/solvers/l2.h"
#include "strictmin/solvers/linf.h"
#include "strictmin/solvers/no_flips.h"
#include "solvers/no_flips_step.h"
#include "tasks/no_new_flips.h"

using namespace strictmin;

namespace {

// A 24 x 4 bar of [0, 6] x [0, 1], its ends turned by -+angle and moved to x = ends, 6 - ends.
Problem bar(double angle, double ends) {
  const Mesh m = make_grid(24, 4, 6.0, 1.0);
  std::vector<Handle> handles;
  for (int v = 0; v < m.num_vertices(); ++v) {
    const double x = m.V(v, 0);
    if (x > 0 && x < 6.0) continue;
    const Eigen::Vector2d c(x, 0.5), to(x == 0 ? ends : 6.0 - ends, 0.5);
    handles.push_back({v, Eigen::Rotation2Dd(x == 0 ? -angle : angle) * (m.V.row(v).transpose() - c) + to});
  }
  Problem p = make_problem(m);
  p.fix(handles);
  return p;
}

// A 12 x 2 x 2 tet box of [0, 6] x [0, 1] x [0, 1], its ends turned about the x axis by
// -+angle and moved to x = ends, 6 - ends.
Problem tet_bar(double angle, double ends) {
  const Mesh m = make_tet_box(12, 2, 2, 6.0, 1.0, 1.0);
  std::vector<Handle> handles;
  for (int v = 0; v < m.num_vertices(); ++v) {
    const double x = m.V(v, 0);
    if (x > 0 && x < 6.0) continue;
    const Eigen::Vector3d c(x, 0.5, 0.5), to(x == 0 ? ends : 6.0 - ends, 0.5, 0.5);
    const Eigen::AngleAxisd turn(x == 0 ? -angle : angle, Eigen::Vector3d::UnitX());
    handles.push_back({v, turn * (m.V.row(v).transpose() - c) + to});
  }
  Problem p = make_problem(m);
  p.fix(handles);
  return p;
}

int flipped(const Problem& p, const Eigen::MatrixXd& X) {
  const Eigen::VectorXi positive = positively_oriented(p, X);
  return static_cast<int>(positive.size() - positive.sum());
}

}  // namespace

// Ends turned by 0.6 rad (tets: 0.4 rad about the bar's axis), not moved: from the L2 map,
// the unconstrained optimum adds no flip, so the cones (Lipman's; on tets the diagonally
// dominant ones) do not bind and both programs have the same optimum (each to a gap of 1e-8).
TEST(NoFlipsLinf, SameOptimumWhereTheConesDoNotBind) {
  for (const bool tets : {false, true}) {
    Problem p = tets ? tet_bar(0.4, 0.0) : bar(0.6, 0.0);
    const Eigen::MatrixXd X0 = solve_l2(p).positions;
    ASSERT_EQ(flipped(p, X0), 0);
    p.positions = X0;
    const Result free_step = solve_linf(p, {});
    ASSERT_EQ(free_step.status, SolveStatus::Solved) << free_step.message;
    ASSERT_EQ(flips_added(p, X0, free_step.positions), 0);
    const Result cone_step = linf_without_new_flips(p, X0, 1e-8);
    ASSERT_EQ(cone_step.status, SolveStatus::Solved) << cone_step.message;
    const double k_free = free_step.distortion.maxCoeff(), k_cone = cone_step.distortion.maxCoeff();
    EXPECT_NEAR(k_cone, k_free, 1e-6 * k_free);
    EXPECT_LE(cone_step.lower_bound, k_cone * (1 + 1e-9));
    EXPECT_GE(cone_step.lower_bound, k_free * (1 - 1e-6));
    EXPECT_EQ(flips_added(p, X0, cone_step.positions), 0);
    std::printf("%s: free %.10f, cones %.10f (bound %.10f, %d iterations)\n", tets ? "tets" : "planar", k_free,
                k_cone, cone_step.lower_bound, cone_step.iterations);
  }
}

// Ends squeezed to a third of the bar and turned inwards by 1.6 rad (tets: twisted about the
// axis): the L-infinity optimum from the L2 map flips elements that the cone step keeps
// positive; its maximum is no lower than the unconstrained optimum and no higher than the
// start's.
TEST(NoFlipsLinf, NoFlipAddedWhereTheConesBind) {
  for (const bool tets : {false, true}) {
    Problem p = tets ? tet_bar(1.6, 2.0) : bar(1.6, 2.0);
    const Eigen::MatrixXd X0 = solve_l2(p).positions;
    p.positions = X0;
    const Result free_step = solve_linf(p, {});
    const Result cone_step = linf_without_new_flips(p, X0, 1e-8);
    std::printf("start: %d flipped, max %.6g; free: max %.6g, %d added; cones: max %.6g, %d added (%s)\n",
                flipped(p, X0), field_deviation(p, X0).maxCoeff(), free_step.distortion.maxCoeff(),
                flips_added(p, X0, free_step.positions), cone_step.distortion.maxCoeff(),
                flips_added(p, X0, cone_step.positions), cone_step.message.c_str());
    ASSERT_GT(flips_added(p, X0, free_step.positions), 0) << "the case must make the cones bind";
    EXPECT_EQ(cone_step.status, SolveStatus::Solved) << cone_step.message;
    EXPECT_EQ(flips_added(p, X0, cone_step.positions), 0);
    EXPECT_GE(cone_step.distortion.maxCoeff(), free_step.distortion.maxCoeff() * (1 - 1e-8));
    EXPECT_LT(cone_step.distortion.maxCoeff(), field_deviation(p, X0).maxCoeff());
  }
}

// deform --no-flips with fd and linf, from the rest pose with the handles moved (planar and
// tets): the unconstrained optimum flips elements; cutting it back alone stays near the start,
// the steps inside the cones go on to a maximum far lower, still adding no flip, and stop
// when a step no longer lowers it (solved). The unconstrained bound stays the lower bound.
TEST(NoFlipsLinf, StepsAfterTheCutBack) {
  for (const bool tets : {false, true}) {
    const Problem p = tets ? tet_bar(1.6, 2.0) : bar(1.6, 2.0);
    const Eigen::MatrixXd start = p.positions;
    const Result free_solve = solve_linf(p, {});
    ASSERT_GT(flips_added(p, start, free_solve.positions), 0) << "the case must flip";
    Result cut = free_solve;
    cut_back_result(p, start, cut);
    Result stepped = free_solve;
    remove_added_flips(p, start, Method::Linf, {}, stepped);
    std::printf("%s: free %.6g, cut back %.6g, steps %.6g (%s)\n", tets ? "tets" : "planar",
                free_solve.distortion.maxCoeff(), cut.distortion.maxCoeff(), stepped.distortion.maxCoeff(),
                stepped.message.c_str());
    EXPECT_EQ(flips_added(p, start, stepped.positions), 0);
    EXPECT_EQ(stepped.status, SolveStatus::Solved) << stepped.message;
    EXPECT_NE(stepped.message.find("steps inside the orientation-preserving cones"), std::string::npos);
    EXPECT_EQ(stepped.lower_bound, free_solve.lower_bound);
    EXPECT_GE(stepped.distortion.maxCoeff(), free_solve.lower_bound);
    EXPECT_LT(stepped.distortion.maxCoeff(), 0.5 * cut.distortion.maxCoeff());
    EXPECT_NEAR(stepped.distortion.maxCoeff(), field_deviation(p, stepped.positions).maxCoeff(), 1e-12);
  }
}

// The same for l2 (--no-flips with fd and l2): steps of least L2 energy inside the cones.
// Each step lowers the energy of a flip-free map; the result adds no flip, its energy is at
// least the unconstrained minimum's, and closes most of the cut-back map's excess over it.
TEST(NoFlipsLinf, L2StepsAfterTheCutBack) {
  for (const bool tets : {false, true}) {
    // (L2 spreads the twist more evenly than L-infinity: the tets need a larger one to flip.)
    const Problem p = tets ? tet_bar(2.6, 2.0) : bar(1.6, 2.0);
    const Eigen::MatrixXd start = p.positions;
    const Result free_solve = solve_l2(p);
    ASSERT_GT(flips_added(p, start, free_solve.positions), 0) << "the case must flip";
    Result cut = free_solve;
    cut_back_result(p, start, cut);
    Result stepped = free_solve;
    remove_added_flips(p, start, Method::L2, {}, stepped);
    const double e_free = weighted_energy(p, free_solve.distortion), e_cut = weighted_energy(p, cut.distortion),
                 e_steps = weighted_energy(p, stepped.distortion);
    std::printf("%s: energy free %.6g, cut back %.6g, steps %.6g (%s)\n", tets ? "tets" : "planar", e_free, e_cut,
                e_steps, stepped.message.c_str());
    EXPECT_EQ(flips_added(p, start, stepped.positions), 0);
    EXPECT_EQ(stepped.status, SolveStatus::Solved) << stepped.message;
    EXPECT_NE(stepped.message.find("L2 steps inside the orientation-preserving cones"), std::string::npos);
    EXPECT_GE(e_steps, e_free * (1 - 1e-9));
    EXPECT_LT(e_steps - e_free, 0.1 * (e_cut - e_free));  // (measured: 0.1% and 3% of the cut's excess)
  }
}

// relax under --no-flips after one solve: its start (linf) is first stepped to add no flip,
// then the sweeps stay in the rings' kernels. Before, the sweeps ran from linf's flipped map
// and the result was cut back at the end (boy.mesh: 94.7).
TEST(NoFlipsLinf, RelaxStartsFromTheSteppedMap) {
  for (const bool tets : {false, true}) {
    const Problem p = tets ? tet_bar(1.6, 2.0) : bar(1.6, 2.0);
    const Eigen::MatrixXd start = p.positions;
    SolverOptions linf;
    linf.method = Method::Linf;
    const Result stepped = run_method_without_new_flips(p, start, linf);
    SolverOptions relax = linf;
    relax.method = Method::Relax;
    relax.relax.sweeps = 20;
    const Result r = run_method_without_new_flips(p, start, relax);
    std::printf("%s: linf steps %.6g, relax %.6g (%s)\n", tets ? "tets" : "planar", stepped.distortion.maxCoeff(),
                r.distortion.maxCoeff(), r.message.c_str());
    EXPECT_EQ(flips_added(p, start, r.positions), 0);
    EXPECT_EQ(r.status, SolveStatus::Solved) << r.message;
    EXPECT_LE(r.distortion.maxCoeff(), stepped.distortion.maxCoeff() * (1 + 1e-9));
    EXPECT_EQ(r.lower_bound, stepped.lower_bound);
    EXPECT_NE(r.message.find("initial linf: "), std::string::npos) << r.message;
  }
}

// When relax's sweeps from its start method's own (flipped) map turn every flipped element
// back, that map is taken: the tet bar turned by 2 rad each way ends at linf's certified
// bound, where the steps inside the cones stop higher.
TEST(NoFlipsLinf, RelaxSweepsThatLeaveNoFlipAreTaken) {
  const Problem p = tet_bar(2.0, 0.0);
  SolverOptions linf;
  linf.method = Method::Linf;
  const Result stepped = run_method_without_new_flips(p, p.positions, linf);
  SolverOptions relax = linf;
  relax.method = Method::Relax;
  relax.relax.sweeps = 20;
  const Result r = run_method_without_new_flips(p, p.positions, relax);
  std::printf("linf steps %.6g, relax %.6g, bound %.6g\n", stepped.distortion.maxCoeff(), r.distortion.maxCoeff(),
              r.lower_bound);
  EXPECT_NE(r.message.find("no flip left by the sweeps from the start method's map"), std::string::npos) << r.message;
  EXPECT_EQ(flips_added(p, p.positions, r.positions), 0);
  EXPECT_EQ(r.status, SolveStatus::Solved) << r.message;
  EXPECT_LE(r.distortion.maxCoeff(), stepped.distortion.maxCoeff() * (1 + 1e-9));
  EXPECT_LE(r.distortion.maxCoeff(), r.lower_bound * (1 + 1e-6));
}
