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
// Prints the levels, the time (wall and process CPU), the status and the message.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>

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
int env_int(const char* name, int fallback) {
  const char* v = std::getenv(name);
  return v ? std::atoi(v) : fallback;
}
}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: bench_gparam_direct mesh.obj\n");
    return 1;
  }
  const Mesh mesh = read_mesh(argv[1]);
  GParamOptions o;
  o.solver.method = Method::L2;
  if (const char* f = std::getenv("STRICTMIN_GPARAM_FIELD")) {
    const std::string field = f;
    if (field != "smoothest" && field != "curvature" && field != "unit") {
      std::fprintf(stderr, "STRICTMIN_GPARAM_FIELD=%s: smoothest, curvature or unit\n", f);
      return 1;
    }
    o.curvature_field = field == "curvature";
    o.field_options.unit = field == "unit";
  }
  const GParamOutcome g = global_parametrize(mesh, o, argv[1]);
  DirectOptions direct;
  direct.delta_k = 1e-3;
  direct.k_min = 0.1;
  if (const int steps = env_int("STRICTMIN_DIRECT_MAX_STEPS", 0); steps > 0) direct.max_steps = steps;
  direct.pin_essential = std::getenv("STRICTMIN_DIRECT_NO_PIN") == nullptr;
  direct.warm_levels = std::getenv("STRICTMIN_DIRECT_COLD_LEVELS") == nullptr;
  direct.moving_rings = env_int("STRICTMIN_MOVING_RINGS", direct.moving_rings);
  const int verbose = env_int("STRICTMIN_LINF_VERBOSE", 0);
  const int verbose_level = env_int("STRICTMIN_DIRECT_VERBOSE_LEVEL", 0);
  const bool penalty = std::getenv("STRICTMIN_LINF_PENALTY") != nullptr;
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
    std::fprintf(stderr, "level %d: k %.8f, fixed %d (+%d), %d ipm iterations, %d moving vertices, %.2f s\n", s.step,
                 s.k, s.fixed_total, s.fixed_now, s.level_iterations, s.level_free_vertices, s.time_s);
  };
  const auto t0 = std::chrono::steady_clock::now();
  const double c0 = process_cpu();
  const Result r = solve_direct(g.problem, direct, LinfOptions{});
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("%s faces %d levels %d time %.2f s cpu %.2f s status %s worst level gap %.3g\n%s\n", argv[1],
              mesh.num_elements(), r.iterations, s, process_cpu() - c0, status_name(r.status).c_str(),
              worst_level_gap(r), r.message.c_str());
  return 0;
}
