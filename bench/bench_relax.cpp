// Relaxation (paper Algorithm 3): 50 sweeps on planar grids of ~10k, ~50k and ~100k
// triangles (boundary fixed, centre moved by 0.15, from the L2 map) on 1 and 2 threads,
// one sweep alone, 50 sweeps on a tet bar (6,144 tets) and on a cylinder patch in 3D (10,000
// triangles, 3x2 Jacobians), both with one end turned, and the exact 1-ring solver alone on
// rings taken from perturbed meshes (2D: grid rings of 4 or 8 triangles, 6 on average; 3D:
// interior tet-box rings of 24 tets).
// Run: build/bench/bench_relax --benchmark_out=relax.json --benchmark_out_format=json
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <Eigen/Geometry>
#include <map>
#include <memory>
#include <random>

#include "strictmin/measures/field_deviation.h"
#include "strictmin/tasks/examples.h"
#include "strictmin/mesh/generators.h"
#include "strictmin/mesh/surface_generators.h"
#include "strictmin/problem/surface_deformation.h"
#include "strictmin/solvers/l2.h"
#include "strictmin/solvers/one_ring.h"
#include "strictmin/solvers/relax.h"

using namespace strictmin;

namespace {

// A square grid with 2 n^2 triangles, boundary fixed, the centre moved by 0.15 in x.
Problem grid_problem(int n) { return example_problem(make_square_example(n, 0.15)); }

struct Case {
  Problem problem;
  Eigen::MatrixXd start;  // the L2 map
};

const Case& cached(int n) {
  static std::map<int, std::unique_ptr<Case>> cache;
  auto& slot = cache[n];
  if (!slot) {
    slot = std::make_unique<Case>();
    slot->problem = grid_problem(n);
    slot->start = solve_l2(slot->problem).positions;
  }
  return *slot;
}

void relax_50_sweeps(benchmark::State& state, const Case& c) {
  RelaxOptions options;
  options.sweeps = 50;
  double max_distortion = 0;
  for (auto _ : state) {
    const Result r = relax(c.problem, c.start, options);
    max_distortion = r.history.back().max_distortion;
    benchmark::DoNotOptimize(r.positions.data());
  }
  state.counters["elements"] = c.problem.num_elements();
  state.counters["max_l2"] = field_deviation(c.problem, c.start).maxCoeff();
  state.counters["max_relaxed"] = max_distortion;
  state.counters["ns_per_ring"] = benchmark::Counter(
      50.0 * c.problem.num_free(), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void BM_Relax50Sweeps(benchmark::State& state) {
  const Case& c = cached(static_cast<int>(state.range(0)));
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, state.range(1));
  relax_50_sweeps(state, c);
  state.counters["threads"] = static_cast<double>(state.range(1));
}

void BM_OneSweep(benchmark::State& state) {
  const Case& c = cached(static_cast<int>(state.range(0)));
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, state.range(1));
  const RelaxSweeper sweeper(c.problem);
  Eigen::MatrixXd X = c.start;
  for (auto _ : state) benchmark::DoNotOptimize(sweeper.sweep(c.problem, X));
  state.counters["colours"] = sweeper.num_colours();
  state.counters["threads"] = static_cast<double>(state.range(1));
}

// One end (the lowest coordinate `axis`) held, the other turned by 0.5 radians about `axis`
// through the origin (and, for the cylinder patch, lifted by 0.2); the L2 map as the start.
Case end_turned(Problem p, const Mesh& mesh, int axis) {
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(0.5, Eigen::Vector3d::Unit(axis)).toRotationMatrix();
  const double lo = mesh.V.col(axis).minCoeff(), hi = mesh.V.col(axis).maxCoeff();
  std::vector<Handle> handles;
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    const Eigen::Vector3d x = mesh.V.row(v).transpose();
    if (x(axis) < lo + 1e-9) handles.push_back({v, x});
    if (x(axis) > hi - 1e-9) handles.push_back({v, Eigen::Vector3d(turn * x + 0.2 * Eigen::Vector3d::Unit(axis))});
  }
  p.fix(handles);
  Case c;
  c.problem = std::move(p);
  c.start = solve_l2(c.problem).positions;
  return c;
}


void BM_Relax50SweepsTets(benchmark::State& state) {
  static const Mesh bar = make_tet_box(16, 8, 8, 2.0, 1.0, 1.0);
  static const Case c = end_turned(make_problem(bar), bar, 0);
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 1);
  relax_50_sweeps(state, c);
}

