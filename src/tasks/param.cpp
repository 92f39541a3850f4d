#include "strictmin/tasks/param.h"

#include <chrono>

#include "strictmin/io/input_error.h"
#include "strictmin/param/lscm.h"
#include "strictmin/param/topology.h"
#include "strictmin/param/tutte.h"
#include "strictmin/param/uv_checks.h"
#include "strictmin/report/stats.h"
#include "strictmin/solvers/no_flips.h"

namespace strictmin {
namespace {

// fd against the problem's frames: ||J_T - R_T||_F.
MapDistortion frame_distortion(const Problem& p, const Eigen::MatrixXd& X) {
  MapDistortion d;
  const int E = p.num_elements();
  d.distortion.resize(E);
  d.flipped = Eigen::VectorXi::Zero(E);
  d.weights = p.weights;
  for (int e = 0; e < E; ++e) {
    const Eigen::MatrixXd J = p.jacobian(e, X);
    d.distortion(e) = (J - p.target(e)).norm();
    d.flipped(e) = is_flipped(J) ? 1 : 0;
  }
  d.stats = distortion_stats(d.distortion, d.weights);
  d.stats.flipped = d.flipped.sum();
  return d;
}

}  // namespace

std::string init_name(ParamInit i) { return i == ParamInit::Tutte ? "tutte" : "lscm"; }

ParamOutcome parametrize(const Mesh& mesh, const ParamOptions& options, const std::string& source) {
  const Measure m = options.measure;
  if (m != Measure::Arap && m != Measure::Asap && m != Measure::FieldDeviation)
    throw InputError("param minimizes arap, asap or fd; '" + measure_name(m) + "' is not available");
  ParamOutcome out;
  out.boundary = disk_boundary(mesh, source);
  out.problem = make_problem(mesh);
  const auto t0 = std::chrono::steady_clock::now();
  out.initial = options.init == ParamInit::Tutte ? tutte_embedding(mesh, out.boundary) : lscm(mesh, out.boundary);
  orient_and_scale(out.problem.elements, out.initial, out.problem.weights.sum());
  out.init_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  Problem& p = out.problem;
  p.positions = out.initial;
  p.fix({Handle{out.boundary.front(), out.initial.row(out.boundary.front()).transpose()}});
  LocalGlobalOptions lg = options.local_global;
  lg.local = m == Measure::Asap ? LocalStep::Similarity : LocalStep::Rotation;
  lg.no_flips = lg.no_flips || options.no_flips;
  SolverOptions solver = options.solver;
  solver.relax.no_flips = solver.relax.no_flips || options.no_flips;
  if (options.init_only) {
    out.result.positions = out.initial;
    out.result.time_s = out.init_time_s;
    if (m == Measure::FieldDeviation) local_step(p, out.initial, lg);
  } else if (m == Measure::FieldDeviation) {
    local_step(p, out.initial, lg);  // the frames: rotations of the initial map
    out.result = run_method(p, solver);
    // One solve: cut back along the segment from the initial map when it adds flips (fd is
    // convex, so the cut map's maximum is at most the initial map's).
    if (options.no_flips && out.result.usable())
      out.result.positions = cut_back_to_no_new_flips(p, out.initial, out.result.positions);
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
  return out;
}

}  // namespace strictmin
