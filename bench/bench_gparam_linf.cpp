// One L-infinity solve of the seamless problem of a closed mesh (global parametrization,
// field deviation, docs/gparam.md), with the solver's timers:
//
//   STRICTMIN_LINF_VERBOSE=1 bench_gparam_linf mesh.obj [mesh.obj ...]
//
// Prints per mesh: faces, the time of the solve (wall and process CPU), iterations, status, k, certified bound,
// seam violation (largest |A q - b|). STRICTMIN_LINF_PENALTY=1: the equalities by the penalty
// (LinfOptions::eliminate_equalities false), for comparisons. STRICTMIN_GPARAM_PARALLEL=1: the
// field made parallel with its singularities (--parallel).
#include <chrono>
#include <cstdio>
#include <ctime>
#include <cstdlib>
#include <string>

#include "problems.h"
#include "strictmin/io/mesh_io.h"
#include "strictmin/solvers/linf.h"
#include "strictmin/tasks/gparam.h"

using namespace strictmin;

namespace {
double process_cpu() {  // both cores' seconds: a figure less sensitive to other jobs than the wall clock
  timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}
}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: bench_gparam_linf mesh.obj [mesh.obj ...]\n");
    return 1;
  }
  for (int a = 1; a < argc; ++a) {
    const Mesh mesh = read_mesh(argv[a]);
    GParamOptions o;
    o.solver.method = Method::L2;
    o.parallel_field = std::getenv("STRICTMIN_GPARAM_PARALLEL") != nullptr;
    const GParamOutcome g = global_parametrize(mesh, o, argv[a]);
    LinfOptions lo = bench::linf_options_from_env();
    const auto t0 = std::chrono::steady_clock::now();
    const double c0 = process_cpu();
    if (std::getenv("STRICTMIN_LINF_PENALTY")) lo.eliminate_equalities = false;
    const Result r = solve_linf(g.problem, lo);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double cpu = process_cpu() - c0;
    // positions are #V by 2 column-major; the equalities are on the vertex-major vector.
    Eigen::VectorXd qv(r.positions.size());
    for (int v = 0; v < r.positions.rows(); ++v)
      for (int c = 0; c < r.positions.cols(); ++c) qv[v * r.positions.cols() + c] = r.positions(v, c);
    const double seam = (g.problem.eq_matrix * qv - g.problem.eq_rhs).cwiseAbs().maxCoeff();
    std::printf("%s faces %d time %.3f s cpu %.3f s iterations %d status %s k %.12f bound %.12f seam %.2e\n", argv[a],
                mesh.num_elements(), s, cpu, r.iterations, status_name(r.status).c_str(), r.distortion.maxCoeff(),
                r.lower_bound, seam);
  }
  return 0;
}
