#pragma once
// Primal-dual path-following interior-point method for a ConeProgram (cone_program.h),
// infeasible start, Nesterov-Todd scaling, Mehrotra predictor-corrector (the structure of
// CVXOPT's coneqp and of ECOS without the homogeneous embedding):
//
//   1. residuals, NT scaling W and lambda = W z = W^{-1} s, mu = lambda^T lambda / #cones;
//   2. factorise the normal equations (kkt.h);
//   3. affine direction: linearised complementarity lambda o (W^{-1} ds + W dz) = -lambda o lambda;
//   4. sigma = (1 - a + a^2 ds~^T dz~ / lambda^T lambda)^3 from its step a;
//   5. combined direction with the second-order term and centring:
//      lambda o (W^{-1} ds + W dz) = -lambda o lambda - ds~_a o dz~_a + sigma mu e;
//   6. Gondzio's centrality correctors (settings.max_correctors, same factorisation): aim at
//      a longer step, correct the cones whose complementarity products there would leave
//      [0.1, 10] sigma mu, keep the corrector if the step gets longer;
//   7. step: step_fraction (fast_step_fraction once sigma < fast_sigma) times the longest
//      step keeping s and z inside the cones, computed on the scaled point (well centred, so
//      accurate to the end).
//
// The caller gives the starting x, k (initialize builds interior s and z from them) and a
// monitor that sees every iterate and decides when to stop (e.g. on a certified gap).
#include <functional>

#include "solvers/socp/cone_program.h"
#include "solvers/socp/residuals.h"
#include "solvers/socp/settings.h"

namespace strictmin::socp {

// s = M v + o moved inside the cones where it is not (heads raised to ||tail|| + margin, and,
// with equalities, the small elements' further, so that det(s_i) w_i is at least its smallest
// value: ipm.cpp),
// z = mu0 s^{-1} (so that s o z = mu0 e: a perfectly centred start) with mu0 chosen so that
// the k part of the dual residual vanishes (or from dual_scale without k), y = 0.
// bounded_margin > 0: the element cones with a constant head (fixed bounds k_T) instead get
// s_0 = max(k_T, ||tail||) + bounded_margin, a start that meets (or nearly meets) their bound;
// z = mu0 s^{-1} then starts their multipliers large (docs/strict.md, "The start of a level";
// used on the programs with equalities, linf_main_solve.cpp).
void initialize(const ConeProgram& p, const Eigen::VectorXd& x0, double k0, double margin, double dual_scale,
                IpmState& st, double bounded_margin = 0.0);

// Returns true to stop (the iterate satisfies the caller).
using IpmMonitor = std::function<bool(const IpmState&, const Residuals&, const IpmIteration&)>;

// The standard test: relative residuals below feasibility_tolerance and
// gap <= gap_tolerance * max(1, min(|pobj|, |dobj|)).
bool default_converged(const Residuals& r, const IpmSettings& settings);

class NormalEquations;

// normal_equations: the program's normal equations, analysed beforehand (e.g. on another
// thread while the caller prepared the start); null: analysed here.
IpmOutcome run_ipm(const ConeProgram& p, IpmState& st, const IpmSettings& settings, const IpmMonitor& monitor,
                   NormalEquations* normal_equations = nullptr);

// The normal equations from a source called once, after the start's residuals and the
// monitor's first call, just before the first factorisation: an analysis running on another
// thread (solve_linf's) overlaps that first call. A null result: analysed here.
using NormalEquationsSource = std::function<NormalEquations*()>;
IpmOutcome run_ipm(const ConeProgram& p, IpmState& st, const IpmSettings& settings, const IpmMonitor& monitor,
                   const NormalEquationsSource& source);

}  // namespace strictmin::socp
