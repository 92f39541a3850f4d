// The interior-point start (solvers/socp/ipm.h, initialize): s = M (x0, k0) + o with heads
// raised into the cones, z = mu0 s^{-1} (perfectly centred), and, with a bounded margin, the
// cones of fixed bounds started just above their bound (docs/strict.md, "The start of a
// level"). Checked entry by entry against the definitions on a small program.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "solvers/socp/cone_program.h"
#include "solvers/socp/ipm.h"
#include "solvers/socp/soc.h"

using namespace strictmin::socp;

namespace {

// A 4 x 4 grid of vertices on [0, 3]^2 (its 4 inner vertices free), 18 triangles: the first
// 9 with head k, the others bounded, their bound bound(i).
template <class Bound>
ConeProgram grid_program(Bound bound) {
  ConeProgram p;
  p.n = p.m = 2;
  p.num_x = 8;
  auto free_index = [](int i, int j) { return (i >= 1 && i <= 2 && j >= 1 && j <= 2) ? (j - 1) * 2 + (i - 1) : -1; };
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      const int corners[2][3][2] = {{{i, j}, {i + 1, j}, {i + 1, j + 1}}, {{i, j}, {i + 1, j + 1}, {i, j + 1}}};
      for (const auto& tri : corners) {
        p.element.push_back(static_cast<int>(p.element.size()));
        const Eigen::Vector2d p0(tri[0][0], tri[0][1]), p1(tri[1][0], tri[1][1]), p2(tri[2][0], tri[2][1]);
        Eigen::Matrix2d d;
        d << p1 - p0, p2 - p0;
        const Eigen::Matrix2d inv = d.inverse();  // rows: gradients of corners 1 and 2
        const Eigen::Vector2d g1 = inv.row(0).transpose(), g2 = inv.row(1).transpose(), g0 = -g1 - g2;
        for (const Eigen::Vector2d& g : {g0, g1, g2}) p.grad.insert(p.grad.end(), {g[0], g[1]});
        for (const auto& c : tri) {
          const int f = free_index(c[0], c[1]);
          p.dof_base.push_back(f < 0 ? -1 : 2 * f);
        }
      }
    }
  const int E = static_cast<int>(p.element.size());
  p.h = Eigen::VectorXd::Zero(E * 4);  // target 0: the tails are the Jacobians
  p.weight = Eigen::VectorXd::Constant(E, 0.5);
  p.head_a = Eigen::VectorXd::Zero(E);
  p.head_b = Eigen::VectorXd::Zero(E);
  for (int i = 0; i < E; ++i) {
    if (i < E / 2)
      p.head_a[i] = 1.0;
    else
      p.head_b[i] = bound(i);
  }
  p.finalize();
  return p;
}

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
  ConeProgram probe = grid_program([](int) { return 1.0; });
  Eigen::VectorXd m0;
  probe.apply_m(x0, 0.0, true, m0);
  const ConeProgram p = grid_program([&](int i) {
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
  const ConeProgram p = grid_program([](int) { return 3.0; });
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
