#pragma once
// Settings and per-iteration information of the interior-point method (socp/ipm.h).
#include <limits>
#include <string>

namespace strictmin::socp {

struct IpmSettings {
  int max_iterations = 100;
  double gap_tolerance = 1e-8;          // default stopping test (ipm.h: default_converged)
  double feasibility_tolerance = 1e-8;
  double step_fraction = 0.95;          // fraction of the step to the cone boundary
  // ... raised to fast_step_fraction when the centring parameter sigma is below fast_sigma
  // (the predictor went almost all the way: the fast local phase).
  double fast_step_fraction = 0.99;
  double fast_sigma = 1e-2;
  // Gondzio's multiple centrality correctors: after the predictor-corrector direction, at most
  // max_correctors extra solves (same factorisation) that move the complementarity products of
  // the point a longer step away (step + corrector_step_increase) towards [0.1, 10] sigma mu;
  // each is kept only if it lengthens the step by at least corrector_acceptance times the
  // increase aimed at.
  int max_correctors = 2;
  double corrector_step_increase = 0.2;
  double corrector_acceptance = 0.1;
  // Correctors only while the longest step is below this (near 1 they cannot gain much).
  double corrector_max_step = 0.95;
  // Static regularisation of the normal matrix: each diagonal entry is multiplied by
  // 1 + regularization (plus 1e-3 * regularization * the largest one); regularization is
  // multiplied by 100 on every failed factorisation (at most factorization_retries times).
  double regularization = 1e-15;
  // Normal equations with at least this many free dofs are split by a vertex separator and
  // their halves factorised on two threads (split_cholesky.h). At 8,000 rather than 20,000
  // (2026-11-26): the 10k square 0.17-0.19 -> 0.13-0.15 s, lion (16,674 triangles) 0.65 ->
  // 0.53 s, homer's seamless problem 0.40 -> 0.34-0.37 s; below it (cow_disk, hand) splitting
  // cost 5-10%.
  int split_min_dofs = 8000;
  int factorization_retries = 4;
  // Refinement of each Newton direction: at most refinement_steps preconditioned CG steps
  // on the normal equations, stopping at a relative residual of refinement_tolerance.
  int refinement_steps = 10;
  double refinement_tolerance = 1e-10;
  // The same for the predictor (it only sets sigma and the second-order term) and for the
  // centrality correctors (added to the direction, so their error adds to its residual).
  // CG stops early after refinement_patience steps in a row that do not reduce the best
  // residual by the factor refinement_progress.
  double refinement_progress = 0.5;
  int refinement_patience = 2;
  // Step directions whose residual in the unreduced Newton system (not only in the normal
  // equations) is above unreduced_refinement_above get at most unreduced_refinement steps of
  // iterative refinement on that system, towards refinement_tolerance (kkt.h: solve_newton).
  // Predictor and correctors are not checked (without penalised equalities).
  int unreduced_refinement = 3;
  double unreduced_refinement_above = 1e-8;
  double predictor_tolerance = 1e-4;
  double corrector_tolerance = 1e-6;
  // Newton directions whose relative residual stays above max_newton_residual for
  // max_bad_directions iterations in a row are unreliable: the normal equations have become
  // too ill-conditioned for double precision; the method stops with NumericalError (the
  // caller may accept the iterate).
  double max_newton_residual = 1e-1;
  int max_bad_directions = 5;
  // Equality constraints are eliminated by a penalty A^T A / rho with rho =
  // equality_penalty / max diagonal, then refined against the exact saddle-point system.
  // A mild penalty: the refinement does the rest. On the seamless problems of global
  // parametrization (docs/gparam.md) 1e-8 left the certified gap at ~1e-4 (ill-conditioned
  // Newton systems); 1e-1 reaches the 1e-8 gap (cow, fertility) with seams to ~1e-12.
  double equality_penalty = 1e-1;
  // Equalities in vertex-block form are eliminated exactly instead (kkt.h, null_space.h).
  bool eliminate_equalities = true;
  // Consecutive iterations with a step below min_step before giving up.
  double min_step = 1e-10;
  int max_small_steps = 3;
  // 1: one line per iteration on stderr (objectives, residuals, mu, step, sigma, CG steps,
  // Newton residual) and the factorisation size; 2: also every Newton solve's residuals.
  int verbose = 0;
};

// MonitorStopped: the caller's monitor asked to stop (its own criterion or a stall: the caller
// decides the status, see linf.cpp); the method itself never declares convergence.
enum class IpmStatus { Running, MonitorStopped, MaxIterations, NumericalError };

// What the method knows after an iteration (iteration 0 is the starting point).
struct IpmIteration {
  int iteration = 0;
  double pobj = 0, dobj = 0;  // primal and dual objectives of the cone program
  double gap = 0;             // s^T z
  double mu = 0;              // s^T z / (number of cones)
  double pres = 0;            // relative primal residual (cones and equalities), max norm
  double dres = 0;            // relative dual residual, max norm
  double step = 0, sigma = 0; // step length and centring parameter of the iteration
  int refinement = 0;         // refinement steps used by the last Newton solve
  double kkt_residual = 0;    // relative residual of the last Newton solve
  double time_s = 0;          // since the method started
};

struct IpmOutcome {
  IpmStatus status = IpmStatus::Running;
  int iterations = 0;
  std::string message;
  // Where the time went (seconds): symbolic analysis, numeric factorisations (with the
  // bordering solve), Newton solves (with refinement), the caller's monitor, everything.
  double analyze_s = 0, factor_s = 0, solve_s = 0, monitor_s = 0, total_s = 0;
};

}  // namespace strictmin::socp
