// L2 field-deviation solve: assembly + symbolic analysis, numeric factorization and the
// solve, on planar grids of ~10k, ~50k and ~100k triangles (boundary fixed, one interior
// handle moved) and on the real disk meshes of ../shared/data (vertex 0 pinned at the origin,
// the one fixed vertex field deviation needs: file_problem).
// Run: build/bench/bench_l2 --benchmark_out=l2.json --benchmark_out_format=json
#include <benchmark/benchmark.h>

#include <filesystem>
#include <map>
#include <memory>

#include "strictmin/tasks/examples.h"
#include "strictmin/io/mesh_io.h"
#include "strictmin/mesh/generators.h"
#include "strictmin/solvers/l2.h"

using namespace strictmin;

namespace {

// A square grid with 2 * n * n triangles, boundary fixed, the centre moved sideways.
Problem grid_problem(int n) { return example_problem(make_square_example(n, 0.1)); }

Problem file_problem(const std::string& name) {
  const Mesh mesh = read_mesh(std::string(STRICTMIN_SHARED_DATA) + "/" + name);
  Problem p = make_problem(mesh);
  p.fix({{0, Eigen::Vector2d(0, 0)}});
  return p;
}

const Problem& cached(int n) {
  static std::map<int, std::unique_ptr<Problem>> cache;
  auto& slot = cache[n];
  if (!slot) slot = std::make_unique<Problem>(grid_problem(n));
  return *slot;
}

void report(benchmark::State& state, const Problem& p) {
  state.counters["elements"] = p.num_elements();
  state.counters["unknowns"] = p.num_free() * p.image_dim;
}

void BM_L2_AssembleAnalyzeFactorize(benchmark::State& state) {
  const Problem& p = cached(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    L2Solver solver(p);
    benchmark::DoNotOptimize(solver.status());
  }
  report(state, p);
}

void BM_L2_Factorize(benchmark::State& state) {
  const Problem& p = cached(static_cast<int>(state.range(0)));
  const L2Solver solver(p);
  SparseCholesky chol;
  chol.analyze(solver.matrix());
  for (auto _ : state) benchmark::DoNotOptimize(chol.factorize(solver.matrix()));
  report(state, p);
}

void BM_L2_Solve(benchmark::State& state) {
  const Problem& p = cached(static_cast<int>(state.range(0)));
  const L2Solver solver(p);
  for (auto _ : state) benchmark::DoNotOptimize(solver.solve(p));
  report(state, p);
}

void BM_L2_Total(benchmark::State& state) {
  const Problem& p = cached(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(solve_l2(p));
  report(state, p);
}

// n = 71, 158, 224: 10,082, 49,928 and 100,352 triangles.
#define L2_SIZES ->Arg(71)->Arg(158)->Arg(224)->Unit(benchmark::kMillisecond)
BENCHMARK(BM_L2_AssembleAnalyzeFactorize) L2_SIZES;
BENCHMARK(BM_L2_Factorize) L2_SIZES;
BENCHMARK(BM_L2_Solve) L2_SIZES;
BENCHMARK(BM_L2_Total) L2_SIZES;

void register_file_benchmarks() {
  for (const char* name : {"disk/face.obj", "disk/bimba_89k.obj"}) {
    if (!std::filesystem::exists(std::string(STRICTMIN_SHARED_DATA) + "/" + name)) continue;
    benchmark::RegisterBenchmark((std::string("BM_L2_Total/") + name).c_str(), [name](benchmark::State& state) {
      const Problem p = file_problem(name);
      for (auto _ : state) benchmark::DoNotOptimize(solve_l2(p));
      report(state, p);
    })->Unit(benchmark::kMillisecond);
  }
}

}  // namespace

int main(int argc, char** argv) {
  register_file_benchmarks();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
