// The interior-point start (solvers/socp/ipm.h, initialize): s = M (x0, k0) + o with heads
// raised into the cones, z = mu0 s^{-1} (perfectly centred), and, with a bounded margin, the
// cones of fixed bounds started just above their bound (docs/strict.md, "The start of a
// level"). Checked entry by entry against the definitions on a small program.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "grid_cone_program.h"
#include "solvers/socp/cone_program.h"
#include "solvers/socp/ipm.h"
#include "solvers/socp/soc.h"

using namespace strictmin::socp;

namespace {


// The inner vertices moved off the grid, so that the Jacobians differ between elements.
Eigen::VectorXd inner_positions() {
  Eigen::VectorXd x(8);
  x << 1.1, 0.9, 2.0, 1.2, 0.8, 2.1, 2.2, 1.9;
  return x;
}

struct Cone {
  double head, tail_norm;
};
Cone cone_at(const ConeProgram& p, const Eigen::VectorXd& u, int i) {
  const double* c = u.data() + p.cone_offset(i);
  return {c[0], tail_norm(c, p.cone_dim(i))};
}

// s o z = mu0 e in every cone (the centred start), mu0 from the k equation sum a_i z_i0 = c_k.
void expect_centred(const ConeProgram& p, const IpmState& st) {
  double k_equation = 0;
  for (int i = 0; i < p.num_cones(); ++i) k_equation += p.head_a[i] * st.z[p.cone_offset(i)];
  EXPECT_NEAR(k_equation, p.c_k, 1e-12);
  const double mu0 = st.s.segment(0, p.cone_dim(0)).dot(st.z.segment(0, p.cone_dim(0)));
  ASSERT_GT(mu0, 0);
  for (int i = 0; i < p.num_cones(); ++i) {
    const int d = p.cone_dim(i);
    double prod[16];
    jordan_product(st.s.data() + p.cone_offset(i), st.z.data() + p.cone_offset(i), d, prod);
    EXPECT_NEAR(prod[0], mu0, 1e-12 * mu0) << "cone " << i;
    for (int j = 1; j < d; ++j) EXPECT_NEAR(prod[j], 0.0, 1e-12 * mu0) << "cone " << i << " entry " << j;
  }
}

}  // namespace

// With a bounded margin, a bounded cone's head is max(bound, ||tail||) + that margin: just
// above the bound where the start meets it (here bound ||J|| + 1e-6, the slack of a newly
// fixed element), just above ||tail|| where it misses it; the free cones keep their rule
// (head k0 or ||tail|| + margin); the tails are the start's G x - h; the start stays centred.
TEST(IpmStart, BoundedConesStartJustAboveTheirBound) {
  const Eigen::VectorXd x0 = inner_positions();
  // Every bounded element's bound is its Jacobian's norm at x0, plus 1e-6 (met) for even i
  // and minus 1e-3 (missed) for odd i.
  ConeProgram probe = grid_cone_program([](int) { return 1.0; });
  Eigen::VectorXd m0;
  probe.apply_m(x0, 0.0, true, m0);
  const ConeProgram p = grid_cone_program([&](int i) {
    const double jn = tail_norm(m0.data() + probe.cone_offset(i), probe.cone_dim(i));
    return i % 2 == 0 ? jn + 1e-6 : jn - 1e-3;
  });
  const double k0 = 1.5, margin = 0.05, bounded_margin = 5e-4;
  IpmState st;
  initialize(p, x0, k0, margin, 1.0, st, bounded_margin);
  Eigen::VectorXd m;
  p.apply_m(x0, k0, true, m);
  const int E = p.num_element_cones();
  for (int i = 0; i < E; ++i) {
    const Cone s = cone_at(p, st.s, i), target = cone_at(p, m, i);
    EXPECT_NEAR(s.tail_norm, target.tail_norm, 1e-15) << "cone " << i;
    if (i < E / 2) {
      EXPECT_NEAR(s.head, std::max(k0, target.tail_norm + margin), 1e-15) << "free cone " << i;
    } else {
      const double expected = std::max(p.head_b[i], target.tail_norm) + bounded_margin;
      EXPECT_NEAR(s.head, expected, 1e-15) << "bounded cone " << i;
      EXPECT_LE(s.head - p.head_b[i], bounded_margin + 1e-3 + 1e-15) << "bounded cone " << i;
    }
  }
  expect_centred(p, st);
}

// Without a bounded margin (the default) every cone gets the free cones' rule: the head at
// least ||tail|| + margin, whatever its bound.
TEST(IpmStart, WithoutABoundedMarginBoundedConesGetTheMargin) {
  const Eigen::VectorXd x0 = inner_positions();
  const ConeProgram p = grid_cone_program([](int) { return 3.0; });
  const double k0 = 1.5, margin = 0.05;
  IpmState st;
  initialize(p, x0, k0, margin, 1.0, st);
  Eigen::VectorXd m;
  p.apply_m(x0, k0, true, m);
  for (int i = 0; i < p.num_element_cones(); ++i) {
    const Cone s = cone_at(p, st.s, i), target = cone_at(p, m, i);
    EXPECT_NEAR(s.head, std::max(target.head, target.tail_norm + margin), 1e-15) << "cone " << i;
  }
  expect_centred(p, st);
}
