// Cooperative interruption (solvers/interrupt.h): with the flag set, every iterative solver
// throws Interrupted at its first iteration; without a scope, or with the flag clear, the
// solves run as before (the same maps).
#include <gtest/gtest.h>

#include <atomic>

#include "strictmin/solvers/interrupt.h"
#include "strictmin/solvers/l2.h"
#include "strictmin/solvers/local_global.h"
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
