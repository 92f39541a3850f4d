#include "strictmin/tasks/deform.h"

#include <cmath>
#include <cstdio>
#include <map>

#include "strictmin/io/input_error.h"
#include "strictmin/mesh/validate.h"
#include "strictmin/problem/parts.h"
#include "strictmin/problem/surface_deformation.h"
#include "strictmin/solvers/l2.h"
#include "strictmin/solvers/no_flips.h"
#include "tasks/no_new_flips.h"
#include "strictmin/tasks/conformal_method.h"
#include "strictmin/tasks/deform_start.h"

namespace strictmin {

namespace {

// Two handles on one vertex with different targets: the later one won silently (the handle
// file and the Python module refuse them). The same target twice is one handle.
void check_one_target_per_vertex(const std::vector<Handle>& handles) {
  std::map<int, const Handle*> seen;
  for (const Handle& h : handles) {
    const auto [it, inserted] = seen.try_emplace(h.vertex, &h);
    const Eigen::VectorXd& first = it->second->position;
    if (!inserted && (first.size() != h.position.size() || first != h.position))
      throw InputError("vertex " + std::to_string(h.vertex) + " has two handles with different targets");
  }
}

}  // namespace

DeformOutcome deform(const Mesh& mesh, const std::vector<Handle>& handles, const DeformOptions& options) {
  const bool local_global_measure = options.measure == Measure::Arap || options.measure == Measure::Asap;
  const bool conformal = is_conformal_measure(options.measure);
  if (conformal && mesh.element_type() != ElementType::Triangle)
    throw InputError("--measure " + measure_name(options.measure) +
                     " is defined for planar triangle meshes (2D maps); this is a tet mesh");
  if (options.measure != Measure::FieldDeviation && !local_global_measure && !conformal)
    throw InputError("deform minimizes fd, arap or asap; '" + measure_name(options.measure) +
                     "' is not available for deformation yet");
  if (handles.empty()) throw InputError("deform needs at least one handle (--handles FILE)");
  DeformOutcome out;
  const bool surface = mesh.element_type() == ElementType::Triangle && !mesh.is_planar();
  if (surface && conformal)
    throw InputError("--measure " + measure_name(options.measure) +
                     " is defined for planar triangle meshes (2D maps); this is a triangle surface in 3D");
  // A triangle of a 3D surface maps by a 3 by 2 Jacobian: it has no determinant, so "flipped"
  // (det J <= 0) is undefined there, and no convex set of "unflipped" 3 by 2 maps exists
  // (docs/arap.md, "Surfaces in 3D").
  if (surface && (options.no_flips || options.local_global.no_flips || options.solver.relax.no_flips))
    throw InputError("--no-flips is for planar triangle meshes and tet meshes; a triangle surface in 3D has no "
                     "orientation to keep (each triangle's 3x2 Jacobian has no determinant sign)");
  // Targets within the sizes a mesh may have (kLargestSize, mesh/validate.h): a handle at 1e200
  // made every distortion overflow to inf, reported by l2 as solved.
  for (const Handle& h : handles)
    for (Eigen::Index k = 0; k < h.position.size(); ++k)
      if (!(std::abs(h.position(k)) <= kLargestSize)) {
        char value[32];
        std::snprintf(value, sizeof value, "%g", h.position(k));
        throw InputError("the handle of vertex " + std::to_string(h.vertex) + " has the coordinate " + value +
                         (std::isnan(h.position(k)) ? ", not a number"
                                                    : ", beyond 1e150 (strictmin takes sizes up to 1e150: scale the "
                                                      "mesh and the targets)"));
      }
  check_one_target_per_vertex(handles);
  out.problem = surface ? make_surface_deformation_problem(mesh) : make_problem(mesh);
  const Eigen::MatrixXd rest = out.problem.positions;
  out.problem.fix(handles);
  const std::vector<int> loose = unanchored_components(out.problem);
  if (!loose.empty())
    throw InputError("the part of the mesh containing vertex " + std::to_string(loose.front()) +
                     " has no handle, so its position is not determined; add a handle there");
  if (conformal) {
    // Section 7: from the L2 field-deviation map (where it flips, the first bisection step
    // looks for an orientation-preserving map, conformal.h).
    out.start = solve_l2(out.problem).positions;
    out.result = run_conformal_method(out.problem, out.start, options.measure, options.solver, &out.conformal);
  } else if (local_global_measure) {
    LocalGlobalOptions lg = options.local_global;
    lg.local = options.measure == Measure::Asap ? LocalStep::Similarity : LocalStep::Rotation;
    lg.no_flips = lg.no_flips || options.no_flips;
    SolverOptions solver = options.solver;
    solver.relax.no_flips = solver.relax.no_flips || options.no_flips;
    // Inverted elements of the starting map do not stop the method (paper Figure 10): the
    // local step projects them to the closest proper rotation like any other.
    out.start = options.start == DeformStart::L2 ? deform_start(out.problem, rest, handles, lg) : out.problem.positions;
    out.result = local_global(out.problem, out.start, solver, lg);
  } else {
    out.start = out.problem.positions;
    SolverOptions solver = options.solver;
    solver.relax.no_flips = solver.relax.no_flips || options.no_flips;
    // One solve, under --no-flips stepped or cut back to add no flip to the start (fd is
    // convex: a cut map's maximum is at most the start's; tasks/no_new_flips.h).
    out.result = options.no_flips ? run_method_without_new_flips(out.problem, out.start, solver)
                                  : run_method(out.problem, solver);
  }
  out.flips_added = flips_added(out.problem, out.start, out.result.positions);
  out.deformed = mesh;
  out.deformed.V = out.result.positions;
  out.measured = map_distortion(mesh, corner_images(mesh.F, out.result.positions), options.measure);
  return out;
}

}  // namespace strictmin
