#pragma once
// One solve that adds no flip to its start (--no-flips with fd in deform and param), and relax
// (paper Algorithm 3) after its start method (--init), which run_method's relax shares.
#include <Eigen/Core>

#include "solvers/no_flips_step.h"
#include "strictmin/problem/problem.h"
#include "strictmin/solvers/linf.h"
#include "strictmin/solvers/result.h"
#include "strictmin/tasks/method.h"

namespace strictmin {

// --no-flips with field deviation after one solve (deform, param) that added flips to `start`:
// from the solve cut back to add none (cut_back_result), steps X <- step(X)
// (solvers/no_flips_step.h) until the objective changes by less than relative_change
// (relative) or max_steps steps were taken. `result` is the unconstrained solve on entry and
// the map on return; its lower_bound stays (it bounds every map, flip-free or not). Status:
// solved when the steps converged, stalled when the last step's cone program stopped short,
// max-iterations at max_steps. options: gap_tolerance (the finest step gap) and progress
// (may be null: one record per step, also kept in result.history).
void steps_without_new_flips(const Problem& problem, const Eigen::MatrixXd& start, StepObjective objective,
                             const LinfOptions& options, Result& result, int max_steps = 100,
                             double relative_change = 1e-3);

// --no-flips after one solve: the Maximum steps for linf, the Energy steps for l2 (where they
// apply), else cut_back_result.
void remove_added_flips(const Problem& problem, const Eigen::MatrixXd& start, Method method, const LinfOptions& options,
                        Result& result);

// options.relax's sweeps from `start` (the start method's result): the start's lower bound is
// kept, and its shortfall (a status other than solved) stays visible in the status and message.
Result relax_after(const Problem& problem, const SolverOptions& options, const Result& start);

// --no-flips with relax after one solve (fd in deform and param): the sweeps, their moves
// inside the rings' kernels, from the start method's own map when they leave no flip against
// `start_map`; else from that map stepped or cut back to add none (remove_added_flips).
// Before, the sweeps ran from the start method's map and the result was cut back at the end
// (boy.mesh: 94.7, stalled).
Result relax_without_new_flips(const Problem& problem, const Eigen::MatrixXd& start_map, const SolverOptions& options);

// run_method, adding no flip to start_map: relax_without_new_flips for relax, else the
// solve followed by remove_added_flips (steps inside the orientation cones for linf and l2,
// else the cut-back).
Result run_method_without_new_flips(const Problem& problem, const Eigen::MatrixXd& start_map,
                                    const SolverOptions& options);

}  // namespace strictmin
