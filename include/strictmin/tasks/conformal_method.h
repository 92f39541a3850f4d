#pragma once
// The methods of the tasks (deform, param) for the Section 7 measures qc and iso
// (solvers/conformal.h): l2 = the starting map itself (the L2 field-deviation map for
// deform, Tutte / LSCM for param), linf = bisection with frame updates, direct = Algorithm 2
// over it. relax is not offered: its exact 1-ring step (one_ring.h) is a small SOCP in one
// vertex for a convex measure, and qc / iso are convex only for fixed frames, which a 1-ring
// move changes (see docs/measures.md).
#include <Eigen/Core>

#include "strictmin/measures/measures.h"
#include "strictmin/problem/problem.h"
#include "strictmin/solvers/conformal.h"
#include "strictmin/tasks/method.h"

namespace strictmin {

bool is_conformal_measure(Measure m);  // qc or iso

// Throws InputError for a method other than l2, linf, direct (naming the supported ones).
Result run_conformal_method(const Problem& problem, const Eigen::MatrixXd& start, Measure measure,
                            const SolverOptions& options, ConformalStats* stats);

}  // namespace strictmin
