// Direct (Algorithm 2) on the seamless problem of a closed mesh (global parametrization,
// docs/gparam.md), one line per level, for studying its levels' Newton systems:
//
//   bench_gparam_direct mesh.obj
//
// Environment: STRICTMIN_DIRECT_MAX_STEPS=N (stop after N levels), STRICTMIN_DIRECT_VERBOSE_LEVEL=L
// with STRICTMIN_LINF_VERBOSE=1|2 (the interior-point lines of level L only; every level when
// L is unset; these two run the levels through a level solver of the benchmark's own, which
// turns pinning off), STRICTMIN_LINF_PENALTY=1 (the equalities by the penalty from the start),
// STRICTMIN_MOVING_RINGS=R (DirectOptions::moving_rings), STRICTMIN_GPARAM_FIELD=curvature|unit (the
// curvature-aligned field, --field curvature, or the unit field, --field unit, instead of the smoothest).
// STRICTMIN_DIRECT_NO_PIN=1: DirectOptions::pin_essential off (--no-pin).
// STRICTMIN_DIRECT_COLD_LEVELS=1: DirectOptions::warm_levels off (--level-cold-start).
// Prints the levels, the time (wall and process CPU), the status and the message. Exits 1 with
// a message on bad input (an option, a mesh that does not read or is not closed, a bad
// environment value such as STRICTMIN_MOVING_RINGS=-1).
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <stdexcept>
#include <string>

#include "args.h"
#include "strictmin/io/mesh_io.h"
#include "strictmin/solvers/linf.h"
#include "strictmin/solvers/strict.h"
#include "strictmin/tasks/gparam.h"

using namespace strictmin;

namespace {
double process_cpu() {
  timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

constexpr const char* kUsage =
    "usage: bench_gparam_direct MESH.obj\n"
    "Direct on a closed mesh's seamless problem, one line per level (environment: see the source's header).\n";

// STRICTMIN_GPARAM_FIELD: the field of the global parametrization.
void field_from_env(GParamOptions& o) {
  const char* f = std::getenv("STRICTMIN_GPARAM_FIELD");
  if (!f) return;
  const std::string field = f;
  if (field != "smoothest" && field != "curvature" && field != "unit")
    throw std::invalid_argument("STRICTMIN_GPARAM_FIELD=" + field + ": smoothest, curvature or unit");
  o.curvature_field = field == "curvature";
  o.field_options.unit = field == "unit";
}

// "N moving vertices", or "all vertices moving" when the level does not say (-1: every vertex).
std::string moving(int vertices) {
  return vertices < 0 ? "all vertices moving" : std::to_string(vertices) + " moving vertices";
}

int run(int argc, char** argv) {
  if (argc == 2 && (std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h")) {
    std::fputs(kUsage, stdout);
    return 0;
  }
  if (argc != 2) throw std::invalid_argument(std::string(argc < 2 ? "no mesh given" : "one mesh only") + "\n" + kUsage);
  const std::string file = argv[1];
  if (file.rfind("-", 0) == 0) throw std::invalid_argument(file + ": unknown option\n" + kUsage);
  // The environment first: a bad value is refused before minutes of solving.
  DirectOptions direct;
  direct.delta_k = 1e-3;
  direct.k_min = 0.1;
  if (const int steps = bench::env_int("STRICTMIN_DIRECT_MAX_STEPS", 0, 0); steps > 0) direct.max_steps = steps;
  direct.pin_essential = std::getenv("STRICTMIN_DIRECT_NO_PIN") == nullptr;
  direct.warm_levels = std::getenv("STRICTMIN_DIRECT_COLD_LEVELS") == nullptr;
  direct.moving_rings = bench::env_int("STRICTMIN_MOVING_RINGS", direct.moving_rings, 0);
  const int verbose = bench::env_int("STRICTMIN_LINF_VERBOSE", 0, 0, 2);
  const int verbose_level = bench::env_int("STRICTMIN_DIRECT_VERBOSE_LEVEL", 0, 0);
  const bool penalty = std::getenv("STRICTMIN_LINF_PENALTY") != nullptr;
  GParamOptions o;
  o.solver.method = Method::L2;
  field_from_env(o);

  const Mesh mesh = read_mesh(file);
  const GParamOutcome g = global_parametrize(mesh, o, file);
  int level = 0;
  // A level solver of our own (for the verbose lines and the penalty) turns pinning off
  // (DirectOptions::level_solver): set only when asked for.
  if (verbose || penalty) direct.level_solver = [&](const Problem& p, const LinfOptions& lo, const Eigen::MatrixXd& X) {
    ++level;
    LinfOptions l = lo;
    l.verbose = verbose_level == 0 || verbose_level == level ? verbose : 0;
    if (penalty) l.eliminate_equalities = false;
    Problem q = p;
    q.positions = X;
    Result r = solve_linf(q, l);
    if (r.status != SolveStatus::Solved)
      std::fprintf(stderr, "level %d (%d free vertices, %d equalities): %s: %s\n", level, q.num_free(),
                   static_cast<int>(q.eq_matrix.rows()), status_name(r.status).c_str(), r.message.c_str());
    return r;
  };
  direct.progress = [&](const StrictStep& s) {
    std::fprintf(stderr, "level %d: k %.8f, fixed %d (+%d), %d ipm iterations, %s, %.2f s\n", s.step, s.k,
                 s.fixed_total, s.fixed_now, s.level_iterations, moving(s.level_free_vertices).c_str(), s.time_s);
  };
  const auto t0 = std::chrono::steady_clock::now();
  const double c0 = process_cpu();
  const Result r = solve_direct(g.problem, direct, LinfOptions{});
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("%s faces %d levels %d time %.2f s cpu %.2f s status %s worst level gap %.3g\n%s\n", file.c_str(),
              mesh.num_elements(), r.iterations, s, process_cpu() - c0, status_name(r.status).c_str(),
              worst_level_gap(r), r.message.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return bench::guarded_main("bench_gparam_direct", run, argc, argv); }
