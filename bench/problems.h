#pragma once
// Problems shared by the benchmarks (header only: every bench_*.cpp is its own program).
#include <Eigen/Core>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include "args.h"
#include "strictmin/mesh/generators.h"
#include "strictmin/problem/problem.h"
#include "strictmin/solvers/linf.h"
#include "strictmin/tasks/examples.h"

namespace strictmin::bench {

// The paper's Figure 2 on an N x N grid (2 N^2 triangles): boundary fixed, centre moved
// sideways by 0.2.
inline Problem square_problem(int cells) { return example_problem(make_square_example(cells, 0.2)); }

// A 4N x N bar (8 N^2 triangles), random rotation targets (+-0.5 rad, fixed seed), left end
// fixed, right end moved and turned by 0.6 rad.
inline Problem bar_problem(int n) {
  const int nx = 4 * n, ny = n;
  const Mesh mesh = make_grid(nx, ny, 4.0, 1.0);
  Problem p = make_problem(mesh);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> angle(-0.5, 0.5);
  for (int e = 0; e < p.num_elements(); ++e) {
    const double a = angle(rng);
    Eigen::Matrix2d R;
    R << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
    p.set_target(e, R);
  }
  Eigen::Matrix2d R;
  R << std::cos(0.6), -std::sin(0.6), std::sin(0.6), std::cos(0.6);
  std::vector<Handle> handles;
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    const int i = v % (nx + 1);
    const Eigen::Vector2d q = mesh.V.row(v).transpose();
    if (i == 0) handles.push_back({v, q});
    if (i == nx) handles.push_back({v, Eigen::Vector2d(3.5, 1.0) + R * (q - Eigen::Vector2d(4.0, 0.5))});
  }
  p.fix(handles);
  return p;
}

// L-infinity options of the benchmarks: STRICTMIN_LINF_VERBOSE=0|1|2 prints the solver's
// per-iteration lines and phase timers; STRICTMIN_LINF_NO_PROBES=1 turns the active-set
// probes off (LinfOptions::active_set_probes), for A/B comparisons. A bad verbosity throws
// std::invalid_argument naming the variable (bench::env_int).
inline LinfOptions linf_options_from_env() {
  LinfOptions o;
  o.verbose = env_int("STRICTMIN_LINF_VERBOSE", 0, 0, 2);
  if (std::getenv("STRICTMIN_LINF_NO_PROBES")) o.active_set_probes = false;
  if (o.verbose)
    o.progress = [](const IterationRecord& r) {
      std::fprintf(stderr, "linf %3d k %.12f certified bound %.12f gap %.2e %.3f s\n", r.iteration, r.max_distortion,
                   r.lower_bound, r.certified_gap, r.time_s);
    };
  return o;
}

}  // namespace strictmin::bench
