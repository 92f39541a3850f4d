#include "strictmin/tasks/deform.h"

#include "strictmin/io/input_error.h"
#include "strictmin/problem/parts.h"
#include "strictmin/solvers/l2.h"
#include "strictmin/tasks/conformal_method.h"

namespace strictmin {

DeformOutcome deform(const Mesh& mesh, const std::vector<Handle>& handles, const DeformOptions& options) {
  if (mesh.element_type() == ElementType::Triangle && !mesh.is_planar())
    throw InputError("deform needs a planar triangle mesh (every z equal) or a tet mesh; this is a 3D surface");
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
  out.problem = make_problem(mesh);
  out.problem.fix(handles);
  const std::vector<int> loose = unanchored_components(out.problem);
  if (!loose.empty())
    throw InputError("the part of the mesh containing vertex " + std::to_string(loose.front()) +
                     " has no handle, so its position is not determined; add a handle there");
  if (conformal) {
    // Section 7: from the L2 field-deviation map (where it flips, the first bisection step
    // looks for an orientation-preserving map, conformal.h).
    out.result = run_conformal_method(out.problem, solve_l2(out.problem).positions, options.measure, options.solver,
                                      &out.conformal);
  } else if (local_global_measure) {
    LocalGlobalOptions lg = options.local_global;
    lg.local = options.measure == Measure::Asap ? LocalStep::Similarity : LocalStep::Rotation;
    // Inverted elements of the starting map do not stop the method (paper Figure 10): the
    // local step projects them to the closest proper rotation like any other.
    const Eigen::MatrixXd start = options.start == DeformStart::L2 ? solve_l2(out.problem).positions
                                                                  : out.problem.positions;
    out.result = local_global(out.problem, start, options.solver, lg);
  } else {
    out.result = run_method(out.problem, options.solver);
  }
  out.deformed = mesh;
  out.deformed.V = out.result.positions;
  out.measured = map_distortion(mesh, corner_images(mesh.F, out.result.positions), options.measure);
  return out;
}

}  // namespace strictmin
