#pragma once
// A small cone program for the interior-point tests: a 4 x 4 grid of vertices on [0, 3]^2
// (its 4 inner vertices free, 8 dofs), 18 triangles with target 0 (the cones' tails are the
// Jacobians), weight 0.5 each; the first 9 elements have head k, the others are bounded,
// element i by bound(i) (a fixed bound, as on direct's later levels).
#include <Eigen/Dense>
#include <functional>

#include "solvers/socp/cone_program.h"

inline strictmin::socp::ConeProgram grid_cone_program(const std::function<double(int)>& bound) {
  strictmin::socp::ConeProgram p;
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
  p.h = Eigen::VectorXd::Zero(E * 4);
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
