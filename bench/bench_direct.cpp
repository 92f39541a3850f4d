// The direct strict minimizer (paper Algorithm 2, delta_k = 1e-3, k_min = 0.1 as in the
// paper) at ~10k, ~50k and ~100k triangles, on the problems of bench_linf (problems.h).
// Counters: triangles, steps (the paper's Table 1 "direct, #" column), L-infinity solves,
// the first level k and the last. Progress per step on stderr: one run takes minutes.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "benchmark_main.h"
#include "problems.h"
#include "strictmin/solvers/strict.h"

using namespace strictmin;

namespace {

constexpr int kNoLevelCap = 100000;  // DirectOptions::max_steps's default

// The environment's options; a bad value throws std::invalid_argument naming the variable.
DirectOptions options_from_env(int max_steps) {
  DirectOptions options;
  options.max_steps = max_steps;
  // STRICTMIN_DIRECT_MAX_STEPS: another cap on the levels (0: none), e.g. the bar to the end.
  if (const int steps = bench::env_int("STRICTMIN_DIRECT_MAX_STEPS", -1, 0); steps >= 0)
    options.max_steps = steps > 0 ? steps : kNoLevelCap;
  // STRICTMIN_MOVING_RINGS: DirectOptions::moving_rings (0: every vertex at every level).
  options.moving_rings = bench::env_int("STRICTMIN_MOVING_RINGS", options.moving_rings, 0);
  // STRICTMIN_DIRECT_COLD_LEVELS=1: DirectOptions::warm_levels off (--level-cold-start).
  options.warm_levels = std::getenv("STRICTMIN_DIRECT_COLD_LEVELS") == nullptr;
  return options;
}

// STRICTMIN_DIRECT_DISTORTION=FILE: each element's area and distortion, one pair per line.
// False when the file cannot be written.
bool write_distortion(const char* path, const Problem& p, const Result& r) {
  FILE* f = std::fopen(path, "w");
  if (!f) return false;
  for (Eigen::Index e = 0; e < r.distortion.size(); ++e) std::fprintf(f, "%.17g %.17g\n", p.weights[e], r.distortion[e]);
  return std::fclose(f) == 0;
}

void run(benchmark::State& state, const Problem& p, int max_steps = kNoLevelCap) {
  const char* distortion_file = std::getenv("STRICTMIN_DIRECT_DISTORTION");
  if (distortion_file) {  // a missing folder is refused before minutes of solving
    const std::filesystem::path folder = std::filesystem::path(distortion_file).parent_path();
    if (!folder.empty() && !std::filesystem::is_directory(folder)) {
      state.SkipWithError(("STRICTMIN_DIRECT_DISTORTION=" + std::string(distortion_file) + ": no folder " +
                           folder.string()).c_str());
      return;
    }
  }
  Result r;
  StrictStep last;
  DirectOptions options = options_from_env(max_steps);
  // STRICTMIN_LINF_VERBOSE=1|2: every level's interior-point iterations (as in bench_linf).
  LinfOptions linf;
  linf.verbose = bench::env_int("STRICTMIN_LINF_VERBOSE", 0, 0, 2);
  options.progress = [&](const StrictStep& s) {
    last = s;
    std::fprintf(stderr, "  step %d: k %.6f, fixed %d (+%d), %d ipm iterations, %d free vertices, %.1f s\n", s.step,
                 s.k, s.fixed_total, s.fixed_now, s.level_iterations, s.level_free_vertices, s.time_s);
  };
  for (auto _ : state) {
    r = solve_direct(p, options, linf);
    benchmark::DoNotOptimize(r.positions.data());
  }
  state.counters["triangles"] = p.num_elements();
  state.counters["steps"] = r.iterations;
  state.counters["solves"] = last.solves;
  state.counters["k_first"] = r.history.empty() ? 0.0 : r.history.front().max_distortion;
  state.counters["k_last"] = r.history.empty() ? 0.0 : r.history.back().max_distortion;
  state.counters["worst_level_gap"] = worst_level_gap(r);
  if (!r.message.empty()) std::fprintf(stderr, "direct: %s\n", r.message.c_str());
  if (distortion_file && !write_distortion(distortion_file, p, r))
    state.SkipWithError(("STRICTMIN_DIRECT_DISTORTION=" + std::string(distortion_file) + ": cannot be written").c_str());
  // A run capped on purpose (the bar, or STRICTMIN_DIRECT_MAX_STEPS) ends max-iterations at its
  // level cap: that is the request. The cap is the effective one, options.max_steps.
  const bool capped = options.max_steps < kNoLevelCap && r.status == SolveStatus::MaxIterations &&
                      r.iterations == options.max_steps;
  if (!r.ok() && !capped) state.SkipWithError(("not solved: " + status_name(r.status) + ": " + r.message).c_str());
}

void BM_DirectSquare(benchmark::State& state) { run(state, bench::square_problem(static_cast<int>(state.range(0)))); }
// The bar's random rotation targets spread the distortion over a continuum of values: most
// levels fix a handful of elements, so a run to k_min would take hundreds of levels. It is
// timed over its first 50 levels (per-level cost and conditioning; docs/performance.md).
void BM_DirectBar(benchmark::State& state) {
  run(state, bench::bar_problem(static_cast<int>(state.range(0))), 50);
}

}  // namespace

// ~10k, ~50k, ~100k triangles.
BENCHMARK(BM_DirectSquare)->Arg(71)->Arg(158)->Arg(224)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_DirectBar)->Arg(35)->Arg(79)->Arg(112)->Unit(benchmark::kSecond)->Iterations(1);

// The environment is checked before the first benchmark (a bad value: exit 1).
static void check_environment() {
  options_from_env(kNoLevelCap);
  bench::env_int("STRICTMIN_LINF_VERBOSE", 0, 0, 2);
}

int main(int argc, char** argv) { return bench::benchmark_main("bench_direct", check_environment, argc, argv); }
