// One L-infinity solve of the seamless problem of a closed mesh (global parametrization,
// field deviation, docs/gparam.md), with the solver's timers:
//
//   STRICTMIN_LINF_VERBOSE=1 bench_gparam_linf mesh.obj [mesh.obj ...]
//
// Prints per mesh: faces, the time of the solve (wall and process CPU), iterations, status, k, certified bound,
// seam violation (largest |A q - b|). STRICTMIN_LINF_PENALTY=1: the equalities by the penalty
// (LinfOptions::eliminate_equalities false), for comparisons. STRICTMIN_GPARAM_PARALLEL=1: the
// field made parallel with its singularities (--parallel).
// Exits 1 with a message on bad input (an option, a mesh that does not read or is not closed,
// a bad environment value): the lines of the meshes before it are printed.
#include <chrono>
#include <cstdio>
#include <ctime>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "args.h"
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

constexpr const char* kUsage =
    "usage: bench_gparam_linf MESH.obj [MESH.obj ...]\n"
    "One L-infinity solve of each closed mesh's seamless problem (environment: see the source's header).\n";

// The meshes of the command line; --help prints the usage (and returns no meshes).
std::vector<std::string> parse_meshes(int argc, char** argv, bool& help) {
  std::vector<std::string> meshes;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--help" || a == "-h") {
      help = true;
      return {};
    }
    if (a.rfind("-", 0) == 0) throw std::invalid_argument(a + ": unknown option\n" + kUsage);
    meshes.push_back(a);
  }
  if (meshes.empty()) throw std::invalid_argument(std::string("no mesh given\n") + kUsage);
  return meshes;
}

// Largest |A q - b| of the seam equalities; positions are #V by 2, the equalities are on the
// vertex-major vector.
double seam_violation(const Problem& p, const Eigen::MatrixXd& X) {
  Eigen::VectorXd qv(X.size());
  for (int v = 0; v < X.rows(); ++v)
    for (int c = 0; c < X.cols(); ++c) qv[v * X.cols() + c] = X(v, c);
  return (p.eq_matrix * qv - p.eq_rhs).cwiseAbs().maxCoeff();
}

int run(int argc, char** argv) {
  bool help = false;
  const std::vector<std::string> meshes = parse_meshes(argc, argv, help);
  if (help) {
    std::fputs(kUsage, stdout);
    return 0;
  }
  const int verbose = bench::env_int("STRICTMIN_LINF_VERBOSE", 0, 0, 2);  // checked before the first solve
  for (const std::string& file : meshes) {
    const Mesh mesh = read_mesh(file);
    GParamOptions o;
    o.solver.method = Method::L2;
    o.parallel_field = std::getenv("STRICTMIN_GPARAM_PARALLEL") != nullptr;
    const GParamOutcome g = global_parametrize(mesh, o, file);
    LinfOptions lo = bench::linf_options_from_env();
    lo.verbose = verbose;
    if (std::getenv("STRICTMIN_LINF_PENALTY")) lo.eliminate_equalities = false;
    const auto t0 = std::chrono::steady_clock::now();
    const double c0 = process_cpu();
    const Result r = solve_linf(g.problem, lo);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double cpu = process_cpu() - c0;
    std::printf("%s faces %d time %.3f s cpu %.3f s iterations %d status %s k %.12f bound %.12f seam %.2e\n",
                file.c_str(), mesh.num_elements(), s, cpu, r.iterations, status_name(r.status).c_str(),
                r.distortion.maxCoeff(), r.lower_bound, seam_violation(g.problem, r.positions));
    std::fflush(stdout);  // a later mesh's error must not lose this line
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return bench::guarded_main("bench_gparam_linf", run, argc, argv); }
