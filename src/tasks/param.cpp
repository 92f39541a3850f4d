#include "strictmin/tasks/param.h"

#include <chrono>

#include "strictmin/io/input_error.h"
#include "strictmin/param/lscm.h"
#include "strictmin/param/topology.h"
#include "strictmin/param/tutte.h"
#include "strictmin/param/uv_checks.h"
#include "strictmin/report/stats.h"
#include "strictmin/tasks/conformal_method.h"
#include "strictmin/solvers/no_flips.h"
#include "tasks/no_new_flips.h"
#include "tasks/unit_size.h"

namespace strictmin {
namespace {

ParamOutcome parametrize_as_given(const Mesh& mesh, const ParamOptions& options, const std::string& source);

// A problem of the surface scaled down by `scale`, in the surface's units: lengths times
// scale, gradients divided by it, areas times its square (the targets, rotations or frames of
// the map's Jacobians, do not change with a uniform scale).
void scale_problem_up(Problem& p, double scale) {
  p.positions *= scale;
  p.gradients /= scale;
  p.weights *= scale * scale;
  p.eq_rhs *= scale;
}

// The outcome of the surface scaled down by `scale`, in the surface's units.
void scale_outcome_up(ParamOutcome& out, const Mesh& mesh, double scale) {
  scale_problem_up(out.problem, scale);
  out.initial *= scale;
  out.result.positions *= scale;
  for (IterationRecord& record : out.result.history) record.largest_move *= scale;
  out.mapped = mesh;
  out.mapped.UV = out.result.positions;
  out.mapped.FUV = mesh.F;
  out.measured.weights *= scale * scale;
}

// What the status does not say: a map that folds over itself (flipped triangles, a
// boundary that crosses itself) meets its method's criterion all the same. ASAP's L-infinity
// map of bimba_1k had 639 of 1,275 triangles flipped, "solved"; with --no-flips, 0 at almost
// the same maximum.
void add_fold_warnings(const Mesh& mesh, const ParamOptions& options, ParamOutcome& out) {
  if (out.flips > 0)
    out.warnings.push_back(std::to_string(out.flips) + " of " + std::to_string(mesh.num_elements()) +
                           " triangles are flipped (turned against the map's majority orientation): the map folds "
                           "over itself there" +
                           (options.no_flips ? std::string(" (flipped in the starting map already: --no-flips keeps "
                                                           "orientations, it does not mend them)")
                                             : std::string("; --no-flips keeps every triangle's orientation")));
  if (out.boundary_overlap)
    out.warnings.push_back("the map's boundary crosses itself: the map overlaps itself (not a bijection)");
}

}  // namespace

std::string init_name(ParamInit i) { return i == ParamInit::Tutte ? "tutte" : "lscm"; }

// The map is homogeneous in the surface's size (free boundary, one pinned vertex where the
// start puts it, targets of Jacobians), so a surface far from unit size is parametrized
// scaled down by a power of two and its map scaled back: the file's units change nothing (a
// disk with coordinates about 1e55 stopped on "gradients are not finite", one about 1e-55
// ended numerical-error with a maximum of 7e83).
ParamOutcome parametrize(const Mesh& mesh, const ParamOptions& options, const std::string& source) {
  // The starting map itself is returned as computed: no solve to keep from flipping (LSCM's
  // map may flip triangles, and the summary said no_flips all the same).
  if (options.init_only && options.no_flips)
    throw InputError(std::string("--no-flips applies to a solve, and --method ") +
                     (options.init == ParamInit::Tutte ? "tutte" : "lscm") +
                     " returns the starting map itself (Tutte's has no flip; LSCM's may): drop --no-flips, or "
                     "solve from it (--method l2|linf|... --init " +
                     (options.init == ParamInit::Tutte ? "tutte" : "lscm") + ")");
  const double scale = unit_size_scale(mesh);
  if (scale == 1) return parametrize_as_given(mesh, options, source);
  ParamOptions scaled_options = options;
  scaled_options.solver.relax.move_tolerance /= scale;  // a length: surface units
  ParamOutcome out = parametrize_as_given(scaled_down(mesh, scale), scaled_options, source);
  scale_outcome_up(out, mesh, scale);
  return out;
}

namespace {

ParamOutcome parametrize_as_given(const Mesh& mesh, const ParamOptions& options, const std::string& source) {
  const Measure m = options.measure;
  const bool conformal = is_conformal_measure(m);
  if (m != Measure::Arap && m != Measure::Asap && m != Measure::FieldDeviation && !conformal)
    throw InputError("param minimizes arap, asap, fd, qc or iso; '" + measure_name(m) + "' is not available");
  ParamOutcome out;
  out.boundary = disk_boundary(mesh, source);
  out.problem = make_problem(mesh);
  const auto t0 = std::chrono::steady_clock::now();
  out.initial = options.init == ParamInit::Tutte ? tutte_embedding(mesh, out.boundary) : lscm(mesh, out.boundary);
  orient_and_scale(out.problem.elements, out.initial, out.problem.weights.sum());
  out.init_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  Problem& p = out.problem;
  p.positions = out.initial;
  std::vector<Handle> pins{Handle{out.boundary.front(), out.initial.row(out.boundary.front()).transpose()}};
  // qc and asap are invariant under similarities: a second pin (the boundary vertex halfway
  // round) fixes rotation and scale as well. Without it asap's minimizers shrink the map to a
  // point (distortion 0: every J is the zero similarity), and qc's bisection slack could grow
  // by scaling.
  if ((m == Measure::Quasiconformal || m == Measure::Asap) && out.boundary.size() > 2) {
    const int v = out.boundary[out.boundary.size() / 2];
    pins.push_back(Handle{v, out.initial.row(v).transpose()});
  }
  p.fix(pins);
  LocalGlobalOptions lg = options.local_global;
  lg.local = m == Measure::Asap ? LocalStep::Similarity : LocalStep::Rotation;
  lg.no_flips = lg.no_flips || options.no_flips;
  SolverOptions solver = options.solver;
  solver.relax.no_flips = solver.relax.no_flips || options.no_flips;
  if (options.init_only) {
    out.result.positions = out.initial;
    out.result.time_s = out.init_time_s;
    out.result.message = options.init == ParamInit::Tutte ? "the starting map itself: Tutte's embedding (boundary on a circle)"
                                                          : "the starting map itself: LSCM (two boundary vertices pinned)";
    if (m == Measure::FieldDeviation) local_step(p, out.initial, lg);
  } else if (conformal) {
    out.result = run_conformal_method(p, out.initial, m, options.solver, &out.conformal);
  } else if (m == Measure::FieldDeviation) {
    local_step(p, out.initial, lg);  // the frames: rotations of the initial map
    // One solve, under --no-flips stepped or cut back to add no flip to the initial map
    // (tasks/no_new_flips.h).
    out.result = options.no_flips ? run_method_without_new_flips(p, out.initial, solver) : run_method(p, solver);
  } else {
    out.result = local_global(p, out.initial, solver, lg);
  }
  const Eigen::MatrixXd& X = out.result.positions;
  out.mapped = mesh;
  out.mapped.UV = X;
  out.mapped.FUV = mesh.F;
  out.measured = m == Measure::FieldDeviation ? frame_distortion(p, X) : map_distortion(mesh, corner_images(mesh.F, X), m);
  if (options.init_only) out.result.distortion = out.measured.distortion;
  out.flips = count_flips(mesh.F, X);
  out.flips_added = flips_added(p, out.initial, X);
  out.boundary_overlap = polygon_self_intersects(X, out.boundary);
  add_fold_warnings(mesh, options, out);
  return out;
}

}  // namespace

}  // namespace strictmin
