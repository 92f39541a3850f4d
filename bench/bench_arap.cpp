// ARAP local-global (paper Section 5.4) with L-infinity and with relaxation global steps,
// on ../shared/data/tet/armadillo.mesh (56,917 tets) and a planar bar of 100,000 triangles,
// both from the L2 field-deviation map. Handles: the vertices in the lowest and the highest
// 5% of the longest extent; the high slab is turned by 60 degrees about the long axis
// (tets, a twist) or by 90 degrees in the plane to where a quarter-circle bend ends (bar).
// Counters: local-global iterations run, seconds per iteration, the first iteration whose
// relative change of the maximum is below 1e-4 (-1: not within the cap), start and final max.
// linf iterations are capped (each is one SOCP of 10-30 s at these sizes): see docs/performance.md.
// Run: build/bench/bench_arap --benchmark_out=arap.json --benchmark_out_format=json
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <numbers>

#include "strictmin/io/mesh_io.h"
#include "strictmin/mesh/generators.h"
#include "strictmin/solvers/l2.h"
#include "strictmin/solvers/local_global.h"

using namespace strictmin;

namespace {

struct Case {
  Problem problem;
  Eigen::MatrixXd start;  // L2 field-deviation map with the handles
  bool ok = false;
};

// Fixes the slabs at both ends of axis `axis`; the high one moved by `move`.
template <class Move>
void slab_handles(Problem& p, const Eigen::MatrixXd& V, int axis, Move move) {
  const double lo = V.col(axis).minCoeff(), hi = V.col(axis).maxCoeff(), band = 0.05 * (hi - lo);
  std::vector<Handle> handles;
  for (int v = 0; v < V.rows(); ++v) {
    const Eigen::VectorXd x = V.row(v).transpose();
    if (x(axis) <= lo + band) handles.push_back({v, x});
    if (x(axis) >= hi - band) handles.push_back({v, move(x)});
  }
  p.fix(handles);
}

const Case& armadillo() {
  static std::unique_ptr<Case> c;
  if (c) return *c;
  c = std::make_unique<Case>();
  const std::string path = std::string(STRICTMIN_SHARED_DATA) + "/tet/armadillo.mesh";
  if (!std::filesystem::exists(path)) return *c;
  const Mesh mesh = read_mesh(path);
  c->problem = make_problem(mesh);
  Eigen::Index axis = 0;
  (mesh.V.colwise().maxCoeff() - mesh.V.colwise().minCoeff()).maxCoeff(&axis);
  const Eigen::Vector3d centre = mesh.V.colwise().mean().transpose();
  Eigen::Vector3d dir = Eigen::Vector3d::Zero();
  dir(axis) = 1;
  const Eigen::Matrix3d Q = Eigen::AngleAxisd(std::numbers::pi / 3, dir).toRotationMatrix();
  slab_handles(c->problem, mesh.V, static_cast<int>(axis),
               [&](const Eigen::VectorXd& x) -> Eigen::VectorXd { return centre + Q * (x - centre); });
  c->start = solve_l2(c->problem).positions;
  c->ok = true;
  return *c;
}

const Case& planar_bar() {
  static std::unique_ptr<Case> c;
  if (c) return *c;
  c = std::make_unique<Case>();
  const Mesh mesh = make_grid(500, 100, 10.0, 2.0);  // 100,000 triangles
  c->problem = make_problem(mesh);
  const Eigen::Matrix2d Q = Eigen::Rotation2Dd(std::numbers::pi / 2).toRotationMatrix();
  // The end's centre goes where a quarter circle of the bar's length (radius 20 / pi) ends.
  const Eigen::Vector2d end_centre(20.0 / std::numbers::pi, 1.0 + 20.0 / std::numbers::pi);
  slab_handles(c->problem, mesh.V, 0, [&](const Eigen::VectorXd& x) -> Eigen::VectorXd {
    return end_centre + Q * (x - Eigen::Vector2d(10.0, 1.0));
  });
  c->start = solve_l2(c->problem).positions;
  c->ok = true;
  return *c;
}

void run(benchmark::State& state, const Case& c, Method method, int cap) {
  if (!c.ok) {
    state.SkipWithError("../shared/data/tet/armadillo.mesh not found");
    return;
  }
  SolverOptions solver;
  solver.method = method;
  LocalGlobalOptions o;
  o.max_iterations = cap;
  o.relative_change = 0;  // run to the cap; the 1e-4 crossing is read from the history
  Result r;
  for (auto _ : state) r = local_global(c.problem, c.start, solver, o);
  int reached = -1;
  for (const auto& h : r.history)
    if (h.relative_change <= 1e-4) {
      reached = h.iteration;
      break;
    }
  LocalGlobalOptions measure;
  state.counters["elements"] = c.problem.num_elements();
  state.counters["lg_iterations"] = r.iterations;
  state.counters["s_per_iteration"] = r.iterations > 0 ? r.time_s / r.iterations : 0.0;
  state.counters["total_s"] = r.time_s;
  state.counters["iterations_to_1e-4"] = reached;
  state.counters["max_start"] = local_distortion(c.problem, c.start, measure).maxCoeff();
  state.counters["max_final"] = r.history.empty() ? 0.0 : r.history.back().max_distortion;
}

void BM_ArapArmadilloLinf(benchmark::State& s) { run(s, armadillo(), Method::Linf, static_cast<int>(s.range(0))); }
void BM_ArapArmadilloRelax(benchmark::State& s) { run(s, armadillo(), Method::Relax, static_cast<int>(s.range(0))); }
void BM_ArapBarLinf(benchmark::State& s) { run(s, planar_bar(), Method::Linf, static_cast<int>(s.range(0))); }
void BM_ArapBarRelax(benchmark::State& s) { run(s, planar_bar(), Method::Relax, static_cast<int>(s.range(0))); }

// Argument: the local-global iteration cap. One run each (minutes for linf).
BENCHMARK(BM_ArapArmadilloLinf)->Arg(5)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();
BENCHMARK(BM_ArapArmadilloRelax)->Arg(100)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();
BENCHMARK(BM_ArapBarLinf)->Arg(5)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();
BENCHMARK(BM_ArapBarRelax)->Arg(100)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
