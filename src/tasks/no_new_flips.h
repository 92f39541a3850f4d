#pragma once
// One solve that adds no flip to its start (--no-flips with fd in deform and param), and relax
// (paper Algorithm 3) after its start method (--init), which run_method's relax shares.
#include <Eigen/Core>

#include "strictmin/problem/problem.h"
#include "strictmin/solvers/result.h"
#include "strictmin/tasks/method.h"

namespace strictmin {

// options.relax's sweeps from `start` (the start method's result): the start's lower bound is
// kept, and its shortfall (a status other than solved) stays visible in the status and message.
Result relax_after(const Problem& problem, const SolverOptions& options, const Result& start);

// --no-flips with relax after one solve (fd in deform and param): the start method's result
// stepped or cut back to add no flip to `start_map` (remove_added_flips), then the sweeps with
// their moves inside the rings' kernels. Before, the sweeps ran from the start method's map
// with its flips and the result was cut back at the end (boy.mesh: 94.7, stalled).
Result relax_without_new_flips(const Problem& problem, const Eigen::MatrixXd& start_map, const SolverOptions& options);

// run_method, adding no flip to start_map: relax_without_new_flips for relax, else the
// solve followed by remove_added_flips (steps inside the orientation cones for linf and l2,
// else the cut-back).
Result run_method_without_new_flips(const Problem& problem, const Eigen::MatrixXd& start_map,
                                    const SolverOptions& options);

}  // namespace strictmin
