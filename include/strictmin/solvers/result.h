#pragma once
// What every solver returns: the map, its distortion, and an honest account of how the
// solve ended. Numerical outcomes are reported here, never thrown.
//
// Status vocabulary (one for every solver and wrapper; decided by decide_status below and
// combined across nested solves by worse_status):
//   solved          the solver's own stopping criterion was met
//   almost-solved   stopped short of it, but within a looser documented tolerance
//                   (LinfOptions::acceptable_gap_tolerance; local-global: ten times the
//                   relative-change tolerance)
//   max-iterations  stopped at an iteration cap
//   stalled         stopped because progress stopped (round-off dominates)
//   numerical-error a computation failed (a factorization, a non-finite direction, an
//                   undetermined map)
//   infeasible      the constraints cannot all be met (certified)
// A result is usable when its map is finite and meets the hard constraints: every status
// but numerical-error and infeasible.
#include <Eigen/Core>
#include <limits>
#include <string>
#include <vector>

namespace strictmin {

enum class SolveStatus { Solved, AlmostSolved, MaxIterations, Stalled, NumericalError, Infeasible };

// "solved", "almost-solved", "max-iterations", "stalled", "numerical-error", "infeasible"
std::string status_name(SolveStatus s);

// The worse of two statuses (in the order of the enum): an outer loop reports an inner
// solve's shortfall unless its own criterion makes it irrelevant.
SolveStatus worse_status(SolveStatus a, SolveStatus b);

// Whether a result with this status carries a map that can be used.
bool status_usable(SolveStatus s);

// What a solver knows when it stops; decide_status turns it into the status. The first that
// holds wins, in this order: infeasible, criterion_met, failed, within_acceptable, stalled,
// cap_reached (and with none of them: numerical-error).
struct StopState {
  bool infeasible = false;         // certified: the constraints cannot all be met
  bool criterion_met = false;      // the solver's own stopping criterion
  bool failed = false;             // a computation failed and no usable map is left
  bool within_acceptable = false;  // a looser documented tolerance was met
  bool stalled = false;            // progress stopped
  bool cap_reached = false;        // an iteration cap
};
SolveStatus decide_status(const StopState& state);

constexpr double kNotApplicable = std::numeric_limits<double>::quiet_NaN();

// One iteration of any solver; fields that do not apply to the solver are NaN.
struct IterationRecord {
  int iteration = 0;
  double max_distortion = 0;  // largest distortion after the iteration (the objective)
  double lower_bound = kNotApplicable;      // certified: no map does better (linf, direct)
  double certified_gap = kNotApplicable;    // (max - lower_bound) / max(1, |max|), as --gap
  double relative_change = kNotApplicable;  // |max - previous max| / previous max (local-global)
  double largest_move = kNotApplicable;     // largest vertex displacement (relax sweeps)
  double decrement = kNotApplicable;        // Newton decrement^2 / 2 relative to f (lp)
  // Local-global with acceleration: accelerated steps accepted / rejected so far (-1: n/a).
  int accelerated_accepted = -1;
  int accelerated_rejected = -1;
  // direct and exact: the level's solve's own iterations (interior-point iterations,
  // local-global steps or frame iterations; -1: n/a).
  int inner_iterations = -1;
  double time_s = 0;                        // since the solve started
};

struct Result {
  Eigen::MatrixXd positions;  // #V by image_dim: the map
  Eigen::VectorXd distortion; // #E: the distortion of the map in the solved measure
  SolveStatus status = SolveStatus::Solved;
  std::string message;        // the stop reason: which criterion ended the solve and why
  int iterations = 0;
  double lower_bound = std::numeric_limits<double>::quiet_NaN();  // no map does better (linf)
  // linf: per element, the dual multiplier lambda_T of its constraint in the certificate of
  // lower_bound (0 for elements with every vertex fixed); over the free elements they sum to
  // 1, and every map x meeting the fixed bounds k_T has
  //   sum_free lambda_T D_T(x) + sum_bounded lambda_T (D_T(x) - k_T) >= lower_bound,
  // so a free element with lambda_T > 0 cannot drop below k by more than
  // (k - lower_bound) / lambda_T while the others stay at most k (strict_exact.cpp).
  Eigen::VectorXd multipliers;
  std::vector<IterationRecord> history;
  double time_s = 0;
  bool ok() const { return status == SolveStatus::Solved; }
  // A finite map that meets the hard constraints (status_usable and finite positions).
  bool usable() const;
};

}  // namespace strictmin
