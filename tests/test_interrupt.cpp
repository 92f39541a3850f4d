// Cooperative interruption (solvers/interrupt.h): with the flag set, every iterative solver
// throws Interrupted at its first iteration; without a scope, or with the flag clear, the
// solves run as before (the same maps).
#include <gtest/gtest.h>

#include <atomic>

#include "strictmin/solvers/conformal.h"
#include "strictmin/solvers/interrupt.h"
#include "strictmin/solvers/l2.h"
#include "strictmin/mesh/polycube.h"
#include "strictmin/solvers/local_global.h"
#include "strictmin/tasks/gparam.h"
#include "strictmin/tasks/integer_grid.h"
#include "strictmin/tasks/method.h"
#include "test_meshes.h"

using namespace strictmin;

namespace {

SolverOptions with_method(Method m) {
  SolverOptions o;
  o.method = m;
  o.relax.sweeps = 3;
  o.direct.k_min = 0.2;
  return o;
}

}  // namespace

TEST(Interrupt, EveryIterativeMethodStopsWhenTheFlagIsSet) {
  const Problem p = test_support::figure2(6, 0.3);
  for (Method m : {Method::Linf, Method::Lp, Method::Irls, Method::Relax, Method::Direct, Method::Exact}) {
    std::atomic<bool> stop{true};
    InterruptScope scope(stop);
    EXPECT_THROW(run_method(p, with_method(m)), Interrupted) << method_name(m);
  }
  std::atomic<bool> stop{true};
  InterruptScope scope(stop);
  EXPECT_THROW(local_global(p, p.positions, with_method(Method::L2), LocalGlobalOptions{}), Interrupted);
  EXPECT_NO_THROW(solve_l2(p));  // one factorization: no iteration to stop at
}

// Global parametrization stops in its field phase (the Lanczos steps, the unit field's
// steps) before any solve: a second or more on 100k faces that Ctrl-C did not stop before.
TEST(Interrupt, GlobalParametrizationStopsInItsField) {
  const Mesh cube = make_cube_surface(3);
  for (bool unit : {false, true}) {
    GParamOptions o;
    o.solver.method = Method::L2;
    o.field_options.unit = unit;
    int phases = 0;
    o.progress = [&](const std::string&) { ++phases; };
    std::atomic<bool> stop{true};
    InterruptScope scope(stop);
    EXPECT_THROW(global_parametrize(cube, o), Interrupted) << (unit ? "unit" : "smoothest");
    EXPECT_EQ(phases, 1) << "only the surface graph's line: the field stopped";
  }
}

// The integer grid's rounding (tens of L2 solves: 2 s on horse) stops at its next step: Ctrl-C
// waited for the whole rounding before.
TEST(Interrupt, IntegerGridRoundingStops) {
  const Mesh cube = make_cube_surface(3);
  GParamOptions o;
  o.solver.method = Method::L2;
  o.edge_length = 2.0;
  GParamOutcome g = global_parametrize(cube, o);  // the graph, cut, singularities and problem
  std::atomic<bool> stop{true};
  InterruptScope scope(stop);
  Problem problem = g.problem;
  EXPECT_THROW(round_to_integer_grid(cube, g.graph, g.cut, g.singular, g.edge_length, problem), Interrupted);
}

// The quasiconformal and isometric solves (their own cone programs, src/solvers/qc) stop too:
// they ran to the end of their bisections through Ctrl-C and SIGTERM before.
TEST(Interrupt, QuasiconformalAndIsometricSolvesStop) {
  const Problem p = test_support::figure2(6, 0.3);
  for (Measure m : {Measure::Quasiconformal, Measure::Isometric}) {
    ConformalOptions o;
    o.measure = m;
    std::atomic<bool> stop{true};
    InterruptScope scope(stop);
    EXPECT_THROW(solve_conformal_linf(p, p.positions, o), Interrupted) << measure_name(m);
    EXPECT_THROW(solve_conformal_direct(p, p.positions, o, DirectOptions{}), Interrupted) << measure_name(m);
    std::atomic<bool> go{false};
    InterruptScope clear(go);
    EXPECT_NO_THROW(solve_conformal_linf(p, p.positions, o)) << measure_name(m);
  }
}

TEST(Interrupt, AClearFlagOrNoScopeChangesNothing) {
  const Problem p = test_support::figure2(6, 0.3);
  const Result plain = run_method(p, with_method(Method::Relax));
  std::atomic<bool> stop{false};
  {
    InterruptScope scope(stop);
    const Result watched = run_method(p, with_method(Method::Relax));
    EXPECT_EQ(watched.positions, plain.positions);
    EXPECT_EQ(watched.status, plain.status);
  }
  stop = true;  // the scope is gone: the flag is no longer read
  EXPECT_NO_THROW(run_method(p, with_method(Method::Linf)));
}

TEST(Interrupt, ScopesNest) {
  std::atomic<bool> outer{false}, inner{true};
  InterruptScope a(outer);
  {
    InterruptScope b(inner);
    EXPECT_THROW(check_interrupt(), Interrupted);
  }
  EXPECT_NO_THROW(check_interrupt());
  outer = true;
  EXPECT_THROW(check_interrupt(), Interrupted);
}