void BM_Relax50SweepsSurface(benchmark::State& state) {
  static const Mesh patch = make_cylinder_patch(100, 50, 1.0, 2.0, 2.0);
  static const Case c = end_turned(make_surface_deformation_problem(patch), patch, 2);
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 1);
  relax_50_sweeps(state, c);
}

BENCHMARK(BM_Relax50SweepsTets)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Relax50SweepsSurface)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_SweeperSetup(benchmark::State& state) {
  const Case& c = cached(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(RelaxSweeper(c.problem).num_colours());
}

// n = 71, 158, 224: 10,082, 49,928 and 100,352 triangles; 1 and 2 threads.
BENCHMARK(BM_Relax50Sweeps)->ArgsProduct({{71, 158, 224}, {1, 2}})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_OneSweep)->ArgsProduct({{71, 158, 224}, {1, 2}})->Unit(benchmark::kMicrosecond)->UseRealTime();
BENCHMARK(BM_SweeperSetup)->Arg(224)->Unit(benchmark::kMillisecond);

// Rings of every interior vertex of a mesh under a perturbed map with rotated targets,
// stored back to back, built from Problem::jacobian (D_T(q)^2 = a ||q - c||^2 + b).
template <int d>
struct Rings {
  std::vector<RingTerm<d>> terms;
  std::vector<int> start{0};
};

template <int d>
Rings<d> collect_rings(const Mesh& mesh, double noise, int limit) {
  Problem p = make_problem(mesh);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::MatrixXd X = p.positions;
  for (int v = 0; v < X.rows(); ++v)
    for (int k = 0; k < d; ++k) X(v, k) += noise * u(rng);
  for (int e = 0; e < p.num_elements(); ++e) {
    Eigen::Matrix<double, d, d> R;
    if constexpr (d == 2)
      R = Eigen::Rotation2Dd(0.3 * u(rng)).toRotationMatrix();
    else
      R = Eigen::AngleAxisd(0.3 * u(rng), Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized()).toRotationMatrix();
    p.set_target(e, R);
  }
  std::vector<std::vector<std::pair<int, int>>> incident(p.num_vertices);
  for (int e = 0; e < p.num_elements(); ++e)
    for (int j = 0; j < p.corners(); ++j) incident[p.elements(e, j)].push_back({e, j});
  const size_t full = incident[p.num_vertices / 2].size();  // an interior vertex's ring size
  Rings<d> rings;
  for (int v = 0; v < p.num_vertices && static_cast<int>(rings.start.size()) <= limit; ++v) {
    if (d == 3 && incident[v].size() != full) continue;  // interior tet-box vertices only
    bool boundary = false;
    for (int k = 0; k < d; ++k) boundary = boundary || mesh.V(v, k) == 0.0 || mesh.V(v, k) == 1.0;
    if (boundary) continue;
    for (const auto& [e, j] : incident[v]) {
      const Eigen::VectorXd g = p.gradients.row(e * p.corners() + j).transpose();
      const Eigen::MatrixXd M = p.jacobian(e, X) - p.target(e) - X.row(v).transpose() * g.transpose();
      RingTerm<d> t;
      t.a = g.squaredNorm();
      t.centre = -M * g / t.a - X.row(v).transpose();  // relative to the vertex, as in a sweep
      t.b = std::max(0.0, M.squaredNorm() - (M * g).squaredNorm() / t.a);
      rings.terms.push_back(t);
    }
    rings.start.push_back(static_cast<int>(rings.terms.size()));
  }
  return rings;
}

template <int d>
void solve_rings(benchmark::State& state, const Rings<d>& rings) {
  const int count = static_cast<int>(rings.start.size()) - 1;
  for (auto _ : state)
    for (int i = 0; i < count; ++i) {
      const auto sol = solve_one_ring<d>(&rings.terms[rings.start[i]], rings.start[i + 1] - rings.start[i]);
      benchmark::DoNotOptimize(sol.value);
    }
  state.counters["ns_per_ring"] =
      benchmark::Counter(count, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["terms_per_ring"] = static_cast<double>(rings.terms.size()) / count;
}

void BM_RingSolve2D(benchmark::State& state) {
  static const Rings<2> rings = collect_rings<2>(make_grid(40, 40), 0.25 / 40, 1024);
  solve_rings<2>(state, rings);
}

void BM_RingSolve3D(benchmark::State& state) {
  static const Rings<3> rings = collect_rings<3>(make_tet_box(12, 12, 12), 0.2 / 12, 1024);
  solve_rings<3>(state, rings);
}

BENCHMARK(BM_RingSolve2D)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_RingSolve3D)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
