#pragma once
// Deformation with positional constraints (planar triangle meshes, tet meshes, and triangle
// surfaces in 3D): the handles are fixed, every element's target is the identity (field
// deviation ||J - I||; on a surface the rest frame, surface_deformation.h); planar meshes also
// take the Section 7 measures qc and iso (solvers/conformal.h).
#include <functional>
#include <string>
#include <vector>

#include "strictmin/measures/measures.h"
#include "strictmin/mesh/handle.h"
#include "strictmin/mesh/mesh.h"
#include "strictmin/problem/problem.h"
#include "strictmin/solvers/conformal.h"
#include "strictmin/solvers/local_global.h"
#include "strictmin/solvers/result.h"
#include "strictmin/tasks/map_distortion.h"
#include "strictmin/tasks/method.h"

namespace strictmin {

enum class DeformStart { L2, Rest };

struct DeformOptions {
  SolverOptions solver;  // the method and its options
  // fd: ||J - I||; arap / asap: local-global iterations around the solver.
  Measure measure = Measure::FieldDeviation;
  LocalGlobalOptions local_global;  // arap / asap (local is set from measure)
  // arap / asap: start from the L2 fd map (the better of identity targets and targets turned
  // by the handles' best rotation, deform_start.h) or the rest pose
  DeformStart start = DeformStart::L2;
  // No new flips relative to the start (planar and tet meshes): every global step is cut
  // back to add none, relax moves stay in their rings' kernels (LocalGlobalOptions::no_flips,
  // RelaxOptions::no_flips).
  bool no_flips = false;
};

struct DeformOutcome {
  Problem problem;
  Result result;          // positions, the solver's field deviation, status, iterations
  Mesh deformed;          // the input mesh with the new positions
  MapDistortion measured; // distortion of the result in options.measure, stats, flips
  ConformalStats conformal;  // qc / iso: bisection steps, frame iterations
  Eigen::MatrixXd start;  // the map the method started from (#V by image_dim)
  int flips_added = 0;    // elements flipped in the result and not in the start
};

// Throws InputError for input the task can't take: no handles, two handles on one vertex with
// different targets, a part of the mesh without a handle, a measure the method can't minimize.
DeformOutcome deform(const Mesh& mesh, const std::vector<Handle>& handles, const DeformOptions& options);

}  // namespace strictmin
