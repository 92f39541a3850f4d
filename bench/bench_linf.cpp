// One L-infinity solve (solve_linf: interior-point method on CHOLMOD) at several sizes.
//   square/N: the paper's Figure 2 on an N x N grid (2 N^2 triangles): boundary fixed,
//             centre moved sideways by 0.2;
//   bar/N:    a 4N x N bar (8 N^2 triangles), random rotation targets (+-0.5 rad), left end
//             fixed, right end moved and rotated;
//   bimba_89k: ../shared/data/disk/bimba_89k.obj as a surface (per-triangle frames, identity
//             targets), three boundary vertices fixed where an L2 map puts them
//             (three_pin_disk_problem, tasks/examples.h).
// Counters: triangles, interior-point iterations, k, certified relative gap.
// Measure on an idle machine: CHOLMOD, OpenBLAS and TBB all use both cores.
#include <benchmark/benchmark.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "benchmark_main.h"
#include "problems.h"
#include "strictmin/tasks/examples.h"
#include "strictmin/io/mesh_io.h"
#include "strictmin/mesh/generators.h"
#include "strictmin/solvers/linf.h"

using namespace strictmin;

namespace {

using bench::bar_problem;
using bench::square_problem;

LinfOptions bench_options() { return bench::linf_options_from_env(); }

void run(benchmark::State& state, const Problem& p) {
  Result r;
  const LinfOptions options = bench_options();
  for (auto _ : state) {
    r = solve_linf(p, options);
    benchmark::DoNotOptimize(r.positions.data());
  }
  const double k = r.distortion.maxCoeff();
  state.counters["triangles"] = p.num_elements();
  state.counters["iterations"] = r.iterations;
  state.counters["k"] = k;
  state.counters["gap"] = (k - r.lower_bound) / std::max(1.0, std::abs(k));
  if (!r.ok()) state.SkipWithError(("not solved: " + r.message).c_str());
}

void BM_LinfSquare(benchmark::State& state) { run(state, square_problem(static_cast<int>(state.range(0)))); }
void BM_LinfBar(benchmark::State& state) { run(state, bar_problem(static_cast<int>(state.range(0)))); }

void BM_LinfBimba(benchmark::State& state) {
  const std::string path = std::string(STRICTMIN_SHARED_DATA) + "/disk/bimba_89k.obj";
  if (!std::filesystem::exists(path)) {
    state.SkipWithError((path + " is absent").c_str());
    for (auto _ : state) {
    }
    return;
  }
  run(state, three_pin_disk_problem(read_mesh(path)));
}

}  // namespace

// ~10k, ~50k, ~100k triangles.
BENCHMARK(BM_LinfSquare)->Arg(71)->Arg(158)->Arg(224)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_LinfBar)->Arg(35)->Arg(79)->Arg(112)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_LinfBimba)->Unit(benchmark::kMillisecond)->Iterations(1);

int main(int argc, char** argv) {
  return bench::benchmark_main("bench_linf", [] { bench::linf_options_from_env(); }, argc, argv);
}
