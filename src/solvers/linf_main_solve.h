#pragma once
// Phase 2 of solve_linf (private): min k over the main program by the interior-point method,
// keeping the best map that meets every constraint and the best certified bound, and
// stopping on the certified gap or a stall. Near the optimum the active-set policy
// (linf_active_set_policy.h) adds bounds and maps from restricted solves.
#include <Eigen/Core>
#include <chrono>
#include <functional>
#include <vector>

#include "linf_program.h"
#include "linf_warm_start.h"
#include "strictmin/solvers/result.h"
#include "solvers/socp/certificate.h"
#include "solvers/socp/ipm.h"
#include "solvers/socp/kkt.h"
#include "solvers/socp/settings.h"

namespace strictmin::linf_detail {

// The best of the main solve so far.
struct BestSoFar {
  Eigen::VectorXd x;                    // the best map meeting every constraint (its free dofs)
  double k = kInf;                      // its k
  double lower_bound = -kInf;           // the best certified bound
  Eigen::VectorXd multipliers;          // per element cone, of the iterates' best certificate
  Eigen::VectorXd element_multipliers;  // or per element, when the bound came from a restriction
  double iterate_bound = -kInf;         // the best of the iterates' own certificates
  double previous_k = kInf;             // k of the previous iterate
};

struct MainSolve {
  BestSoFar best;
  socp::IpmOutcome outcome;
  bool stalled = false;  // the certified gap stopped shrinking
  Eigen::VectorXd final_z, final_y;  // the last dual iterate (a warm start for the next solve)
};

// Whether `warm` can start the main solve of mp: kept from a program of the same shape, not
// after a large change; or, by element, with a kept cone for at least half of mp's cones.
bool warm_start_applies(const MainProgram& mp, const LinfWarmStart& warm);
// Keeps ms's last dual iterate in `warm` for the next solve (emptied when ms failed or stalled).
void keep_dual(const MainProgram& mp, MainSolve& ms, LinfWarmStart& warm);

// Runs phase 2 from `start` (which meets the bounds). `effective_bounds` are the element
// bounds as widened by the start's round-off; records every iteration in `history` (and
// reports it to options.progress), elapsed times from t0.
MainSolve solve_main(const MainProgram& mp, const socp::WeightedLeastSquares& ls, const Candidate& start,
                     const Eigen::VectorXd& effective_bounds, const socp::NormalEquationsSource& normal_equations,
                     std::vector<IterationRecord>& history, std::chrono::steady_clock::time_point t0,
                     const LinfWarmStart* warm);

}  // namespace strictmin::linf_detail
