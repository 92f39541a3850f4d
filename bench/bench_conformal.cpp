// qc / iso by bisection over convex cones (solvers/conformal.h, paper Section 7).
//   QcStep/N/F:     one feasibility program (one bisection step) on Figure 2's set-up, N x N
//                   grid (2 N^2 triangles), frames from a coarse first frame iteration, level
//                   1% (F = 0: infeasible) or 0.1% (F = 1) below its maximum;
//   QcFrames/N:     one frame iteration (a whole bisection for one set of frames, bracket 1e-6);
//   QcLinf/N, QcDirect/N: the whole qc linf / direct (delta_k 1e-2) from the L2 map;
//   QcLinfDisk, QcDirectDisk: the same on ../shared/data/disk/dragon.obj (10,000 triangles),
//                   parametrized from Tutte with two pins (tasks/param.h).
//   IsoFrames/N/P:  one iso frame iteration from the L2 map (bracket 1e-6), P = 1: the level
//                   in one program (iso_level.h), P = 0: by bisection;
//   IsoLinf/N, IsoLinfDisk: the whole iso linf (square from L2; dragon from Tutte).
// Counters: triangles, bisection steps, frame iterations, interior-point iterations, K.
// Each runs once (Iterations(1)): the larger ones take minutes on 2 cores.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <string>

#include "problems.h"
#include "strictmin/io/mesh_io.h"
#include "strictmin/solvers/conformal.h"
#include "strictmin/solvers/l2.h"
#include "solvers/qc/bisection.h"
#include "strictmin/tasks/param.h"

using namespace strictmin;

namespace {

void QcStep(benchmark::State& state) {
  const Problem p = bench::square_problem(static_cast<int>(state.range(0)));
  const qc::ConformalParts parts = qc::conformal_parts(p);
  // The start: one coarse frame iteration from the L2 map (which flips near the centre).
  ConformalOptions coarse;
  coarse.max_frame_iterations = 1;
  coarse.bisection_tolerance = 1e-2;
  const Eigen::VectorXd x = p.free_dofs(solve_conformal_linf(p, solve_l2(p).positions, coarse).positions);
  qc::SparseCholeskyCache cache;
  qc::BisectionSetup s;
  s.parts = &parts;
  s.frames = qc::frames_of(parts, x);
  s.slack_scale = qc::slack_scales(Measure::Quasiconformal, parts, x);  // as solve_conformal_linf
  s.ipm = qc::feasibility_settings(80);
  s.cache = &cache;
  // Arg 2: 0 = a level 1% below the start's maximum (infeasible: the full program), 1 = 0.1%
  // below (feasible).
  const double level = (state.range(1) ? 0.999 : 0.99) * qc::free_max(s, x);
  int iterations = 0;
  qc::Verdict verdict = qc::Verdict::Undecided;
  for (auto _ : state) {
    const qc::FeasibilityTest t = qc::test_level(s, level, x);
    iterations = t.ipm_iterations;
    verdict = t.verdict;
  }
  state.counters["feasible"] = verdict == qc::Verdict::Feasible;
  state.counters["triangles"] = p.num_elements();
  state.counters["ipm_iterations"] = iterations;
}

void report(benchmark::State& state, const Problem& p, const Result& r, const ConformalStats& st) {
  state.counters["triangles"] = p.num_elements();
  state.counters["bisection_steps"] = st.bisection_steps;
  state.counters["frame_iterations"] = st.frame_iterations;
  state.counters["ipm_iterations"] = st.ipm_iterations;
  state.counters["K"] = r.distortion.maxCoeff();
  state.counters["solved"] = r.status == SolveStatus::Solved;
}

// One frame iteration from the L2 map, bracket 1e-6 (iso: in one program or by bisection).
void frames(benchmark::State& state, Measure measure, bool iso_one_program) {
  const Problem p = bench::square_problem(static_cast<int>(state.range(0)));
  const Eigen::MatrixXd start = solve_l2(p).positions;
  ConformalOptions o;
  o.measure = measure;
  o.iso_one_program = iso_one_program;
  o.max_frame_iterations = 1;
  o.bisection_tolerance = 1e-6;
  for (auto _ : state) {
    ConformalStats st;
    const Result r = solve_conformal_linf(p, start, o, &st);
    report(state, p, r, st);
  }
}
void QcFrames(benchmark::State& state) { frames(state, Measure::Quasiconformal, true); }
void IsoFrames(benchmark::State& state) { frames(state, Measure::Isometric, state.range(1) == 1); }

void IsoLinf(benchmark::State& state) {
  const Problem p = bench::square_problem(static_cast<int>(state.range(0)));
  const Eigen::MatrixXd start = solve_l2(p).positions;
  ConformalOptions o;
  o.measure = Measure::Isometric;
  for (auto _ : state) {
    ConformalStats st;
    const Result r = solve_conformal_linf(p, start, o, &st);
    report(state, p, r, st);
  }
}

void QcLinf(benchmark::State& state) {
  const Problem p = bench::square_problem(static_cast<int>(state.range(0)));
  const Eigen::MatrixXd start = solve_l2(p).positions;
  for (auto _ : state) {
    ConformalStats st;
    const Result r = solve_conformal_linf(p, start, ConformalOptions{}, &st);
    report(state, p, r, st);
  }
}

void QcDirect(benchmark::State& state) {
  const Problem p = bench::square_problem(static_cast<int>(state.range(0)));
  const Eigen::MatrixXd start = solve_l2(p).positions;
  DirectOptions d;
  d.delta_k = 1e-2;
  d.k_min = 1.0;
  for (auto _ : state) {
    ConformalStats st;
    const Result r = solve_conformal_direct(p, start, ConformalOptions{}, d, &st);
    report(state, p, r, st);
    state.counters["levels"] = r.iterations;
  }
}

void Disk(benchmark::State& state, Method method, Measure measure = Measure::Quasiconformal) {
  const std::string path = std::string(STRICTMIN_SHARED_DATA) + "/disk/dragon.obj";
  if (!std::filesystem::exists(path)) {
    state.SkipWithError("../shared/data/disk/dragon.obj is absent");
    return;
  }
  const Mesh mesh = read_mesh(path);
  ParamOptions o;
  o.measure = measure;
  o.solver.method = method;
  o.solver.direct.delta_k = 1e-2;
  o.solver.direct.k_min = 1.0;
  for (auto _ : state) {
    const ParamOutcome out = parametrize(mesh, o, path);
    report(state, out.problem, out.result, out.conformal);
    state.counters["flips"] = out.flips;
  }
}
void QcLinfDisk(benchmark::State& state) { Disk(state, Method::Linf); }
void QcDirectDisk(benchmark::State& state) { Disk(state, Method::Direct); }
void IsoLinfDisk(benchmark::State& state) { Disk(state, Method::Linf, Measure::Isometric); }

}  // namespace

BENCHMARK(QcStep)->Args({71, 0})->Args({71, 1})->Args({158, 0})->Args({158, 1})->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(QcFrames)->Arg(71)->Arg(158)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(QcLinf)->Arg(71)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(QcLinfDisk)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(QcDirect)->Arg(71)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(QcDirectDisk)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(IsoFrames)->Args({71, 1})->Args({71, 0})->Args({158, 1})->Args({158, 0})->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(IsoLinf)->Arg(71)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(IsoLinfDisk)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_MAIN();
