#pragma once
// Local-global iterations for ARAP and ASAP (paper Section 5.4, docs/maths.md)
// around any solver. The local step sets each element's target to the rotation (ARAP) or
// similarity (ASAP) closest to its current Jacobian, which never increases any single D_T;
// the global step runs the chosen solver with the targets fixed. With linf the maximum never
// increases from one iteration to the next; relax first runs local-global with its init
// method (SolverOptions::relax_init, default linf), then relax.sweeps iterations whose global
// step is one sweep (all of them: the maximum's change is no stopping signal for relax);
// with direct every level's L-infinity solve becomes local-global iterations.
//
// A per-element shape S_T (interpolation: the symmetric factor Y_T(t)) makes the target
// Q_T S_T with Q_T the rotation closest to J_T S_T^T.
#include <Eigen/Core>
#include <functional>
#include <string>

#include "strictmin/problem/problem.h"
#include "strictmin/solvers/result.h"
#include "strictmin/tasks/method.h"

namespace strictmin {

enum class LocalStep { Rotation, Similarity };

struct LocalGlobalOptions {
  LocalStep local = LocalStep::Rotation;
  Eigen::MatrixXd shapes;          // #E*n by m (as Problem::targets); empty: identity
  int max_iterations = 100;
  double relative_change = 1e-4;   // stop when |max_k - max_{k-1}| <= this * max_{k-1}
  // Anderson acceleration of the local-global fixed point (Peng et al. 2018) with this many
  // previous steps (0: off). An accelerated map is taken only when its objective (the maximum
  // for linf, lp, irls and direct; the energy sum A_T D_T^2 for l2) is no worse than the
  // plain global step's, so the maximum still never increases with linf. For l2 the plain
  // step's energy is first bounded by its global objective sum A_T ||J_T - R_T||^2 (no local
  // step needed); its exact energy is computed only when that bound refuses the accelerated
  // map. Either way the energy never increases. Not used for relax sweeps.
  int acceleration_window = 5;
  // linf global steps: early ones run to a looser gap (at most 1e-3, about a tenth of the
  // last relative change); the step that meets the stopping criterion is repeated at the
  // solver's own gap_tolerance, so the final map is certified as without this.
  bool inexact_early_steps = true;
  // linf global steps (and those within each level of direct) start from the previous
  // step's dual iterate: the cone program's dual does not depend on the targets, so it is
  // still nearly feasible and nearly optimal, and a step takes about half the interior-point
  // iterations of a cold start (docs/arap.md). Results meet the same criteria either way.
  bool warm_start = true;
  // Extrapolated targets (a momentum on the rotations): after a step whose map moved every
  // target from R_prev to R, the next global step's target is R + beta (R - R_prev) taken back
  // to the nearest rotation (similarity). A step whose maximum ends above the previous one is
  // repeated with the plain targets, so the maximum still never increases. 0: off. For linf
  // global steps (and direct's levels); not for interpolation's shapes.
  double target_extrapolation = 0.5;
  // Methods other than l2 first run l2 local-global from the given start (cheap: one
  // factorization, accelerated back-substitutions) and start from its map when its maximum
  // is lower and it has no more flipped elements than the start (a map with more leads linf
  // to a worse local optimum): the rotations are then close to the answer's and few costly
  // global steps remain.
  bool l2_start = true;
  // No new flips: every global step is cut back along the segment from the previous map
  // until no element with det J > 0 there has det J <= 0 (the field deviation with the
  // targets fixed is convex, so the cut step is still no worse than the previous map; the
  // maximum keeps never increasing). Relax sweeps stay in each ring's kernel instead
  // (RelaxOptions::no_flips, set from this by local_global).
  bool no_flips = false;
  // With no_flips, first run without it and keep that map when it adds no flip (the cut-back
  // steps can stall where the path to the optimum passes through a flip); false: cut back
  // from the first step.
  bool no_flips_try_unconstrained = true;
  std::function<void(const IterationRecord&)> progress;

  // Ranges: max_iterations >= 0, acceleration_window in [0, 50], relative_change not NaN (negative: never stop on the
  // change), target_extrapolation in [0, 1], shapes empty or #E*n by m and finite (checked against the problem by local_global).
  bool is_valid(std::string* why = nullptr) const;
};

// Sets problem.targets from the map X (#V by n) by the local step. Both throw InputError for
// a problem that fails check_problem, an X of another size, or shapes that are not empty or
// #E*n by m and finite (local_global too).
void local_step(Problem& problem, const Eigen::MatrixXd& X, const LocalGlobalOptions& options);

// The distortion the local step measures: D_T = min over the local step's family of
// ||J_T - target||, i.e. ||J_T - local target of J_T||.
Eigen::VectorXd local_distortion(const Problem& problem, const Eigen::MatrixXd& X, const LocalGlobalOptions& options);

// Runs local-global from X0 with the solver of `solver` (exact is not supported: status
// numerical-error). Result.distortion is the local distortion (ARAP / ASAP), history has one
// record per iteration, iterations = local-global iterations; Result.message says whether it
// stopped on the relative change or the cap.
Result local_global(const Problem& problem, const Eigen::MatrixXd& X0, const SolverOptions& solver,
                    const LocalGlobalOptions& options);

}  // namespace strictmin
