#pragma once
// Free-boundary parametrization of a disk-topology surface (paper Section 6, the main use
// case): an initial map (Tutte or LSCM), then the chosen method around it. arap / asap run
// local-global iterations (docs/maths.md section 4); fd takes its frames from the initial map
// (one local step: R_T = closest rotation to the initial J_T) and then runs the method once.
// One boundary vertex is pinned where the initial map puts it: with a free boundary the
// problem is otherwise translation invariant (singular for L2, unbounded directions for linf).
#include <string>
#include <vector>

#include "strictmin/measures/measures.h"
#include "strictmin/mesh/mesh.h"
#include "strictmin/problem/problem.h"
#include "strictmin/solvers/conformal.h"
#include "strictmin/solvers/local_global.h"
#include "strictmin/solvers/result.h"
#include "strictmin/tasks/map_distortion.h"
#include "strictmin/tasks/method.h"

namespace strictmin {

enum class ParamInit { Tutte, Lscm };

std::string init_name(ParamInit i);  // "tutte", "lscm"

struct ParamOptions {
  Measure measure = Measure::Arap;  // arap, asap, fd, or qc / iso (solvers/conformal.h, from the initial map)
  ParamInit init = ParamInit::Tutte;
  bool init_only = false;           // the initial map is the result (--method tutte|lscm)
  SolverOptions solver;
  LocalGlobalOptions local_global;  // arap / asap (local is set from measure)
  // No new flips relative to the initial map (flip-free from Tutte): every global step cut
  // back to add none, relax moves inside their rings' kernels (local_global.h, relax.h).
  bool no_flips = false;
};

struct ParamOutcome {
  Problem problem;             // after the fd frames / last local step
  std::vector<int> boundary;   // the boundary loop
  Eigen::MatrixXd initial;     // #V by 2, oriented and scaled to the surface's area
  double init_time_s = 0;
  Result result;               // positions = the map
  Mesh mapped;                 // the input mesh with UV = the map, FUV = F
  MapDistortion measured;      // in options.measure (fd: against the frames)
  int flips = 0;               // triangles against the majority orientation
  int flips_added = 0;         // triangles with det J <= 0 in the map and > 0 in the initial map
  bool boundary_overlap = false;
  std::vector<std::string> warnings;  // what the status does not say: flipped triangles, an overlapping boundary
  ConformalStats conformal;    // qc / iso: bisection steps, frame iterations
};

// Throws InputError when the mesh is not a disk (param/topology.h) or the measure is not
// arap, asap or fd. `source` names the mesh in messages.
ParamOutcome parametrize(const Mesh& mesh, const ParamOptions& options, const std::string& source = "");

}  // namespace strictmin
