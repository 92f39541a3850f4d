#pragma once
// Deformation with positional constraints (planar triangle meshes and tet meshes): the
// handles are fixed, every element's target is the identity (field deviation ||J - I||);
// planar meshes also take the Section 7 measures qc and iso (solvers/conformal.h).
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
  DeformStart start = DeformStart::L2;  // arap / asap: start from the L2 fd map or the rest pose
};

struct DeformOutcome {
  Problem problem;
  Result result;          // positions, the solver's field deviation, status, iterations
  Mesh deformed;          // the input mesh with the new positions
  MapDistortion measured; // distortion of the result in options.measure, stats, flips
  ConformalStats conformal;  // qc / iso: bisection steps, frame iterations
};

// Throws InputError for input the task can't take: a surface (non-planar triangle) mesh,
// no handles, a part of the mesh without a handle, a measure the method can't minimize.
DeformOutcome deform(const Mesh& mesh, const std::vector<Handle>& handles, const DeformOptions& options);

}  // namespace strictmin
